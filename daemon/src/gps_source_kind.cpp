#include "headingd/daemon/gps_source_kind.hpp"

#include "headingd/core/toml_table_reader.hpp"
#include "headingd/daemon/gpsd_gps_source.hpp"
#include "headingd/daemon/serial_gps_source.hpp"

namespace headingd::daemon {

std::unique_ptr<SourceConfig> parseGpsSource(const SourceTable& table) {
  core::TomlTableReader r(&table.table, table.source, "gps");
  if (r.choice("source", "serial", {"serial", "gpsd"}) == "gpsd") return parseGpsdGpsSource(table);
  return parseSerialGpsSource(table);
}

std::unique_ptr<Source> createGpsSource(const SourceConfig& config, SourceContext& context) {
  if (dynamic_cast<const GpsdGpsSourceConfig*>(&config) != nullptr) return createGpsdGpsSource(config, context);
  return createSerialGpsSource(config, context);
}

}  // namespace headingd::daemon
