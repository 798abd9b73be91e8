// nimbus.guide.metropolis: Metropolis photon guiding in primary sample space (caustics-solver.md §6.3),
// "nimbus.iface.guiding" rev 2. An integrator (nimbus.caustics) owns tracing and the target; this plugin
// owns the chains: the caller's chain_count chains per pass, each with its share of the path budget and
// random numbers from (seed, pass, chain) alone (metropolis_chain.hpp), and the mutation size, adapted
// between passes and kept in the render state (mutation_schedule.hpp).
#include <nimbus/nimbus.hpp>

#include <optional>
#include <string>
#include <vector>

#include <nimbus/cpp/photon_guide.hpp>
#include <nimbus/cpp/render_state.hpp>

#include "metropolis_chain.hpp"
#include "mutation_schedule.hpp"

namespace nimbus::guide {
namespace {

class MetropolisGuide final : public sdk::PhotonGuide {
 public:
  NIMBUS_DESCRIPTOR("nimbus.guide.metropolis", "Metropolis photon guide (primary sample space)", "Nimbus",
                    NIMBUS_KIND_GUIDING, 1, 0, 0, nullptr, nullptr)

  const void *interface(const char *id, uint32_t rev) override {
    if (const void *t = sdk::render_state_interface<MetropolisGuide>(id, rev)) return t;
    return PhotonGuide::interface(id, rev);
  }

  nimbus_status_t prepare(const nimbus_scene_info_t &) override {
    schedule_.reset();
    chains_.clear();
    return NIMBUS_OK;
  }

  nimbus_status_t begin_pass(const nimbus_guide_pass_t &pass) override {
    if (pass.chain_count == 0 || pass.dims == 0) {
      log(NIMBUS_LOG_ERROR, "begin_pass: a pass needs at least one chain and one dimension");
      return NIMBUS_E_INVALID_ARG;
    }
    const std::optional<double> d = schedule_.begin(pass.pass);
    if (!d) {
      log(NIMBUS_LOG_ERROR, "begin_pass: pass " + std::to_string(pass.pass) +
                                " comes before a pass already ended (passes are 1-based and go forward; "
                                "prepare starts a new render)");
      return NIMBUS_E_INVALID_ARG;
    }
    pass_ = pass;
    mutation_size_ = *d;
    // One slot per chain, written only by that chain's run_chain: chains run concurrently without locks.
    chains_.assign(pass.chain_count, ChainTotals{});
    return NIMBUS_OK;
  }

  nimbus_status_t run_chain(const nimbus_thread_ctx_t &, uint32_t chain, sdk::GuideTracer &tracer,
                            nimbus_guide_totals_t &totals) override {
    if (chain >= chains_.size() || tracer.dims() != pass_.dims) return NIMBUS_E_INVALID_ARG;
    const ChainSettings settings{chain_budget(pass_.path_budget, pass_.chain_count, chain), mutation_size_};
    MetropolisChain metropolis(settings, pass_.dims, chain_stream(pass_.seed, pass_.pass, chain), tracer);
    const ChainTotals t = metropolis.run();
    chains_[chain] = t;
    totals.uniform_paths = t.uniform_paths, totals.chain_steps = t.chain_steps;
    totals.uniform_target_sum = t.uniform_target_sum;
    totals.proposals = t.proposals, totals.accepted = t.accepted;
    return NIMBUS_OK;
  }

  // Adapts d from the chains' own counts, not the caller's sums: the guide's state then depends on
  // nothing but its chains.
  nimbus_status_t end_pass(const nimbus_guide_totals_t &) override {
    ChainTotals sum;
    for (const ChainTotals &c : chains_) sum += c;
    if (!schedule_.end(sum.accepted, sum.proposals)) {
      log(NIMBUS_LOG_ERROR, "end_pass without begin_pass");
      return NIMBUS_E_INVALID_ARG;
    }
    return NIMBUS_OK;
  }

  // nimbus.iface.render-state: the mutation sizes (of the next pass, and of the last one for its replay).
  nimbus_status_t save_state(uint64_t, sdk::StateWriter &w) {
    schedule_.save(w);
    return NIMBUS_OK;
  }
  nimbus_status_t restore_state(uint64_t, sdk::StateReader &r) {
    const nimbus_status_t s = schedule_.restore(r);
    if (s != NIMBUS_OK) log(NIMBUS_LOG_WARNING, "restore_state: the saved state is not this guide's format");
    return s;
  }

 private:
  MutationSchedule schedule_;
  nimbus_guide_pass_t pass_{};
  double mutation_size_ = MutationSchedule::kInitial;  // d of the current pass
  std::vector<ChainTotals> chains_;                    // what each chain of the current pass did
};

}  // namespace
}  // namespace nimbus::guide

NIMBUS_PLUGIN_LIBRARY(nimbus::guide::MetropolisGuide)
