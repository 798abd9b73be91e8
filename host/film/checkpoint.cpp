#include "film/checkpoint.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "core/checksum.hpp"
#include "core/one_line.hpp"
#include "film/atomic_file.hpp"
#include "film/checkpoint_io.hpp"

namespace nimbus {
namespace {

constexpr std::array<char, 8> kMagic = {'N', 'I', 'M', 'B', 'U', 'S', 'C', 'K'};
// A bound no real checkpoint reaches, on the counts of elements and of plugin states.
constexpr uint32_t kMaxElements = 1u << 16;

using checkpoint_io::File;
using checkpoint_io::kMaxStringBytes;
using checkpoint_io::Reader;
using checkpoint_io::Writer;

struct StoredElement {
  std::string name;
  uint32_t channels = 0;
  std::vector<double> sums;
};

struct Stored {
  uint32_t version = 0;
  uint32_t width = 0, height = 0;
  uint64_t nonfinite = 0;
  CheckpointInfo info;
  std::vector<StoredElement> elements;
};

Error checkpoint_error(const std::string &path, const std::string &reason) {
  return Error{"checkpoint '" + path + "': " + reason};
}

Expected<File> open_for_reading(const std::string &path, uint64_t &size) {
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) return checkpoint_error(path, std::string("cannot open: ") + std::strerror(errno));
  if (std::fseek(f.get(), 0, SEEK_END) != 0)
    return checkpoint_error(path, "cannot seek: " + std::string(std::strerror(errno)));
  const long end = std::ftell(f.get());
  if (end < 0 || std::fseek(f.get(), 0, SEEK_SET) != 0)
    return checkpoint_error(path, "cannot determine its size: " + std::string(std::strerror(errno)));
  size = static_cast<uint64_t>(end);
  return f;
}

// Everything up to the element count.
Status read_header(const std::string &path, Reader &r, Stored &s) {
  std::array<char, 8> magic{};
  if (r.size() < magic.size())
    return checkpoint_error(path,
                            "not a Nimbus checkpoint (" + std::to_string(r.size()) + " bytes is too short)");
  if (!r.bytes(magic.data(), magic.size(), "the magic number")) return checkpoint_error(path, r.error());
  if (magic != kMagic) return checkpoint_error(path, "not a Nimbus checkpoint (wrong magic number)");
  uint32_t version = 0;
  if (!r.u32(version, "the format version")) return checkpoint_error(path, r.error());
  if (version != kCheckpointVersion && version != 1) {
    return checkpoint_error(path, "format version " + std::to_string(version) +
                                      " is not supported (this Nimbus reads version " +
                                      std::to_string(kCheckpointVersion) + ")");
  }
  CheckpointInfo &i = s.info;
  if (!(r.u32(s.width, "the header") && r.u32(s.height, "the header") && r.u64(i.iterations, "the header") &&
        r.u64(i.seed, "the header") && r.u64(s.nonfinite, "the header") && r.f64(i.seconds, "the header") &&
        r.str(i.integrator, "the integrator id") && r.str(i.fingerprint, "the fingerprint")))
    return checkpoint_error(path, r.error());
  s.version = version;
  return Ok{};
}

// The plugins' states (none in version 1).
Status read_states(const std::string &path, Reader &r, Stored &s) {
  if (s.version < 2) return Ok{};
  uint32_t count = 0;
  if (!r.u32(count, "the plugin state count")) return checkpoint_error(path, r.error());
  if (count > kMaxElements)
    return checkpoint_error(path, "corrupted: " + std::to_string(count) + " plugin states");
  for (uint32_t k = 0; k < count; ++k) {
    PluginState st;
    const std::string which = "plugin state #" + std::to_string(k + 1);
    if (!r.str(st.plugin, "the plugin id of " + which) ||
        !r.blob(st.bytes, "the state of plugin '" + shown(st.plugin) + "'"))
      return checkpoint_error(path, r.error());
    s.info.states.push_back(std::move(st));
  }
  return Ok{};
}

Expected<Stored> read_all(const std::string &path) {
  uint64_t size = 0;
  auto file = open_for_reading(path, size);
  if (!file) return file.error();
  Reader r(file->get(), size);
  Stored s;
  if (Status h = read_header(path, r, s); !h) return h.error();

  uint32_t count = 0;
  if (!r.u32(count, "the element count")) return checkpoint_error(path, r.error());
  if (count > kMaxElements)
    return checkpoint_error(path, "corrupted: " + std::to_string(count) + " elements");
  const uint64_t pixels = uint64_t(s.width) * s.height;
  for (uint32_t k = 0; k < count; ++k) {
    StoredElement e;
    const std::string which = "element #" + std::to_string(k + 1);
    if (!r.str(e.name, "the name of " + which) || !r.u32(e.channels, "element '" + shown(e.name) + "'"))
      return checkpoint_error(path, r.error());
    if (e.channels != 1 && e.channels != 3)
      return checkpoint_error(
          path, "corrupted: element '" + shown(e.name) + "' has " + std::to_string(e.channels) + " channels");
    if (!r.doubles(e.sums, pixels * e.channels, "the sums of element '" + shown(e.name) + "'"))
      return checkpoint_error(path, r.error());
    s.elements.push_back(std::move(e));
  }
  if (Status st = read_states(path, r, s); !st) return st.error();
  const uint64_t expected = r.checksum_so_far();
  uint8_t b[8];
  // The stored checksum is read raw: Reader's running sum would include it.
  if (size - r.offset() < 8) {
    return checkpoint_error(
        path, "truncated: the file ends at byte " + std::to_string(size) + ", inside the checksum");
  }
  if (std::fread(b, 1, 8, file->get()) != 8) return checkpoint_error(path, "read error inside the checksum");
  if (size - r.offset() > 8)
    return checkpoint_error(
        path, "corrupted: " + std::to_string(size - r.offset() - 8) + " unexpected bytes after the checksum");
  if (load_le(b, 8) != expected) return checkpoint_error(path, "corrupted: checksum mismatch");
  return s;
}

std::vector<std::pair<std::string, std::string>> fingerprint_fields(const std::string &fingerprint) {
  std::vector<std::pair<std::string, std::string>> fields;
  size_t start = 0;
  while (start < fingerprint.size()) {
    size_t end = fingerprint.find('\n', start);
    if (end == std::string::npos) end = fingerprint.size();
    const std::string line = fingerprint.substr(start, end - start);
    const size_t eq = line.find('=');
    if (!line.empty())
      fields.emplace_back(line.substr(0, eq), eq == std::string::npos ? "" : line.substr(eq + 1));
    start = end + 1;
  }
  return fields;
}

// "seed: checkpoint 7, this render 8; scene_hash: checkpoint ..., this render ..."
std::string fingerprint_differences(const std::string &stored, const std::string &current) {
  const auto a = fingerprint_fields(stored), b = fingerprint_fields(current);
  const auto find = [](const auto &fields, const std::string &key) -> const std::string * {
    for (const auto &[k, v] : fields)
      if (k == key) return &v;
    return nullptr;
  };
  std::vector<std::string> keys;
  for (const auto *fields : {&a, &b})
    for (const auto &[k, v] : *fields)
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  std::string out;
  for (const std::string &k : keys) {
    const std::string *x = find(a, k), *y = find(b, k);
    if (x && y && *x == *y) continue;
    out += (out.empty() ? "" : "; ") + k + ": checkpoint '" + (x ? *x : "(none)") + "', this render '" +
           (y ? *y : "(none)") + "'";
  }
  return out.empty() ? "the fingerprints differ" : out;
}

std::string element_list(const std::vector<std::pair<std::string, uint32_t>> &elements) {
  std::string out;
  for (const auto &[name, channels] : elements)
    out += (out.empty() ? "" : ", ") + shown(name) + " (" + std::to_string(channels) + ")";
  return out;
}

}  // namespace

Status write_checkpoint(const Film &film, const std::string &path, const CheckpointInfo &info) {
  if (film.has_pending_splats())
    return checkpoint_error(path, "the film has splats not merged into its sums");
  if (info.integrator.size() > kMaxStringBytes || info.fingerprint.size() > kMaxStringBytes ||
      info.states.size() > kMaxElements)
    return checkpoint_error(path, "the integrator id or fingerprint is too long");
  return write_atomically(path, [&](const std::string &tmp) -> Status {
    File f(std::fopen(tmp.c_str(), "wb"));
    if (!f) return Error{"cannot create '" + tmp + "': " + std::strerror(errno)};
    Writer w(f.get());
    w.bytes(kMagic.data(), kMagic.size());
    w.u32(kCheckpointVersion);
    w.u32(film.width());
    w.u32(film.height());
    w.u64(film.iterations());
    w.u64(info.seed);
    w.u64(film.nonfinite_count());
    w.f64(info.seconds);
    w.str(info.integrator);
    w.str(info.fingerprint);
    const std::vector<int32_t> ids = film.active_elements();
    w.u32(static_cast<uint32_t>(ids.size()));
    for (int32_t id : ids) {
      w.str(film.element_name(id));
      w.u32(film.element_channels(id));
      w.doubles(film.sums(id));
    }
    w.u32(static_cast<uint32_t>(info.states.size()));
    for (const PluginState &st : info.states) {
      w.str(st.plugin);
      w.blob(st.bytes);
    }
    w.finish();
    if (!w.ok()) return Error{std::string("write error: ") + std::strerror(errno)};
    if (std::fclose(f.release()) != 0) return Error{std::string("write error: ") + std::strerror(errno)};
    return Ok{};
  });
}

Status read_checkpoint(Film &film, const std::string &path, CheckpointInfo &info) {
  auto read = read_all(path);
  if (!read) return read.error();
  Stored &s = read.value();

  if (s.width != film.width() || s.height != film.height()) {
    return checkpoint_error(path, "it was made for a " + std::to_string(s.width) + "x" +
                                      std::to_string(s.height) + " image; this render is " +
                                      std::to_string(film.width()) + "x" + std::to_string(film.height()));
  }
  if (s.info.integrator != info.integrator) {
    return checkpoint_error(path, "it was made with integrator '" + shown(s.info.integrator) +
                                      "'; this render uses '" + info.integrator + "'");
  }
  if (s.info.seed != info.seed) {
    return checkpoint_error(path, "it was made with seed " + std::to_string(s.info.seed) +
                                      "; this render uses " + std::to_string(info.seed));
  }
  if (s.info.fingerprint != info.fingerprint) {
    return checkpoint_error(path, "it was made for a different render (" +
                                      fingerprint_differences(s.info.fingerprint, info.fingerprint) + ")");
  }
  std::vector<std::pair<std::string, uint32_t>> stored, current;
  for (const StoredElement &e : s.elements) stored.emplace_back(e.name, e.channels);
  const std::vector<int32_t> ids = film.active_elements();
  for (int32_t id : ids) current.emplace_back(film.element_name(id), film.element_channels(id));
  auto sorted = [](auto v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  if (sorted(stored) != sorted(current)) {
    return checkpoint_error(
        path, "it holds the elements " + element_list(stored) + "; this render has " + element_list(current));
  }

  // Validated: only now is the film changed.
  for (int32_t id : ids) {
    const auto it = std::find_if(s.elements.begin(), s.elements.end(),
                                 [&](const StoredElement &e) { return e.name == film.element_name(id); });
    const std::span<double> sums = film.sums(id);
    std::copy(it->sums.begin(), it->sums.end(), sums.begin());
  }
  film.set_iterations(s.info.iterations);
  film.set_nonfinite_count(s.nonfinite);
  info.iterations = s.info.iterations;
  info.seconds = s.info.seconds;
  info.states = std::move(s.info.states);
  return Ok{};
}

Expected<CheckpointInfo> peek_checkpoint(const std::string &path) {
  uint64_t size = 0;
  auto file = open_for_reading(path, size);
  if (!file) return file.error();
  Reader r(file->get(), size);
  Stored s;
  if (Status h = read_header(path, r, s); !h) return h.error();
  return s.info;
}

}  // namespace nimbus
