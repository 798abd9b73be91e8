// org.nimbus.test.recording: a uniform light sampler that adapts (sdk::LightSampler::adapts), so that its
// table carries record and end_iteration, and counts what it is told: per light the NEE samples the
// camera-path layer reported and those with light, records that break the contract (a worker out of
// range, a negative or non-finite v), and the iterations ended. A test fixture only, built into a
// directory of its own. A plugin exports nothing but its entry point, so it writes its counts, after
// every iteration, to the file that NIMBUS_RECORDING_SAMPLER_OUT names: "samples lit" per light, then
// "bad iterations".
#include <nimbus/nimbus.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace {

constexpr uint32_t kMaxLights = 8;
std::atomic<uint64_t> g_samples[kMaxLights], g_lit[kMaxLights], g_bad{0}, g_iterations{0};

const char *const kRequired[] = {nullptr};

class RecordingSampler final : public nimbus::sdk::LightSampler {
 public:
  NIMBUS_DESCRIPTOR("org.nimbus.test.recording", "Test fixture: uniform light sampler that counts records",
                    "Nimbus tests", NIMBUS_KIND_LIGHT_SAMPLER, 1, 0, 0, nullptr, kRequired)

  nimbus_status_t prepare(const nimbus_scene_info_t &info) override {
    n_ = info.light_count, workers_ = info.worker_count;
    for (auto &c : g_samples) c = 0;
    for (auto &c : g_lit) c = 0;
    g_bad = 0, g_iterations = 0;
    return NIMBUS_OK;
  }
  uint32_t pick(const nimbus_interaction_t &, float u, float *pmf) override { return pick_emitter(u, pmf); }
  float pmf(const nimbus_interaction_t &, uint32_t light) override {
    return light < n_ ? 1.0f / float(n_) : 0;
  }
  uint32_t pick_emitter(float u, float *pmf) override {
    if (n_ == 0) return NIMBUS_NONE;
    *pmf = 1.0f / float(n_);
    return std::min(n_ - 1, uint32_t(u * float(n_)));
  }
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
    out << g_bad << " " << g_iterations << "\n";
  }

 private:
  uint32_t n_ = 0, workers_ = 0;
};

}  // namespace

NIMBUS_PLUGIN_LIBRARY(RecordingSampler)
