// The words for a plugin's nimbus_status_t in the host's messages (refusals, failed hooks).
#pragma once

#include <nimbus/version.h>

#include <string>

namespace nimbus {

// "internal error (status -6)"; a code the SDK does not define reads "status <n>".
inline std::string status_text(nimbus_status_t s) {
  const char *words = nullptr;
  switch (s) {
    case NIMBUS_E_INVALID_ARG:
      words = "invalid argument";
      break;
    case NIMBUS_E_UNSUPPORTED:
      words = "unsupported";
      break;
    case NIMBUS_E_NO_MEMORY:
      words = "out of memory";
      break;
    case NIMBUS_E_VERSION:
      words = "version mismatch";
      break;
    case NIMBUS_E_CANCELLED:
      words = "cancelled";
      break;
    case NIMBUS_E_INTERNAL:
      words = "internal error";
      break;
    default:
      break;
  }
  const std::string code = "status " + std::to_string(s);
  return words ? std::string(words) + " (" + code + ")" : code;
}

}  // namespace nimbus
