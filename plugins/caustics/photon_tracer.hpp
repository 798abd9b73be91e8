// Photon paths (solver spec section 4): emission by the solver's light selection and projection maps,
// storage at rough vertices after a sharp one, termination after two consecutive rough vertices, and the
// photon-side MIS state of every stored photon.
#pragma once

#include <nimbus/nimbus.hpp>

#include <algorithm>
#include <vector>

#include <nimbus/cpp/light_selection.hpp>
#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/path_services.hpp>
#include <nimbus/cpp/rng.hpp>
#include <nimbus/cpp/spectral_path.hpp>
#include <nimbus/nimbus.hpp>

#include "emitters.hpp"
#include "importance_map.hpp"
#include "light_paths.hpp"
#include "mis.hpp"
#include "path_use.hpp"
#include "photon_map.hpp"
#include "photon_splats.hpp"
#include "schedule.hpp"
#include "sharpness.hpp"

namespace nimbus::caustics {

// A photon path a guide's chain traced (guided_pass.cpp): its photons in the chunk and what its weight
// needs (spec 6.3).
struct GuidedPath {
  uint32_t first = 0, count = 0;  // photons [first, first + count) of the chunk
  float target = 0;               // T
  bool uniform = false;           // traced as a uniform sample
  uint64_t multiplicity = 0;      // chain steps credited
};

// The output of one photon-pass task (or guide chain); a cache line of its own, since tasks on different
// workers update their chunks on every path.
struct alignas(sdk::kCacheLineBytes) PhotonChunk {
  std::vector<Photon> photons;
  std::vector<GuidedPath> guided;       // a chain's paths, in the order traced (guided passes only)
  std::vector<uint32_t> path_light;     // every traced path's light (path_use.hpp), in the order traced
  std::vector<uint32_t> path_emission;  // and its emission-map cell (emission_map.hpp)
  std::vector<PhotonSplat> splats;      // its photons' connections to the lens (photon_splats.hpp)
  uint64_t paths = 0;                   // completed paths
  uint64_t work = 0;                    // budget work units (schedule.hpp)
  // Empty for the next pass, keeping the buffers' memory.
  void reset() {
    photons.clear(), guided.clear(), path_light.clear(), path_emission.clear(), splats.clear();
    paths = 0, work = 0;
  }
};

// Random-number stream of photon path p of photon pass j: derive(p, j, kStreamPhoton).
inline constexpr uint64_t kStreamPhoton = 0x70686f746f6e;  // "photon"

// The numbers a photon path consumes, in a fixed order (emission, then four per vertex): the host's
// stream of an unguided path, or a guide's primary-sample vector u (spec 6.3), so that a path is a
// deterministic function of u. kPhotonDims covers the longest path; a path's scene time, when photons
// carry one (photon_windows.hpp), is one more dimension after them, so a static scene's paths are unchanged.
inline constexpr uint32_t kPhotonDims = 10 + 4 * kPhotonMaxVertices;
inline uint32_t photon_dims(bool timed) { return kPhotonDims + (timed ? 1u : 0u); }
class PhotonSamples {
 public:
  explicit PhotonSamples(const nimbus_rng_t &rng) : rng_(rng), rng_start_(rng) {}
  PhotonSamples(const float *u, uint32_t dims) : u_(u), dims_(dims) {}
  float next() {
    if (!u_) return next_uniform(rng_);
    return used_ < std::min(dims_, kPhotonDims) ? u_[used_++] : 0.5f;
  }
  // The number that picks the path's scene time: the guide's last dimension, or for the host's stream a
  // hash of the stream's start (the stream's own numbers stay those of a static scene).
  float time_number() const {
    if (u_) return dims_ > kPhotonDims ? u_[kPhotonDims] : 0.5f;
    return float(hash_keys({rng_start_.state, rng_start_.inc, 0x74696d65}) >> 40) * 0x1p-24f;
  }
  // The stream's paths stratify their emission along the pass (emission_strata.hpp); a guide's u is
  // used as given.
  bool from_stream() const { return u_ == nullptr; }

 private:
  nimbus_rng_t rng_{};
  nimbus_rng_t rng_start_{};
  const float *u_ = nullptr;
  uint32_t dims_ = 0, used_ = 0;
};

// A vertex's unoccluded connection to the lens (PhotonTracer::link_to_lens).
struct LensLink {
  float raster[2];
  Rgb value;       // beta * f * |cos| * W at the lens: its light at the film before 1 / N and MIS
  float w_cam;     // omega^C_1: pdf that a camera path at the vertex samples its incoming direction
  double density;  // C_1: the camera paths' density of first vertices there (mis.hpp, camera_density)
  float length;    // distance from the lens
  bool same_side;  // the lens sees the side the vertex's light arrived on (a merge there finds it)
};

// A vertex of a path from a light, photon or light path alike: the hit and what the light side's MIS
// and the next bounce read of it.
struct LightSideVertex {
  nimbus_interaction_t ix;
  Vec3f wo, ng;    // towards where the path came from; the geometric normal
  float c_in = 0;  // |cos| of the arrival at ng
  nimbus_lobe_t lobes = 0;
  bool rough = false;        // not sharp (sharpness.hpp): photons are stored and light paths connect here
  bool smooth_only = false;  // no diffuse or glossy lobe: NEE and connections see nothing here
};

// Traces photon paths against the scene, reading only state that is fixed during a photon pass.
class PhotonTracer {
 public:
  // selection: the camera paths' NEE light selection (the photon's first vertex weighs NEE from it).
  // scene: the photons' view of it, timed when the clock is. spectral: the host's spectral service when
  // the scene disperses light (sdk::PathSpectrum::needed), else null.
  PhotonTracer(const nimbus_host_t *host, const sdk::PathServices &svc, const sdk::LightSelection &selection,
               const EmitterSet &emitters, uint32_t max_depth, const sdk::TimedScene &scene,
               const nimbus_host_spectral_v1_t *spectral)
      : h_(host),
        svc_(svc),
        selection_(selection),
        emitters_(emitters),
        max_depth_(max_depth),
        scene_(scene),
        spectral_(spectral) {}

  // [main-thread] Connects every stored photon to the lens with `camera` (photon_splats.hpp); not
  // called, or disabled, no photon is.
  void connect_to(const SplatCamera &camera) { splat_ = camera; }

  // [main-thread] With the light-tracing technique on, photons carry their density against its
  // (light_paths.hpp); null: off.
  void light_paths_from(const LightPathEmission *lt) { lt_ = lt; }
  bool rates_light_paths() const { return lt_ != nullptr; }

  // Whether its photons carry scene times, and wavelengths after a dispersive vertex.
  bool timed() const { return scene_.timed; }
  bool dispersive() const { return spectral_ != nullptr; }

  // [render-thread] Photon path `path` of the `paths` of pass `pass` (1-based), into `out`.
  void trace(const nimbus_thread_ctx_t &ctx, uint64_t path, uint64_t paths, uint32_t pass,
             PhotonChunk &out) const;
  // [render-thread] The photon path of `samples` (for the stream's, path `path` of `paths` stratifies the
  // emission) into `out`. With an importance map, the photons carry B_importance and the return value is
  // the path's target T: the largest importance at its stored photons (spec 6.3); else 0.
  float trace(const nimbus_thread_ctx_t &ctx, PhotonSamples &samples, uint64_t path, uint64_t paths,
              const ImportanceMap *importance, PhotonChunk &out) const;
  // [render-thread] Light path `path` of the `in.merge->lt_paths` of a camera pass (light_paths.cpp): its
  // connections to the lens go to the film with their weights.
  void trace_light(const nimbus_thread_ctx_t &ctx, uint64_t path, const LightTracing &in,
                   LightTally &out) const;

 private:
  Rgb emitted(uint32_t light, const nimbus_light_emission_t &es, const Vec3f &w, float time) const;
  void connect_to_lens(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                       const Rgb &beta, float time, uint64_t key, PhotonChunk &out) const;
  bool link_to_lens(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                    const Rgb &beta, const float lens_u[2], float time, bool reflection_only,
                    const Vec3f &axis, float theta_pix, LensLink &link, uint64_t &work,
                    uint64_t ray_work) const;
  void connect_light_vertex(const nimbus_thread_ctx_t &ctx, const nimbus_interaction_t &ix, const Vec3f &wo,
                            const Rgb &beta, const PhotonMis &state, const LightVertexClass &c,
                            const float lens_u[2], const LightTracing &in, LightTally &out) const;
  Mis first_vertex_nee(const nimbus_interaction_t &ix, uint32_t light, const Emitter &em,
                       const nimbus_light_emission_t &es, const Vec3f &wo, float lp, float c_in) const;
  // The bounce loop's two halves, shared by photon paths and light paths. arrive: follows `ray` at
  // `time` to its hit, counting ray_work; false when it leaves the scene or only grazes a surface.
  bool arrive(const nimbus_thread_ctx_t &ctx, const nimbus_ray_t &ray, float time, PhotonMis &mis,
              LightSideVertex &v, uint64_t &work, uint64_t ray_work) const;
  // scatter: samples the BSDF at v with u (importance transport), carries the MIS state and beta over
  // the bounce, plays Russian roulette on its throughput with the number next() (drawn only when the
  // bounce can survive) and spawns the next ray; false when the path ends. stored, nee_term,
  // importance: PhotonMis::scatter's.
  template <class Next>
  bool scatter(const LightSideVertex &v, const sdk::PathSpectrum &spectrum, const float u[3], Next &&next,
               bool stored, Mis nee_term, float importance, PhotonMis &mis, Rgb &beta,
               nimbus_ray_t &ray) const {
    float wo_arr[3];
    v.wo.store(wo_arr);
    nimbus_bsdf_sample_t bs;
    spectrum.sample(&v.ix, wo_arr, u, NIMBUS_MODE_IMPORTANCE, &bs);
    if (!(bs.pdf > 0)) return false;
    const Vec3f wi = Vec3f::load(bs.wi);
    const bool delta = has(bs.lobe, NIMBUS_LOBE_SPECULAR);
    mis.scatter(std::abs(dot(v.ng, wi)), bs.pdf, bs.pdf_rev, v.rough, stored, delta ? 0.0 : nee_term,
                importance);
    const Rgb t = Rgb::load(bs.f) * (std::abs(dot(wi, Vec3f::load(v.ix.ns))) / bs.pdf);
    // Russian roulette on this bounce's throughput: the path's power stays roughly constant.
    const float q = std::min(1.0f, max_component(t));
    if (!(q > 0) || next() >= q) return false;
    beta *= t / q;
    if (is_black(beta) || !is_finite(beta)) return false;
    svc_.scene->spawn_ray(h_, &v.ix, bs.wi, kInfinity, &ray);
    return true;
  }

  const nimbus_host_t *h_;
  const sdk::PathServices &svc_;
  const sdk::LightSelection &selection_;
  const EmitterSet &emitters_;
  uint32_t max_depth_;
  sdk::TimedScene scene_;
  const nimbus_host_spectral_v1_t *spectral_;
  SplatCamera splat_;
  const LightPathEmission *lt_ = nullptr;
};

}  // namespace nimbus::caustics
