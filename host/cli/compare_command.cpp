// `nimbus compare TEST.exr REF.exr`: error metrics of a render against a reference
// (film/image_compare.hpp defines them), as text or JSON, and optionally a false-colour error heatmap.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "film/image_compare.hpp"
#include "film/image_read.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus compare TEST.exr REF.exr [--element NAME] [--heatmap OUT.png] [--json]\n"
    "\n"
    "Compares one layer of TEST against the same layer of REF, over every channel of every pixel finite\n"
    "in both (t = test, r = reference, eps = 0.01):\n"
    "  RMSE        sqrt(mean (t-r)^2)\n"
    "  relMSE      mean (t-r)^2 / (r^2 + eps)\n"
    "  MAPE        mean |t-r| / (|r| + eps)         (a fraction: 0.05 = 5%)\n"
    "  relMSE (Y)  relMSE of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B, per pixel\n"
    "and counts the pixels with a NaN or infinite channel (left out of the metrics) in TEST and in REF.\n"
    "\n"
    "options:\n"
    "  --element NAME    the layer to compare (default: beauty), e.g. albedo, lightmix.key\n"
    "  --heatmap OUT.png per-pixel relative squared error, log scale, viridis colours\n"
    "  --json            print one JSON object instead of text\n"
    "\n"
    "Exit code 0 when the images were compared (whatever the error), 1 when they cannot be (missing file\n"
    "or layer, different sizes), 2 on bad usage.\n";

struct Args {
  std::string test, ref, element = "beauty", heatmap;
  bool json = false;
};

std::string parse_args(const std::vector<std::string> &args, Args &a, bool &help) {
  std::vector<std::string> files;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &k = args[i];
    const bool has_value = i + 1 < args.size() && !args[i + 1].empty();
    if (k == "--help" || k == "-h") {
      help = true;
      return "";
    } else if (k == "--element") {
      if (!has_value) return "--element: expected a layer name";
      a.element = args[++i];
    } else if (k == "--heatmap") {
      if (!has_value) return "--heatmap: expected a PNG file name";
      a.heatmap = args[++i];
    } else if (k == "--json") {
      a.json = true;
    } else if (!k.empty() && k[0] == '-') {
      return "unknown option '" + k + "'";
    } else {
      files.push_back(k);
    }
  }
  if (files.size() != 2)
    return "expected two images, TEST and REF (got " + std::to_string(files.size()) + ")";
  a.test = files[0];
  a.ref = files[1];
  return "";
}

std::string layer_list(const ImageLayers &img) {
  std::string out;
  for (const auto &[name, layer] : img.layers) out += (out.empty() ? "" : ", ") + name;
  return out;
}

std::string json_string(const std::string &s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

// JSON has no NaN: a metric with no pixel to average over is null.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

int fail(const std::string &message) {
  std::fprintf(stderr, "nimbus compare: %s\n", message.c_str());
  return kExitFailure;
}

}  // namespace

int compare_command(const std::vector<std::string> &argv) {
  Args a;
  bool help = false;
  if (const std::string err = parse_args(argv, a, help); !err.empty()) {
    std::fprintf(stderr, "nimbus compare: %s\n\n%s", err.c_str(), kHelp);
    return kExitUsage;
  }
  if (help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  auto test = read_exr_layers(a.test);
  if (!test) return fail(test.error().message);
  auto ref = read_exr_layers(a.ref);
  if (!ref) return fail(ref.error().message);
  if (test->width != ref->width || test->height != ref->height) {
    return fail("the images differ in size: '" + a.test + "' is " + std::to_string(test->width) + "x" +
                std::to_string(test->height) + ", '" + a.ref + "' is " + std::to_string(ref->width) + "x" +
                std::to_string(ref->height));
  }
  for (const auto *img : {&test.value(), &ref.value()}) {
    if (!img->layers.count(a.element)) {
      return fail("'" + (img == &test.value() ? a.test : a.ref) + "' has no layer '" + a.element +
                  "' (available: " + layer_list(*img) + ")");
    }
  }
  const ImageLayer &t = test->layers.at(a.element), &r = ref->layers.at(a.element);
  auto metrics = compare_images(t, r, test->width, test->height);
  if (!metrics) return fail("layer '" + a.element + "': " + metrics.error().message);
  const ImageMetrics &m = metrics.value();

  if (!a.heatmap.empty()) {
    if (Status s = write_error_heatmap(a.heatmap, relative_error_map(t, r, test->width, test->height),
                                       test->width, test->height);
        !s)
      return fail(s.error().message);
  }

  if (a.json) {
    std::printf(
        "{\"test\": %s, \"reference\": %s, \"element\": %s, \"width\": %u, \"height\": %u, \"channels\": "
        "%zu, "
        "\"rmse\": %s, \"relmse\": %s, \"relmse_luminance\": %s, \"mape\": %s, \"pixels\": %llu, "
        "\"compared_pixels\": %llu, \"nonfinite_test\": %llu, \"nonfinite_reference\": %llu, "
        "\"heatmap\": %s}\n",
        json_string(a.test).c_str(), json_string(a.ref).c_str(), json_string(a.element).c_str(), test->width,
        test->height, t.channel_names.size(), json_number(m.rmse).c_str(), json_number(m.relmse).c_str(),
        json_number(m.relmse_luminance).c_str(), json_number(m.mape).c_str(), (unsigned long long)m.pixels,
        (unsigned long long)m.compared_pixels, (unsigned long long)m.nonfinite_test,
        (unsigned long long)m.nonfinite_reference,
        a.heatmap.empty() ? "null" : json_string(a.heatmap).c_str());
    return kExitOk;
  }
  std::printf("test       %s\nreference  %s\nelement    %s (%zu channels, %ux%u)\n", a.test.c_str(),
              a.ref.c_str(), a.element.c_str(), t.channel_names.size(), test->width, test->height);
  std::printf("RMSE         %.6g\nrelMSE       %.6g\nrelMSE (Y)   %.6g\nMAPE         %.6g\n", m.rmse,
              m.relmse, m.relmse_luminance, m.mape);
  std::printf("NaN/Inf pixels in TEST: %llu (in REF: %llu; compared %llu of %llu pixels)\n",
              (unsigned long long)m.nonfinite_test, (unsigned long long)m.nonfinite_reference,
              (unsigned long long)m.compared_pixels, (unsigned long long)m.pixels);
  if (!a.heatmap.empty()) std::printf("heatmap    %s: %s\n", a.heatmap.c_str(), heatmap_legend().c_str());
  return kExitOk;
}

}  // namespace nimbus::cli
