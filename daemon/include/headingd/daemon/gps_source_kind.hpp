#pragma once
// The [gps] table's two sources: source = "serial" (the default, the receiver's port read by
// the daemon) or "gpsd" (gpsd's JSON socket). One row in the registry; these pick the kind.
#include <memory>

#include "headingd/daemon/source_registry.hpp"

namespace headingd::daemon {

std::unique_ptr<SourceConfig> parseGpsSource(const SourceTable& table);
std::unique_ptr<Source> createGpsSource(const SourceConfig& config, SourceContext& context);

}  // namespace headingd::daemon
