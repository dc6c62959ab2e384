#pragma once
// Compares the HEADING and ATTITUDE messages of LCM logs bit for bit, for the black box's
// replay contract (daemon/README.md, "Black box"): every field but utime, sample_age_us and
// validity (those depend on when the daemon published, not on what it computed).
#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "headingd/attitude_t.hpp"
#include "headingd/heading_t.hpp"

namespace headingd::daemon::test {

// Encoded messages of one channel with the timing fields zeroed, by sample_utime; messages
// without an estimate (validity NONE) are counted apart.
struct EstimateMessages {
  std::map<std::int64_t, std::vector<std::vector<std::uint8_t>>> by_sample_utime;
  std::size_t messages = 0;
  std::size_t without_estimate = 0;
};

template <class Message>
std::vector<std::uint8_t> normalised(Message m) {
  m.utime = 0;
  m.sample_age_us = 0;
  m.validity = 0;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

template <class Message>
EstimateMessages readEstimates(const std::string& log_path, const std::string& channel) {
  EstimateMessages out;
  lcm::LogFile log(log_path, "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    if (e->channel != channel) continue;
    Message m;
    if (m.decode(e->data, 0, e->datalen) < 0) continue;
    ++out.messages;
    if (m.validity == 0) {
      ++out.without_estimate;
      continue;
    }
    out.by_sample_utime[m.sample_utime].push_back(normalised(m));
  }
  return out;
}

struct Comparison {
  std::size_t compared = 0;  // messages with an estimate, looked up
  std::size_t equal = 0;     // equal, bit for bit, to a reference state of the same sample
  std::int64_t first_unequal_sample_utime = 0;
};

// Every message of `published` against the states of `reference` (every state a replay went
// through: after each IMU sample and each GPS epoch) of the same sample time.
inline Comparison compareWithStates(const EstimateMessages& published, const EstimateMessages& reference) {
  Comparison c;
  for (const auto& [sample_utime, messages] : published.by_sample_utime) {
    const auto states = reference.by_sample_utime.find(sample_utime);
    for (const auto& m : messages) {
      ++c.compared;
      bool found = false;
      if (states != reference.by_sample_utime.end()) {
        for (const auto& s : states->second) found = found || s == m;
      }
      if (found) {
        ++c.equal;
      } else if (c.first_unequal_sample_utime == 0) {
        c.first_unequal_sample_utime = sample_utime;
      }
    }
  }
  return c;
}

}  // namespace headingd::daemon::test
