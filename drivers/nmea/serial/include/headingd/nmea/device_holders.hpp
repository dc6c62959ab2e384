#pragma once
// Who else has a device open: the processes whose /proc/PID/fd links name it. Used to say
// which program holds the GPS port ("gpsd (pid 812)") when it is busy.
//
// Best effort: another user's /proc/PID/fd is unreadable without privileges (and hidden
// altogether under systemd's ProtectProc=invisible), so an empty answer means "none that this
// process can see", not "none". Links are compared as text (readlink), never followed, so a
// holder's descriptor on a hung file system cannot block the caller.
#include <sys/types.h>

#include <string>
#include <vector>

namespace headingd::nmea {

struct DeviceHolder {
  pid_t pid = 0;
  std::string name;  // /proc/PID/comm: the program's name as the kernel keeps it (15 characters at most)
};

// Processes other than `exclude_pid` with a descriptor on `device_path`, the device's real
// path (symlinks resolved, as the kernel shows it in /proc/PID/fd). In pid order, at most
// `max_holders` of them.
std::vector<DeviceHolder> findDeviceHolders(const std::string& device_path, pid_t exclude_pid,
                                            std::size_t max_holders = 4);

// "gpsd (pid 812)", "gpsd (pid 812), cat (pid 900)", or "an unknown program" when empty.
std::string describeDeviceHolders(const std::vector<DeviceHolder>& holders);

}  // namespace headingd::nmea
