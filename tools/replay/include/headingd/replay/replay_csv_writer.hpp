#pragma once
// headingd-replay's output CSV, one row per estimate: t,qw,qx,qy,qz,roll_deg,pitch_deg,
// yaw_deg (and with GPS the heading columns). Rows are formatted with std::to_chars into one
// reused buffer and written in large blocks: the bytes are those of printf's "%.9g" (time),
// "%.9f" (quaternion) and "%.6f" (angles), which std::to_chars gives exactly (both are
// correctly rounded), at a fraction of printf's cost per field.
#include <cstdint>
#include <cstdio>
#include <string>
#include <memory>

#include "headingd/core/heading_pipeline.hpp"

namespace headingd::replay {

class ReplayCsvWriter {
 public:
  // Opens `path` and writes the header line; throws std::runtime_error if it cannot.
  ReplayCsvWriter(const std::string& path, bool with_gps);
  ~ReplayCsvWriter();
  ReplayCsvWriter(const ReplayCsvWriter&) = delete;
  ReplayCsvWriter& operator=(const ReplayCsvWriter&) = delete;

  // One row: the sample's time and the estimate after it. An estimate that is not valid
  // yet is written as a row of nan (nothing usable yet: say so rather than invent one).
  void write(std::int64_t t_ns, const core::HeadingOutput& estimate);
  // Writes what is buffered and closes the file; throws std::runtime_error on a write error.
  void close();

 private:
  void flushIfFull();
  void flush();

  std::string path_;
  std::FILE* file_ = nullptr;
  bool with_gps_ = false;
  std::unique_ptr<char[]> buffer_;  // not zeroed: only written bytes are read
  std::size_t used_ = 0;
  bool failed_ = false;
};

}  // namespace headingd::replay
