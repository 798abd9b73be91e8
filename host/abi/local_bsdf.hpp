// The BSDF at an interaction as the BSDF services (bsdf_service.cpp, spectral_service.cpp) see it: the
// material's BSDF (built per point for textured materials), its shading frame, and the factor f carries
// for importance transport and normal maps.
#pragma once

#include <optional>

#include "abi/host_services.hpp"

namespace nimbus::abi_bsdf {

inline TexturedMaterials::SurfacePoint surface_point(const nimbus_interaction_t *ix) {
  return {Vec3f::load(ix->ng), Vec3f::load(ix->ns), Vec3f::load(ix->dpdu), Vec3f::load(ix->dpdv),
          Vec2f{ix->uv[0], ix->uv[1]}};
}

// The adjoint BSDF's shading-normal factor |wo.ns||wi.ng| / (|wo.ng||wi.ns|) for importance transport
// with shading normal ns (wo: where the particle came from).
inline float adjoint_factor(const nimbus_interaction_t *ix, const Vec3f &ns, const Vec3f &wo,
                            const Vec3f &wi) {
  const Vec3f ng = Vec3f::load(ix->ng);
  const float den = std::abs(dot(wo, ng)) * std::abs(dot(wi, ns));
  return den > 0 ? std::abs(dot(wo, ns)) * std::abs(dot(wi, ng)) / den : 0.0f;
}

// The BSDF built with the scene for ix's material, or null when textures make it vary over the surface.
inline const Bsdf *untextured_bsdf(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  const World &world = world_of(host);
  const TexturedMaterials *textured = world.textures.get();
  return textured && textured->textured(ix->material) ? nullptr : &world.bsdfs[ix->material];
}

// The diffuse BSDF of an untextured material at ix, or null. Its value and densities read only the
// directions' cosines to the shading normal (cosine_only): evaluating it needs no shading frame.
inline const DiffuseBsdf *plain_diffuse(const nimbus_host_t *host, const nimbus_interaction_t *ix) {
  const Bsdf *b = untextured_bsdf(host, ix);
  return b ? b->diffuse() : nullptr;
}

// w in a shading frame with normal n as a BSDF that reads only cosines sees it: the z component is
// Frame::to_local's bit for bit, the other two are left out.
inline Vec3f cosine_only(const Vec3f &w, const Vec3f &n) { return {0, 0, dot(w, n)}; }

// The BSDF and shading frame at an interaction. Untextured materials use the BSDF built with the scene (no
// lookups, no copies); textured ones get theirs built here from texture lookups at ix->uv, and a normal map
// replaces the shading normal.
class Local {
 public:
  Local(const nimbus_host_t *host, const nimbus_interaction_t *ix) : ns_(Vec3f::load(ix->ns)) {
    bsdf_ = untextured_bsdf(host, ix);
    if (!bsdf_) {
      const TexturedMaterials &textured = *world_of(host).textures;
      const TexturedMaterials::Shading &s = own_.emplace(textured.shade(ix->material, surface_point(ix)));
      bsdf_ = &s.bsdf;
      ns_ = s.ns;
      mapped_ = s.normal_mapped;
    }
    frame_ = Frame::from_normal_tangent(ns_, Vec3f::load(ix->dpdu));
  }
  Local(const Local &) = delete;  // bsdf_ may point into the object

  const Bsdf &bsdf() const { return *bsdf_; }
  const Frame &frame() const { return frame_; }

  // What f is multiplied by on its way out, for a pair (wo, wi) in world space.
  // Importance transport: the adjoint BSDF with shading normals is not symmetric, so it carries
  // |wo.ns||wi.ng| / (|wo.ng||wi.ns|) (Veach 1997, section 5.3; wo: where the particle came from).
  // Normal maps: integrators multiply f by |wi.ns| with the interaction's ns, while the BSDF shades with
  // the mapped normal n'; f carries |wi.n'| / |wi.ns| so that the product is f |wi.n'|.
  float factor(const nimbus_interaction_t *ix, nimbus_transport_mode_t mode, const Vec3f &wo,
               const Vec3f &wi) const {
    float k = mode == NIMBUS_MODE_IMPORTANCE ? adjoint_factor(ix, ns_, wo, wi) : 1.0f;
    if (mapped_) {
      const float den = std::abs(dot(wi, Vec3f::load(ix->ns)));
      k *= den > 0 ? std::abs(dot(wi, ns_)) / den : 0.0f;
    }
    return k;
  }
  bool needs_factor(nimbus_transport_mode_t mode) const { return mode == NIMBUS_MODE_IMPORTANCE || mapped_; }

 private:
  const Bsdf *bsdf_ = nullptr;
  std::optional<TexturedMaterials::Shading> own_;  // textured materials only
  Vec3f ns_;
  bool mapped_ = false;
  Frame frame_;
};

// The BSDF for questions that do not depend on direction (lobes, min roughness): only a roughness texture
// makes those vary over the surface.
template <class F>
auto at_point(const nimbus_host_t *host, const nimbus_interaction_t *ix, F &&query) {
  const World &world = world_of(host);
  const TexturedMaterials *textured = world.textures.get();
  if (textured && textured->varies_lobes(ix->material))
    return query(textured->shade(ix->material, surface_point(ix)).bsdf);
  return query(world.bsdfs[ix->material]);
}

inline TransportMode mode_of(nimbus_transport_mode_t m) {
  return m == NIMBUS_MODE_IMPORTANCE ? TransportMode::Importance : TransportMode::Radiance;
}

}  // namespace nimbus::abi_bsdf
