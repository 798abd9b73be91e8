#include "film/image_read.hpp"

#include <algorithm>
#include <array>

#include "core/image_io.hpp"
#include "core/limits.hpp"
#include "core/one_line.hpp"

namespace nimbus {
namespace {

constexpr size_t kBandValues = size_t(1) << 22;  // floats read per band: 16 MB

// Within a layer, R G B (and X Y Z, A last) keep their conventional order whatever order the file
// stored them in (OpenEXR sorts channels alphabetically); anything else follows alphabetically.
int channel_rank(const std::string &suffix) {
  static constexpr std::array<const char *, 8> order = {"R", "G", "B", "X", "Y", "Z", "A", ""};
  for (size_t i = 0; i + 1 < order.size(); ++i) {
    if (suffix == order[i]) return static_cast<int>(i);
  }
  return static_cast<int>(order.size());
}

std::pair<std::string, std::string> split_channel(const std::string &name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos) return {"beauty", name};
  return {name.substr(0, dot), name.substr(dot + 1)};
}

void read_attributes(const ImageDesc &desc, ImageLayers &out) {
  for (const ImageAttribute &a : desc.attributes) {
    if (a.kind == ImageAttribute::Kind::String)
      out.strings[a.name] = a.text;
    else
      out.numbers[a.name] = a.number;
  }
}

// The file opened at its first part, whose size has been checked.
Expected<std::unique_ptr<ImageFile>> open_exr(const std::string &path) {
  auto in = open_image_file(path);
  if (!in) return Error{"cannot read '" + path + "': " + one_line(in.error().message)};
  const ImageDesc &spec = (*in)->desc();
  if (spec.width < 1 || spec.height < 1 || spec.channels.empty())
    return Error{"cannot read '" + path + "': no pixels"};
  if (spec.width > kMaxResolution || spec.height > kMaxResolution) {
    return Error{"cannot read '" + path + "': " + std::to_string(spec.width) + "x" +
                 std::to_string(spec.height) + " pixels, more than Nimbus renders (" +
                 std::to_string(kMaxResolution) + " per side)"};
  }
  return std::move(*in);
}

}  // namespace

Expected<ImageLayers> read_exr_header(const std::string &path) {
  auto opened = open_exr(path);
  if (!opened) return opened.error();
  const ImageDesc &spec = opened.value()->desc();
  ImageLayers out;
  out.width = uint32_t(spec.width), out.height = uint32_t(spec.height);
  read_attributes(spec, out);
  return out;
}

Expected<ImageLayers> read_exr_layers(const std::string &path) {
  auto opened = open_exr(path);
  if (!opened) return opened.error();
  ImageFile &in = *opened.value();
  const ImageDesc &spec = in.desc();
  const size_t width = static_cast<size_t>(spec.width), height = static_cast<size_t>(spec.height);
  const size_t n = spec.channels.size();
  // A band of rows at a time, so that memory follows the pixels the file really holds: its header alone
  // may claim any size, and a damaged file must fail at its first missing rows.
  // Tiled files are read in whole rows of tiles.
  const int64_t tile_rows = spec.tile_width > 0 ? std::max(1, spec.tile_height) : 1;
  const int64_t band_rows = std::max<int64_t>(1, int64_t(kBandValues / (width * n)) / tile_rows) * tile_rows;
  std::vector<float> pixels, band;
  for (int64_t y = 0; y < spec.height; y += band_rows) {
    const int64_t rows = std::min(band_rows, spec.height - y);
    band.resize(size_t(rows) * width * n);
    if (!in.read_rows(int(spec.y + y), int(spec.y + y + rows), PixelType::Float, band.data()))
      return Error{"cannot read '" + path + "': " + one_line(in.error())};
    pixels.insert(pixels.end(), band.begin(), band.end());
  }

  ImageLayers out;
  out.width = static_cast<uint32_t>(width);
  out.height = static_cast<uint32_t>(height);
  const size_t count = width * height;
  for (size_t c = 0; c < n; ++c) {
    std::vector<float> plane(count);
    for (size_t p = 0; p < count; ++p) plane[p] = pixels[p * n + c];
    out.channels[spec.channels[c]] = std::move(plane);
  }

  std::map<std::string, std::vector<std::string>> grouped;
  for (const auto &[name, plane] : out.channels) grouped[split_channel(name).first].push_back(name);
  for (auto &[layer, names] : grouped) {
    std::stable_sort(names.begin(), names.end(), [](const std::string &a, const std::string &b) {
      return channel_rank(split_channel(a).second) < channel_rank(split_channel(b).second);
    });
    ImageLayer &l = out.layers[layer];
    l.channel_names = names;
    l.data.resize(count * names.size());
    for (size_t k = 0; k < names.size(); ++k) {
      const std::vector<float> &plane = out.channels[names[k]];
      for (size_t p = 0; p < count; ++p) l.data[p * names.size() + k] = plane[p];
    }
  }

  read_attributes(spec, out);
  return out;
}

}  // namespace nimbus
