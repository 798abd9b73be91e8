// Declared plugin options: reading, value checking and resolution; see plugin_options.hpp.
#include "loader/plugin_options.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "core/one_line.hpp"

namespace nimbus {
namespace {

bool valid_name(const char *s) {
  if (!s || !std::islower(static_cast<unsigned char>(*s))) return false;
  for (; *s; ++s)
    if (!std::islower(static_cast<unsigned char>(*s)) && !std::isdigit(static_cast<unsigned char>(*s)) &&
        *s != '_')
      return false;
  return true;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string names_of(const std::vector<OptionDecl> &decls) {
  if (decls.empty()) return "it declares no options";
  std::string s = "its options: ";
  for (size_t i = 0; i < decls.size(); ++i) s += (i ? ", " : "") + decls[i].name;
  return s;
}

}  // namespace

std::optional<std::string> normalize_option_value(const OptionDecl &decl, const std::string &value) {
  switch (decl.type) {
    case NIMBUS_OPTION_SWITCH: {
      const std::string v = lower(value);
      if (v == "on" || v == "true" || v == "yes" || v == "1") return "on";
      if (v == "off" || v == "false" || v == "no" || v == "0") return "off";
      return std::nullopt;
    }
    case NIMBUS_OPTION_CHOICE:
      if (std::find(decl.allowed.begin(), decl.allowed.end(), value) != decl.allowed.end()) return value;
      return std::nullopt;
    case NIMBUS_OPTION_INT: {
      int64_t n = 0;
      const char *end = value.data() + value.size();
      const auto r = std::from_chars(value.data(), end, n);
      if (value.empty() || r.ec != std::errc() || r.ptr != end) return std::nullopt;
      return std::to_string(n);
    }
    case NIMBUS_OPTION_FLOAT: {
      char *end = nullptr;
      const double x = std::strtod(value.c_str(), &end);
      if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(x)) return std::nullopt;
      return value;
    }
    case NIMBUS_OPTION_STRING:
      return value;
    default:
      return std::nullopt;
  }
}

std::string describe_option_values(const OptionDecl &decl) {
  switch (decl.type) {
    case NIMBUS_OPTION_SWITCH:
      return "on|off";
    case NIMBUS_OPTION_CHOICE: {
      std::string s;
      for (size_t i = 0; i < decl.allowed.size(); ++i) s += (i ? "|" : "") + decl.allowed[i];
      return s;
    }
    case NIMBUS_OPTION_INT:
      return "an integer";
    case NIMBUS_OPTION_FLOAT:
      return "a number";
    default:
      return "text";
  }
}

Expected<std::vector<OptionDecl>> read_option_declarations(const nimbus_descriptor_t &desc) {
  std::vector<OptionDecl> decls;
  for (auto *h = static_cast<const nimbus_struct_header_t *>(desc.header.next); h;
       h = static_cast<const nimbus_struct_header_t *>(h->next)) {
    if (h->s_type != NIMBUS_S_TYPE_OPTION_LIST) continue;  // unknown add-ons are skipped (sdk-idioms 1.3)
    if (h->struct_size < sizeof(nimbus_option_list_t)) return Error{"its option list is truncated"};
    const auto *list = reinterpret_cast<const nimbus_option_list_t *>(h);
    if (list->count > 0 && !list->options) return Error{"its option list has no options array"};
    for (uint32_t i = 0; i < list->count; ++i) {
      const nimbus_option_decl_t &o = list->options[i];
      if (!valid_name(o.name))
        return Error{"option " + std::to_string(i) + " has an invalid name (want [a-z][a-z0-9_]*)"};
      OptionDecl d{o.name, o.type, "", {}, o.doc ? o.doc : ""};
      for (const OptionDecl &e : decls)
        if (e.name == d.name) return Error{"option '" + d.name + "' is declared twice"};
      if (o.type < NIMBUS_OPTION_SWITCH || o.type > NIMBUS_OPTION_STRING)
        return Error{"option '" + d.name + "' has unknown type " + std::to_string(o.type)};
      if (o.type == NIMBUS_OPTION_CHOICE) {
        for (const char *const *a = o.allowed; a && *a; ++a) d.allowed.emplace_back(*a);
        if (d.allowed.empty()) return Error{"choice option '" + d.name + "' lists no allowed values"};
      }
      const auto def = normalize_option_value(d, o.default_value ? o.default_value : "");
      if (!o.default_value || !def)
        return Error{"option '" + d.name + "' has default '" +
                     (o.default_value ? shown(o.default_value) : "(null)") + "', not " +
                     shown(describe_option_values(d))};
      d.default_value = *def;
      decls.push_back(std::move(d));
    }
  }
  return decls;
}

Expected<std::vector<std::pair<std::string, std::string>>> resolve_options(
    const std::string &plugin_id, const std::vector<OptionDecl> &decls,
    const std::vector<OptionRequest> &requests) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const OptionDecl &d : decls) out.emplace_back(d.name, d.default_value);
  for (const OptionRequest &r : requests) {
    const auto it =
        std::find_if(decls.begin(), decls.end(), [&](const OptionDecl &d) { return d.name == r.name; });
    if (it == decls.end())
      return Error{r.where + ": " + plugin_id + " has no option '" + r.name + "' (" + names_of(decls) + ")" +
                   (r.hint.empty() ? "" : "; " + r.hint)};
    const auto v = normalize_option_value(*it, r.value);
    if (!v)
      return Error{r.where + ": " + plugin_id + " option '" + r.name + "' expects " +
                   describe_option_values(*it) + ", got '" + r.value + "'"};
    out[size_t(it - decls.begin())].second = *v;
  }
  return out;
}

}  // namespace nimbus
