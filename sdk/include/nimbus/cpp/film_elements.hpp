// The render elements of a camera-path integrator: registered with the film in prepare, reduced to the
// requested ones in begin_render (no work for an element nobody asked for), and written per sample from
// a SampleRecord. Requires C++20.
#pragma once

#include <nimbus/film.h>
#include <nimbus/host.h>

#include <nimbus/cpp/sample_record.hpp>

namespace nimbus::sdk {

class SampleElements {
 public:
  // [main-thread, !rendering] Registers direct, indirect, emission, albedo, normal, depth and, when
  // `diverted_name` is given, the integrator's own lighting element (name borrowed).
  void register_all(const nimbus_host_film_v1_t *film, const nimbus_host_t *h,
                    const char *diverted_name = nullptr) {
    registered_ = {};
    registered_.direct = film->register_element(h, "direct", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.indirect = film->register_element(h, "indirect", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.emission = film->register_element(h, "emission", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.albedo = film->register_element(h, "albedo", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.normal = film->register_element(h, "normal", 3, NIMBUS_ELEMENT_AVERAGE);
    registered_.depth = film->register_element(h, "depth", 1, NIMBUS_ELEMENT_AVERAGE);
    if (diverted_name)
      registered_.diverted = film->register_element(h, diverted_name, 3, NIMBUS_ELEMENT_AVERAGE);
  }

  // [main-thread] Requests are known once the render begins: keeps the ids of active elements only.
  void activate(const nimbus_host_film_v1_t *film, const nimbus_ext_lightmix_v1_t *lightmix,
                const nimbus_host_t *h) {
    const auto active = [&](nimbus_element_t e) {
      return film->is_active(h, e) ? e : NIMBUS_ELEMENT_INVALID;
    };
    ids_.direct = active(registered_.direct);
    ids_.indirect = active(registered_.indirect);
    ids_.emission = active(registered_.emission);
    ids_.albedo = active(registered_.albedo);
    ids_.normal = active(registered_.normal);
    ids_.depth = active(registered_.depth);
    ids_.diverted = active(registered_.diverted);
    ids_.split_light = ids_.direct >= 0 || ids_.indirect >= 0 || ids_.emission >= 0 || ids_.diverted >= 0;
    ids_.lightmix = lightmix && lightmix->is_active(h);
  }

  const ElementIds &ids() const { return ids_; }

  // [render-thread] Adds one sample's record to pixel (x, y) of the current tile.
  void write(const nimbus_host_film_v1_t *film, const nimbus_ext_lightmix_v1_t *lightmix,
             const nimbus_host_t *h, const nimbus_thread_ctx_t &ctx, uint32_t x, uint32_t y,
             const SampleRecord &rec) const {
    const auto put = [&](nimbus_element_t e, const Rgb &v) {
      if (e < 0) return;
      float a[3];
      v.store(a);
      film->accumulate(h, &ctx, e, x, y, a);
    };
    put(NIMBUS_ELEMENT_BEAUTY, rec.beauty);
    put(ids_.direct, rec.direct);
    put(ids_.indirect, rec.indirect);
    put(ids_.emission, rec.emission);
    put(ids_.diverted, rec.diverted);
    put(ids_.albedo, rec.albedo);
    put(ids_.normal, rec.normal);
    if (ids_.depth >= 0) film->accumulate(h, &ctx, ids_.depth, x, y, &rec.depth);
    for (const auto &[g, v] : rec.groups) {
      float a[3];
      v.store(a);
      lightmix->accumulate(h, &ctx, g, x, y, a);
    }
  }

 private:
  ElementIds registered_, ids_;  // all registered elements; the active ones
};

}  // namespace nimbus::sdk
