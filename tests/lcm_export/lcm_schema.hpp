#pragma once
// An independent oracle for the exporter's tables: the message types as declared in
// daemon/lcm/*.lcm (parsed here, not taken from the exporter), and LCM's wire encoding of a
// CSV row written from that declaration (LCM type specification: big-endian integers and
// IEEE doubles, strings as int32 length with the NUL counted, then bytes and NUL; nested
// structs without their fingerprint). A row that encodes to the bytes that were logged
// holds every field, with its value, under the documented column name.
#include <gtest/gtest.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace headingd::lcm_export::test {

struct LcmField {
  std::string type;  // int64_t, double, string, boolean, counter_t, ...
  std::string name;
  std::vector<std::string> dims;  // "4" (fixed) or "num_sources" (the count field)
};

struct LcmStruct {
  std::string name;
  std::vector<LcmField> fields;
};

using LcmSchema = std::map<std::string, LcmStruct>;

inline LcmSchema readLcmSchema(const std::filesystem::path& dir) {
  LcmSchema schema;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".lcm") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    // Comments out, then one declaration per ';'.
    const std::string source = std::regex_replace(text.str(), std::regex(R"(//[^\n]*|/\*[\s\S]*?\*/)"), " ");
    const std::regex struct_re(R"(struct\s+(\w+)\s*\{([^}]*)\})");
    const std::regex field_re(R"(^\s*(\w+)\s+(\w+)\s*((?:\[\s*\w+\s*\])*)\s*$)");
    const std::regex dim_re(R"(\[\s*(\w+)\s*\])");
    for (std::sregex_iterator s(source.begin(), source.end(), struct_re), end; s != end; ++s) {
      LcmStruct st;
      st.name = (*s)[1];
      std::stringstream body((*s)[2].str());
      for (std::string declaration; std::getline(body, declaration, ';');) {
        if (std::regex_search(declaration, std::regex(R"(^\s*const\s)"))) continue;
        std::smatch m;
        if (!std::regex_match(declaration, m, field_re)) {
          if (declaration.find_first_not_of(" \t\r\n") != std::string::npos) {
            throw std::runtime_error(entry.path().string() + ": cannot read declaration: " + declaration);
          }
          continue;
        }
        LcmField f{m[1], m[2], {}};
        const std::string dims = m[3];
        for (std::sregex_iterator d(dims.begin(), dims.end(), dim_re); d != std::sregex_iterator(); ++d) {
          f.dims.push_back((*d)[1]);
        }
        st.fields.push_back(f);
      }
      schema[st.name] = st;
    }
  }
  return schema;
}

// One CSV table: header and rows, cells by column name.
struct CsvTableData {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

// RFC 4180 reader (quoted cells may hold commas, quotes and line breaks).
inline CsvTableData readCsv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string cell;
  bool quoted = false, cell_started = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cell.push_back('"');
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell.push_back(c);
      }
    } else if (c == '"' && !cell_started) {
      quoted = cell_started = true;
    } else if (c == ',') {
      record.push_back(cell);
      cell.clear();
      cell_started = false;
    } else if (c == '\n') {
      record.push_back(cell);
      records.push_back(record);
      record.clear();
      cell.clear();
      cell_started = false;
    } else {
      cell.push_back(c);
      cell_started = true;
    }
  }
  if (quoted || !record.empty() || !cell.empty()) throw std::runtime_error(path.string() + ": last line unfinished");
  CsvTableData table;
  if (records.empty()) return table;
  table.header = records.front();
  for (std::size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() != table.header.size()) {
      throw std::runtime_error(path.string() + ": row " + std::to_string(r) + " has " +
                               std::to_string(records[r].size()) + " cells, the header " +
                               std::to_string(table.header.size()));
    }
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < table.header.size(); ++c) row[table.header[c]] = records[r][c];
    table.rows.push_back(row);
  }
  return table;
}

// Encodes a CSV row as the LCM message it was exported from.
class RowEncoder {
 public:
  RowEncoder(const LcmSchema& schema, const std::vector<std::string>& header,
             const std::map<std::string, std::string>& row)
      : schema_(schema), header_(header), row_(row) {}

  std::vector<std::uint8_t> encode(const std::string& type, std::int64_t fingerprint) {
    bytes_.clear();
    putInt(static_cast<std::uint64_t>(fingerprint), 8);
    encodeStruct(schema_.at(type), "", "");
    return bytes_;
  }

 private:
  const std::string& cell(const std::string& key) const {
    const auto found = row_.find(key);
    if (found == row_.end()) throw std::runtime_error("no column " + key);
    return found->second;
  }
  std::int64_t integer(const std::string& key) const {
    const std::string& text = cell(key);
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size())
      throw std::runtime_error(key + ": not an integer: " + text);
    return value;
  }
  void putInt(std::uint64_t value, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) bytes_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void putString(const std::string& text) {
    putInt(text.size() + 1, 4);
    bytes_.insert(bytes_.end(), text.begin(), text.end());
    bytes_.push_back(0);
  }
  void putScalar(const std::string& type, const std::string& key) {
    if (type == "int8_t" || type == "boolean" || type == "byte") {
      putInt(static_cast<std::uint64_t>(integer(key)), 1);
    } else if (type == "int16_t") {
      putInt(static_cast<std::uint64_t>(integer(key)), 2);
    } else if (type == "int32_t") {
      putInt(static_cast<std::uint64_t>(integer(key)), 4);
    } else if (type == "int64_t") {
      putInt(static_cast<std::uint64_t>(integer(key)), 8);
    } else if (type == "double") {
      const std::string& text = cell(key);
      double value = 0.0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (ec != std::errc() || end != text.data() + text.size())
        throw std::runtime_error(key + ": not a double: " + text);
      std::uint64_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      putInt(bits, 8);
    } else if (type == "string") {
      putString(cell(key));
    } else {
      encodeStruct(schema_.at(type), key + ".", "");
    }
  }
  // `implicit_name`: the element's name, given by its column key instead of a column.
  void encodeStruct(const LcmStruct& st, const std::string& prefix, const std::string& implicit_name) {
    for (const LcmField& f : st.fields) {
      const std::string key = prefix + f.name;
      if (!implicit_name.empty() && f.name == "name") {
        putString(implicit_name);
      } else if (f.dims.empty()) {
        putScalar(f.type, key);
      } else if (std::isdigit(static_cast<unsigned char>(f.dims[0][0]))) {
        encodeFixed(f, key, 0);
      } else {
        encodeKeyed(f, key, integer(prefix + f.dims[0]));
      }
    }
  }
  void encodeFixed(const LcmField& f, const std::string& key, std::size_t dim) {
    if (dim == f.dims.size()) return putScalar(f.type, key);
    for (int i = 0; i < std::stoi(f.dims[dim]); ++i) encodeFixed(f, key + "_" + std::to_string(i), dim + 1);
  }
  // name.<element>.field, or name.<counter> for (name, value) elements; name.#i.field when
  // keyed by index. Elements in column order, those with a cell in this row.
  void encodeKeyed(const LcmField& f, const std::string& key, std::int64_t count) {
    const LcmStruct& element = schema_.at(f.type);
    const bool name_value = element.fields.size() == 2 && element.fields[1].name == "value";
    std::vector<std::string> elements;
    std::map<std::string, bool> present;
    for (const std::string& column : header_) {
      if (column.rfind(key + ".", 0) != 0) continue;
      const std::string rest = column.substr(key.size() + 1);
      const std::string id = rest[0] == '#' ? rest.substr(0, rest.find('.'))
                             : name_value   ? rest
                                            : elementName(element, rest);
      if (present.emplace(id, false).second) elements.push_back(id);
      if (!cell(column).empty()) present[id] = true;
    }
    std::int64_t written = 0;
    for (const std::string& id : elements) {
      if (!present[id]) continue;
      ++written;
      if (id[0] == '#') {
        encodeStruct(element, key + "." + id + ".", "");
      } else if (name_value) {
        putString(id);
        putScalar(element.fields[1].type, key + "." + id);
      } else {
        encodeStruct(element, key + "." + id + ".", id);
      }
    }
    if (written != count)
      throw std::runtime_error(key + ": " + std::to_string(written) + " elements, count " + std::to_string(count));
  }

  // The element's name in `rest` ("candump_log.imu.capacity": names may hold dots): what
  // comes before the first ".field" that starts with one of the element's fields.
  static std::string elementName(const LcmStruct& element, const std::string& rest) {
    for (std::size_t dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.', dot + 1)) {
      const std::string tail = rest.substr(dot + 1);
      for (const LcmField& f : element.fields) {
        if (tail == f.name || tail.rfind(f.name + ".", 0) == 0 || tail.rfind(f.name + "_", 0) == 0) {
          return rest.substr(0, dot);
        }
      }
    }
    throw std::runtime_error("no field of " + element.name + " in column part " + rest);
  }

  const LcmSchema& schema_;
  const std::vector<std::string>& header_;
  const std::map<std::string, std::string>& row_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace headingd::lcm_export::test
