// The pixel filters a render can use and the names scene files (`render.filter`) and the command line
// (`--filter`) give them: one table, so that a name is checked in one place. world/pixel_filter.hpp has
// the filters themselves.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace nimbus {

enum class FilterType { Box, Gaussian, BlackmanHarris };

struct FilterName {
  std::string_view name;
  FilterType type;
};

inline constexpr std::array<FilterName, 3> kFilterNames{{
    {"box", FilterType::Box},
    {"gaussian", FilterType::Gaussian},
    {"blackman-harris", FilterType::BlackmanHarris},
}};

// The filter called `name`, or nullopt for a name that is not in kFilterNames.
inline std::optional<FilterType> filter_from_name(std::string_view name) {
  for (const FilterName &f : kFilterNames)
    if (f.name == name) return f.type;
  return std::nullopt;
}

inline std::string_view filter_name(FilterType type) {
  for (const FilterName &f : kFilterNames)
    if (f.type == type) return f.name;
  return "unknown";
}

// "box, gaussian, blackman-harris", for messages.
inline std::string filter_names() {
  std::string out;
  for (const FilterName &f : kFilterNames) out += (out.empty() ? "" : ", ") + std::string(f.name);
  return out;
}

}  // namespace nimbus
