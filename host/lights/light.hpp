// The lights of a scene as value types behind one variant: point, spot, area (any emissive shape), sun
// (a distant disk, or a delta direction) and environment (uniform colour, lat-long map, or analytic
// sky baked into a map). Every routine follows the conventions of sdk/include/nimbus/lights.h.
#pragma once

#include <nimbus/lights.h>

#include <memory>
#include <variant>

#include <nimbus/cpp/alias_table.hpp>
#include <nimbus/cpp/distribution.hpp>
#include <nimbus/cpp/math.hpp>
#include "core/motion_transform.hpp"
#include "geometry/geometry_scene.hpp"

namespace nimbus {

// What infinite lights need to know of the scene: the bounding sphere their photons start from.
struct LightScene {
  const GeometryScene *geometry = nullptr;
  Vec3f center;
  float radius = 1;
};

struct PointLight {
  Vec3f position;
  Rgb intensity;  // W/sr
};

struct SpotLight {
  Vec3f position;
  Frame frame;                                       // n = the axis
  Rgb intensity;                                     // W/sr on the axis
  float cos_falloff_start = 1, cos_falloff_end = 0;  // full intensity inside start, zero outside end
  float falloff(float cos_theta) const;
};

struct AreaLight {
  uint32_t shape = 0;
  Rgb radiance;
  bool two_sided = false;
  AliasTable triangles;  // by area, for mesh shapes
};

struct SunLight {
  Vec3f to_sun;              // unit, towards the sun
  Frame frame;               // n = to_sun
  Rgb radiance;              // inside the disk (cone); for a delta sun: the irradiance
  float cos_half_angle = 1;  // 1 = delta direction
  bool is_delta() const { return cos_half_angle >= 1; }
};

struct EnvironmentLight {
  Rgb color;             // uniform part (used when the map is empty)
  std::vector<Rgb> map;  // lat-long, row-major, width x height, v = 0 at +z; input of finish_build()
  uint32_t width = 0, height = 0;
  float rotate_radians = 0;  // about +z
  // Radiance interpolated between texel centres (baked skies: a smooth function on a coarse map) rather
  // than the nearest texel (photographed maps, shown as they are).
  bool bilinear = false;
  // A texel's radiance beside its sampling density in (u, v): an escaped ray looks up both (radiance,
  // then the MIS pdf), so they share a cache line where two separate tables would miss twice.
  struct Texel {
    Rgb radiance;
    float pdf_uv = 0;
  };
  std::vector<Texel> texels;
  Distribution2D distribution;  // luminance x sin(theta), for sampling

  bool uniform() const { return texels.empty(); }
  // Builds the sampling distribution and the texels from `map` (which it then releases); returns the
  // integral of the luminance over the sphere.
  double finish_build();
  Rgb lookup(const Vec3f &dir) const;
  Rgb interpolate(float u, float v) const;  // bilinear radiance at lat-long (u, v)
  float pdf(const Vec3f &dir) const;
};

struct Light {
  std::variant<PointLight, SpotLight, AreaLight, SunLight, EnvironmentLight> kind;
  uint32_t group = 0;
  float power = 0;  // luminance of the emitted flux (infinite lights: through the scene's disk)
  // Point and spot lights: rigid motion over the shutter (null: the light holds still).
  std::shared_ptr<const MotionTransform> motion;
  bool infinite() const {
    return std::holds_alternative<SunLight>(kind) || std::holds_alternative<EnvironmentLight>(kind);
  }
};

void light_sample_incident(const Light &light, const LightScene &scene, const nimbus_interaction_t &ref,
                           const float u[2], nimbus_light_incident_t &out);
float light_pdf_incident(const Light &light, const LightScene &scene, const nimbus_interaction_t &ref,
                         const Vec3f &wi, const nimbus_interaction_t *on_light);
Rgb light_eval_emitted(const Light &light, const nimbus_interaction_t &on_light, const Vec3f &wo);
// Radiance an infinite light sends back along an escaped ray with direction `dir`.
Rgb light_eval_infinite(const Light &light, const Vec3f &dir);
void light_sample_emission(const Light &light, const LightScene &scene, const float u[4],
                           nimbus_light_emission_t &out);
// What the light emits from p (area lights: with normal *n) along dir, and the densities with which
// light_sample_emission produces that photon (conventions of nimbus_host_lights_v1_t's eval_emission and
// pdf_emission). n may be null: area lights then emit nothing and have pdf_dir 0.
Rgb light_eval_emission(const Light &light, const Vec3f *n, const Vec3f &dir);
void light_pdf_emission(const Light &light, const LightScene &scene, const Vec3f *n, const Vec3f &dir,
                        float &pdf_pos, float &pdf_dir);
void light_fill_info(const Light &light, const LightScene &scene, nimbus_light_info_t &info);

// The light where it is at scene time `time`: `light` itself when it holds still, else `moved`, filled
// with its kind carried by the motion (moving_light.cpp).
const Light &light_at(const Light &light, float time, Light &moved);
// A moving light's info over the whole shutter: bounds of its sweep, and a spot's cone widened to every
// axis it takes (moving_light.cpp). `info` holds the light's info at rest.
void widen_info_over_motion(const Light &light, nimbus_light_info_t &info);

// Per-kind helpers (one file each).
void area_sample_incident(const AreaLight &a, const GeometryScene &geo, const Vec3f &p, const float u[2],
                          nimbus_light_incident_t &out);
float area_pdf_incident(const AreaLight &a, const GeometryScene &geo, const Vec3f &p, const Vec3f &wi,
                        const nimbus_interaction_t &on_light);
void area_sample_emission(const AreaLight &a, const GeometryScene &geo, const float u[4],
                          nimbus_light_emission_t &out);
void area_pdf_emission(const AreaLight &a, const GeometryScene &geo, const Vec3f *n, const Vec3f &dir,
                       float &pdf_pos, float &pdf_dir);
void area_fill_info(const AreaLight &a, const GeometryScene &geo, nimbus_light_info_t &info);

}  // namespace nimbus
