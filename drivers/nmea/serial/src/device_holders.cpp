#include "headingd/nmea/device_holders.hpp"

#include <dirent.h>
#include <unistd.h>

#include <limits.h>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <memory>

namespace headingd::nmea {
namespace {

struct DirCloser {
  void operator()(DIR* d) const { ::closedir(d); }
};
using Dir = std::unique_ptr<DIR, DirCloser>;

bool isPid(const char* name) {
  if (*name == '\0') return false;
  for (const char* c = name; *c != '\0'; ++c) {
    if (std::isdigit(static_cast<unsigned char>(*c)) == 0) return false;
  }
  return true;
}

bool holds(const std::string& fd_dir, const std::string& device_path) {
  const Dir fds(::opendir(fd_dir.c_str()));
  if (!fds) return false;  // gone, or another user's process
  char target[PATH_MAX];
  while (const dirent* e = ::readdir(fds.get())) {
    if (e->d_name[0] == '.') continue;
    const std::string link = fd_dir + "/" + e->d_name;
    const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
    if (n <= 0) continue;
    if (device_path.compare(0, std::string::npos, target, static_cast<std::size_t>(n)) == 0) return true;
  }
  return false;
}

std::string commOf(const std::string& proc_dir) {
  std::ifstream in(proc_dir + "/comm");
  std::string name;
  std::getline(in, name);
  return name.empty() ? "?" : name;
}

}  // namespace

std::vector<DeviceHolder> findDeviceHolders(const std::string& device_path, pid_t exclude_pid,
                                            std::size_t max_holders) {
  std::vector<DeviceHolder> holders;
  const Dir proc(::opendir("/proc"));
  if (!proc || device_path.empty()) return holders;
  while (const dirent* e = ::readdir(proc.get())) {
    if (!isPid(e->d_name)) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(e->d_name));
    if (pid == exclude_pid) continue;
    const std::string proc_dir = std::string("/proc/") + e->d_name;
    if (holds(proc_dir + "/fd", device_path)) holders.push_back(DeviceHolder{pid, commOf(proc_dir)});
  }
  std::sort(holders.begin(), holders.end(), [](const auto& a, const auto& b) { return a.pid < b.pid; });
  if (holders.size() > max_holders) holders.resize(max_holders);
  return holders;
}

std::string describeDeviceHolders(const std::vector<DeviceHolder>& holders) {
  if (holders.empty()) return "an unknown program";
  std::string s;
  for (const DeviceHolder& h : holders) {
    if (!s.empty()) s += ", ";
    s += h.name + " (pid " + std::to_string(h.pid) + ")";
  }
  return s;
}

}  // namespace headingd::nmea
