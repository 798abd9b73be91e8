// make_bsdf: the scene's material description becomes the right BSDF with the right parameters.
#include <gtest/gtest.h>

#include "materials/bsdf.hpp"
#include "scene/metals.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {
namespace material_test {

const Vec3f kUp(0, 0, 1);

TEST(MakeBsdf, Diffuse) {
  MaterialDesc m;
  m.type = MaterialType::Diffuse;
  m.albedo = Rgb(0.2f, 0.4f, 0.6f);
  const Bsdf b = make_bsdf(m);
  EXPECT_EQ(b.lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_DIFFUSE);
  EXPECT_EQ(b.albedo(kUp), m.albedo);
  EXPECT_NEAR(b.eval(kUp, kUp, TransportMode::Radiance).y, 0.4f / kPi, 1e-7);
  // A default Bsdf is the default material.
  EXPECT_EQ(Bsdf().albedo(kUp), make_bsdf(MaterialDesc{}).albedo(kUp));
}

TEST(MakeBsdf, ConductorRoughnessIsSquared) {
  MaterialDesc m;
  m.type = MaterialType::Conductor;
  const MetalIor gold = *find_metal("gold");
  m.eta = gold.eta, m.k = gold.k;
  m.roughness = 0.5f;
  const Bsdf b = make_bsdf(m);
  EXPECT_FLOAT_EQ(b.min_alpha(), 0.25f);
  EXPECT_EQ(b.lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_GLOSSY);
  EXPECT_EQ(b.albedo(kUp), fresnel_complex(1, gold.eta, gold.k));
  m.roughness = 0;
  EXPECT_EQ(make_bsdf(m).lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_SPECULAR);
}

TEST(MakeBsdf, MirrorIgnoresFresnel) {
  MaterialDesc m;
  m.type = MaterialType::Conductor;
  m.use_reflectance = true;
  m.reflectance = Rgb(0.9f, 0.8f, 0.7f);
  const Bsdf b = make_bsdf(m);
  const Vec3f grazing = normalize(Vec3f(1, 0, 0.05f)), wo = normalize(Vec3f(0.3f, 0, 1));
  EXPECT_EQ(b.albedo(kUp), m.reflectance);
  const BsdfSample s = b.sample(wo, 0.5f, {0.5f, 0.5f}, TransportMode::Radiance);
  EXPECT_NEAR(s.f.x * abs_cos_theta(s.wi), 0.9f, 1e-6);
  const BsdfSample g = b.sample(grazing, 0.5f, {0.5f, 0.5f}, TransportMode::Radiance);
  EXPECT_NEAR(g.f.z * abs_cos_theta(g.wi), 0.7f, 1e-6);
}

TEST(MakeBsdf, Dielectric) {
  MaterialDesc m;
  m.type = MaterialType::Dielectric;
  m.ior = 1.5f;
  m.roughness = 0.2f;
  const Bsdf b = make_bsdf(m);
  EXPECT_FLOAT_EQ(b.min_alpha(), 0.04f);
  EXPECT_EQ(b.lobes(), NIMBUS_LOBE_REFLECTION | NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_GLOSSY);
  m.ior = 1;
  EXPECT_EQ(make_bsdf(m).lobes(), NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
  // Out-of-range input still gives a usable BSDF (the parser reports the error; rendering must not crash).
  m.ior = -2;
  m.roughness = 7;
  const Bsdf odd = make_bsdf(m);
  EXPECT_EQ(odd.lobes(), NIMBUS_LOBE_TRANSMISSION | NIMBUS_LOBE_SPECULAR);
}

}  // namespace material_test
}  // namespace nimbus
