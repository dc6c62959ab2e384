#pragma once
// Names in a recording directory: one folder per run, named for its UTC start time, and in
// it each stream's segments `<stream>.<NNNNNN>.log` beside the files written at start.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace headingd::daemon {

// "YYYY-MM-DDTHH-MM-SSZ" (UTC; no ':' so the name is valid on every file system).
std::string recordingFolderName(std::chrono::system_clock::time_point t);

// Creates `dir` (with its parents) and in it a new folder named for `t`, with the suffix -2,
// -3 ... when that name is taken, and writes each of `files` (name in the folder, content)
// there. Returns the folder's path. Throws std::runtime_error naming the path and the
// system's reason when something cannot be made (a half-made folder is removed).
std::string makeRecordingFolder(const std::string& dir, std::chrono::system_clock::time_point t,
                                const std::vector<std::pair<std::string, std::string>>& files);

// "<stream>.<number, at least 6 digits>.log".
std::string segmentFileName(std::string_view stream, std::uint64_t number);

struct SegmentFileName {
  std::string stream;
  std::uint64_t number = 0;
};
// The parts of a segment's file name; nothing for any other name.
std::optional<SegmentFileName> parseSegmentFileName(std::string_view file_name);

// The order of recording folders from oldest to newest: by name, a -N suffix counted as a
// number (so "...Z-10" comes after "...Z-9").
bool recordingFolderBefore(const std::string& a, const std::string& b);

}  // namespace headingd::daemon
