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
  auto header = read_exr_header(path);  // part 0: the metadata, and a check of the file's structure
  if (!header) return header.error();
  PartialImage out;
  out.width = header->width, out.height = header->height;
  for (const auto &[key, value] : header->strings)
    if (key.rfind("nimbus:", 0) == 0) out.strings[key.substr(7)] = value;
  for (const auto &[key, value] : header->numbers)
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
  // Channels pair up as <channel>.lo, <channel>.hi, in whatever order the file stores them.
  std::map<std::string, size_t> low, high;        // image channel name -> index of its word in the sums part
  std::map<std::string, uint32_t> channel_count;  // element -> its channels
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string name = spec.channel_name(c);
    const bool is_low = name.size() > 3 && name.compare(name.size() - 3, 3, kLow) == 0;
    const bool is_high = name.size() > 3 && name.compare(name.size() - 3, 3, kHigh) == 0;
    if (!is_low && !is_high) return fail("unexpected sums channel '" + name + "'");
    const std::string channel = name.substr(0, name.size() - 3);
    if (!(is_low ? low : high).emplace(channel, size_t(c)).second)
      return fail("sums channel '" + name + "' appears twice");
    if (is_low) ++channel_count[element_of(channel)];
  }
  if (high.size() != low.size()) return fail("its '.lo' and '.hi' sums channels do not pair up");
  if (!channel_count.count("beauty")) return fail("no beauty sums");
  std::vector<uint32_t> words(pixels * n);
  if (!in->read_image(1, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, words.data()))
    return fail(one_line(in->geterror()));
  // Beauty first, then the other elements by name (merge matches them by name).
  std::vector<std::string> order = {"beauty"};
  for (const auto &[element, count] : channel_count)
    if (element != "beauty") order.push_back(element);
  for (const std::string &element : order) {
    PartialElement e;
    e.name = element;
    e.channels = channel_count[element];
    if (e.channels != 1 && e.channels != 3)
      return fail("element '" + element + "' has neither 1 nor 3 channels");
    e.sums.resize(pixels * e.channels);
    // The channels in image order (R, G, B; or Y), named as the writer names them.
    const std::vector<std::string> names = exr_channel_names(element == "beauty" ? "" : element, e.channels);
    for (uint32_t k = 0; k < e.channels; ++k) {
      const auto lo = low.find(names[k]), hi = high.find(names[k]);
      if (lo == low.end() || hi == high.end()) return fail("no sums for channel '" + names[k] + "'");
      for (size_t p = 0; p < pixels; ++p) {
        const uint64_t bits =
            uint64_t(words[p * n + lo->second]) | (uint64_t(words[p * n + hi->second]) << 32);
        std::memcpy(&e.sums[p * e.channels + k], &bits, sizeof bits);
      }
    }
    out.elements.push_back(std::move(e));
  }
  return out;
}

}  // namespace nimbus
