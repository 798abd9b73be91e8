#include "film/partial_exr.hpp"

#include <cstring>

#include "core/image_io.hpp"
#include "core/one_line.hpp"
#include "film/atomic_file.hpp"
#include "film/exr_layout.hpp"
#include "film/exr_write.hpp"
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
  ImageDesc sums_desc = image_desc(film.width(), film.height(), sums.names, PixelType::UInt32);
  sums_desc.attributes = {text_attribute("compression", "zip"), text_attribute("name", kSumsPartName)};
  const ImagePart parts[2] = {{image.desc, image.pixels.data()}, {std::move(sums_desc), sums.words.data()}};
  return write_atomically(path, [&](const std::string &tmp) { return write_exr_file(tmp, parts); });
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
  auto opened = open_image_file(path);
  if (!opened) return fail(one_line(opened.error().message));
  ImageFile &in = **opened;
  if (!in.seek_part(1))
    return fail("no part '" + std::string(kSumsPartName) + "': not a partial render of nimbus render --task");
  const ImageDesc &spec = in.desc();
  if (spec.width != int(out.width) || spec.height != int(out.height) || spec.x != 0 || spec.y != 0)
    return fail("its sums part is not the size of its image");
  const size_t n = spec.channels.size(), pixels = size_t(out.width) * out.height;
  // Channels pair up as <channel>.lo, <channel>.hi, in whatever order the file stores them.
  std::map<std::string, size_t> low, high;        // image channel name -> index of its word in the sums part
  std::map<std::string, uint32_t> channel_count;  // element -> its channels
  for (size_t c = 0; c < n; ++c) {
    const std::string &name = spec.channels[c];
    const bool is_low = name.size() > 3 && name.compare(name.size() - 3, 3, kLow) == 0;
    const bool is_high = name.size() > 3 && name.compare(name.size() - 3, 3, kHigh) == 0;
    if (!is_low && !is_high) return fail("unexpected sums channel '" + name + "'");
    const std::string channel = name.substr(0, name.size() - 3);
    if (!(is_low ? low : high).emplace(channel, c).second)
      return fail("sums channel '" + name + "' appears twice");
    if (is_low) ++channel_count[element_of(channel)];
  }
  if (high.size() != low.size()) return fail("its '.lo' and '.hi' sums channels do not pair up");
  if (!channel_count.count("beauty")) return fail("no beauty sums");
  std::vector<uint32_t> words(pixels * n);
  if (!in.read_rows(spec.y, spec.y + spec.height, PixelType::UInt32, words.data()))
    return fail(one_line(in.error()));
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
