#include "film/image_read.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>

namespace nimbus {
namespace {

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

void read_attribute(const OIIO::ParamValue &p, ImageLayers &out) {
  const OIIO::TypeDesc t = p.type();
  if (t == OIIO::TypeString) {
    out.strings[p.name().string()] = p.get<OIIO::ustring>().string();
    return;
  }
  if (t.aggregate != OIIO::TypeDesc::SCALAR || t.arraylen != 0 || p.nvalues() != 1) return;
  double v;
  switch (t.basetype) {
    case OIIO::TypeDesc::INT8:
      v = p.get<int8_t>();
      break;
    case OIIO::TypeDesc::UINT8:
      v = p.get<uint8_t>();
      break;
    case OIIO::TypeDesc::INT16:
      v = p.get<int16_t>();
      break;
    case OIIO::TypeDesc::UINT16:
      v = p.get<uint16_t>();
      break;
    case OIIO::TypeDesc::INT32:
      v = p.get<int32_t>();
      break;
    case OIIO::TypeDesc::UINT32:
      v = p.get<uint32_t>();
      break;
    case OIIO::TypeDesc::INT64:
      v = static_cast<double>(p.get<int64_t>());
      break;
    case OIIO::TypeDesc::UINT64:
      v = static_cast<double>(p.get<uint64_t>());
      break;
    case OIIO::TypeDesc::HALF:
      v = p.get_float();
      break;
    case OIIO::TypeDesc::FLOAT:
      v = p.get<float>();
      break;
    case OIIO::TypeDesc::DOUBLE:
      v = p.get<double>();
      break;
    default:
      return;
  }
  out.numbers[p.name().string()] = v;
}

}  // namespace

Expected<ImageLayers> read_exr_layers(const std::string &path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return Error{"cannot read '" + path + "': " + OIIO::geterror()};
  const OIIO::ImageSpec &spec = in->spec();
  const size_t width = static_cast<size_t>(spec.width), height = static_cast<size_t>(spec.height);
  const size_t n = static_cast<size_t>(spec.nchannels);
  std::vector<float> pixels(width * height * n);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
    return Error{"cannot read '" + path + "': " + in->geterror()};
  }

  ImageLayers out;
  out.width = static_cast<uint32_t>(width);
  out.height = static_cast<uint32_t>(height);
  const size_t count = width * height;
  for (size_t c = 0; c < n; ++c) {
    std::vector<float> plane(count);
    for (size_t p = 0; p < count; ++p) plane[p] = pixels[p * n + c];
    out.channels[spec.channel_name(static_cast<int>(c))] = std::move(plane);
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

  for (const OIIO::ParamValue &p : spec.extra_attribs) read_attribute(p, out);
  in->close();
  return out;
}

}  // namespace nimbus
