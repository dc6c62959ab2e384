#include "headingd/lcm_export/log_export.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "headingd/lcm_export/column_layout.hpp"
#include "headingd/lcm_export/csv_table.hpp"
#include "headingd/lcm_export/message_types.hpp"

namespace headingd::lcm_export {
namespace {

constexpr std::size_t kFirstFieldColumn = 2;  // after log_utime, event
constexpr std::size_t kFingerprintsShown = 4;

struct Table {
  std::string channel;
  const MessageType* type = nullptr;
  ColumnLayout layout;
  std::uint64_t rows = 0;
  std::unique_ptr<CsvTable> csv;
};

// The tables of a log, found by channel and type; ordered by first appearance.
class Tables {
 public:
  Table& get(const std::string& channel, const MessageType* type) {
    auto& by_type = index_[channel];
    for (const auto& [t, i] : by_type) {
      if (t == type) return *tables_[i];
    }
    by_type.emplace_back(type, tables_.size());
    tables_.push_back(std::make_unique<Table>());
    tables_.back()->channel = channel;
    tables_.back()->type = type;
    return *tables_.back();
  }
  std::size_t typesOn(const std::string& channel) const {
    const auto found = index_.find(channel);
    return found == index_.end() ? 0 : found->second.size();
  }
  std::vector<std::unique_ptr<Table>>& all() { return tables_; }

 private:
  std::unordered_map<std::string, std::vector<std::pair<const MessageType*, std::size_t>>> index_;
  std::vector<std::unique_ptr<Table>> tables_;
};

std::string describeEvent(const LcmLogEvent& event) {
  return "event " + std::to_string(event.event_number) + " on channel " + event.channel;
}

void countUnknown(UnknownMessages& u, const LcmLogEvent& event) {
  u.channel = event.channel;
  ++u.messages;
  if (event.data.size() < 8) return;
  const std::int64_t fingerprint = fingerprintOf(event.data);
  if (u.fingerprints.size() < kFingerprintsShown &&
      std::find(u.fingerprints.begin(), u.fingerprints.end(), fingerprint) == u.fingerprints.end()) {
    u.fingerprints.push_back(fingerprint);
  }
}

}  // namespace

std::string tableFileName(const std::string& channel, const std::string& type, bool several_types) {
  std::string name;
  for (const char c : channel) {
    const bool plain =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    name.push_back(plain ? c : '_');
  }
  if (!name.empty() && name.front() == '.') name.front() = '_';
  if (several_types) name += "." + type;
  return name + ".csv";
}

ExportResult exportLcmLog(const ExportOptions& options) {
  ExportResult result;
  const std::set<std::string> wanted(options.channels.begin(), options.channels.end());
  const auto selected = [&](const std::string& channel) { return wanted.empty() || wanted.count(channel) != 0; };

  // --- Pass 1: tables, columns, unknown types, the first bad event ---
  Tables tables;
  std::map<std::string, UnknownMessages> unknown;
  std::set<std::string> seen;
  FlatRow row;
  std::uint64_t good_events = 0;
  {
    LcmLogReader reader(options.log_path);
    LcmLogEvent event;
    try {
      while (reader.next(event)) {
        seen.insert(event.channel);
        if (selected(event.channel)) {
          const MessageType* type = event.data.size() >= 8 ? findMessageType(fingerprintOf(event.data)) : nullptr;
          if (type == nullptr) {
            countUnknown(unknown[event.channel], event);
          } else {
            row.clear();
            std::string error;
            if (!type->flatten(event.data, row, error)) {
              throw LcmLogError(event.offset, describeEvent(event) + ": " + std::string(type->name) + " message of " +
                                                  std::to_string(event.data.size()) + " bytes " + error);
            }
            tables.get(event.channel, type).layout.merge(row);
          }
        }
        ++good_events;
      }
    } catch (const LcmLogError& e) {
      result.log_error = e;
    }
  }
  result.events_read = good_events;
  result.log_channels.assign(seen.begin(), seen.end());
  for (const std::string& channel : wanted) {
    if (seen.count(channel) == 0) result.missing_channels.push_back(channel);
  }
  for (auto& [channel, u] : unknown) result.unknown.push_back(std::move(u));

  // --- Pass 2: every good event into its table ---
  std::filesystem::create_directories(options.out_dir);
  std::set<std::string> file_names;
  std::vector<std::filesystem::path> table_paths;
  for (auto& table : tables.all()) {
    const std::string type(table->type->name);
    std::string name = tableFileName(table->channel, type, tables.typesOn(table->channel) > 1);
    // Two channels that differ only in replaced bytes ("a/b", "a_b") get "-2", "-3", ...
    const std::string stem = name.substr(0, name.size() - 4);
    for (int n = 2; !file_names.insert(name).second; ++n) name = stem + "-" + std::to_string(n) + ".csv";
    table_paths.push_back(options.out_dir / name);
    // Renaming a table into place over the log would destroy it (also through a link).
    std::error_code not_there;
    if (std::filesystem::equivalent(options.log_path, table_paths.back(), not_there)) {
      throw TableOverLogError("the table " + table_paths.back().string() + " would be the log " +
                              options.log_path.string() +
                              " itself: refusing to overwrite the log (choose another --out-dir)");
    }
  }
  std::size_t table_index = 0;
  for (auto& table : tables.all()) {
    table->csv = std::make_unique<CsvTable>(table_paths[table_index++]);
    std::vector<std::string> header{"log_utime", "event"};
    header.insert(header.end(), table->layout.columns().begin(), table->layout.columns().end());
    table->csv->writeRow(header);
  }
  {
    LcmLogReader reader(options.log_path);
    LcmLogEvent event;
    std::vector<std::string> cells;
    for (std::uint64_t i = 0; i < good_events; ++i) {
      if (!reader.next(event)) throw std::runtime_error(options.log_path.string() + ": shorter on the second pass");
      if (!selected(event.channel) || event.data.size() < 8) continue;
      const MessageType* type = findMessageType(fingerprintOf(event.data));
      if (type == nullptr) continue;
      row.clear();
      std::string error;
      if (!type->flatten(event.data, row, error)) {
        throw std::runtime_error(options.log_path.string() + ": changed between the passes at " + describeEvent(event));
      }
      Table& table = tables.get(event.channel, type);
      if (table.csv == nullptr) {
        throw std::runtime_error(options.log_path.string() + ": changed between the passes at " + describeEvent(event));
      }
      cells.resize(kFirstFieldColumn + table.layout.columns().size());
      table.layout.place(row, cells, kFirstFieldColumn);
      cells[0] = std::to_string(event.utime);
      cells[1] = std::to_string(event.event_number);
      table.csv->writeRow(cells);
      ++table.rows;
    }
  }
  for (auto& table : tables.all()) {
    table->csv->finish();
    result.tables.push_back(
        ExportedTable{table->channel, std::string(table->type->name), table->csv->path(), table->rows});
  }
  return result;
}

}  // namespace headingd::lcm_export
