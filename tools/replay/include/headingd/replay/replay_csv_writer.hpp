#pragma once
// headingd-replay's output CSV, one row per estimate: t,qw,qx,qy,qz,roll_deg,pitch_deg,
// yaw_deg (and with GPS the heading columns). Rows are formatted with std::to_chars into one
// reused buffer and written in large blocks: the time in seconds with nine decimals, exact from
// the integer nanoseconds (UNIX times too), and the bytes of printf's "%.9f" (quaternion) and
// "%.6f" (angles), which std::to_chars gives exactly (both are correctly rounded), at a
// fraction of printf's cost per field. The file is written through files::OutputFile: it
// appears under its name only when close() succeeded.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "headingd/core/heading_pipeline.hpp"
#include "headingd/files/output_file.hpp"

namespace headingd::replay {

class ReplayCsvWriter {
 public:
  // Opens (a temporary file for) `path` and writes the header line; throws if it cannot.
  ReplayCsvWriter(const std::string& path, bool with_gps);
  ~ReplayCsvWriter();
  ReplayCsvWriter(const ReplayCsvWriter&) = delete;
  ReplayCsvWriter& operator=(const ReplayCsvWriter&) = delete;

  // One row: the sample's time and the estimate after it. An estimate that is not valid
  // yet is written as a row of nan (nothing usable yet: say so rather than invent one).
  void write(std::int64_t t_ns, const core::HeadingOutput& estimate);
  // Writes what is buffered, closes the file and renames it into place; throws on a write
  // error. Without close() (an error stopped the replay) nothing appears under the name.
  void close();

 private:
  void flushIfFull();
  void flush();

  std::string path_;
  std::unique_ptr<files::OutputFile> file_;
  bool with_gps_ = false;
  std::unique_ptr<char[]> buffer_;  // not zeroed: only written bytes are read
  std::size_t used_ = 0;
};

}  // namespace headingd::replay
