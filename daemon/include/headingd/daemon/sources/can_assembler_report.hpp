#pragma once
// The CAN epoch assembler's counters on STATUS, named the same for every CAN source
// ([can] and [candump_log]).
#include <cstddef>

#include "headingd/can/epoch_assembler.hpp"
#include "headingd/daemon/sources/source.hpp"

namespace headingd::daemon {

// Sets them from counter index `*i` on and advances it.
inline void reportAssemblerCounters(SourceReport& out, std::size_t* i, const can::AssemblerCounters& a) {
  out.set((*i)++, "samples", a.samples);
  out.set((*i)++, "samples_with_mag", a.samples_with_mag);
  out.set((*i)++, "incomplete_epochs", a.incomplete_epochs);
  out.set((*i)++, "sequence_gaps", a.sequence_gaps);
  out.set((*i)++, "missing_epochs", a.missing_epochs);
  out.set((*i)++, "reordered_epochs", a.reordered_epochs);
  out.set((*i)++, "duplicate_frames", a.duplicate_frames);
  out.set((*i)++, "late_frames", a.late_frames);
  out.set((*i)++, "late_mag_frames", a.late_mag_frames);
  out.set((*i)++, "unknown_id_frames", a.unknown_id_frames);
  out.set((*i)++, "wrong_length_frames", a.wrong_length_frames);
  out.set((*i)++, "error_frames", a.error_frames);
}

}  // namespace headingd::daemon
