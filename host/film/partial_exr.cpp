#include "film/partial_exr.hpp"

#include <OpenImageIO/imageio.h>

#include <cstring>

#include "core/one_line.hpp"
#include "film/atomic_file.hpp"
#include "film/exr_layout.hpp"
#include "film/image_read.hpp"

namespace nimbus {
namespace {

constexpr const char *kLow = ".lo", *kHigh = ".hi";

struct SumChannels {
  std::vector<std::string> names;  // "<channel>.lo", "<channel>.hi" per channel of every element
  std::vector<uint32_t> words;     // names.size() per pixel, interleaved
};

SumChannels sum_channels(const Film &film) {
  SumChannels out;
  const std::vector<int32_t> ids = film.active_elements();
  for (int32_t id : ids)
    for (const std::string &c :
         exr_channel_names(id == Film::kBeauty ? "" : film.element_name(id), film.element_channels(id))) {
      out.names.push_back(c + kLow);
      out.names.push_back(c + kHigh);
    }
  const size_t pixels = size_t(film.width()) * film.height(), total = out.names.size();
  out.words.resize(pixels * total);
  size_t first = 0;
  for (int32_t id : ids) {
    const std::span<const double> sums = film.sums(id);
    const size_t channels = film.element_channels(id);
    for (size_t p = 0; p < pixels; ++p)
      for (size_t k = 0; k < channels; ++k) {
        uint64_t bits;
        std::memcpy(&bits, &sums[p * channels + k], sizeof bits);
        out.words[p * total + first + 2 * k] = uint32_t(bits);
        out.words[p * total + first + 2 * k + 1] = uint32_t(bits >> 32);
      }
    first += 2 * channels;
  }
  return out;
}

Status write_two_parts(const std::string &file, const ExrImage &image, const OIIO::ImageSpec &sums_spec,
                       const std::vector<uint32_t> &words) {
  auto out = OIIO::ImageOutput::create("openexr");
  if (!out) return Error{"OpenImageIO has no 'openexr' writer: " + OIIO::geterror()};
  const OIIO::ImageSpec specs[2] = {image.spec, sums_spec};
  if (!out->open(file, 2, specs)) return Error{out->geterror()};
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) &&
                       out->open(file, sums_spec, OIIO::ImageOutput::AppendSubimage) &&
                       out->write_image(OIIO::TypeDesc::UINT, words.data());
  if (!written) {
    const std::string reason = out->geterror();
    out->close();
    return Error{reason};
  }
  if (!out->close()) return Error{out->geterror()};
  return Ok{};
}

// The element a channel belongs to, as part 0's reader names layers ("beauty" for R, G, B).
std::string element_of(const std::string &channel) {
  const size_t dot = channel.rfind('.');
  return dot == std::string::npos ? "beauty" : channel.substr(0, dot);
}

}  // namespace

Status write_partial_exr(const Film &film, const std::string &path,
                         const std::vector<std::pair<std::string, std::string>> &string_meta,
                         const std::vector<std::pair<std::string, double>> &numeric_meta) {
  const ExrImage image = film_exr_image(film, string_meta, numeric_meta);
  const SumChannels sums = sum_channels(film);
  OIIO::ImageSpec spec(int(film.width()), int(film.height()), int(sums.names.size()), OIIO::TypeDesc::UINT);
  spec.channelnames = sums.names;
  spec.alpha_channel = -1;
  spec.attribute("compression", "zip");
  spec.attribute("name", kSumsPartName);
  return write_atomically(
      path, [&](const std::string &tmp) { return write_two_parts(tmp, image, spec, sums.words); });
}

Expected<PartialImage> read_partial_exr(const std::string &path) {
  auto layers = read_exr_layers(path);  // part 0: the metadata, and a check of the file's structure
  if (!layers) return layers.error();
  PartialImage out;
  out.width = layers->width, out.height = layers->height;
  for (const auto &[key, value] : layers->strings)
    if (key.rfind("nimbus:", 0) == 0) out.strings[key.substr(7)] = value;
  for (const auto &[key, value] : layers->numbers)
    if (key.rfind("nimbus:", 0) == 0) out.numbers[key.substr(7)] = value;

  const auto fail = [&](const std::string &why) { return Error{"cannot read '" + path + "': " + why}; };
  auto in = OIIO::ImageInput::open(path);
  if (!in) return fail(one_line(OIIO::geterror()));
  if (!in->seek_subimage(1, 0)) {
    (void)in->geterror();
    return fail("no part '" + std::string(kSumsPartName) + "': not a partial render of nimbus render --task");
  }
  const OIIO::ImageSpec spec = in->spec();
  if (spec.width != int(out.width) || spec.height != int(out.height) || spec.x != 0 || spec.y != 0)
    return fail("its sums part is not the size of its image");
  const size_t n = size_t(spec.nchannels), pixels = size_t(out.width) * out.height;
  // Channels pair up as <channel>.lo, <channel>.hi; OpenEXR stores them sorted, so group by element.
  std::map<std::string, size_t> low, high;  // image channel name -> index of its word in the sums part
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string name = spec.channel_name(c);
    const bool is_low = name.size() > 3 && name.compare(name.size() - 3, 3, kLow) == 0;
    const bool is_high = name.size() > 3 && name.compare(name.size() - 3, 3, kHigh) == 0;
    if (!is_low && !is_high) return fail("unexpected sums channel '" + name + "'");
    if (!(is_low ? low : high).emplace(name.substr(0, name.size() - 3), size_t(c)).second)
      return fail("sums channel '" + name + "' appears twice");
  }
  std::vector<uint32_t> words(pixels * n);
  if (!in->read_image(1, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, words.data()))
    return fail(one_line(in->geterror()));
  // Element order: beauty first, then as part 0's layers list them (alphabetical; merge matches by name).
  std::map<std::string, std::vector<std::string>> by_element;
  for (const auto &[channel, index] : low) {
    if (!high.count(channel)) return fail("sums channel '" + channel + ".lo' has no '.hi'");
    by_element[element_of(channel)].push_back(channel);
  }
  if (high.size() != low.size()) return fail("a sums channel '.hi' has no '.lo'");
  if (!by_element.count("beauty")) return fail("no beauty sums");
  std::vector<std::string> order = {"beauty"};
  for (const auto &[element, channels] : by_element)
    if (element != "beauty") order.push_back(element);
  for (const std::string &element : order) {
    const std::vector<std::string> &channels = by_element[element];
    // The layer's channels in image order (R, G, B; or Y), as part 0's reader ranks them.
    const ImageLayer &layer = layers->layers[element];
    if (layer.channel_names.size() != channels.size())
      return fail("element '" + element + "' has " + std::to_string(channels.size()) + " sums channels and " +
                  std::to_string(layer.channel_names.size()) + " image channels");
    PartialElement e;
    e.name = element;
    e.channels = uint32_t(channels.size());
    if (e.channels != 1 && e.channels != 3)
      return fail("element '" + element + "' has neither 1 nor 3 channels");
    e.sums.resize(pixels * e.channels);
    for (uint32_t k = 0; k < e.channels; ++k) {
      const std::string &channel = layer.channel_names[k];
      if (!low.count(channel)) return fail("no sums for channel '" + channel + "'");
      const size_t lo = low[channel], hi = high[channel];
      for (size_t p = 0; p < pixels; ++p) {
        const uint64_t bits = uint64_t(words[p * n + lo]) | (uint64_t(words[p * n + hi]) << 32);
        std::memcpy(&e.sums[p * e.channels + k], &bits, sizeof bits);
      }
    }
    out.elements.push_back(std::move(e));
  }
  return out;
}

}  // namespace nimbus
