#pragma once
// One message flattened into (column name, cell text) pairs, in declaration order:
//   scalar            name
//   fixed array       name_0, name_1, ...; 2-D name_0_0, name_0_1, ...
//   nested struct     name.field
//   variable array of structs with a `name` field (sources, rings, counters):
//                     name.<element's name>.field, the element's `name` itself not repeated;
//                     counter_t elements (name, value) give one column name.<counter's name>
//   other variable arrays   name_0, name_1, ...
// An element whose name is empty or already used earlier in the same array is keyed by its
// index instead, with its name as a field: name.#3.name, name.#3.value (so no value is lost
// and no column is written twice).
// Cells: integers in decimal, doubles in the shortest text that reads back to the same
// double (std::to_chars; nan, inf, -inf), booleans 0/1, strings as they are (quoted on
// output).
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "headingd/counter_t.hpp"

namespace headingd::lcm_export {

// Reused from message to message: strings keep their capacity, so a row costs no allocation
// once the first has been built.
struct FlatRow {
  std::vector<std::string> keys;
  std::vector<std::string> cells;
  std::size_t size = 0;

  void clear() { size = 0; }
  std::string& addKey(std::string_view key) {
    if (size == keys.size()) {
      keys.emplace_back();
      cells.emplace_back();
    }
    keys[size].assign(key);
    return cells[size++];
  }
  // The same column names, in the same order, as `other` (the common case from one message
  // to the next on a channel).
  bool sameKeysAs(const std::vector<std::string>& other) const {
    if (other.size() != size) return false;
    for (std::size_t i = 0; i < size; ++i) {
      if (keys[i] != other[i]) return false;
    }
    return true;
  }
};

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};

class ColumnWriter {
 public:
  explicit ColumnWriter(FlatRow& row) : row_(row) {}

  template <class Value>
  void field(std::string_view name, const Value& value) {
    // Inside a keyed element the element's name is the column's key already.
    if (name == "name" && key_.size() == skip_name_at_) return;
    const std::size_t mark = key_.size();
    key_.append(name);
    write(value);
    key_.resize(mark);
  }

 private:
  template <class Value>
  void write(const Value& value);

  void appendIndex(std::size_t i) {
    char digits[24];
    const auto end = std::to_chars(digits, digits + sizeof digits, i).ptr;
    key_.append(digits, end);
  }

  template <class Element>
  void writeKeyed(const std::vector<Element>& elements);

  FlatRow& row_;
  std::string key_;
  std::size_t skip_name_at_ = std::string::npos;
};

// describeFields(message, writer): calls writer.field(name, member) for every field of the
// message in declaration order (message_fields.hpp).
template <class Value>
void ColumnWriter::write(const Value& value) {
  if constexpr (std::is_array_v<Value>) {
    for (std::size_t i = 0; i < std::extent_v<Value>; ++i) {
      const std::size_t mark = key_.size();
      key_.push_back('_');
      appendIndex(i);
      write(value[i]);
      key_.resize(mark);
    }
  } else if constexpr (IsVector<Value>::value) {
    using Element = typename Value::value_type;
    if constexpr (requires(const Element& e) { e.name; }) {
      writeKeyed(value);
    } else {
      for (std::size_t i = 0; i < value.size(); ++i) {
        const std::size_t mark = key_.size();
        key_.push_back('_');
        appendIndex(i);
        write(value[i]);
        key_.resize(mark);
      }
    }
  } else if constexpr (std::is_same_v<Value, bool>) {
    row_.addKey(key_).assign(value ? "1" : "0");
  } else if constexpr (std::is_arithmetic_v<Value>) {
    char text[32];
    // Integers exact; doubles shortest round-trip (int8_t as a number, not a character).
    const auto end = std::is_integral_v<Value>
                         ? std::to_chars(text, text + sizeof text, static_cast<std::int64_t>(value)).ptr
                         : std::to_chars(text, text + sizeof text, value).ptr;
    row_.addKey(key_).assign(text, end);
  } else if constexpr (std::is_same_v<Value, std::string>) {
    row_.addKey(key_).assign(value);
  } else {
    const std::size_t mark = key_.size();
    key_.push_back('.');
    describeFields(value, *this);
    key_.resize(mark);
  }
}

template <class Element>
void ColumnWriter::writeKeyed(const std::vector<Element>& elements) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const std::string& name = elements[i].name;
    bool usable = !name.empty();
    for (std::size_t j = 0; usable && j < i; ++j) usable = elements[j].name != name;
    const std::size_t mark = key_.size();
    key_.push_back('.');
    if (usable) {
      key_.append(name);
    } else {
      key_.push_back('#');
      appendIndex(i);
    }
    if (usable && std::is_same_v<Element, headingd::counter_t>) {
      if constexpr (std::is_same_v<Element, headingd::counter_t>) write(elements[i].value);
    } else {
      // An element keyed by its index keeps its name as a column of its own.
      const std::size_t outer_skip = skip_name_at_;
      key_.push_back('.');
      skip_name_at_ = usable ? key_.size() : std::string::npos;
      describeFields(elements[i], *this);
      skip_name_at_ = outer_skip;
    }
    key_.resize(mark);
  }
}

}  // namespace headingd::lcm_export
