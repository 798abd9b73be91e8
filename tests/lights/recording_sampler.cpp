// org.nimbus.test.recording: a uniform light sampler that adapts (sdk::LightSampler::adapts), so that its
// table carries record and end_iteration, and counts what it is told: per light the NEE samples the
// camera-path layer reported and those with light, records that break the contract (a worker out of
// range, a negative or non-finite v), and the iterations ended. A test fixture only, built into a
// directory of its own. It also takes photon-emission feedback (update_emission) and emits light l with
// probability proportional to l + 1 among the lights with photon power, so that a test can tell its
// table from any other. A plugin exports nothing but its entry point, so it writes its counts, after
// every iteration, to the file that NIMBUS_RECORDING_SAMPLER_OUT names: "samples lit" per light, then
// "bad iterations", then "updates bad_feedback", then the last feedback's "emitted contributed power"
// per light.
#include <nimbus/nimbus.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <vector>

namespace {

constexpr uint32_t kMaxLights = 8;
std::atomic<uint64_t> g_samples[kMaxLights], g_lit[kMaxLights], g_bad{0}, g_iterations{0};
uint64_t g_updates = 0, g_bad_feedback = 0, g_emitted[kMaxLights], g_contributed[kMaxLights];
double g_power[kMaxLights];

const char *const kRequired[] = {nullptr};

class RecordingSampler final : public nimbus::sdk::LightSampler {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.test.recording", "Test fixture: uniform light sampler that counts records",
                    "Nimbus tests", NIMBUS_KIND_LIGHT_SAMPLER, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t prepare(const nimbus_scene_info_t &info) override {
    n_ = info.light_count, workers_ = info.worker_count;
    for (auto &c : g_samples) c = 0;
    for (auto &c : g_lit) c = 0;
    g_bad = 0, g_iterations = 0, g_updates = 0, g_bad_feedback = 0;
    for (uint32_t l = 0; l < kMaxLights; ++l) g_emitted[l] = g_contributed[l] = 0, g_power[l] = 0;
    weights_.assign(n_, n_ > 0 ? 1.0 / n_ : 0.0);
    return NIMBUS_OK;
  }
  uint32_t pick(const nimbus_interaction_t &, float u, float *pmf) override {
    if (n_ == 0) return NIMBUS_NONE;
    *pmf = 1.0f / float(n_);
    return std::min(n_ - 1, uint32_t(u * float(n_)));
  }
  float pmf(const nimbus_interaction_t &, uint32_t light) override {
    return light < n_ ? 1.0f / float(n_) : 0;
  }
  uint32_t pick_emitter(float u, float *pmf) override {
    double cdf = 0;
    for (uint32_t l = 0; l < n_; ++l)
      if (weights_[l] > 0 && (u < (cdf += weights_[l]) || l + 1 == n_)) return *pmf = float(weights_[l]), l;
    return NIMBUS_NONE;
  }
  bool adapts_emission() const override { return true; }
  nimbus_status_t update_emission(const nimbus_emission_feedback_t &f) override {
    ++g_updates;
    if (f.light_count != n_ || f.header.s_type != NIMBUS_S_TYPE_EMISSION_FEEDBACK)
      return ++g_bad_feedback, NIMBUS_OK;
    double sum = 0;
    for (uint32_t l = 0; l < n_; ++l) {
      // Counts cover every earlier pass: they never fall, and a path contributes only if it was emitted.
      if (f.contributed[l] > f.emitted[l] || (l < kMaxLights && f.emitted[l] < g_emitted[l]))
        ++g_bad_feedback;
      weights_[l] = f.photon_power[l] > 0 ? double(l + 1) : 0.0;
      sum += weights_[l];
      if (l < kMaxLights)
        g_emitted[l] = f.emitted[l], g_contributed[l] = f.contributed[l], g_power[l] = f.photon_power[l];
    }
    for (double &w : weights_) w = sum > 0 ? w / sum : 0.0;
    return NIMBUS_OK;
  }
  float pmf_emitter(uint32_t light) override { return light < n_ ? float(weights_[light]) : 0.0f; }
  bool adapts() const override { return true; }
  void record(const nimbus_thread_ctx_t &ctx, uint32_t light, float v) override {
    if (light >= kMaxLights || light >= n_ || ctx.worker_index >= workers_ || !(v >= 0) ||
        !std::isfinite(v)) {
      ++g_bad;
      return;
    }
    ++g_samples[light];
    if (v > 0) ++g_lit[light];
  }
  void end_iteration(uint64_t) override {
    ++g_iterations;
    const char *path = std::getenv("NIMBUS_RECORDING_SAMPLER_OUT");
    if (!path) return;
    std::ofstream out(path);
    for (uint32_t l = 0; l < std::min(n_, kMaxLights); ++l) out << g_samples[l] << " " << g_lit[l] << "\n";
    out << g_bad << " " << g_iterations << "\n" << g_updates << " " << g_bad_feedback << "\n";
    for (uint32_t l = 0; l < std::min(n_, kMaxLights); ++l)
      out << g_emitted[l] << " " << g_contributed[l] << " " << g_power[l] << "\n";
  }

 private:
  uint32_t n_ = 0, workers_ = 0;
  std::vector<double> weights_;  // photon emission table
};

}  // namespace

NIMBUS_PLUGIN_LIBRARY(RecordingSampler)
