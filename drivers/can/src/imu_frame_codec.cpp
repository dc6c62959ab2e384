#include "headingd/can/imu_frame_codec.hpp"

#include <cmath>

#include "headingd/can/j1939.hpp"
#include "headingd/can/signal_codec.hpp"
#include "headingd/can/units.hpp"

namespace headingd::can {
namespace {

std::string refWhere(const CanConfig& c, const SignalRef& ref, const char* key) {
  return c.source + ":" + std::to_string(ref.line) + ": [can] " + key + ": '" + ref.text() + "'";
}

const DbcSignal& resolve(const CanConfig& c, const DbcDatabase& dbc, const SignalRef& ref, const char* key,
                         const DbcMessage** message_out) {
  const DbcMessage* m = dbc.findMessage(ref.message);
  if (m == nullptr) {
    throw ConfigError(refWhere(c, ref, key) + ": expected a message (BO_) of " + dbc.source + ", there is no '" +
                      ref.message + "'");
  }
  const DbcSignal* s = m->findSignal(ref.signal);
  if (s == nullptr) {
    throw ConfigError(refWhere(c, ref, key) + ": expected a signal (SG_) of message " + m->name + " in " + dbc.source +
                      ", there is no '" + ref.signal + "'");
  }
  if (s->multiplexed) {
    throw ConfigError(refWhere(c, ref, key) + ": expected a plain signal, " + dbc.source + ":" +
                      std::to_string(s->line) + " defines it as multiplexed (not supported)");
  }
  *message_out = m;
  return *s;
}

}  // namespace

ImuFrameCodec::ImuFrameCodec(const CanConfig& c, const DbcDatabase& dbc) {
  auto bindingFor = [&](const DbcMessage& m, const SignalRef& ref, const char* key) -> MessageBinding& {
    for (auto& b : messages_) {
      if (b.name == m.name) return b;
    }
    MessageBinding b;
    b.name = m.name;
    b.id = m.id;
    b.extended = m.extended;
    b.dlc = m.dlc;
    b.match_mask = m.extended ? kExtendedIdMask : kStandardIdMask;
    if (c.j1939) {
      if (!m.extended) {
        throw ConfigError(refWhere(c, ref, key) + ": j1939 = true expects 29-bit ids, message " + m.name + " (" +
                          dbc.source + ":" + std::to_string(m.line) + ") has a standard id");
      }
      b.match_mask = j1939PgnMask(m.id);
    }
    messages_.push_back(std::move(b));
    return messages_.back();
  };

  struct Group {
    const char* key;
    const std::array<SignalRef, 3>* refs;
    Quantity quantity;
    std::optional<double> factor;
    int first_axis;
  };
  std::vector<Group> groups = {{"gyro", &c.gyro, Quantity::angular_rate, c.gyro_unit_factor, 0},
                               {"accel", &c.accel, Quantity::acceleration, c.accel_unit_factor, 3}};
  if (c.mag) groups.push_back({"mag", &*c.mag, Quantity::magnetic_field, c.mag_unit_factor, 6});
  has_mag_ = c.mag.has_value();

  for (const auto& g : groups) {
    for (int i = 0; i < 3; ++i) {
      const SignalRef& ref = (*g.refs)[static_cast<std::size_t>(i)];
      const DbcMessage* m = nullptr;
      const DbcSignal& s = resolve(c, dbc, ref, g.key, &m);
      double factor = 0.0;
      if (g.factor) {
        factor = *g.factor;
      } else if (const auto f = unitFactorToSi(g.quantity, s.unit)) {
        factor = *f;
      } else {
        throw ConfigError(refWhere(c, ref, g.key) + ": unit \"" + s.unit + "\" (" + dbc.source + ":" +
                          std::to_string(s.line) + ") is not a known " + quantityName(g.quantity) +
                          " unit; expected one of " + acceptedUnits(g.quantity) + ", or set " + g.key +
                          "_unit_factor (" + siUnitName(g.quantity) + " per DBC unit)");
      }
      MessageBinding& b = bindingFor(*m, ref, g.key);
      const int axis = g.first_axis + i;
      for (const auto& other : messages_) {
        if ((other.axis_mask & (1u << axis)) != 0) {
          throw ConfigError(refWhere(c, ref, g.key) + ": axis bound twice");
        }
      }
      b.axes.push_back({axis, s, ref.negate ? -factor : factor});
      b.axis_mask = static_cast<std::uint16_t>(b.axis_mask | (1u << axis));
    }
  }
  for (const auto& ref : c.sequence) {
    const DbcMessage* m = nullptr;
    const DbcSignal& s = resolve(c, dbc, ref, "sequence", &m);
    if (ref.negate) throw ConfigError(refWhere(c, ref, "sequence") + ": expected no '-' on a counter");
    if (s.is_signed || s.length > 32) {
      throw ConfigError(refWhere(c, ref, "sequence") + ": expected an unsigned counter of at most 32 bits");
    }
    if (sequence_bits_ != 0 && s.length != sequence_bits_) {
      throw ConfigError(refWhere(c, ref, "sequence") + ": expected the same width as the other counters (" +
                        std::to_string(sequence_bits_) + " bits)");
    }
    sequence_bits_ = s.length;
    MessageBinding* b = nullptr;
    for (auto& candidate : messages_) {
      if (candidate.name == m->name) b = &candidate;
    }
    if (b == nullptr) {
      throw ConfigError(refWhere(c, ref, "sequence") + ": expected a counter in a message that carries mapped axes");
    }
    if (b->has_sequence) throw ConfigError(refWhere(c, ref, "sequence") + ": a second counter in " + m->name);
    b->has_sequence = true;
    b->sequence = s;
  }
  // Two bindings that the same frame could match would make decoding ambiguous.
  for (std::size_t i = 0; i < messages_.size(); ++i) {
    for (std::size_t j = i + 1; j < messages_.size(); ++j) {
      const auto& a = messages_[i];
      const auto& b = messages_[j];
      const std::uint32_t mask = a.match_mask & b.match_mask;
      if (a.extended == b.extended && (a.id & mask) == (b.id & mask)) {
        throw ConfigError(c.where("j1939") + ": messages " + a.name + " and " + b.name +
                          " cannot be told apart (same id" + (c.j1939 ? " / PGN" : "") + ")");
      }
    }
  }
}

DecodeStatus ImuFrameCodec::decode(const CanFrame& frame, DecodedFrame& out) const {
  if (frame.error_frame) return DecodeStatus::error_frame;
  const MessageBinding* binding = nullptr;
  for (const auto& b : messages_) {
    if (b.extended == frame.extended && (frame.id & b.match_mask) == (b.id & b.match_mask)) {
      binding = &b;
      break;
    }
  }
  if (binding == nullptr) return DecodeStatus::unknown_id;
  if (frame.remote) return DecodeStatus::remote_frame;
  if (frame.len != binding->dlc) return DecodeStatus::wrong_length;
  out.axis_mask = binding->axis_mask;
  out.message = binding;
  out.full_scale_mask = 0;
  for (const auto& a : binding->axes) {
    out.values[static_cast<std::size_t>(a.axis)] = decodeSignal(a.signal, frame.data) * a.scale_to_si;
    if (atFullScale(a.signal, frame.data)) out.full_scale_mask |= static_cast<std::uint16_t>(1u << a.axis);
  }
  out.has_sequence = binding->has_sequence;
  out.sequence = binding->has_sequence ? extractRawBits(binding->sequence, frame.data) : 0;
  return DecodeStatus::decoded;
}

int ImuFrameCodec::encode(const core::ImuSample& sample, std::uint64_t sequence, bool include_mag,
                          std::vector<CanFrame>& frames) const {
  int clamped = 0;
  for (const auto& b : messages_) {
    if (!include_mag && (b.axis_mask & ~kMagAxes) == 0) continue;
    CanFrame f;
    f.id = b.id;
    f.extended = b.extended;
    f.len = static_cast<std::uint8_t>(b.dlc);
    for (const auto& a : b.axes) {
      double si = 0.0;
      if (a.axis < 3)
        si = sample.gyro_rad_s[a.axis];
      else if (a.axis < 6)
        si = sample.accel_m_s2[a.axis - 3];
      else
        si = sample.mag_uT[a.axis - 6];
      if (encodeSignal(a.signal, si / a.scale_to_si, f.data) != EncodeResult::exact_or_rounded) ++clamped;
    }
    if (b.has_sequence) insertRawBits(b.sequence, sequence, f.data);
    frames.push_back(f);
  }
  return clamped;
}

std::vector<IdFilter> ImuFrameCodec::kernelFilters() const {
  std::vector<IdFilter> filters;
  for (const auto& b : messages_) filters.push_back({b.id & b.match_mask, b.match_mask, b.extended});
  return filters;
}

CanSetup loadCanSetup(const std::string& config_path) {
  CanSetup setup;
  setup.config = loadCanConfigFile(config_path);
  try {
    setup.dbc = loadDbcFile(setup.config.dbc_path);
  } catch (const DbcError& e) {
    throw ConfigError(setup.config.where("dbc") + ": expected a readable DBC file: " + e.what());
  }
  return setup;
}

}  // namespace headingd::can
