#include "headingd/daemon/recorder/recorder_disk_cap.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <tuple>
#include <vector>

#include "headingd/daemon/recorder/recorder_folder.hpp"

namespace headingd::daemon {
namespace {

namespace fs = std::filesystem;

// Regular files only (a symbolic link counts as nothing: what it points to is elsewhere).
std::uint64_t sizeOf(const fs::directory_entry& entry) {
  std::error_code ec;
  if (!entry.is_regular_file(ec) || entry.is_symlink(ec)) return 0;
  const std::uintmax_t size = entry.file_size(ec);
  return ec ? 0 : static_cast<std::uint64_t>(size);
}

std::uint64_t bytesUnder(const fs::path& folder) {
  std::uint64_t bytes = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) bytes += sizeOf(*it);
  return bytes;
}

}  // namespace

RecorderDiskCap::RecorderDiskCap(std::string dir, std::string current_folder, std::uint64_t max_bytes,
                                 RecorderTally& tally)
    : dir_(std::move(dir)), current_folder_(std::move(current_folder)), max_bytes_(max_bytes), tally_(tally) {}

void RecorderDiskCap::scan() {
  struct Segment {
    fs::file_time_type last_written;
    std::uint64_t number;
    std::string path;
    std::uint64_t bytes;
  };
  total_bytes_ = 0;
  oldest_first_.clear();
  old_folders_.clear();
  std::vector<std::string> folders;
  std::error_code ec;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code entry_ec;
    if (it->is_directory(entry_ec) && !it->is_symlink(entry_ec)) {
      if (it->path().string() == current_folder_) {
        total_bytes_ += bytesUnder(it->path());
      } else {
        folders.push_back(it->path().filename().string());
      }
    } else {
      total_bytes_ += sizeOf(*it);  // not in a recording folder: counted, never deleted
    }
  }
  std::sort(folders.begin(), folders.end(), recordingFolderBefore);
  for (const std::string& name : folders) {
    const std::string folder = dir_ + "/" + name;
    OldFolder& old = old_folders_[folder];
    std::vector<Segment> segments;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      std::error_code entry_ec;
      const auto parsed = parseSegmentFileName(it->path().filename().string());
      if (parsed && !it->is_directory(entry_ec)) {
        segments.push_back({it->last_write_time(entry_ec), parsed->number, it->path().string(), sizeOf(*it)});
      } else {
        old.other_bytes += it->is_directory(entry_ec) ? bytesUnder(it->path()) : sizeOf(*it);
      }
    }
    std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) {
      return std::tie(a.last_written, a.number, a.path) < std::tie(b.last_written, b.number, b.path);
    });
    total_bytes_ += old.other_bytes;
    old.segments_left = segments.size();
    // A folder without segments (a run that recorded nothing) goes whole, in its turn.
    if (segments.empty()) oldest_first_.push_back({folder, "", old.other_bytes});
    for (Segment& s : segments) {
      total_bytes_ += s.bytes;
      oldest_first_.push_back({folder, std::move(s.path), s.bytes});
    }
  }
  publishTotal();
}

void RecorderDiskCap::grew(std::uint64_t bytes) {
  total_bytes_ += bytes;
  publishTotal();
}

void RecorderDiskCap::segmentClosed(const std::string& path, std::uint64_t bytes) {
  oldest_first_.push_back({current_folder_, path, bytes});
}

void RecorderDiskCap::enforce() {
  while (total_bytes_ > max_bytes_ && !oldest_first_.empty()) {
    const Deletable victim = std::move(oldest_first_.front());
    oldest_first_.pop_front();
    if (victim.path.empty()) {
      removeOldFolder(victim.folder);
      continue;
    }
    if (::unlink(victim.path.c_str()) != 0 && errno != ENOENT) {
      RecorderTally::add(tally_.write_errors, 1);
      spdlog::warn("recorder: cannot delete {} to keep the recordings under {} bytes: {}", victim.path, max_bytes_,
                   std::strerror(errno));
    } else {
      total_bytes_ -= std::min(total_bytes_, victim.bytes);
      RecorderTally::add(tally_.segments_deleted, 1);
    }
    const auto old = old_folders_.find(victim.folder);
    if (old != old_folders_.end() && --old->second.segments_left == 0) removeOldFolder(victim.folder);
  }
  if (total_bytes_ > max_bytes_ && !said_cap_unreachable_) {
    said_cap_unreachable_ = true;
    spdlog::warn(
        "recorder: {} bytes under {}, above total_max_bytes = {}, and nothing left that may be deleted "
        "(segments being written, this recording's own files, files outside recording folders)",
        total_bytes_, dir_, max_bytes_);
  }
  publishTotal();
}

void RecorderDiskCap::removeOldFolder(const std::string& folder) {
  const auto old = old_folders_.find(folder);
  const std::uint64_t bytes = old != old_folders_.end() ? old->second.other_bytes : 0;
  std::error_code ec;
  fs::remove_all(folder, ec);
  if (ec) {
    RecorderTally::add(tally_.write_errors, 1);
    spdlog::warn("recorder: cannot delete the old recording {}: {}", folder, ec.message());
  } else {
    total_bytes_ -= std::min(total_bytes_, bytes);
  }
  if (old != old_folders_.end()) old_folders_.erase(old);
}

void RecorderDiskCap::publishTotal() { tally_.bytes_on_disk.store(total_bytes_, std::memory_order_relaxed); }

}  // namespace headingd::daemon
