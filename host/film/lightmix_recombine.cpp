#include "film/lightmix_recombine.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>

namespace nimbus {
namespace {

constexpr std::string_view kPrefix = "lightmix.";

std::string shortest(float v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, end);
}

Error malformed(std::string_view text, const std::string &why) {
  return Error{"malformed setting '" + std::string(text) + "': " + why + " (expected GROUP=SCALE[,R,G,B])"};
}

}  // namespace

Expected<LightMixSetting> parse_lightmix_setting(std::string_view text) {
  const size_t eq = text.find('=');
  if (eq == std::string_view::npos) return malformed(text, "no '='");
  LightMixSetting s;
  s.group = std::string(text.substr(0, eq));
  if (s.group.starts_with(kPrefix)) s.group.erase(0, kPrefix.size());
  if (s.group.empty()) return malformed(text, "no group name");

  std::vector<float> values;
  std::string_view rest = text.substr(eq + 1);
  for (;;) {
    const size_t comma = rest.find(',');
    const std::string_view item = rest.substr(0, comma);
    float v = 0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size())
      return malformed(text, "'" + std::string(item) + "' is not a number");
    if (!std::isfinite(v) || v < 0)
      return malformed(text, "'" + std::string(item) + "' is not finite and >= 0");
    values.push_back(v);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (values.size() != 1 && values.size() != 4)
    return malformed(text,
                     std::to_string(values.size()) + " numbers (a scale, optionally followed by R,G,B)");
  s.scale = values[0];
  if (values.size() == 4) s.color = {values[1], values[2], values[3]};
  return s;
}

std::vector<std::string> lightmix_groups(const ImageLayers &image) {
  std::vector<std::string> groups;
  for (const auto &[name, layer] : image.layers) {
    if (name.size() > kPrefix.size() && name.starts_with(kPrefix))
      groups.push_back(name.substr(kPrefix.size()));
  }
  return groups;  // std::map keeps them sorted
}

Expected<std::string> recombine_lightmix(ImageLayers &image, const std::vector<LightMixSetting> &settings) {
  const auto beauty_it = image.layers.find("beauty");
  if (beauty_it == image.layers.end() || beauty_it->second.channel_names.size() != 3)
    return Error{"the image has no RGB beauty (channels R, G, B)"};
  const std::vector<std::string> groups = lightmix_groups(image);
  if (groups.empty())
    return Error{"the image has no LightMix layers (lightmix.*); render with --elements lightmix"};
  std::string available;
  for (const std::string &g : groups) available += (available.empty() ? "" : ", ") + g;

  // Effective multiplier per group, validated before anything changes.
  std::map<std::string, std::array<double, 3>> gain;
  for (const std::string &g : groups) {
    if (image.layers.at(std::string(kPrefix) + g).channel_names.size() != 3)
      return Error{"LightMix layer 'lightmix." + g + "' is not RGB"};
    gain[g] = {1, 1, 1};
  }
  std::vector<std::string> seen;
  for (const LightMixSetting &s : settings) {
    const auto it = gain.find(s.group);
    if (it == gain.end())
      return Error{"unknown light group '" + s.group + "' (available: " + available + ")"};
    if (std::find(seen.begin(), seen.end(), s.group) != seen.end())
      return Error{"light group '" + s.group + "' is set more than once"};
    seen.push_back(s.group);
    for (int c = 0; c < 3; ++c) it->second[c] = double(s.scale) * s.color[c];
  }

  struct Group {
    ImageLayer *layer;
    std::array<double, 3> gain;
  };
  std::vector<Group> mix;
  for (const auto &[g, k] : gain) mix.push_back({&image.layers.at(std::string(kPrefix) + g), k});

  // Per value in double: with every gain 1 the result is within a few double ulps of the float beauty,
  // which the one rounding to float removes, so beauty comes back bit for bit.
  ImageLayer &beauty = beauty_it->second;
  for (size_t i = 0; i < beauty.data.size(); ++i) {
    const size_t c = i % 3;
    double layers = 0, mixed = 0;
    for (const Group &g : mix) {
      const double v = g.layer->data[i];
      layers += v;
      mixed += g.gain[c] * v;
    }
    beauty.data[i] = static_cast<float>(mixed + (double(beauty.data[i]) - layers));
  }
  for (Group &g : mix) {
    for (size_t i = 0; i < g.layer->data.size(); ++i)
      g.layer->data[i] = static_cast<float>(g.gain[i % 3] * g.layer->data[i]);
  }
  // Keep the per-channel planes in step with the layers they were split from.
  std::vector<const ImageLayer *> changed{&beauty};
  for (const Group &g : mix) changed.push_back(g.layer);
  for (const ImageLayer *l : changed) {
    const size_t n = l->channel_names.size();
    for (size_t k = 0; k < n; ++k) {
      std::vector<float> &plane = image.channels.at(l->channel_names[k]);
      for (size_t p = 0; p < plane.size(); ++p) plane[p] = l->data[p * n + k];
    }
  }

  std::string description;
  for (const auto &[g, k] : gain) {
    const auto s = std::find_if(settings.begin(), settings.end(),
                                [&g = g](const LightMixSetting &x) { return x.group == g; });
    description += (description.empty() ? "" : ";") + g + "=";
    if (s == settings.end()) {
      description += "1";
    } else {
      description += shortest(s->scale);
      if (s->color != std::array<float, 3>{1, 1, 1})
        description +=
            "," + shortest(s->color[0]) + "," + shortest(s->color[1]) + "," + shortest(s->color[2]);
    }
  }
  return description;
}

}  // namespace nimbus
