#include <cctype>
#include <charconv>
#include <cmath>

#include "headingd/can/can_frame.hpp"
#include "headingd/can/dbc.hpp"
#include "headingd/can/signal_codec.hpp"
#include "headingd/files/input_file.hpp"

namespace headingd::can {
namespace {

// Tools put signals that belong to no message into this pseudo-message (id 0xC0000000).
constexpr std::string_view kIndependentSignalsMessage = "VECTOR__INDEPENDENT_SIG_MSG";
constexpr std::uint32_t kExtendedFlag = 0x80000000u;

// A cursor over one line; every failure throws DbcError naming source:line and what was expected.
class LineCursor {
 public:
  LineCursor(std::string_view line, const std::string& source, int line_number)
      : rest_(line), source_(source), line_number_(line_number) {}

  [[noreturn]] void fail(std::string_view expected) const {
    std::string found = std::string(rest_.substr(0, 24));
    if (found.empty())
      found = "end of line";
    else
      found = "'" + found + "'";
    throw DbcError(source_ + ":" + std::to_string(line_number_) + ": expected " + std::string(expected) + ", found " +
                   found);
  }

  void skipSpace() {
    while (!rest_.empty() && (rest_.front() == ' ' || rest_.front() == '\t' || rest_.front() == '\r')) {
      rest_.remove_prefix(1);
    }
  }
  bool atEnd() {
    skipSpace();
    return rest_.empty();
  }
  bool peek(char c) {
    skipSpace();
    return !rest_.empty() && rest_.front() == c;
  }
  void expect(char c, std::string_view what) {
    skipSpace();
    if (rest_.empty() || rest_.front() != c) fail(what);
    rest_.remove_prefix(1);
  }
  // C identifier (DBC names: letters, digits, underscore; not starting with a digit).
  std::string identifier(std::string_view what) {
    skipSpace();
    std::size_t n = 0;
    while (n < rest_.size() && (std::isalnum(static_cast<unsigned char>(rest_[n])) != 0 || rest_[n] == '_')) ++n;
    if (n == 0 || std::isdigit(static_cast<unsigned char>(rest_.front())) != 0) fail(what);
    std::string id(rest_.substr(0, n));
    rest_.remove_prefix(n);
    return id;
  }
  std::uint64_t unsignedNumber(std::string_view what) {
    skipSpace();
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(rest_.data(), rest_.data() + rest_.size(), v);
    if (ec != std::errc() || end == rest_.data()) fail(what);
    rest_.remove_prefix(static_cast<std::size_t>(end - rest_.data()));
    return v;
  }
  double realNumber(std::string_view what) {
    skipSpace();
    std::string_view s = rest_;
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars rejects a leading '+'
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end == s.data()) fail(what);
    rest_ = std::string_view(end, static_cast<std::size_t>(s.data() + s.size() - end));
    return v;
  }
  std::string quoted(std::string_view what) {
    skipSpace();
    if (rest_.empty() || rest_.front() != '"') fail(what);
    std::string out;
    std::size_t i = 1;
    for (; i < rest_.size() && rest_[i] != '"'; ++i) {
      if (rest_[i] == '\\' && i + 1 < rest_.size()) ++i;
      out.push_back(rest_[i]);
    }
    if (i >= rest_.size()) fail(what);
    rest_.remove_prefix(i + 1);
    return out;
  }
  std::string_view rest() {
    skipSpace();
    return rest_;
  }

 private:
  std::string_view rest_;
  const std::string& source_;
  int line_number_;
};

std::string_view firstToken(std::string_view line) {
  std::size_t b = 0;
  while (b < line.size() && (line[b] == ' ' || line[b] == '\t')) ++b;
  std::size_t e = b;
  while (e < line.size() && line[e] != ' ' && line[e] != '\t' && line[e] != '\r') ++e;
  return line.substr(b, e - b);
}

// True when `line` leaves a double-quoted string open (a multi-line CM_ comment, for example).
bool leavesQuoteOpen(std::string_view line, bool open) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\\' && open) {
      ++i;
    } else if (line[i] == '"') {
      open = !open;
    }
  }
  return open;
}

DbcMessage parseMessage(LineCursor& c) {
  DbcMessage m;
  const std::uint64_t raw_id = c.unsignedNumber("a message id (decimal, bit 31 set for extended ids)");
  if (raw_id > 0xFFFFFFFFull) c.fail("a message id below 2^32");
  m.extended = (raw_id & kExtendedFlag) != 0;
  m.id = static_cast<std::uint32_t>(raw_id & ~static_cast<std::uint64_t>(kExtendedFlag));
  m.name = c.identifier("a message name");
  c.expect(':', "':' after the message name");
  const std::uint64_t dlc = c.unsignedNumber("the message length in bytes");
  if (dlc > 8) c.fail("a length of at most 8 bytes (classic CAN)");
  m.dlc = static_cast<unsigned>(dlc);
  if (!c.atEnd()) m.transmitter = c.identifier("the transmitting node");
  if (!c.atEnd()) c.fail("end of line after the transmitter");
  return m;
}

DbcSignal parseSignal(LineCursor& c) {
  DbcSignal s;
  s.name = c.identifier("a signal name");
  if (!c.peek(':')) {
    // Multiplexer indicator: "M" (the multiplexer) or "m<N>" (a multiplexed signal).
    const std::string mux = c.identifier("':' or a multiplexer indicator (M, m<N>)");
    if (mux != "M" && !(mux.size() > 1 && mux[0] == 'm')) c.fail("':' or a multiplexer indicator (M, m<N>)");
    s.multiplexed = true;
  }
  c.expect(':', "':' after the signal name");
  const std::uint64_t start = c.unsignedNumber("the start bit");
  c.expect('|', "'|' between start bit and length");
  const std::uint64_t length = c.unsignedNumber("the signal length in bits");
  if (start > 63) c.fail("a start bit 0..63 (classic CAN)");
  if (length < 1 || length > 64) c.fail("a signal length of 1..64 bits");
  s.start_bit = static_cast<unsigned>(start);
  s.length = static_cast<unsigned>(length);
  c.expect('@', "'@' before the byte order");
  const std::string_view order = c.rest();
  if (order.empty() || (order.front() != '0' && order.front() != '1')) c.fail("byte order 0 (Motorola) or 1 (Intel)");
  s.byte_order = order.front() == '1' ? ByteOrder::little_endian : ByteOrder::big_endian;
  c.expect(order.front(), "byte order");
  const std::string_view sign = c.rest();
  if (sign.empty() || (sign.front() != '+' && sign.front() != '-')) c.fail("'+' (unsigned) or '-' (signed)");
  s.is_signed = sign.front() == '-';
  c.expect(sign.front(), "sign");
  c.expect('(', "'(' before factor,offset");
  s.factor = c.realNumber("the factor");
  c.expect(',', "',' between factor and offset");
  s.offset = c.realNumber("the offset");
  c.expect(')', "')' after factor,offset");
  // Every decoded value is raw * factor + offset: a nan or inf here rejects every sample.
  if (!std::isfinite(s.factor) || s.factor == 0.0) c.fail("a finite, non-zero factor");
  if (!std::isfinite(s.offset)) c.fail("a finite offset");
  c.expect('[', "'[' before minimum|maximum");
  s.minimum = c.realNumber("the minimum");
  c.expect('|', "'|' between minimum and maximum");
  s.maximum = c.realNumber("the maximum");
  c.expect(']', "']' after minimum|maximum");
  s.unit = c.quoted("the unit in double quotes");
  while (!c.atEnd()) {
    s.receivers.push_back(c.identifier("a receiving node"));
    if (c.peek(',')) c.expect(',', "','");
  }
  return s;
}

void checkSignalFits(const DbcSignal& s, const DbcMessage& m, LineCursor& c) {
  const unsigned bytes = signalBytesNeeded(s);
  if (bytes == 0) c.fail("a signal that fits in 64 bits (start bit and length exceed the payload)");
  if (bytes > m.dlc) {
    c.fail("a signal inside the message's " + std::to_string(m.dlc) + " bytes (it needs " + std::to_string(bytes) +
           ")");
  }
}

}  // namespace

const DbcSignal* DbcMessage::findSignal(std::string_view signal_name) const {
  for (const auto& s : signals) {
    if (s.name == signal_name) return &s;
  }
  return nullptr;
}

const DbcMessage* DbcDatabase::findMessage(std::string_view message_name) const {
  for (const auto& m : messages) {
    if (m.name == message_name) return &m;
  }
  return nullptr;
}

DbcDatabase parseDbc(std::string_view text, const std::string& source) {
  DbcDatabase db;
  db.source = source;
  DbcMessage* current = nullptr;  // the BO_ that SG_ lines attach to
  bool skipping_current = false;  // signals of the pseudo-message are parsed but dropped
  bool in_quote = false;          // inside a multi-line string of a skipped statement
  int line_number = 0;
  while (!text.empty()) {
    const std::size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    ++line_number;
    if (in_quote) {
      in_quote = leavesQuoteOpen(line, true);
      continue;
    }
    const std::string_view keyword = firstToken(line);
    if (keyword.empty()) continue;
    if (keyword.substr(0, 2) == "//") continue;
    LineCursor c(line, source, line_number);
    if (keyword == "BO_") {
      c.identifier("BO_");
      DbcMessage m = parseMessage(c);
      m.line = line_number;
      if (m.name == kIndependentSignalsMessage) {
        current = nullptr;
        skipping_current = true;
        continue;
      }
      skipping_current = false;
      if (!m.extended && m.id > kStandardIdMask) {
        c.fail("a standard id up to 0x7FF (set bit 31, 0x80000000, for a 29-bit id)");
      }
      if (m.extended && m.id > 0x1FFFFFFFu) c.fail("a 29-bit extended id");
      for (const auto& other : db.messages) {
        if (other.name == m.name) c.fail("a message name not used before (line " + std::to_string(other.line) + ")");
        if (other.id == m.id && other.extended == m.extended) {
          c.fail("a message id not used before (line " + std::to_string(other.line) + ")");
        }
      }
      db.messages.push_back(std::move(m));
      current = &db.messages.back();
    } else if (keyword == "SG_") {
      c.identifier("SG_");
      DbcSignal s = parseSignal(c);
      s.line = line_number;
      if (skipping_current) continue;
      if (current == nullptr) c.fail("SG_ lines directly after their BO_ line");
      checkSignalFits(s, *current, c);
      if (current->findSignal(s.name) != nullptr) c.fail("a signal name not used before in " + current->name);
      current->signals.push_back(std::move(s));
    } else {
      // Any other section (VERSION, NS_, BS_, BU_, CM_, BA_DEF_, BA_, VAL_, ...) is skipped,
      // including strings that run over several lines.
      current = nullptr;
      skipping_current = false;
      in_quote = leavesQuoteOpen(line, false);
    }
  }
  if (in_quote) {
    throw DbcError(source + ":" + std::to_string(line_number) + ": expected a closing '\"' before the end of the file");
  }
  return db;
}

DbcDatabase loadDbcFile(const std::string& path) {
  std::string text;
  try {
    text = files::readWholeFile(path, files::kDbcFileLimit);
  } catch (const files::FileError& e) {
    throw DbcError(std::string(e.what()) + " (the DBC file)");
  }
  return parseDbc(text, path);
}

}  // namespace headingd::can
