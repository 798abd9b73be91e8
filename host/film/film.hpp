// The film: a registry of render elements, their per-pixel accumulation, and the image writers.
//
// Elements are declared, not assumed: integrators register what they can produce, the scene or the CLI
// requests what it wants, and allocate() gives buffers only to elements that are both. Beauty (id 0,
// RGB) is always registered and active. Sums are kept in double so that millions of samples per pixel
// still average to the last float bit; the resolved value of a pixel is (accumulated + splatted) / N,
// where N is the number of completed iterations.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nimbus/nimbus.hpp>

#include "core/expected.hpp"

namespace nimbus {

class Film {
 public:
  static constexpr int32_t kBeauty = 0;
  static constexpr int32_t kInvalid = -1;
  static constexpr uint32_t kAverage = 0;  // flags, as NIMBUS_ELEMENT_AVERAGE / _SPLAT in sdk film.h
  static constexpr uint32_t kSplat = 1;

  Film(uint32_t width, uint32_t height);
  Film(const Film &) = delete;
  Film &operator=(const Film &) = delete;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // ---- setup: main thread, not rendering ----------------------------------------------------------
  // `name` matches [a-z0-9_.]+ (dots separate segments, as in "lightmix.key"); channels 1 or 3. Returns
  // the new id, the existing id when `name` is already registered with the same channel count (flags
  // are merged), or kInvalid.
  int32_t register_element(std::string_view name, uint32_t channels, uint32_t flags);
  // The scene or CLI wants element `name` in the output. Checked by allocate(), which knows the registry.
  void request(std::string_view name);
  // Gives buffers to every element that is registered and requested; may be called again after more
  // requests. A requested name nobody registered is an error and allocates nothing.
  Status allocate();
  // The render region [x0, x1) x [y0, y1): splats outside it are dropped, as the camera renders only its
  // pixels (the whole film until set).
  void set_region(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
    region_[0] = x0, region_[1] = y0, region_[2] = x1, region_[3] = y1;
  }
  // Splat buffers are per worker so render threads never share a cache line; call before rendering.
  // Pending (unmerged) splats are merged first so none are lost.
  void set_worker_count(uint32_t workers);

  // ---- queries: any thread ------------------------------------------------------------------------
  bool is_active(int32_t id) const {
    return id >= 0 && static_cast<size_t>(id) < elements_.size() && elements_[id].active;
  }
  const std::string &element_name(int32_t id) const { return elements_.at(id).name; }
  uint32_t element_channels(int32_t id) const { return elements_.at(id).channels; }
  std::vector<int32_t> active_elements() const;
  // Sum buffers plus per-worker splat buffers, in bytes: lets tests prove "no request, no buffer".
  size_t allocated_bytes() const;
  uint64_t nonfinite_count() const { return nonfinite_.load(std::memory_order_relaxed); }

  // ---- render threads -----------------------------------------------------------------------------
  // Adds `v` (element_channels floats) to pixel (x, y). Callers own disjoint pixels, so there is no
  // synchronisation. A sample with any non-finite channel is dropped whole and counted, so a single
  // NaN can never poison a pixel for the rest of the render. Inactive elements ignore the call.
  void accumulate(int32_t el, uint32_t x, uint32_t y, const float *v);
  // Adds `v` at raster position (fx, fy), any pixel, into worker `worker`'s private buffer (allocated on
  // first use). Only elements registered with kSplat take splats; positions off the film are dropped.
  void splat(uint32_t worker, int32_t el, float fx, float fy, const float *v);

  // ---- main thread, between iterations ------------------------------------------------------------
  // Folds every worker's splats into the sums. Per pixel, the workers are summed in index order into a
  // double before the single addition to the running sum, so how splats were distributed over workers
  // does not change the result (float inputs summed in double are exact unless their magnitudes span
  // more than ~2^29).
  void merge_splats();
  void end_iteration() { ++iterations_; }
  uint64_t iterations() const { return iterations_; }
  void set_iterations(uint64_t n) { iterations_ = n; }
  // Splats not yet folded into the sums: a checkpoint taken now would lose them.
  bool has_pending_splats() const;
  // Drops the splats not yet folded into the sums: those of an iteration a plugin failed in.
  void discard_splats();
  // A film with the same elements and sums, without splat buffers: what the output writers read while
  // the render threads may still write into this one. Main thread, or any thread once no tile starts.
  std::unique_ptr<Film> snapshot() const;

  // ---- checkpoints (main thread, between iterations) ----------------------------------------------
  // The running double sums of element `el` (width * height * channels, channel-interleaved; empty when
  // inactive). A checkpoint saves and restores them bit for bit, so a resumed render adds its samples
  // to exactly the values an uninterrupted one would have.
  std::span<const double> sums(int32_t el) const;
  std::span<double> sums(int32_t el);
  void set_nonfinite_count(uint64_t n) { nonfinite_.store(n, std::memory_order_relaxed); }

  // Channel-interleaved image of element `el` (width * height * channels floats), sums / N; zeros
  // before the first iteration, empty for an inactive element.
  std::vector<float> resolve(int32_t el) const;

  // ---- output (main thread; both write `<path>.tmp-<pid>` and rename, so `path` is never truncated) --
  // One multi-layer float EXR, zip-compressed: beauty as R, G, B; element e as e.R, e.G, e.B or e.Y.
  // Strings become "nimbus:<key>" string attributes; numbers become "nimbus:<key>" int attributes when
  // integral and within int32, double attributes otherwise (exact round trip either way).
  Status write_exr(const std::string &path,
                   const std::vector<std::pair<std::string, std::string>> &string_meta,
                   const std::vector<std::pair<std::string, double>> &numeric_meta) const;
  // Beauty through the OCIO config's default display/view from its scene_linear role, as 8-bit RGB PNG.
  Status write_png(const std::string &path, const std::string &ocio_config_path) const;

 private:
  struct alignas(sdk::kCacheLineBytes)
      WorkerSplats {          // one cache line per worker: the dirty flag is written hot
    std::vector<double> sum;  // empty until the worker's first splat into this element
    bool dirty = false;
  };
  struct Element {
    Element(std::string_view name_, uint32_t channels_, uint32_t flags_)
        : name(name_), channels(channels_), flags(flags_) {}
    std::string name;
    uint32_t channels;
    uint32_t flags;
    bool active = false;
    std::vector<double> sum;  // width * height * channels once active
    std::vector<WorkerSplats> workers;
  };

  size_t pixel_count() const { return size_t(width_) * height_; }
  void activate(Element &e);

  uint32_t width_, height_;
  uint32_t region_[4] = {0, 0, ~0u, ~0u};  // x0, y0, x1, y1 (clipped to the film by splat)
  uint32_t worker_count_ = 1;
  uint64_t iterations_ = 0;
  std::vector<Element> elements_;
  std::vector<std::string> requested_;
  std::atomic<uint64_t> nonfinite_{0};
};

// The writers behind Film::write_exr and Film::write_png, for images that do not live in a film
// (`nimbus lightmix` rewrites an EXR it read). One layer's channels, interleaved, width * height pixels.
struct ExrLayer {
  std::vector<std::string> channel_names;  // full names: "R", "G", "B" for beauty, "albedo.R", "depth.Y"
  const float *pixels = nullptr;
};
// One multi-layer float EXR as Film::write_exr describes (compression, metadata keys and types), written
// atomically.
Status write_layered_exr(const std::string &path, uint32_t width, uint32_t height,
                         const std::vector<ExrLayer> &layers,
                         const std::vector<std::pair<std::string, std::string>> &string_meta,
                         const std::vector<std::pair<std::string, double>> &numeric_meta);
// Scene-linear RGB (width * height, interleaved) through the OCIO display transform to an 8-bit PNG,
// written atomically, as Film::write_png.
Status write_display_png(const std::string &path, std::vector<float> rgb, uint32_t width, uint32_t height,
                         const std::string &ocio_config_path);

// The OCIO config used for PNG output, in order: $NIMBUS_OCIO_CONFIG if set; the install or build
// layout `<dir of the executable>/../share/nimbus/ocio/config.ocio` if it exists; the source tree's
// host/film/ocio/config.ocio.
std::string default_ocio_config_path();

}  // namespace nimbus
