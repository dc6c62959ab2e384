#pragma once
// A live driver's state and last error, set together when an attempt fails or the link is
// lost. The message is logged only when it or the state changes, so a device or peer that
// stays away is reported once, not on every retry.
#include <string>
#include <string_view>

namespace headingd::live {

// A warning "<log_prefix>: <message>".
void warnLinkError(std::string_view log_prefix, const std::string& message);

template <class State>
void setLinkError(State& state, std::string& last_error, State next, const std::string& message,
                  std::string_view log_prefix) {
  if (message != last_error || next != state) warnLinkError(log_prefix, message);
  state = next;
  last_error = message;
}

}  // namespace headingd::live
