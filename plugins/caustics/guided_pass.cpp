// A photon pass whose paths a guide chooses (solver spec 6.3): the guide's chains run as host tasks, one
// chunk of photons per chain, through a tracer that scores each path with its target T (the largest
// importance at its stored photons). Once every chain is done, the pass's totals give each path its
// mixture weight and each photon's B its effective photon counts; photons of paths with weight 0
// (rejected proposals) are dropped. See photon_pass.hpp.
#include <algorithm>

#include "photon_pass.hpp"

namespace nimbus::caustics {
namespace {

// A chunk may hold this many photons per path it traced (photon_pass.cpp's memory guard).
constexpr uint64_t kGuidedPhotonsPerPathCap = 4;

// What one chain's tracer callbacks reach.
struct ChainTracer {
  const PhotonTracer *tracer;
  const ImportanceMap *importance;
  const nimbus_thread_ctx_t *ctx;
  PhotonChunk *chunk;
  uint64_t cap;  // photons the chunk may hold
};

// nimbus_guide_tracer_t.trace: a guide is another party's code, so u is checked (a value outside [0, 1)
// becomes 0.5) before it reaches the photon tracer.
double trace_path(void *user, const float *u, uint32_t kind, uint64_t *path) {
  const ChainTracer &c = *static_cast<const ChainTracer *>(user);
  PhotonChunk &chunk = *c.chunk;
  const uint32_t dims = photon_dims(c.tracer->timed());
  float v[kPhotonDims + 1];
  for (uint32_t i = 0; i < dims; ++i) v[i] = u && u[i] >= 0.0f && u[i] < 1.0f ? u[i] : 0.5f;
  GuidedPath rec;
  rec.first = uint32_t(chunk.photons.size());
  rec.uniform = kind == NIMBUS_GUIDE_UNIFORM;
  if (chunk.photons.size() < c.cap) {
    PhotonSamples samples(v, dims);
    rec.target = c.tracer->trace(*c.ctx, samples, 0, 0, c.importance, chunk);
  } else {
    chunk.path_light.push_back(kNoLight);
    chunk.path_emission.push_back(kNoEmissionCell);
  }
  if (!rec.uniform) chunk.path_light.back() |= kProposalPath;
  rec.count = uint32_t(chunk.photons.size()) - rec.first;
  if (path) *path = chunk.guided.size();
  chunk.guided.push_back(rec);
  ++chunk.paths;
  return rec.target;
}

// nimbus_guide_tracer_t.credit: unknown paths are ignored.
void credit_path(void *user, uint64_t path, uint64_t multiplicity) {
  PhotonChunk &chunk = *static_cast<const ChainTracer *>(user)->chunk;
  if (path < chunk.guided.size()) chunk.guided[path].multiplicity += multiplicity;
}

}  // namespace

nimbus_status_t PhotonPass::run_guided(const PhotonTracer &tracer, const GuideBinding &guide,
                                       const ImportanceMap &importance, const nimbus_host_tasks_v1_t *tasks,
                                       const nimbus_host_t *h, uint64_t seed, uint32_t pass, uint64_t paths,
                                       float filter_reach, Result &result) {
  nimbus_guide_pass_t desc{};
  desc.header = {sizeof(desc), NIMBUS_S_TYPE_GUIDE_PASS, nullptr};
  desc.seed = seed, desc.pass = pass, desc.path_budget = paths;
  desc.chain_count = kGuideChains, desc.dims = photon_dims(tracer.timed());
  if (nimbus_status_t s = guide.iface->begin_pass(guide.plugin, &desc); s != NIMBUS_OK) return s;
  chunks_.resize(kGuideChains);
  for (PhotonChunk &c : chunks_) c.reset();
  std::vector<nimbus_guide_totals_t> totals(kGuideChains);
  std::vector<nimbus_status_t> status(kGuideChains, NIMBUS_OK);
  struct Job {
    const PhotonTracer *tracer;
    const GuideBinding *guide;
    const ImportanceMap *importance;
    std::vector<PhotonChunk> *chunks;
    std::vector<nimbus_guide_totals_t> *totals;
    std::vector<nimbus_status_t> *status;
    uint64_t cap;
  } job{&tracer,
        &guide,
        &importance,
        &chunks_,
        &totals,
        &status,
        (paths / kGuideChains + 1) * kGuidedPhotonsPerPathCap};
  const auto fn = [](const nimbus_thread_ctx_t *ctx, uint64_t b, uint64_t e, void *user) {
    const Job &j = *static_cast<Job *>(user);
    for (uint64_t c = b; c < e; ++c) {
      ChainTracer ct{j.tracer, j.importance, ctx, &(*j.chunks)[c], j.cap};
      const nimbus_guide_tracer_t t{sizeof(nimbus_guide_tracer_t), photon_dims(j.tracer->timed()), &ct,
                                    trace_path, credit_path};
      nimbus_guide_totals_t &out = (*j.totals)[c];
      out = {};
      out.header = {sizeof(out), NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr};
      (*j.status)[c] = j.guide->iface->run_chain(j.guide->plugin, ctx, uint32_t(c), &t, &out);
    }
  };
  if (nimbus_status_t s = tasks->parallel_for(h, kGuideChains, 1, fn, &job); s != NIMBUS_OK) return s;
  nimbus_guide_totals_t sum{};
  sum.header = {sizeof(sum), NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr};
  for (uint32_t c = 0; c < kGuideChains; ++c) {
    if (status[c] != NIMBUS_OK) return status[c];
    sum.uniform_paths += totals[c].uniform_paths, sum.chain_steps += totals[c].chain_steps;
    sum.uniform_target_sum += totals[c].uniform_target_sum;
    sum.proposals += totals[c].proposals, sum.accepted += totals[c].accepted;
  }
  if (nimbus_status_t s = guide.iface->end_pass(guide.plugin, &sum); s != NIMBUS_OK) return s;

  // The mixture's totals from the paths themselves, not from the guide's report: N_u, N_m (steps on
  // states with T > 0 only: a state with T = 0 has zero density under the chain's target, so its steps
  // are not samples of it) and b^.
  // The chain technique enters the balance heuristic with its distinct states, not its steps: N'_m =
  // kappa N_m, kappa = states / steps, so that a state repeated by rejections counts once. Any constant
  // N'_m keeps the weights a partition of unity and the estimate unbiased; counting steps trusted the
  // correlated chain photons over the independent uniform ones (docs/performance.md §8).
  uint64_t n_u = 0, n_m = 0, states = 0;
  double target_sum = 0;
  result = {};
  for (const PhotonChunk &c : chunks_) {
    result.traced += c.paths, result.work += c.work;
    for (const GuidedPath &p : c.guided) {
      if (p.uniform) ++n_u, target_sum += p.target;
      if (p.target > 0) n_m += p.multiplicity, states += p.multiplicity > 0 ? 1 : 0;
    }
  }
  const double b_hat = n_u > 0 ? target_sum / double(n_u) : 0.0;
  const double kappa = n_m > 0 ? double(states) / double(n_m) : 1.0;
  const double ratio = b_hat > 0 ? kappa * double(n_m) / (double(n_u) * b_hat) : 0.0;
  // Each path's weight relative to a uniform path's 1 / N_u: (1[uniform] + kappa m) / (1 + c T).
  const sdk::ParallelFor parallel = sdk::host_parallel_for(tasks, h);
  parallel(chunks_.size(), [&](size_t i) {
    PhotonChunk &c = chunks_[i];
    size_t kept = 0;
    for (const GuidedPath &p : c.guided) {
      const double m = ratio > 0 && p.target > 0 ? kappa * double(p.multiplicity) : 0.0;
      const float w = float(((p.uniform ? 1.0 : 0.0) + m) / (1.0 + ratio * p.target));
      if (!(w > 0)) continue;
      for (uint32_t k = p.first; k < p.first + p.count; ++k) {
        Photon ph = c.photons[k];
        if (w != 1.0f)
          for (float &channel : ph.power) channel *= w;
        ph.B = fold_importance(ph.B, ph.B_importance, ph.B_importance2, ratio);
        c.photons[kept++] = ph;
      }
    }
    c.photons.resize(kept);
  });
  result.paths = n_u, result.guided = true;
  result.importance_ratio = ratio;
  result.proposals = sum.proposals, result.accepted = sum.accepted;
  assemble(parallel, filter_reach, tracer);
  return NIMBUS_OK;
}

}  // namespace nimbus::caustics
