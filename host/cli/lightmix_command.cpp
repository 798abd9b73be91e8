// `nimbus lightmix IN.exr --set GROUP=SCALE[,R,G,B] ... -o OUT.exr`: relight a LightMix render without
// rendering again (film/lightmix_recombine.hpp), writing the EXR and its PNG preview.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "film/film.hpp"
#include "film/image_read.hpp"
#include "film/lightmix_recombine.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus lightmix IN.exr [--set GROUP=SCALE[,R,G,B]]... -o OUT.exr\n"
    "       nimbus lightmix IN.exr --list\n"
    "\n"
    "Relights a render made with --elements lightmix: every light group's layer (lightmix.GROUP) is\n"
    "multiplied by SCALE and the optional RGB tint, and beauty becomes\n"
    "  sum over groups of SCALE * TINT * layer  +  (beauty - sum of layers)\n"
    "where the last term keeps anything no group accounts for (normally ~0). Groups not named keep 1.\n"
    "The output holds the new beauty, the scaled LightMix layers (so it can be mixed again), every other\n"
    "layer unchanged and the input's nimbus metadata plus nimbus:lightmix describing the mix; the PNG\n"
    "preview goes beside it.\n"
    "\n"
    "options:\n"
    "  --set GROUP=SCALE[,R,G,B]  scale (and tint) one light group; repeatable; numbers >= 0\n"
    "  -o, --output OUT.exr       the relit image (may be IN.exr itself)\n"
    "  --list                     print the light groups of IN.exr and exit\n"
    "\n"
    "example: nimbus lightmix out/box.exr --set key=2 --set fill=0.5,1,0.8,0.6 -o out/box-relit.exr\n";

struct Args {
  std::string input, output;
  std::vector<LightMixSetting> settings;
  bool list = false;
};

// Returns an error message, or an empty string on success.
std::string parse_args(const std::vector<std::string> &args, Args &a, bool &help) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &k = args[i];
    const bool has_value = i + 1 < args.size();
    if (k == "--help" || k == "-h") {
      help = true;
      return "";
    } else if (k == "--set") {
      if (!has_value) return "--set: expected GROUP=SCALE[,R,G,B]";
      auto s = parse_lightmix_setting(args[++i]);
      if (!s) return "--set: " + s.error().message;
      a.settings.push_back(std::move(s.value()));
    } else if (k == "-o" || k == "--output") {
      if (!has_value || args[i + 1].empty()) return k + ": expected a file name";
      a.output = args[++i];
    } else if (k == "--list") {
      a.list = true;
    } else if (!k.empty() && k[0] == '-') {
      return "unknown option '" + k + "'";
    } else if (a.input.empty()) {
      a.input = k;
    } else {
      return "unexpected argument '" + k + "' (one input image)";
    }
  }
  if (a.input.empty()) return "no input image given";
  if (a.list) return "";
  if (a.output.empty()) return "no output given (-o OUT.exr)";
  if (std::filesystem::path(a.output).extension() == ".png")
    return "-o: the output is an EXR; its PNG preview is written beside it";
  return "";
}

std::string png_beside(const std::string &exr) {
  std::filesystem::path p(exr);
  p.replace_extension(".png");
  return p.string();
}

// The input's nimbus:* metadata, unprefixed (the writer adds the prefix back), with the new mix appended
// to any earlier one: the layers the earlier mix scaled are what this one scales again.
void carry_metadata(const ImageLayers &in, const std::string &mix, const std::string &source,
                    std::vector<std::pair<std::string, std::string>> &strings,
                    std::vector<std::pair<std::string, double>> &numbers) {
  constexpr std::string_view kPrefix = "nimbus:";
  std::string history;
  for (const auto &[key, value] : in.strings) {
    if (!key.starts_with(kPrefix)) continue;
    const std::string k = key.substr(kPrefix.size());
    if (k == "lightmix") history = value + " then ";
    if (k != "lightmix" && k != "lightmix_source") strings.emplace_back(k, value);
  }
  for (const auto &[key, value] : in.numbers)
    if (key.starts_with(kPrefix)) numbers.emplace_back(key.substr(kPrefix.size()), value);
  strings.emplace_back("lightmix", history + mix);
  strings.emplace_back("lightmix_source", source);
}

}  // namespace

int lightmix_command(const std::vector<std::string> &argv) {
  Args a;
  bool help = false;
  if (const std::string err = parse_args(argv, a, help); !err.empty()) {
    std::fprintf(stderr, "nimbus lightmix: %s\n\n%s", err.c_str(), kHelp);
    return kExitUsage;
  }
  if (help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  auto read = read_exr_layers(a.input);
  if (!read) {
    std::fprintf(stderr, "nimbus lightmix: %s\n", read.error().message.c_str());
    return kExitFailure;
  }
  ImageLayers &image = read.value();
  if (a.list) {
    const std::vector<std::string> groups = lightmix_groups(image);
    for (const std::string &g : groups) std::printf("%s\n", g.c_str());
    if (groups.empty())
      std::fprintf(stderr, "nimbus lightmix: '%s' has no LightMix layers\n", a.input.c_str());
    return groups.empty() ? kExitFailure : kExitOk;
  }
  auto mix = recombine_lightmix(image, a.settings);
  if (!mix) {
    std::fprintf(stderr, "nimbus lightmix: '%s': %s\n", a.input.c_str(), mix.error().message.c_str());
    return kExitFailure;
  }

  std::vector<ExrLayer> layers;
  for (const auto &[name, layer] : image.layers) layers.push_back({layer.channel_names, layer.data.data()});
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, double>> numbers;
  carry_metadata(image, mix.value(), a.input, strings, numbers);
  if (Status s = write_layered_exr(a.output, image.width, image.height, layers, strings, numbers); !s) {
    std::fprintf(stderr, "nimbus lightmix: %s\n", s.error().message.c_str());
    return kExitFailure;
  }
  const std::string png = png_beside(a.output);
  if (Status s = write_display_png(png, image.layers.at("beauty").data, image.width, image.height,
                                   default_ocio_config_path());
      !s) {
    std::fprintf(stderr, "nimbus lightmix: %s\n", s.error().message.c_str());
    return kExitFailure;
  }
  std::fprintf(stderr, "nimbus: lightmix %s -> %s, %s\n", mix.value().c_str(), a.output.c_str(), png.c_str());
  return kExitOk;
}

}  // namespace nimbus::cli
