#include "headingd/live/link_error.hpp"

#include <spdlog/spdlog.h>

namespace headingd::live {

void warnLinkError(std::string_view log_prefix, const std::string& message) {
  spdlog::warn("{}: {}", log_prefix, message);
}

}  // namespace headingd::live
