// One Metropolis chain of a photon pass in primary sample space (caustics-solver.md §6.3). It starts from
// a uniform path picked in proportion to its target among the first hits (resampling), then every step
// traces a uniform path, tries to exchange the state for it and always tries a small mutation of the
// state. Both moves are Metropolis-Hastings moves that keep the density T/b (the exchange is an
// independence sampler with uniform proposals; the mutation is symmetric), so the states are distributed
// as nimbus/guiding.h's estimator contract requires. Header-only and free of the plugin ABI so that tests
// drive it with a C++ target; the plugin drives it with the integrator's tracer (sdk::GuideTracer).
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <span>
#include <vector>

#include <nimbus/cpp/photon_guide.hpp>
#include <nimbus/cpp/rng.hpp>

namespace nimbus::guide {

// What tests and the plugin lend a chain: trace(u, kind) -> {T, path} and credit(path, multiplicity).
template <class T>
concept ChainTracer = requires(T &t, std::span<const float> u, uint32_t kind, uint64_t path) {
  { t.trace(u, kind) } -> std::same_as<sdk::TracedPath>;
  t.credit(path, path);
};

// nimbus_guide_totals_t's counts, for one chain or summed over a pass.
struct ChainTotals {
  uint64_t uniform_paths = 0;
  uint64_t chain_steps = 0;
  double uniform_target_sum = 0;
  uint64_t proposals = 0;
  uint64_t accepted = 0;

  ChainTotals &operator+=(const ChainTotals &o) {
    uniform_paths += o.uniform_paths, chain_steps += o.chain_steps;
    uniform_target_sum += o.uniform_target_sum;
    proposals += o.proposals, accepted += o.accepted;
    return *this;
  }
};

// The random numbers of chain `chain` in pass `pass` of a render seeded `seed`: they depend on nothing
// else (not the thread, not the other chains), so a render is the same at any thread count. PCG32 seeded
// as O'Neill's pcg32_srandom does, with the stream (the odd increment) hashed from the same keys.
inline nimbus_rng_t chain_stream(uint64_t seed, uint64_t pass, uint32_t chain) {
  const uint64_t key = hash_keys({seed, pass, chain});
  nimbus_rng_t r{0, (mix64(key) << 1) | 1u};
  nimbus_rng_next_u32(&r);
  r.state += key;
  nimbus_rng_next_u32(&r);
  return r;
}

// Chain `chain`'s share of a pass's path budget: an equal share, the remainder one path each to the
// lowest chains, so the shares add up to the budget exactly.
constexpr uint64_t chain_budget(uint64_t budget, uint32_t chains, uint32_t chain) {
  if (chains == 0 || chain >= chains) return 0;
  return budget / chains + (chain < budget % chains ? 1 : 0);
}

// Kelemen et al.'s small step, as §6.3 writes it: u +- xi^(1 + 1/d), sign 1/2 each, xi uniform, wrapped
// to [0, 1). Symmetric (u -> v as likely as v -> u), so accepting with T(v)/T(u) keeps T/b; d is roughly
// the mean step (E[xi^(1+1/d)] = d / (2d + 1)).
inline float perturbed(float u, double exponent, nimbus_rng_t &rng) {
  const bool up = nimbus_rng_next_u32(&rng) & 1u;
  const double step = std::pow(double(nimbus_rng_next_float(&rng)), exponent);
  double v = double(u) + (up ? step : -step);
  v -= std::floor(v);
  const float f = float(v);
  return f < 1.0f ? f : 0.0f;  // v just below 1 rounds up to 1 in float; 1 wraps to 0
}

struct ChainSettings {
  uint64_t budget = 0;          // paths the chain traces, uniform and proposals alike
  double mutation_size = 0.05;  // d, fixed for the chain
  // Test only: Hachisuka & Jensen 2011's variant, which skips the mutation in a step whose exchange
  // succeeded. It keeps T/b only for a binary target; tests show it does not for a graded one.
  bool skip_mutation_after_swap = false;
};

template <ChainTracer Tracer>
class MetropolisChain {
 public:
  // Initialisation ends once this many uniform paths hit (T > 0), or after kInitDraws draws.
  static constexpr uint32_t kInitHits = 16, kInitDraws = 256;

  MetropolisChain(const ChainSettings &settings, uint32_t dims, nimbus_rng_t rng, Tracer &tracer)
      : settings_(settings),
        rng_(rng),
        tracer_(tracer),
        exponent_(1.0 + 1.0 / settings.mutation_size),
        state_{std::vector<float>(dims)},
        candidate_(dims) {}

  // Traces exactly the chain's budget and credits every state it kept.
  ChainTotals run() {
    if (start()) {
      while (left() >= 2) step();
      leave_state();
    }
    // An odd path left over (or a chain that found nothing to start from): plain uniform paths.
    while (left() > 0) trace_uniform(candidate_);
    return totals_;
  }

 private:
  struct State {
    std::vector<float> u;
    double target = 0;
    uint64_t path = 0;
    uint64_t multiplicity = 0;  // chain steps not yet credited
  };

  uint64_t left() const { return settings_.budget - traced_; }

  // A target the chain can use: negative, NaN or infinite values count as 0 (never a state).
  static double usable(double t) { return std::isfinite(t) && t > 0 ? t : 0.0; }

  sdk::TracedPath trace(std::span<const float> u, uint32_t kind) {
    sdk::TracedPath p = tracer_.trace(u, kind);
    p.target = usable(p.target);
    ++traced_;
    return p;
  }

  sdk::TracedPath trace_uniform(std::vector<float> &u) {
    for (float &x : u) x = nimbus_rng_next_float(&rng_);
    const sdk::TracedPath p = trace(u, NIMBUS_GUIDE_UNIFORM);
    ++totals_.uniform_paths;
    totals_.uniform_target_sum += p.target;
    return p;
  }

  // Resampling initialisation: the state is one of the first hits, picked in proportion to T. False when
  // no uniform path hit (the chain then stays uniform-only) or the budget ran out first.
  bool start() {
    std::vector<State> hits;
    for (uint32_t draws = 0; draws < kInitDraws && hits.size() < kInitHits && left() > 0; ++draws) {
      const sdk::TracedPath p = trace_uniform(candidate_);
      if (p.target > 0) hits.push_back({candidate_, p.target, p.path, 0});
    }
    if (hits.empty() || left() < 2) return false;
    double sum = 0;
    for (const State &h : hits) sum += h.target;
    double pick = double(nimbus_rng_next_float(&rng_)) * sum;
    size_t i = 0;
    while (i + 1 < hits.size() && pick >= hits[i].target) pick -= hits[i++].target;
    state_ = std::move(hits[i]);
    return true;
  }

  // Metropolis-Hastings acceptance of a proposal with target t against the state's (> 0). The random
  // number is drawn even when the outcome is certain, so every step draws the same count of them.
  bool accept(double t) {
    const double r = nimbus_rng_next_float(&rng_);
    return t > 0 && r * state_.target < t;
  }

  // The chain leaves its state: credit the steps it stayed (the integrator adds up a path's credits).
  void leave_state() {
    if (state_.multiplicity > 0) tracer_.credit(state_.path, state_.multiplicity);
    state_.multiplicity = 0;
  }

  // candidate_ becomes the state.
  void move_to(const sdk::TracedPath &p) {
    leave_state();
    state_.u.swap(candidate_);
    state_.target = p.target;
    state_.path = p.path;
  }

  void step() {
    // (a) a uniform path, (b) replica exchange: the state becomes it with probability min(1, T_U / T).
    const sdk::TracedPath uniform = trace_uniform(candidate_);
    const bool swapped = accept(uniform.target);
    if (swapped) move_to(uniform);
    // (c) always a mutation, accepted with probability min(1, T' / T).
    if (!(swapped && settings_.skip_mutation_after_swap)) {
      for (size_t i = 0; i < candidate_.size(); ++i) candidate_[i] = perturbed(state_.u[i], exponent_, rng_);
      const sdk::TracedPath proposal = trace(candidate_, NIMBUS_GUIDE_PROPOSAL);
      ++totals_.proposals;
      if (accept(proposal.target)) move_to(proposal), ++totals_.accepted;
    }
    // (d) the state counts once more.
    ++state_.multiplicity;
    ++totals_.chain_steps;
  }

  const ChainSettings settings_;
  nimbus_rng_t rng_;
  Tracer &tracer_;
  const double exponent_;  // 1 + 1/d
  State state_;
  std::vector<float> candidate_;  // the path being traced; swapped into the state when it is taken
  uint64_t traced_ = 0;
  ChainTotals totals_;
};

}  // namespace nimbus::guide
