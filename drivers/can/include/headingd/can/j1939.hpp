#pragma once
// SAE J1939 view of a 29-bit identifier: priority (3 bits), data page bits, PDU format (PF),
// PDU specific (PS) and source address (SA). A parameter group number (PGN) is
// EDP/DP/PF/PS when PF >= 240 (PDU2, PS is a group extension) and EDP/DP/PF/00 when PF < 240
// (PDU1, PS is the destination address and not part of the PGN).
#include <cstdint>

namespace headingd::can {

inline constexpr std::uint32_t kJ1939Pdu2Threshold = 240;

constexpr std::uint8_t j1939Priority(std::uint32_t id29) { return static_cast<std::uint8_t>((id29 >> 26) & 0x7u); }
constexpr std::uint8_t j1939PduFormat(std::uint32_t id29) { return static_cast<std::uint8_t>((id29 >> 16) & 0xFFu); }
constexpr std::uint8_t j1939PduSpecific(std::uint32_t id29) { return static_cast<std::uint8_t>((id29 >> 8) & 0xFFu); }
constexpr std::uint8_t j1939SourceAddress(std::uint32_t id29) { return static_cast<std::uint8_t>(id29 & 0xFFu); }
constexpr bool j1939IsPdu2(std::uint32_t id29) { return j1939PduFormat(id29) >= kJ1939Pdu2Threshold; }

// The 18-bit PGN of a 29-bit identifier.
constexpr std::uint32_t j1939Pgn(std::uint32_t id29) {
  const std::uint32_t edp_dp_pf = (id29 >> 16) & 0x3FFu;
  return j1939IsPdu2(id29) ? (edp_dp_pf << 8) | j1939PduSpecific(id29) : edp_dp_pf << 8;
}

// Bits of the identifier that carry the PGN: a frame matches a PGN when
// (id & mask) == (reference_id & mask). Priority and source address are outside the mask;
// for PDU1 the destination address is too.
constexpr std::uint32_t j1939PgnMask(std::uint32_t id29) { return j1939IsPdu2(id29) ? 0x03FFFF00u : 0x03FF0000u; }

// A 29-bit identifier from its parts (for encoders and tests).
constexpr std::uint32_t j1939Id(std::uint8_t priority, std::uint32_t pgn, std::uint8_t source_address,
                                std::uint8_t destination_address = 0xFF) {
  const std::uint32_t pf = (pgn >> 8) & 0xFFu;
  const std::uint32_t ps = pf >= kJ1939Pdu2Threshold ? (pgn & 0xFFu) : destination_address;
  return (static_cast<std::uint32_t>(priority & 0x7u) << 26) | (((pgn >> 16) & 0x3u) << 24) | (pf << 16) | (ps << 8) |
         source_address;
}

}  // namespace headingd::can
