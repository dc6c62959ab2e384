#pragma once
// The real data a test reads, from the folder cmake/test_data.cmake chose: the full set in
// ../shared/data when it is there, else the repository's subset in tests/data. Every access
// goes through here so that each test prints, once per process, which set it used:
//   data: /path/to/shared/data/broad (full set, 14 trials)
// A target gets HEADINGD_<SET>_DIR and HEADINGD_<SET>_KIND from headingd_target_data_set.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace headingd::test_data {

struct DataSet {
  const char* dir;
  const char* kind;    // "full set" or "in-repo subset"
  const char* suffix;  // the files counted: ".csv.gz", ".log", ...
  const char* unit;    // what they are: "trials", "captures", ...
};

// The set's files ending in `suffix`, sorted by name (symbolic links followed).
inline std::vector<std::filesystem::path> files(const DataSet& set) {
  std::vector<std::filesystem::path> found;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(set.dir, ec)) {
    if (e.path().filename().string().ends_with(set.suffix) && std::filesystem::is_regular_file(e.path())) {
      found.push_back(e.path());
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.filename() < b.filename(); });
  return found;
}

// Prints the "data:" line, the first time a process uses the set.
inline void announce(const DataSet& set) {
  static std::set<std::string> announced;
  if (!announced.insert(set.dir).second) return;
  std::printf("data: %s (%s, %zu %s)\n", set.dir, set.kind, files(set).size(), set.unit);
  std::fflush(stdout);
}

// A file of the set by name, announcing the set.
inline std::filesystem::path file(const DataSet& set, const std::string& name) {
  announce(set);
  return std::filesystem::path(set.dir) / name;
}

// All the set's files, announcing the set.
inline std::vector<std::filesystem::path> all(const DataSet& set) {
  announce(set);
  return files(set);
}

#ifdef HEADINGD_BROAD_DIR
// BROAD trials (NN_name.csv.gz).
inline constexpr DataSet kBroad{HEADINGD_BROAD_DIR, HEADINGD_BROAD_KIND, ".csv.gz", "trials"};
#endif
#ifdef HEADINGD_GPSD_LOGS_DIR
// gpsd's receiver captures (*.log, most with gpsd's output *.log.chk).
inline constexpr DataSet kGpsdLogs{HEADINGD_GPSD_LOGS_DIR, HEADINGD_GPSD_LOGS_KIND, ".log", "captures"};
#endif
#ifdef HEADINGD_WMM_DIR
// NOAA's WMM2025 coefficients and test values.
inline constexpr DataSet kWmm{HEADINGD_WMM_DIR, HEADINGD_WMM_KIND, "", "files"};
#endif

}  // namespace headingd::test_data
