#include "render/frame_merge.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "film/image_read.hpp"
#include "film/partial_exr.hpp"

namespace nimbus {
namespace {

struct PartHeader {
  std::string path;
  ImageLayers header;  // size and attributes only
  uint32_t task = 0;
};

std::string text_of(const ImageLayers &h, const std::string &key) {
  const auto it = h.strings.find("nimbus:" + key);
  return it == h.strings.end() ? std::string() : it->second;
}
std::optional<double> number_of(const ImageLayers &h, const std::string &key) {
  const auto it = h.numbers.find("nimbus:" + key);
  return it == h.numbers.end() ? std::nullopt : std::optional<double>(it->second);
}

// The key of the first line where two fingerprints (RenderJob::fingerprint, "key=value" lines) differ.
std::string first_difference(const std::string &a, const std::string &b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  while (true) {
    const bool more_a = bool(std::getline(sa, la)), more_b = bool(std::getline(sb, lb));
    if (!more_a && !more_b) return "fingerprint";
    if (!more_a || !more_b || la != lb) {
      const std::string &line = more_a ? la : lb;
      return line.substr(0, line.find('='));
    }
  }
}

// What differs between two parts' headers that must agree for them to be one frame, or empty.
std::string difference(const PartHeader &a, const PartHeader &b) {
  const ImageLayers &x = a.header, &y = b.header;
  if (x.width != y.width || x.height != y.height)
    return "sizes differ (" + std::to_string(x.width) + "x" + std::to_string(x.height) + " against " +
           std::to_string(y.width) + "x" + std::to_string(y.height) + ")";
  if (number_of(x, "tasks") != number_of(y, "tasks")) return "task counts differ";
  if (text_of(x, "version") != text_of(y, "version"))
    return "Nimbus versions differ (" + text_of(x, "version") + " against " + text_of(y, "version") + ")";
  if (text_of(x, "plugins") != text_of(y, "plugins"))
    return "plugin versions differ (" + text_of(x, "plugins") + " against " + text_of(y, "plugins") + ")";
  if (text_of(x, "fingerprint") != text_of(y, "fingerprint"))
    return "their " + first_difference(text_of(x, "fingerprint"), text_of(y, "fingerprint")) + " differs";
  if (number_of(x, "frame_iterations") != number_of(y, "frame_iterations"))
    return "their frame's iteration counts differ";
  return {};
}

Expected<PartHeader> read_part_header(const std::string &path) {
  auto h = read_exr_header(path);
  if (!h) return h.error();
  PartHeader part{path, std::move(h.value()), 0};
  const std::optional<double> task = number_of(part.header, "task"), tasks = number_of(part.header, "tasks");
  if (!task || !tasks || text_of(part.header, "fingerprint").empty() || !(*tasks >= 1) || !(*task >= 0) ||
      *task >= *tasks)
    return Error{"'" + path + "' is not a part of a shared frame (made by nimbus render --task K --tasks N)"};
  part.task = uint32_t(*task);
  return part;
}

// Film elements as a part's sums name them; beauty is the film's own.
Status set_up_film(Film &film, const PartialImage &part) {
  for (const PartialElement &e : part.elements) {
    if (e.name == "beauty") continue;
    if (film.register_element(e.name, e.channels, Film::kAverage) < 0)
      return Error{"element '" + e.name + "' cannot be made"};
    film.request(e.name);
  }
  return film.allocate();
}

Status add_sums(Film &film, const PartialImage &part) {
  const std::vector<int32_t> ids = film.active_elements();
  if (ids.size() != part.elements.size()) return Error{"its elements are not the first part's"};
  for (const PartialElement &e : part.elements) {
    const auto id = std::find_if(ids.begin(), ids.end(), [&](int32_t i) {
      return (i == Film::kBeauty ? e.name == "beauty" : film.element_name(i) == e.name) &&
             film.element_channels(i) == e.channels;
    });
    if (id == ids.end()) return Error{"its element '" + e.name + "' is not among the first part's"};
    std::span<double> sums = film.sums(*id);
    for (size_t k = 0; k < sums.size(); ++k) sums[k] += e.sums[k];
  }
  return Ok{};
}

}  // namespace

Expected<MergedFrame> merge_parts(const std::vector<std::string> &paths, bool allow_incomplete) {
  if (paths.empty()) return Error{"no parts given"};
  std::vector<PartHeader> parts;
  for (const std::string &path : paths) {
    auto part = read_part_header(path);
    if (!part) return part.error();
    if (!parts.empty())
      if (const std::string d = difference(parts.front(), part.value()); !d.empty())
        return Error{"'" + parts.front().path + "' and '" + path + "' are not parts of one frame: " + d};
    for (const PartHeader &p : parts)
      if (p.task == part->task)
        return Error{"'" + p.path + "' and '" + path + "' overlap: both hold task " + std::to_string(p.task) +
                     " of " + std::to_string(uint32_t(*number_of(p.header, "tasks")))};
    parts.push_back(std::move(part.value()));
  }
  // Added in task order, so the sums do not depend on the order the parts were named in.
  std::sort(parts.begin(), parts.end(),
            [](const PartHeader &a, const PartHeader &b) { return a.task < b.task; });
  const uint32_t tasks = uint32_t(*number_of(parts.front().header, "tasks"));
  MergedFrame out;
  std::string missing_text;
  for (uint32_t t = 0, next = 0; t < tasks; ++t) {
    if (next < parts.size() && parts[next].task == t) {
      ++next;
      continue;
    }
    out.missing.push_back(t);
    missing_text += (missing_text.empty() ? "" : ", ") + std::to_string(t);
  }
  const std::string of_tasks = " of " + std::to_string(tasks);
  if (!out.missing.empty() && !allow_incomplete)
    return Error{"task" + std::string(out.missing.size() > 1 ? "s " : " ") + missing_text + of_tasks +
                 " missing (--allow-incomplete merges the " + std::to_string(parts.size()) + " present)"};

  out.film = std::make_unique<Film>(parts.front().header.width, parts.front().header.height);
  Film &film = *out.film;
  uint64_t iterations = 0, nonfinite = 0;
  double seconds = 0, rays = 0;
  std::set<std::string> stopped_by;
  for (size_t i = 0; i < parts.size(); ++i) {
    auto part = read_partial_exr(parts[i].path);
    if (!part) return part.error();
    if (i == 0)
      if (Status s = set_up_film(film, part.value()); !s)
        return Error{"'" + parts[i].path + "': " + s.error().message};
    if (Status s = add_sums(film, part.value()); !s)
      return Error{"'" + parts[i].path + "': " + s.error().message};
    const auto number = [&](const char *key) {
      return part->numbers.count(key) ? part->numbers.at(key) : 0.0;
    };
    iterations += uint64_t(number("iterations"));
    nonfinite += uint64_t(number("nonfinite_samples"));
    seconds += number("seconds");
    rays += number("rays");
    stopped_by.insert(part->strings.count("stopped_by") ? part->strings.at("stopped_by") : "");
  }
  film.set_iterations(iterations);
  film.set_nonfinite_count(nonfinite);

  const ImageLayers &first = parts.front().header;
  for (const char *key :
       {"version", "integrator", "light_sampler", "guide", "scene", "seed", "filter", "region"})
    if (const std::string v = text_of(first, key); !v.empty()) out.strings.push_back({key, v});
  std::string stops;
  for (const std::string &s : stopped_by) stops += (stops.empty() ? "" : ",") + s;
  out.strings.push_back({"stopped_by", stops});
  if (!out.missing.empty())
    out.strings.push_back({"incomplete", "tasks " + missing_text + of_tasks + " missing"});
  out.numbers = {{"iterations", double(iterations)},
                 {"seconds", seconds},
                 {"nonfinite_samples", double(nonfinite)},
                 {"rays", rays},
                 {"tasks", double(tasks)},
                 {"tasks_merged", double(parts.size())}};
  if (const auto frame = number_of(first, "frame_iterations"); frame && *frame > 0)
    out.numbers.push_back({"frame_iterations", *frame});
  return out;
}

Status write_merged(const MergedFrame &frame, const std::string &exr_path, const std::string &png_path,
                    const std::string &ocio_config) {
  if (Status s = frame.film->write_exr(exr_path, frame.strings, frame.numbers); !s) return s;
  return frame.film->write_png(png_path, ocio_config);
}

}  // namespace nimbus
