#pragma once
// The total cap of a recording directory: the sum of every file under it (old recordings
// from earlier runs included) is kept at or below max_bytes by deleting the oldest closed
// segments first: the oldest recording folder first (by name), in a folder the segment that
// was written to last the longest ago first. Never a segment being written, never a file of
// the current recording that is not a segment; an old folder left without segments goes
// entirely. The directory is scanned once; after that a running total is kept, so checking
// is a comparison. Writer thread only (the counters in the tally are for any thread).
#include <cstdint>
#include <deque>
#include <map>
#include <string>

#include "headingd/daemon/recorder/recorder_tally.hpp"

namespace headingd::daemon {

class RecorderDiskCap {
 public:
  RecorderDiskCap(std::string dir, std::string current_folder, std::uint64_t max_bytes, RecorderTally& tally);

  // Reads what is under the directory now (the current folder's files included).
  void scan();
  // Bytes written to the directory since (segments growing).
  void grew(std::uint64_t bytes);
  // A segment of the current recording is closed: it may be deleted from now on.
  void segmentClosed(const std::string& path, std::uint64_t bytes);
  // Deletes the oldest closed segments while the total is above the cap.
  void enforce();

  std::uint64_t totalBytes() const { return total_bytes_; }

 private:
  struct Deletable {
    std::string folder;
    std::string path;
    std::uint64_t bytes = 0;
  };
  struct OldFolder {
    std::uint64_t segments_left = 0;
    std::uint64_t other_bytes = 0;  // its files that are not segments (header, configuration copies)
  };

  void removeOldFolder(const std::string& folder);
  void publishTotal();

  std::string dir_;
  std::string current_folder_;
  std::uint64_t max_bytes_;
  RecorderTally& tally_;
  std::uint64_t total_bytes_ = 0;
  std::deque<Deletable> oldest_first_;
  std::map<std::string, OldFolder> old_folders_;
  bool said_cap_unreachable_ = false;
};

}  // namespace headingd::daemon
