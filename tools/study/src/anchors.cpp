#include "headingd/study/anchors.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "headingd/files/numeric_csv.hpp"

extern char** environ;

namespace headingd::study {
namespace {

// A private folder that is removed with everything in it when the run ends.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "headingd-study-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder");
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  std::filesystem::path operator/(const char* name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void writeDriverInput(const Recording& r, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z,mag_x,mag_y,mag_z\n";
  core::Vec3 mag = core::Vec3::Zero();
  char line[320];
  for (const core::ImuSample& s : r.samples) {
    if (s.has_mag) mag = s.mag_uT;
    std::snprintf(line, sizeof line, "%.9f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                  1e-9 * static_cast<double>(s.t_ns - r.samples.front().t_ns), s.gyro_rad_s.x(), s.gyro_rad_s.y(),
                  s.gyro_rad_s.z(), s.accel_m_s2.x(), s.accel_m_s2.y(), s.accel_m_s2.z(), mag.x(), mag.y(), mag.z());
    out << line;
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
}

void runProgram(const std::string& binary, const std::string& in, const std::string& out) {
  std::vector<std::string> args = {binary, in, out};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, binary.c_str(), nullptr, nullptr, argv.data(), environ) != 0) {
    throw std::runtime_error("cannot start " + binary);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("lost " + binary);
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error(binary + " failed on " + in);
}

}  // namespace

std::vector<AnchorFilter> findAnchors(const std::string& bin_dir, bool offline) {
  std::vector<AnchorFilter> found;
  using Filters = std::vector<std::pair<const char*, const char*>>;  // name, driver
  const Filters filters = offline ? Filters{{"VQF offline", "anchor_vqf_offline"}, {"VQF", "anchor_vqf"}}
                                  : Filters{{"VQF", "anchor_vqf"}, {"Fusion", "anchor_fusion"}};
  for (const auto& [name, file] : filters) {
    const std::filesystem::path p = std::filesystem::path(bin_dir) / file;
    if (access(p.c_str(), X_OK) == 0) found.push_back({name, p.string()});
  }
  return found;
}

std::vector<core::Quat> runAnchor(const AnchorFilter& anchor, const Recording& r) {
  const TemporaryFolder folder;
  const std::filesystem::path in = folder / "in.csv", out = folder / "out.csv";
  writeDriverInput(r, in);
  runProgram(anchor.binary, in.string(), out.string());
  const auto q = files::readNumericCsv(out.string(), {"qw", "qx", "qy", "qz"});
  if (q.rows != r.size()) {
    throw std::runtime_error(anchor.name + " wrote " + std::to_string(q.rows) + " rows for " +
                             std::to_string(r.size()) + " samples");
  }
  std::vector<core::Quat> estimates;
  estimates.reserve(q.rows);
  for (std::size_t i = 0; i < q.rows; ++i) {
    estimates.emplace_back(q.column("qw")[i], q.column("qx")[i], q.column("qy")[i], q.column("qz")[i]);
  }
  return estimates;
}

}  // namespace headingd::study
