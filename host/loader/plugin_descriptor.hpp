// Reading plugin descriptors safely: they come from foreign code, so every field is validated before the
// host relies on it, and what the host keeps is a copy (descriptors die with the library's deinit).
#pragma once

#include <nimbus/host.h>
#include <nimbus/plugin.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loader/plugin_options.hpp"

namespace nimbus {

// "integrator", "light-sampler", "guiding"; "unknown kind <n>" otherwise.
std::string kind_name(nimbus_plugin_kind_t kind);
// For listings and errors: "integrators", "light-samplers", "guiding plugins".
std::string kind_plural(nimbus_plugin_kind_t kind);
// With its article: "an integrator", "a light-sampler", "a guiding plugin".
std::string kind_with_article(nimbus_plugin_kind_t kind);
bool is_known_kind(nimbus_plugin_kind_t kind);

// The fields of a nimbus_descriptor_t, owned by the host.
struct DescriptorCopy {
  std::string id, name, vendor;
  nimbus_plugin_kind_t kind = 0;
  nimbus_version_t version{};
  std::vector<std::string> features;
  std::vector<std::string> required_services;
  std::vector<OptionDecl> options;  // declared options (SDK 1.2), validated
};

// Validates descriptor `index` of a library and copies it, or returns why it is malformed. Checks the
// header (struct_size covers 1.0, s_type), id (non-empty printable ASCII, no spaces), name, vendor, kind,
// that the NULL-terminated lists end within a sane bound (a missing terminator must not run away), and
// the declared options (plugin_options.hpp).
struct DescriptorResult {
  std::optional<DescriptorCopy> copy;
  std::string error;  // set when copy is empty
};
DescriptorResult read_descriptor(const nimbus_descriptor_t *desc, uint32_t index);

// A required service "id@rev", e.g. "nimbus.host.film@1".
struct ServiceRef {
  std::string id;
  uint32_t revision = 0;
};
std::optional<ServiceRef> parse_service_ref(std::string_view text);

// The first required service `host` does not provide, as the refusal reason, or nullopt when all are
// provided. A NULL host (or one too old to have get_service) provides nothing.
std::optional<std::string> check_required_services(const DescriptorCopy &desc, const nimbus_host_t *host);

}  // namespace nimbus
