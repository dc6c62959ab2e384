#include "headingd/nmea/nmea_log_player.hpp"

#include <stdexcept>
#include <type_traits>
#include <utility>
#include <variant>

#include "headingd/files/input_file.hpp"
#include "headingd/live/clocks.hpp"
#include "headingd/nmea/checksum.hpp"
#include "headingd/nmea/comment_filter.hpp"
#include "headingd/nmea/sentences.hpp"

namespace headingd::nmea {
namespace {

constexpr std::int64_t kDayNs = 86'400'000'000'000;

// The UTC time of day a line stamps its epoch with, by the FixAccumulator's rules: the
// sentences that start an epoch (GGA, RMC, GNS, ZDA, GLL), not GST (it describes an older
// fix). Lines that fail the checksum or do not decode have none, as they have none for the
// parser either.
std::optional<std::int64_t> epochTimeOf(std::string_view line) {
  const std::size_t start = line.find('$');
  if (start == std::string_view::npos) return std::nullopt;
  line.remove_prefix(start);
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n' || line.back() == ' ')) line.remove_suffix(1);
  if (verifyChecksum(line) != ChecksumVerdict::kOk) return std::nullopt;
  const DecodeResult r = decodeSentence(line);
  if (r.status != DecodeStatus::kDecoded) return std::nullopt;
  return std::visit(
      [](const auto& s) -> std::optional<std::int64_t> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Gga> || std::is_same_v<T, Rmc> || std::is_same_v<T, Gns> ||
                      std::is_same_v<T, Zda> || std::is_same_v<T, Gll>) {
          return s.time_of_day_ns;
        } else {
          return std::nullopt;
        }
      },
      r.sentence->data);
}

}  // namespace

NmeaLogPlayer::NmeaLogPlayer(boost::asio::io_context& io, NmeaLogPlayerConfig config, FixHandler on_fix,
                             LineHandler on_line, FinishedHandler on_finished)
    : config_(std::move(config)),
      assembler_(config_.parser, std::move(on_fix), std::move(on_line)),
      on_finished_(std::move(on_finished)),
      timer_(io) {
  if (!(config_.speed > 0.0)) throw std::invalid_argument("NMEA log player: speed must be positive");
  if (!(config_.max_gap_s > 0.0)) throw std::invalid_argument("NMEA log player: max_gap_s must be positive");
  // Held whole (it is indexed into epochs before playing), so limited like every log read whole.
  std::vector<std::uint8_t> raw;
  if (config_.contents) {
    raw.assign(config_.contents->begin(), config_.contents->end());
    config_.contents.reset();
  } else {
    try {
      const std::string text = files::readWholeFile(config_.path, files::kWholeLogLimit);
      raw.assign(text.begin(), text.end());
    } catch (const files::FileError& e) {
      throw std::runtime_error(std::string(e.what()) + " (the NMEA log)");
    }
  }
  CommentFilter comments;
  comments.filter(raw, bytes_);
  counters_.comment_lines = comments.commentLines();
  index();
}

NmeaLogPlayer::~NmeaLogPlayer() { alive_.reset(); }

void NmeaLogPlayer::index() {
  std::optional<std::int64_t> group_tod;     // time of the group being built
  std::optional<std::int64_t> previous_tod;  // of the last group that had one
  const std::size_t n = bytes_.size();
  std::size_t line_begin = 0;
  while (line_begin < n) {
    // A line ends at LF, or at a CR not followed by LF (CR-only logs).
    std::size_t end = line_begin;
    while (end < n && bytes_[end] != '\n' && !(bytes_[end] == '\r' && (end + 1 == n || bytes_[end + 1] != '\n'))) {
      ++end;
    }
    end = std::min(end + 1, n);
    const std::string_view line(reinterpret_cast<const char*>(bytes_.data() + line_begin), end - line_begin);
    const std::optional<std::int64_t> tod = epochTimeOf(line);
    if (groups_.empty() || (tod && tod != group_tod)) {
      Group g;
      g.begin = line_begin;
      if (tod && previous_tod) {
        std::int64_t step = *tod - *previous_tod;
        if (step < -kDayNs / 2) step += kDayNs;  // midnight
        if (step < 0) {
          ++counters_.backward_steps;
          step = 0;
        }
        const auto max_gap = static_cast<std::int64_t>(config_.max_gap_s * 1e9);
        if (step > max_gap) {
          ++counters_.long_gaps;
          step = max_gap;
        }
        g.delay = std::chrono::nanoseconds(static_cast<std::int64_t>(static_cast<double>(step) / config_.speed));
      }
      groups_.push_back(g);
      group_tod = tod;
      if (tod) previous_tod = tod;
    }
    groups_.back().end = end;
    line_begin = end;
  }
  counters_.groups_total = groups_.size();
}

void NmeaLogPlayer::start() {
  if (running_) return;
  running_ = true;
  counters_.finished = false;
  next_group_ = 0;
  next_due_ = std::chrono::steady_clock::now();
  scheduleNext();
}

void NmeaLogPlayer::stop() {
  if (!running_) return;
  running_ = false;
  timer_.cancel();
  assembler_.completeEpoch();
}

NmeaLogPlayerCounters NmeaLogPlayer::counters() const {
  NmeaLogPlayerCounters c = counters_;
  c.parser = assembler_.parserCounters();
  c.epochs = assembler_.epochCounters();
  return c;
}

void NmeaLogPlayer::scheduleNext() {
  if (next_group_ >= groups_.size()) {
    assembler_.endOfStream();
    running_ = false;
    counters_.finished = true;
    if (on_finished_) on_finished_();
    return;
  }
  // Absolute deadlines: the time spent feeding a group does not push the later ones back.
  next_due_ += groups_[next_group_].delay;
  timer_.expires_at(next_due_);
  timer_.async_wait([this, alive = std::weak_ptr<int>(alive_)](const boost::system::error_code& ec) {
    if (alive.expired() || ec || !running_) return;
    playGroup();
  });
}

void NmeaLogPlayer::playGroup() {
  const Group& g = groups_[next_group_++];
  assembler_.feed(std::span<const std::uint8_t>(bytes_.data() + g.begin, g.end - g.begin), live::monotonicNs());
  assembler_.completeEpoch();
  ++counters_.groups_played;
  scheduleNext();
}

}  // namespace headingd::nmea
