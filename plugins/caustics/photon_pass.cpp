// One photon pass and the photon map build; see photon_pass.hpp.
#include "photon_pass.hpp"

#include <algorithm>
#include <cmath>

#include <nimbus/cpp/tasks.hpp>

namespace nimbus::caustics {
namespace {

// Photon paths per task: small enough that a pass at the N_min floor shares out evenly over the
// workers.
constexpr uint64_t kPhotonPathsPerTask = 1024;
// Share of lookups whose radius the occupancy filter in front of the photon map covers
// (occupancy_filter.hpp).
constexpr double kFilterShare = 0.95;

}  // namespace

nimbus_status_t PhotonPass::run(const PhotonTracer &tracer, const nimbus_host_tasks_v1_t *tasks,
                                const nimbus_host_t *h, uint32_t pass, uint64_t paths, float filter_reach,
                                Result &result) {
  const uint64_t task_count = (paths + kPhotonPathsPerTask - 1) / kPhotonPathsPerTask;
  chunks_.resize(task_count);
  for (PhotonChunk &c : chunks_) c.reset();
  struct Job {
    const PhotonTracer *tracer;
    std::vector<PhotonChunk> *chunks;
    uint32_t pass;
    uint64_t paths;
  } job{&tracer, &chunks_, pass, paths};
  const auto fn = [](const nimbus_thread_ctx_t *ctx, uint64_t b, uint64_t e, void *user) {
    const Job &j = *static_cast<Job *>(user);
    PhotonChunk &c = (*j.chunks)[b / kPhotonPathsPerTask];
    c.photons.reserve(256);
    const size_t cap = size_t(e - b) * kPhotonsPerPathCap;
    for (uint64_t i = 0; i < e - b && c.photons.size() < cap; ++i) {
      j.tracer->trace(*ctx, task_path(j.pass, b, e, i), j.paths, j.pass, c);
      ++c.paths;
    }
  };
  if (nimbus_status_t s = tasks->parallel_for(h, paths, kPhotonPathsPerTask, fn, &job); s != NIMBUS_OK)
    return s;
  result = {};
  for (const PhotonChunk &c : chunks_) result.paths += c.paths, result.work += c.work;
  result.traced = result.paths;
  assemble(sdk::host_parallel_for(tasks, h), filter_reach, tracer);
  return NIMBUS_OK;
}

void PhotonPass::assemble(const sdk::ParallelFor &parallel, float filter_reach, const PhotonTracer &tracer) {
  // Concatenate in task order: photon and path indices never depend on threads. The chunks are copied
  // concurrently, their photons' path indices moved to the pass's numbering.
  std::vector<size_t> offset(chunks_.size() + 1, 0), path_offset(chunks_.size() + 1, 0);
  std::vector<size_t> splat_offset(chunks_.size() + 1, 0);
  for (size_t i = 0; i < chunks_.size(); ++i) {
    offset[i + 1] = offset[i] + chunks_[i].photons.size();
    path_offset[i + 1] = path_offset[i] + chunks_[i].path_light.size();
    splat_offset[i + 1] = splat_offset[i] + chunks_[i].splats.size();
  }
  photons_.resize(offset.back());
  splats_.resize(splat_offset.back());
  std::vector<uint32_t> lights(path_offset.back()), cells(path_offset.back());
  parallel(chunks_.size(), [&](size_t i) {
    const PhotonChunk &c = chunks_[i];
    Photon *out = photons_.data() + offset[i];
    for (const Photon &ph : c.photons) *out = ph, (out++)->path = ph.path + uint32_t(path_offset[i]);
    std::copy(c.path_light.begin(), c.path_light.end(), lights.begin() + ptrdiff_t(path_offset[i]));
    std::copy(c.path_emission.begin(), c.path_emission.end(), cells.begin() + ptrdiff_t(path_offset[i]));
    PhotonSplat *splat = splats_.data() + splat_offset[i];
    for (const PhotonSplat &sp : c.splats) *splat = sp, (splat++)->photon = sp.photon + uint32_t(offset[i]);
  });
  use_.reset(std::move(lights), std::move(cells));
  map_.build(photons_, parallel, filter_reach, tracer.timed(), tracer.dispersive(),
             tracer.rates_light_paths());
}

float PhotonPass::filter_reach(sdk::PerWorker<RadiusHistogram> &lookup_radii) {
  RadiusHistogram radii;
  for (RadiusHistogram &r : lookup_radii) radii.add(r), r.clear();
  return radii.quantile(kFilterShare);
}

void PhotonPass::release() {
  map_ = PhotonKdTree();
  chunks_ = std::vector<PhotonChunk>();
  photons_ = std::vector<Photon>();
  splats_ = std::vector<PhotonSplat>();
  use_ = PathUse();
}

}  // namespace nimbus::caustics
