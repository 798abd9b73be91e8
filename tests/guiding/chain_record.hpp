// The guiding tests' integrator stand-in: a tracer that scores paths with a C++ target and records what
// an integrator sees of a chain (every traced u with its kind, every credit in order), and runs of a
// pass's chains of the production chain code (metropolis_chain.hpp) on it.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "metropolis_chain.hpp"

namespace nimbus::guide_test {

using guide::ChainSettings;
using guide::ChainTotals;

// One chain's paths as its tracer saw them. Path ids are indices into `kinds` (and into `u`, dims floats
// per path).
template <class Target>
class RecordingTracer {
 public:
  RecordingTracer(const Target &target, uint32_t dims) : target_(target), dims_(dims) {}

  sdk::TracedPath trace(std::span<const float> u, uint32_t kind) {
    const uint64_t path = kinds.size();
    this->u.insert(this->u.end(), u.begin(), u.end());
    kinds.push_back(kind);
    credited.push_back(0);
    return {target_(u), path};
  }
  void credit(uint64_t path, uint64_t multiplicity) {
    credits.emplace_back(path, multiplicity);
    credited.at(path) += multiplicity;
  }

  std::span<const float> path_u(uint64_t path) const { return std::span(u).subspan(path * dims_, dims_); }
  // The chain's state after each of its steps, as the credits tell them in order.
  std::vector<uint64_t> state_paths() const {
    std::vector<uint64_t> states;
    for (const auto &[path, m] : credits) states.insert(states.end(), m, path);
    return states;
  }

  std::vector<float> u;
  std::vector<uint32_t> kinds;
  std::vector<uint64_t> credited;                      // multiplicity credited per path
  std::vector<std::pair<uint64_t, uint64_t>> credits;  // (path, multiplicity) in the order given

 private:
  const Target &target_;
  uint32_t dims_;
};

// A 1-D pass as the stationarity tests read it.
struct OneDimensionalPass {
  std::vector<std::vector<float>> states;  // per chain: the state's u after every step
  struct Weighted {
    float u;
    uint64_t count;  // 1[uniform] + multiplicity: the numerator of the path's estimator weight
  };
  std::vector<Weighted> weighted;  // the paths whose weight is not 0
  ChainTotals totals;
};

// Runs `chains` chains of pass 1 of a render seeded `seed` on the 1-D target `target(double u)`.
template <class Target>
OneDimensionalPass run_one_dimensional(const Target &target, uint64_t seed, uint32_t chains,
                                       const ChainSettings &settings) {
  const auto score = [&](std::span<const float> u) { return target(double(u[0])); };
  OneDimensionalPass pass;
  pass.states.resize(chains);
  for (uint32_t c = 0; c < chains; ++c) {
    RecordingTracer tracer(score, 1);
    guide::MetropolisChain chain(settings, 1, guide::chain_stream(seed, 1, c), tracer);
    pass.totals += chain.run();
    for (uint64_t path : tracer.state_paths()) pass.states[c].push_back(tracer.u[path]);
    for (uint64_t path = 0; path < tracer.kinds.size(); ++path) {
      const uint64_t count = (tracer.kinds[path] == NIMBUS_GUIDE_UNIFORM ? 1 : 0) + tracer.credited[path];
      if (count > 0) pass.weighted.push_back({tracer.u[path], count});
    }
  }
  return pass;
}

}  // namespace nimbus::guide_test
