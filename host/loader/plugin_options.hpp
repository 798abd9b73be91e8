// Options a plugin declares (nimbus_option_list_t, SDK 1.2): read and checked once when the plugin is
// loaded, then used to validate what the scene and the command line ask for and to hand the plugin
// every declared option with its resolved value. The host knows no plugin's option by name.
#pragma once

#include <nimbus/plugin.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/expected.hpp"

namespace nimbus {

struct OptionDecl {
  std::string name;
  nimbus_option_type_t type = NIMBUS_OPTION_STRING;
  std::string default_value;         // normalised
  std::vector<std::string> allowed;  // CHOICE only
  std::string doc;
};

// A value asked for by the scene or the command line; `where` names it for errors ("scene.yaml:12:3:
// render.caustics" or "--caustics").
struct OptionRequest {
  std::string name;
  std::string value;
  std::string where;
  std::string hint;  // added to the error when the name is unknown (e.g. the host's own keys)
};

// The options chained to `desc` (none when it declares none). An error names what is wrong with the
// declaration; the loader refuses the plugin with it.
Expected<std::vector<OptionDecl>> read_option_declarations(const nimbus_descriptor_t &desc);

// `value` in the canonical form the plugin receives (switches: on/off), or an empty optional when it is
// not a value of the option's type.
std::optional<std::string> normalize_option_value(const OptionDecl &decl, const std::string &value);

// What values an option takes, for errors and `nimbus plugins --options`: "on|off", "one of a|b", ...
std::string describe_option_values(const OptionDecl &decl);

// Every declared option of `plugin_id` with the requested value or its default, in declaration order.
// A request for an undeclared option or with a bad value is an error naming its `where` and the
// plugin's options.
Expected<std::vector<std::pair<std::string, std::string>>> resolve_options(
    const std::string &plugin_id, const std::vector<OptionDecl> &decls,
    const std::vector<OptionRequest> &requests);

}  // namespace nimbus
