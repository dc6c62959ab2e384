#include "headingd/nmea/serial_epoch_assembler.hpp"

#include <utility>

namespace headingd::nmea {

EpochAssembler::EpochAssembler(ParserConfig config, FixHandler on_fix, LineHandler on_line)
    : parser_(config), line_framer_(config.framer), on_fix_(std::move(on_fix)), on_line_(std::move(on_line)) {
  updates_.reserve(4);
}

void EpochAssembler::feed(std::span<const std::uint8_t> bytes, std::int64_t receive_ns) {
  // Byte by byte, so that lines and fixes come out in the order they were completed.
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (on_line_) {
      if (const auto line = line_framer_.push(bytes[i])) on_line_(*line, receive_ns);
    }
    parser_.feed(bytes.subspan(i, 1), updates_);
    for (const FixUpdate& u : updates_) onUpdate(u, receive_ns);
    updates_.clear();
  }
}

void EpochAssembler::onUpdate(const FixUpdate& update, std::int64_t receive_ns) {
  // Sentences before the first time of day (a VTG at the start) belong to no epoch.
  if (!update.fix.time_of_day_ns) return;
  if (current_ && current_->time_of_day_ns != update.fix.time_of_day_ns) {
    if (!delivered_) deliver();
    current_.reset();
  }
  if (current_ && delivered_) {
    ++counters_.late_sentences;
    current_ = update.fix;  // kept only to recognise the rest of this epoch
    return;
  }
  current_ = update.fix;
  current_receive_ns_ = receive_ns;
  delivered_ = false;
}

void EpochAssembler::completeEpoch() {
  if (epochPending()) deliver();
}

void EpochAssembler::endOfStream() {
  parser_.finish();
  line_framer_.finish();
  completeEpoch();
}

void EpochAssembler::deliver() {
  delivered_ = true;
  ++counters_.epochs;
  if (on_fix_) on_fix_(*current_, current_receive_ns_);
}

}  // namespace headingd::nmea
