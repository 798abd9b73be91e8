// Light samplers through the real host: pmfs sum to one over all lights at any receiver, pick()
// frequencies follow pmf() (chi-square), and the tree and power samplers render the same image.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "abi/host_services.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace light_sampler_test {

// A room lit by 40 area lights of powers over 6 decades, 10 point lights, a spot and a sun.
std::string many_lights_scene() {
  std::string s = R"(
render: { resolution: [32, 24], seed: 5, max_depth: 4 }
camera: { position: [0, -9, 3], look_at: [0, 0, 1], up: [0, 0, 1], fov: 60 }
materials:
  white: { type: diffuse, albedo: [0.7, 0.7, 0.7] }
  lamp: { type: diffuse, albedo: [0, 0, 0] }
objects:
  - { shape: rectangle, size: [20, 20], material: white }
  - { shape: rectangle, size: [20, 6], material: white, transform: { rotate: [90, 0, 0], translate: [0, 5, 3] } }
)";
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(0, 1);
  for (int i = 0; i < 40; ++i) {
    const float x = -8 + 16 * U(rng), y = -4 + 8 * U(rng), z = 0.5f + 4 * U(rng);
    const float radiance = std::pow(10.0f, 6 * U(rng) - 3);
    s +=
        "  - { shape: " + std::string(i % 2 ? "sphere, radius: 0.1" : "rectangle, size: [0.3, 0.3]") +
        (i % 2 ? ", center: [" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + "]"
               : "") +
        ", material: lamp, emission: { radiance: [" + std::to_string(radiance) + ", " +
        std::to_string(radiance) + ", " + std::to_string(radiance) + "] }" +
        (i % 2 ? ""
               : ", transform: { rotate: [180, 0, 0], translate: [" + std::to_string(x) + ", " +
                     std::to_string(y) + ", " + std::to_string(z) + "] }") +
        " }\n";
  }
  s += "lights:\n";
  for (int i = 0; i < 10; ++i)
    s += "  - { type: point, position: [" + std::to_string(-8 + 16 * U(rng)) + ", " +
         std::to_string(-4 + 8 * U(rng)) + ", " + std::to_string(0.5f + 4 * U(rng)) + "], intensity: [" +
         std::to_string(std::pow(10.0f, 3 * U(rng))) + ", 1, 1] }\n";
  s += "  - { type: spot, position: [0, -2, 5], direction: [0, 0, -1], cone: 30, softness: 10, intensity: "
       "[50, 50, 50] }\n";
  s += "  - { type: sun, direction: [-1, 1, -2], irradiance: [3, 3, 3], angular_diameter: 0.53 }\n";
  return s;
}

class SamplerHarness {
 public:
  explicit SamplerHarness(const std::string &yaml, const std::string &sampler)
      : registry_([](int, const std::string &) {}) {
    auto desc = parse_scene_string(yaml, "many.yaml");
    EXPECT_TRUE(desc.ok()) << (desc.ok() ? "" : desc.error().message);
    desc_ = std::move(desc.value());
    auto world = World::build(desc_, desc_.render.filter);
    EXPECT_TRUE(world.ok());
    world_ = std::move(world.value());
    run_ = std::make_unique<RunState>(desc_.render.width, desc_.render.height, 1, desc_.render.seed);
    services_ = std::make_unique<HostServices>(world_.get(), run_.get());
    registry_.discover({std::string(NIMBUS_BINARY_DIR) + "/lib/nimbus/plugins"}, services_->host());
    auto p = registry_.create(sampler, NIMBUS_KIND_LIGHT_SAMPLER, services_->host());
    EXPECT_TRUE(p.ok()) << (p.ok() ? "" : p.error().message);
    plugin_ = p.value();
    iface_ = static_cast<const nimbus_light_sampler_v1_t *>(
        plugin_->get_interface(plugin_, NIMBUS_IFACE_LIGHT_SAMPLER, 1));
    nimbus_scene_info_t info{};
    info.header.struct_size = sizeof(info);
    EXPECT_EQ(iface_->prepare(plugin_, &info), NIMBUS_OK);
  }
  ~SamplerHarness() { registry_.destroy(plugin_); }

  uint32_t light_count() const { return world_->lights.count(); }
  float pmf(const nimbus_interaction_t &ix, uint32_t l) const { return iface_->pmf(plugin_, &ix, l); }
  uint32_t pick(const nimbus_interaction_t &ix, float u, float *pmf) const {
    return iface_->pick(plugin_, &ix, u, pmf);
  }

 private:
  SceneDesc desc_;
  std::unique_ptr<World> world_;
  std::unique_ptr<RunState> run_;
  std::unique_ptr<HostServices> services_;
  PluginRegistry registry_;
  const nimbus_plugin_t *plugin_ = nullptr;
  const nimbus_light_sampler_v1_t *iface_ = nullptr;
};

nimbus_interaction_t receiver(const Vec3f &p, const Vec3f &n) {
  nimbus_interaction_t ix{};
  p.store(ix.p);
  n.store(ix.ng);
  n.store(ix.ns);
  ix.light_id = NIMBUS_NONE;
  return ix;
}

class LightSamplerTest : public ::testing::TestWithParam<const char *> {};

TEST_P(LightSamplerTest, PmfSumsToOneAndMatchesPickFrequencies) {
  SamplerHarness h(many_lights_scene(), GetParam());
  ASSERT_EQ(h.light_count(), 40u + 10u + 2u);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(0, 1);
  for (int r = 0; r < 6; ++r) {
    const nimbus_interaction_t ix = receiver({-8 + 16 * U(rng), -4 + 8 * U(rng), U(rng) * 2},
                                             normalize(Vec3f{U(rng) - 0.5f, U(rng) - 0.5f, 1}));
    double sum = 0;
    std::vector<double> pmf(h.light_count());
    for (uint32_t l = 0; l < h.light_count(); ++l) sum += pmf[l] = h.pmf(ix, l);
    EXPECT_NEAR(sum, 1.0, 1e-4) << "receiver " << r;
    // Frequencies of pick() against pmf(), chi-square over lights with expected count >= 5.
    const int n = 200000;
    std::vector<int> counts(h.light_count(), 0);
    for (int i = 0; i < n; ++i) {
      float p = 0;
      const uint32_t l = h.pick(ix, U(rng), &p);
      ASSERT_LT(l, h.light_count());
      ASSERT_NEAR(p, pmf[l], 1e-5 + 1e-4 * pmf[l]) << "pick's pmf must equal pmf()";
      ++counts[l];
    }
    double chi2 = 0;
    int dof = -1;
    double pooled_expected = 0, pooled_observed = 0;
    for (uint32_t l = 0; l < h.light_count(); ++l) {
      const double e = pmf[l] * n;
      if (e < 5) {
        pooled_expected += e, pooled_observed += counts[l];
        continue;
      }
      chi2 += (counts[l] - e) * (counts[l] - e) / e;
      ++dof;
    }
    if (pooled_expected >= 5) chi2 += sqr(float(pooled_observed - pooled_expected)) / pooled_expected, ++dof;
    // 99.9th percentile of chi-square is below dof + 4.5 sqrt(2 dof) + 10 for these sizes.
    EXPECT_LT(chi2, dof + 4.5 * std::sqrt(2.0 * dof) + 10) << "dof " << dof << ", receiver " << r;
  }
}

// Thousands of lights, 500 of them at one point (the split heuristic cannot separate them: median splits
// deep in the tree), powers over 9 decades: pmfs still sum to one and pick() reports pmf().
TEST_P(LightSamplerTest, ThousandsOfLightsSomeCoincident) {
  std::string s = R"(
render: { resolution: [8, 8] }
camera: { position: [0, -9, 3], look_at: [0, 0, 1], up: [0, 0, 1], fov: 60 }
materials: { white: { type: diffuse, albedo: [0.7, 0.7, 0.7] } }
objects: [ { shape: rectangle, size: [20, 20], material: white } ]
lights:
)";
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(0, 1);
  for (int i = 0; i < 3500; ++i) {
    const Vec3f p = i < 500 ? Vec3f{1, 2, 3} : Vec3f{-8 + 16 * U(rng), -8 + 16 * U(rng), 0.1f + 5 * U(rng)};
    const float intensity = std::pow(10.0f, 9 * U(rng) - 4);
    s += "  - { type: point, position: [" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " +
         std::to_string(p.z) + "], intensity: [" + std::to_string(intensity) + ", 1, 1] }\n";
  }
  SamplerHarness h(s, GetParam());
  ASSERT_EQ(h.light_count(), 3500u);
  for (int r = 0; r < 4; ++r) {
    const nimbus_interaction_t ix =
        receiver({-8 + 16 * U(rng), -8 + 16 * U(rng), 0}, normalize(Vec3f{U(rng) - 0.5f, U(rng) - 0.5f, 1}));
    double sum = 0;
    std::vector<float> pmf(h.light_count());
    for (uint32_t l = 0; l < h.light_count(); ++l) sum += pmf[l] = h.pmf(ix, l);
    EXPECT_NEAR(sum, 1.0, 1e-3) << "receiver " << r;
    for (int i = 0; i < 20000; ++i) {
      float p = 0;
      const uint32_t l = h.pick(ix, U(rng), &p);
      ASSERT_LT(l, h.light_count());
      ASSERT_GT(p, 0.0f);
      ASSERT_EQ(p, pmf[l]) << "pick's pmf must be pmf() exactly (light " << l << ")";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Samplers, LightSamplerTest,
                         ::testing::Values("nimbus.lights.power", "nimbus.lights.tree"));

TEST(LightSamplers, TreeAndPowerRenderTheSameImage) {
  SceneRenderer r;
  const std::string scene = many_lights_scene();
  RenderRequest req;
  req.integrator = "nimbus.pt", req.iterations = 128, req.seed = 21;
  req.light_sampler = "nimbus.lights.power";
  const Rgb power = mean_rgb(r.render(scene, req).layers.at("beauty").data);
  req.light_sampler = "nimbus.lights.tree";
  req.seed = 22;
  const Rgb tree = mean_rgb(r.render(scene, req).layers.at("beauty").data);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(tree[c] / power[c], 1.0, 0.03) << "channel " << c;
}

// A sampler that adapts gets every NEE outcome from the camera-path layer (light_sampler.h, record) and
// its end_iteration from the host: a lamp over the floor lights many samples, a lamp shut in a box none,
// and each is picked about half the time (uniform choice).
TEST(LightSamplers, AdaptingSamplerIsToldEveryNeeOutcome) {
  SceneRenderer r({NIMBUS_LIGHT_FIXTURE_DIR});
  const std::string scene = R"(
render: { resolution: [32, 24], max_depth: 3 }
camera: { position: [0, -9, 3], look_at: [0, 0, 1], up: [0, 0, 1], fov: 60 }
materials:
  white: { type: diffuse, albedo: [0.7, 0.7, 0.7] }
objects:
  - { shape: rectangle, size: [20, 20], material: white }
  - { shape: box, size: [1, 1, 1], material: white, transform: { translate: [3, 0, 0.5] } }
lights:
  - { type: point, position: [-2, 0, 2], power: 50 }
  - { type: point, position: [3, 0, 0.5], power: 50 }
)";
  const std::string counts =
      (std::filesystem::temp_directory_path() / ("nimbus-recording-" + std::to_string(::getpid()) + ".txt"))
          .string();
  ::setenv("NIMBUS_RECORDING_SAMPLER_OUT", counts.c_str(), 1);
  RenderRequest req;
  req.integrator = "nimbus.pt", req.iterations = 4, req.seed = 3;
  req.light_sampler = "org.nimbus.test.recording";
  r.render(scene, req);
  ::unsetenv("NIMBUS_RECORDING_SAMPLER_OUT");
  std::ifstream in(counts);
  uint64_t open[4] = {}, boxed[4] = {};
  ASSERT_TRUE(in >> open[0] >> open[1] >> boxed[0] >> boxed[1] >> open[2] >> open[3]) << counts;
  in.close();
  std::filesystem::remove(counts);
  EXPECT_EQ(open[2], 0u) << "records with a bad worker or value";
  EXPECT_EQ(open[3], 4u) << "iterations ended";
  // 32 x 24 pixels x 4 iterations: 3,072 camera paths, most of them reaching the floor (~1,800 NEE
  // samples). Half per lamp: a binomial's sigma at 1,000 samples is 0.016, so 0.05 is over 3 sigma.
  const double n = double(open[0] + boxed[0]);
  EXPECT_GT(n, 1000.0);
  EXPECT_NEAR(double(open[0]) / n, 0.5, 0.05);
  EXPECT_GT(open[1], open[0] / 4) << "the open lamp lights the floor";
  EXPECT_EQ(boxed[1], 0u) << "the boxed lamp lights nothing";
}

// Photon emission through the sampler (light_sampler.h update_emission, since 1.6): the caustics solver
// reports, before every photon pass, each lamp's photon power and its cumulative uniform paths and those
// a lookup used, and emits by the table the sampler then holds (the fixture's: 1/3 and 2/3).
TEST(LightSamplers, CausticsSolverEmitsPhotonsByTheSamplersFeedbackTable) {
  SceneRenderer r({NIMBUS_LIGHT_FIXTURE_DIR});
  const std::string scene = R"(
render: { resolution: [48, 36], max_depth: 6 }
camera: { position: [0, -5, 3], look_at: [0, 0, 0.4], up: [0, 0, 1], fov: 40 }
materials:
  white: { type: diffuse, albedo: [0.7, 0.7, 0.7] }
  glass: { type: dielectric, ior: 1.5 }
objects:
  - { shape: rectangle, size: [20, 20], material: white }
  - { shape: sphere, radius: 0.5, material: glass, transform: { translate: [0, 0, 0.5] } }
lights:
  - { type: point, position: [-0.5, 0, 3], power: 50 }
  - { type: point, position: [0.5, 0, 3], power: 50 }
)";
  const std::string counts =
      (std::filesystem::temp_directory_path() / ("nimbus-emission-" + std::to_string(::getpid()) + ".txt"))
          .string();
  ::setenv("NIMBUS_RECORDING_SAMPLER_OUT", counts.c_str(), 1);
  RenderRequest req;
  req.integrator = "nimbus.caustics", req.iterations = 256, req.seed = 5;
  req.light_sampler = "org.nimbus.test.recording";
  r.render(scene, req);
  ::unsetenv("NIMBUS_RECORDING_SAMPLER_OUT");
  std::ifstream in(counts);
  uint64_t nee[4], ends[2], updates = 0, bad_feedback = 0, emitted[2], contributed[2];
  double power[2];
  ASSERT_TRUE(in >> nee[0] >> nee[1] >> nee[2] >> nee[3] >> ends[0] >> ends[1] >> updates >> bad_feedback >>
              emitted[0] >> contributed[0] >> power[0] >> emitted[1] >> contributed[1] >> power[1])
      << counts;
  in.close();
  std::filesystem::remove(counts);
  EXPECT_EQ(bad_feedback, 0u) << "feedback of the wrong size, or counts that fell or exceed the emitted";
  EXPECT_GE(updates, 3u) << "the first map's table, and one per later photon pass";
  EXPECT_GT(power[0], 0.0);
  EXPECT_GT(power[1], 0.0);
  // The lamp of weight 2 emits 2/3 of the uniform paths: a binomial's sigma at n paths is
  // sqrt(2/9 / n); 5 sigma.
  const double n = double(emitted[0] + emitted[1]);
  ASSERT_GT(n, 10000.0);
  EXPECT_NEAR(double(emitted[1]) / n, 2.0 / 3.0, 5 * std::sqrt(2.0 / 9.0 / n));
  // Both lamps focus light under the ball: lookups use some of each lamp's paths.
  EXPECT_GT(contributed[0], 0u);
  EXPECT_GT(contributed[1], 0u);
  EXPECT_LE(contributed[1], emitted[1]);
}

}  // namespace light_sampler_test
}  // namespace nimbus::testing
