#include "headingd/daemon/lcm_publisher.hpp"

#include <stdexcept>

namespace headingd::daemon {

LcmPublisher::LcmPublisher(const std::string& url) : lcm_(url) {
  if (!lcm_.good()) {
    throw std::runtime_error("LCM: cannot set up '" + url +
                             "' (for udpm: is there a multicast route, e.g. `ip route add 224.0.0.0/4 dev lo`?)");
  }
  buffer_.resize(64 * 1024);  // larger than any message we send; grown if ever needed
}

}  // namespace headingd::daemon
