#pragma once
// The comparator filters (VQF, x-io Fusion) run on the same Recording as headingd, so that
// one scoring (scoring.hpp) serves all three. They are measuring instruments outside the
// repository (../shared/anchors, built by its build.sh): each is a program that reads a CSV
// in BROAD's layout and writes t,qw,qx,qy,qz (sensor to NED, magnetic north) per row.
// Nothing of theirs is linked in; the study runs them as processes.
#include <optional>
#include <string>
#include <vector>

#include "headingd/study/recording.hpp"

namespace headingd::study {

struct AnchorFilter {
  std::string name;    // "VQF", "Fusion"
  std::string binary;  // path of the driver program
};

// The drivers found in bin_dir (anchor_vqf, anchor_fusion), in that order; offline: the acausal
// anchor_vqf_offline and the causal anchor_vqf instead, to set beside a smoother. Empty when
// the folder holds none of them.
std::vector<AnchorFilter> findAnchors(const std::string& bin_dir, bool offline = false);

// Runs one driver on the recording (written to a temporary CSV; a sample without a field
// repeats the last one, as a slower magnetometer's reader would) and returns its estimate
// per sample. Throws std::runtime_error naming the driver when it fails or its output does
// not have one row per sample.
std::vector<core::Quat> runAnchor(const AnchorFilter& anchor, const Recording& r);

}  // namespace headingd::study
