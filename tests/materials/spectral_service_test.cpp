// nimbus.host.spectral@1 in process, as plugins see it: whether the scene disperses, the uplift (white
// is 1, homogeneous, and averaged over sampled wavelengths through the matching functions it gives the
// colour back), and the BSDF calls at one wavelength, for plain and textured materials.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <nimbus/cpp/spectral.hpp>
#include "abi/host_services.hpp"
#include "core/rgb_uplift_table.hpp"
#include "materials/spectral_bsdf.hpp"
#include "scene/scene_parser.hpp"
#include "test_helpers.hpp"
#include "textures/texture_fixtures.hpp"
#include "world/world.hpp"

namespace nimbus::test {
namespace spectral_service_test {

// A scene's world behind a host handle, and the two BSDF services on it.
class SpectralHarness {
 public:
  explicit SpectralHarness(const std::string &materials) {
    auto desc = parse_scene_string(
        "materials:\n" + materials + "objects:\n  - { shape: sphere, radius: 1, material: white }\n",
        "spectral.yaml");
    EXPECT_TRUE(desc.ok()) << (desc.ok() ? "" : desc.error().message);
    desc_ = std::move(desc.value());
    auto world = World::build(desc_, desc_.render.filter);
    EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().message);
    world_ = std::move(world.value());
    services_ = std::make_unique<HostServices>(world_.get());
    spectral_ = static_cast<const nimbus_host_spectral_v1_t *>(
        host()->get_service(host(), NIMBUS_SERVICE_SPECTRAL, 1));
    bsdf_ = static_cast<const nimbus_host_bsdf_v1_t *>(host()->get_service(host(), NIMBUS_SERVICE_BSDF, 1));
  }
  const nimbus_host_t *host() const { return services_->host(); }
  const nimbus_host_spectral_v1_t &spectral() const { return *spectral_; }
  const nimbus_host_bsdf_v1_t &bsdf() const { return *bsdf_; }
  uint64_t material(const std::string &name) const {
    for (size_t i = 0; i < desc_.materials.size(); ++i)
      if (desc_.materials[i].name == name) return i;
    ADD_FAILURE() << "no material " << name;
    return 0;
  }
  // A point of a z-up plane at uv (0.5, 0.5): the local shading frame is the world's.
  nimbus_interaction_t at(const std::string &name) const {
    nimbus_interaction_t ix{};
    ix.ng[2] = ix.ns[2] = 1, ix.dpdu[0] = 1, ix.dpdv[1] = 1, ix.uv[0] = ix.uv[1] = 0.5f, ix.eps = 1e-4f;
    ix.material = material(name);
    return ix;
  }
  float eval(const std::string &name, const Vec3f &wo, const Vec3f &wi, float lambda,
             float *pdf = nullptr) const {
    const nimbus_interaction_t ix = at(name);
    float o[3], i[3], f[3];
    wo.store(o), wi.store(i);
    spectral_->bsdf_eval(host(), &ix, o, i, NIMBUS_MODE_RADIANCE, lambda, f, pdf, nullptr);
    EXPECT_EQ(f[0], f[1]);
    EXPECT_EQ(f[0], f[2]);
    return f[0];
  }
  Rgb eval_rgb(const std::string &name, const Vec3f &wo, const Vec3f &wi) const {
    const nimbus_interaction_t ix = at(name);
    float o[3], i[3], f[3];
    wo.store(o), wi.store(i);
    bsdf_->eval(host(), &ix, o, i, NIMBUS_MODE_RADIANCE, f, nullptr, nullptr);
    return Rgb::load(f);
  }
  float uplift(const Vec3f &rgb, float lambda) const {
    float c[3];
    rgb.store(c);
    return spectral_->uplift(host(), c, lambda);
  }

 private:
  SceneDesc desc_;
  std::unique_ptr<World> world_;
  std::unique_ptr<HostServices> services_;
  const nimbus_host_spectral_v1_t *spectral_ = nullptr;
  const nimbus_host_bsdf_v1_t *bsdf_ = nullptr;
};

const std::string kPlain =
    "  white: { type: diffuse, albedo: [0.7, 0.3, 0.1] }\n  glass: { type: dielectric, ior: 1.5 }\n";
const std::string kFlint = "  flint: { type: dielectric, ior: 1.8, abbe: 25 }\n";

TEST(SpectralService, DispersiveOnlyWithADispersiveMaterial) {
  const SpectralHarness plain(kPlain);
  ASSERT_TRUE(NIMBUS_HAS_MEMBER(&plain.spectral(), nimbus_host_spectral_v1_t, bsdf_eval));
  EXPECT_EQ(plain.spectral().dispersive(plain.host()), 0u);
  // A Cauchy curve without wavelength terms is a constant index.
  const SpectralHarness flat(kPlain + "  flat: { type: dielectric, cauchy: [1.6, 0] }\n");
  EXPECT_EQ(flat.spectral().dispersive(flat.host()), 0u);
  const SpectralHarness flint(kPlain + kFlint);
  EXPECT_EQ(flint.spectral().dispersive(flint.host()), 1u);
  // lobes(): the bit on the dispersive glass only.
  for (const char *name : {"white", "glass", "flint"}) {
    const nimbus_interaction_t ix = flint.at(name);
    EXPECT_EQ((flint.bsdf().lobes(flint.host(), &ix) & NIMBUS_LOBE_DISPERSIVE) != 0,
              std::string(name) == "flint")
        << name;
  }
}

TEST(SpectralService, WhiteIsOneEverywhereAndNothingOutsideTheRange) {
  const SpectralHarness h(kPlain);
  // Greys are exact (the constant spectrum), so the documented error for white is 0: a float rounding.
  for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 1)
    EXPECT_NEAR(h.uplift(Vec3f(1), lambda), 1, 1e-7f);
  EXPECT_EQ(h.uplift(Vec3f(1), 359), 0);
  EXPECT_EQ(h.uplift(Vec3f(1), 831), 0);
  EXPECT_EQ(h.uplift(Vec3f(1), std::nanf("")), 0);
}

TEST(SpectralService, UpliftIsHomogeneous) {
  const SpectralHarness h(kPlain);
  for (const Vec3f &c :
       {Vec3f(0.7f, 0.3f, 0.1f), Vec3f(0.05f, 0.5f, 0.9f), Vec3f(3, 2, 1), Vec3f(0.2f, 0.9f, 0.4f)})
    for (float k : {1e-3f, 0.37f, 2.5f, 1e3f})
      for (float lambda : {380.0f, 450.0f, 520.0f, 600.0f, 700.0f, 820.0f}) {
        const float a = h.uplift(c * k, lambda), b = k * h.uplift(c, lambda);
        // k c / max(k c) equals c / max c to an ulp or two, which the table's trilinear
        // interpolation turns into a relative change of a few 1e-7.
        EXPECT_NEAR(a, b, 2e-6f * b + 1e-12f)
            << c.x << " " << c.y << " " << c.z << " k " << k << " at " << lambda;
      }
  // Negative channels count as 0.
  EXPECT_EQ(h.uplift({0.5f, -1, 0.2f}, 500), h.uplift({0.5f, 0, 0.2f}, 500));
}

// An albedo reflects at no wavelength more than its largest channel: saturated colours included, so a
// spectral path's throughput never grows at a surface that reflects less than it receives in RGB.
TEST(SpectralService, UpliftNeverExceedsTheLargestChannel) {
  const SpectralHarness h(kPlain);
  for (const Vec3f &c : {Vec3f(0.9f, 0.02f, 0.02f), Vec3f(0.02f, 0.9f, 0.02f), Vec3f(0.02f, 0.02f, 0.9f),
                         Vec3f(0.95f, 0.9f, 0.01f), Vec3f(1, 0, 1), Vec3f(0.5f, 0.25f, 0.1f)})
    for (float lambda = kLambdaMin; lambda <= kLambdaMax; lambda += 1)
      EXPECT_LE(h.uplift(c, lambda), max_component(c) * (1 + 1e-6f))
          << c.x << " " << c.y << " " << c.z << " at " << lambda;
}

// E[uplift(c)(lambda) w(lambda) / p(lambda)] = c with lambda ~ p: what every spectral path estimates.
TEST(SpectralService, WavelengthAverageReproducesTheColour) {
  const SpectralHarness h(kPlain);
  const int n = 1 << 20;  // sigma about 1e-3 of the colour: ten times finer than a wrong white point
  for (const Vec3f &c :
       {Vec3f(0.7f, 0.3f, 0.1f), Vec3f(0.1f, 0.4f, 0.8f), Vec3f(0.2f, 0.6f, 0.3f), Vec3f(5, 2.5f, 1)}) {
    Pcg32 rng(seed_from("average " + std::to_string(c.x) + std::to_string(c.y)));
    double sum[3] = {}, sum2[3] = {};
    for (int i = 0; i < n; ++i) {
      const float lambda = sample_visible_wavelength(rng.uniform());
      const Vec3f x = spectral_rgb_weight(lambda) * (h.uplift(c, lambda) / visible_wavelength_pdf(lambda));
      for (int k = 0; k < 3; ++k) sum[k] += x[k], sum2[k] += double(x[k]) * x[k];
    }
    for (int k = 0; k < 3; ++k) {
      const double mean = sum[k] / n, sigma = std::sqrt(std::max(0.0, sum2[k] / n - mean * mean) / n);
      std::printf("colour %g %g %g channel %d: mean %.5f, sigma %.2e, off by %.2f sigma\n", c.x, c.y, c.z, k,
                  mean, sigma, (mean - c[k]) / sigma);
      EXPECT_NEAR(mean, c[k], 4 * sigma) << c.x << " " << c.y << " " << c.z << " channel " << k;
    }
  }
}

TEST(SpectralService, BsdfCallsAtOneWavelength) {
  const SpectralHarness h(kPlain + kFlint);
  const Vec3f wo = normalize(Vec3f(0.3f, 0.2f, 0.9f)), wi = normalize(Vec3f(-0.4f, 0.1f, 0.8f));
  for (float lambda : {420.0f, 550.0f, 680.0f}) {
    // Diffuse: uplift(albedo) / pi in all channels, with the RGB pdf.
    float pdf = 0;
    const float f = h.eval("white", wo, wi, lambda, &pdf);
    const float expected = uplift(Vec3f(0.7f, 0.3f, 0.1f), lambda) * kInvPi;
    EXPECT_NEAR(f, expected, 1e-5f * expected) << lambda;
    EXPECT_FLOAT_EQ(pdf, std::abs(wi.z) * kInvPi);
    // The flint refracts with its index at lambda: Snell's law in world space.
    const nimbus_interaction_t ix = h.at("flint");
    float o[3];
    wo.store(o);
    const float u[3] = {0.9999f, 0.5f, 0.5f};
    nimbus_bsdf_sample_t s;
    h.spectral().bsdf_sample(h.host(), &ix, o, u, NIMBUS_MODE_RADIANCE, lambda, &s);
    ASSERT_GT(s.pdf, 0);
    ASSERT_TRUE(s.lobe & NIMBUS_LOBE_TRANSMISSION);
    const float n = IorCurve::abbe(1.8, 25).at(lambda);
    EXPECT_FLOAT_EQ(s.eta, n);
    EXPECT_NEAR(std::sqrt(1 - wo.z * wo.z), n * std::sqrt(1 - s.wi[2] * s.wi[2]), 4e-6f) << lambda;
    EXPECT_EQ(s.f[0], s.f[1]);
    EXPECT_EQ(s.f[0], s.f[2]);
    // Out of range: no sample, no value.
    h.spectral().bsdf_sample(h.host(), &ix, o, u, NIMBUS_MODE_RADIANCE, 1000, &s);
    EXPECT_EQ(s.pdf, 0);
    EXPECT_EQ(h.eval("white", wo, wi, 200, &pdf), 0);
    EXPECT_EQ(pdf, 0);
  }
}

// Textured materials go through the same per-point BSDFs as nimbus.host.bsdf@1: the texel's albedo is
// uplifted, a roughness texture roughens the dispersive glass.
TEST(SpectralService, TexturedMaterialsAtOneWavelength) {
  texture_test::ScratchDir dir;
  texture_test::write_png8(dir.file("albedo.png"), 1, 1, 3, {200, 100, 50});
  texture_test::write_exr(dir.file("rough.exr"), 1, 1, 1, {0.5f});
  const SpectralHarness h(kPlain +
                          "  painted: { type: diffuse, albedo: { texture: " + dir.file("albedo.png") +
                          " } }\n  frosted: { type: dielectric, ior: 1.8, abbe: 25, roughness: { texture: " +
                          dir.file("rough.exr") + " } }\n");
  const Vec3f wo = normalize(Vec3f(0.3f, 0.2f, 0.9f)), wi = normalize(Vec3f(-0.4f, 0.1f, -0.8f));
  const Vec3f wr = normalize(Vec3f(-0.4f, 0.1f, 0.8f));
  for (float lambda : {420.0f, 550.0f, 680.0f}) {
    const Rgb texel = h.eval_rgb("painted", wo, wr) * kPi;  // the texture's linear albedo
    EXPECT_GT(texel.x, 2 * texel.z);
    const float f = h.eval("painted", wo, wr, lambda);
    EXPECT_NEAR(f, uplift(texel, lambda) * kInvPi, 1e-5f * f) << lambda;
    // The frosted glass at lambda: the dispersive dielectric at n(lambda) with alpha of roughness 0.5.
    const float alpha = TrowbridgeReitz::roughness_to_alpha(0.5f);
    const IorCurve curve = IorCurve::abbe(1.8, 25);
    const SpectralBsdf expected(DielectricBsdf::dispersive(1.8f, alpha), &curve, lambda);
    float pdf = 0, expected_pdf = 0;
    const float t = h.eval("frosted", wo, wi, lambda, &pdf);
    const float t_expected = expected.eval(wo, wi, TransportMode::Radiance, &expected_pdf);
    ASSERT_GT(t_expected, 0);
    EXPECT_NEAR(t, t_expected, 1e-5f * t_expected) << lambda;
    EXPECT_NEAR(pdf, expected_pdf, 1e-5f * expected_pdf) << lambda;
  }
  // Another wavelength, another value: the index really changes with lambda.
  EXPECT_GT(std::abs(h.eval("frosted", wo, wi, 420) / h.eval("frosted", wo, wi, 680) - 1), 1e-2f);
}

}  // namespace spectral_service_test
}  // namespace nimbus::test
