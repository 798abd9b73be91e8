#include "loader/plugin_descriptor.hpp"

#include <charconv>
#include <cstddef>

#include "core/one_line.hpp"

namespace nimbus {
namespace {

// Size of the descriptor at SDK 1.0: later minors only append, so anything smaller is broken.
constexpr uint32_t kDescriptorSize10 =
    offsetof(nimbus_descriptor_t, required_services) + sizeof(const char *const *);

// A NULL-terminated list longer than this is taken as a missing terminator rather than read on.
constexpr size_t kMaxListEntries = 256;

bool is_valid_id(std::string_view id) {
  if (id.empty()) return false;
  for (char c : id) {
    // Printable ASCII without spaces: ids appear in scene files, command lines and log lines.
    if (c <= 0x20 || c >= 0x7f) return false;
  }
  return true;
}

std::optional<std::vector<std::string>> copy_list(const char *const *list) {
  std::vector<std::string> out;
  if (list == nullptr) return out;
  for (size_t i = 0; list[i] != nullptr; ++i) {
    if (i == kMaxListEntries) return std::nullopt;
    out.emplace_back(list[i]);
  }
  return out;
}

DescriptorResult fail(std::string why) { return {std::nullopt, std::move(why)}; }

}  // namespace

bool is_known_kind(nimbus_plugin_kind_t kind) {
  return kind == NIMBUS_KIND_INTEGRATOR || kind == NIMBUS_KIND_LIGHT_SAMPLER || kind == NIMBUS_KIND_GUIDING;
}

std::string kind_name(nimbus_plugin_kind_t kind) {
  switch (kind) {
    case NIMBUS_KIND_INTEGRATOR:
      return "integrator";
    case NIMBUS_KIND_LIGHT_SAMPLER:
      return "light-sampler";
    case NIMBUS_KIND_GUIDING:
      return "guiding";
    default:
      return "unknown kind " + std::to_string(kind);
  }
}

std::string kind_plural(nimbus_plugin_kind_t kind) {
  if (kind == NIMBUS_KIND_GUIDING) return "guiding plugins";
  if (!is_known_kind(kind)) return "plugins of " + kind_name(kind);
  return kind_name(kind) + "s";
}

std::string kind_with_article(nimbus_plugin_kind_t kind) {
  if (kind == NIMBUS_KIND_INTEGRATOR) return "an integrator";
  if (kind == NIMBUS_KIND_GUIDING) return "a guiding plugin";
  if (!is_known_kind(kind)) return "of " + kind_name(kind);
  return "a " + kind_name(kind);
}

DescriptorResult read_descriptor(const nimbus_descriptor_t *desc, uint32_t index) {
  const std::string which = "descriptor " + std::to_string(index);
  if (desc == nullptr) return fail(which + " is NULL");
  if (desc->header.struct_size < kDescriptorSize10) {
    return fail(which + " has struct_size " + std::to_string(desc->header.struct_size) +
                ", smaller than SDK ABI 1.0's " + std::to_string(kDescriptorSize10));
  }
  if (desc->header.s_type != NIMBUS_S_TYPE_DESCRIPTOR) {
    return fail(which + " has s_type " + std::to_string(desc->header.s_type) + ", expected " +
                std::to_string(NIMBUS_S_TYPE_DESCRIPTOR));
  }
  if (desc->id == nullptr) return fail(which + " has no id");
  const std::string id = desc->id;
  if (!is_valid_id(id)) {
    return fail(which + " has a malformed id '" + shown(id) + "' (expected non-empty ASCII without spaces)");
  }
  const std::string plugin = "plugin '" + id + "'";
  if (desc->name == nullptr) return fail(plugin + " has no name");
  if (desc->vendor == nullptr) return fail(plugin + " has no vendor");
  if (!is_known_kind(desc->kind)) return fail(plugin + " has " + kind_name(desc->kind));

  DescriptorCopy copy;
  copy.id = id;
  copy.name = desc->name;
  copy.vendor = desc->vendor;
  copy.kind = desc->kind;
  copy.version = desc->version;
  auto features = copy_list(desc->features);
  if (!features) return fail(plugin + " lists more than 256 features (missing NULL terminator?)");
  copy.features = std::move(*features);
  auto services = copy_list(desc->required_services);
  if (!services) return fail(plugin + " lists more than 256 required services (missing NULL terminator?)");
  copy.required_services = std::move(*services);
  for (const auto &s : copy.required_services) {
    if (!parse_service_ref(s)) {
      return fail(plugin + " has a malformed required service '" + shown(s) + "' (expected id@revision)");
    }
  }
  auto options = read_option_declarations(*desc);
  if (!options) return fail(plugin + ": " + options.error().message);
  copy.options = std::move(options.value());
  return {std::move(copy), {}};
}

std::optional<ServiceRef> parse_service_ref(std::string_view text) {
  const size_t at = text.rfind('@');
  if (at == std::string_view::npos || at == 0 || at + 1 == text.size()) return std::nullopt;
  const std::string_view rev = text.substr(at + 1);
  ServiceRef ref{std::string(text.substr(0, at)), 0};
  const auto [end, ec] = std::from_chars(rev.data(), rev.data() + rev.size(), ref.revision);
  if (ec != std::errc{} || end != rev.data() + rev.size()) return std::nullopt;
  return ref;
}

std::optional<std::string> check_required_services(const DescriptorCopy &desc, const nimbus_host_t *host) {
  const bool can_query = NIMBUS_HAS_MEMBER(host, nimbus_host_t, get_service) && host->get_service != nullptr;
  for (const auto &s : desc.required_services) {
    const auto ref = parse_service_ref(s);
    if (ref && can_query && host->get_service(host, ref->id.c_str(), ref->revision) != nullptr) continue;
    return "plugin '" + desc.id + "' requires host service '" + shown(s) +
           "', which this host does not provide";
  }
  return std::nullopt;
}

}  // namespace nimbus
