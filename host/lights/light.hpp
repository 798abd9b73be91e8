// A light of the scene. Point lights are delta positions; area lights are emissive shapes (any shape)
// found both by sampling and by rays hitting them.
#pragma once

#include <nimbus/lights.h>

#include <string>
#include <variant>

#include "core/alias_table.hpp"
#include "core/math.hpp"
#include "geometry/geometry_scene.hpp"

namespace nimbus {

struct PointLight {
  Vec3f position;
  Rgb intensity;  // W/sr
};

struct AreaLight {
  uint32_t shape = 0;  // geometry index
  Rgb radiance;        // W/(m^2 sr)
  bool two_sided = false;
  AliasTable triangles;  // by area, for mesh shapes
};

struct Light {
  std::variant<PointLight, AreaLight> kind;
  uint32_t group = 0;
  float power = 0;  // luminance of the emitted flux, W
};

// Every routine takes the geometry for the shape data of area lights.
void light_sample_incident(const Light &light, const GeometryScene &geo, const nimbus_interaction_t &ref,
                           const float u[2], nimbus_light_incident_t &out);
float light_pdf_incident(const Light &light, const GeometryScene &geo, const nimbus_interaction_t &ref,
                         const Vec3f &wi, const nimbus_interaction_t *on_light);
Rgb light_eval_emitted(const Light &light, const nimbus_interaction_t &on_light, const Vec3f &wo);
void light_sample_emission(const Light &light, const GeometryScene &geo, const float u[4],
                           nimbus_light_emission_t &out);
void light_fill_info(const Light &light, const GeometryScene &geo, nimbus_light_info_t &info);

}  // namespace nimbus
