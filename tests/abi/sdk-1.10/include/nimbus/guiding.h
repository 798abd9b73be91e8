/* Nimbus SDK: the guiding plugin interfaces. "nimbus.iface.guiding" rev 2 (since 1.5) guides photon paths
 * in primary sample space, e.g. by Metropolis chains; rev 1, a per-worker proposal interface, is kept for
 * plugins built against 1.0 to 1.4 and no host render drives it. */
#ifndef NIMBUS_GUIDING_H
#define NIMBUS_GUIDING_H

#include "light_sampler.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct nimbus_guide_stats {
  uint32_t struct_size;
  uint32_t reserved;
  uint64_t paths_traced;
  uint64_t paths_visible;
} nimbus_guide_stats_t;

#define NIMBUS_IFACE_GUIDING "nimbus.iface.guiding"
typedef struct nimbus_guiding_v1 {
  uint32_t struct_size;
  /* [main-thread, !rendering] info borrowed. */
  nimbus_status_t (*prepare)(const nimbus_plugin_t *plugin, const nimbus_scene_info_t *info);
  /* [main-thread] */
  nimbus_status_t (*begin_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);
  /* [main-thread] Photon paths the guide wants traced in this iteration. */
  uint64_t (*budget)(const nimbus_plugin_t *plugin);
  /* [render-thread] Fills u (out, `dims` floats) with the primary-sample vector of photon path `path`. */
  void (*propose)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint64_t path, float *u,
                  uint32_t dims);
  /* [render-thread] Tells the guide whether path `path` reached an important region. */
  void (*report)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint64_t path,
                 int32_t visible);
  /* [main-thread] stats borrowed. */
  void (*end_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration, const nimbus_guide_stats_t *stats);
} nimbus_guiding_v1_t;

/* Since 1.5: "nimbus.iface.guiding" rev 2.
 *
 * Division of work. A photon path is a deterministic function of a primary-sample vector u in
 * [0,1)^dims. The integrator owns tracing and the target: it turns u into photons and scores the path
 * with a target value T(u) >= 0 (e.g. how much the camera needs the places its photons landed). The
 * guide owns the chains: it decides which u to trace next and how long each state is kept.
 *
 * One photon pass: the integrator calls begin_pass, then run_chain once for every chain c < chain_count
 * (concurrently on render threads, in any order), then end_pass. A chain's samples may depend only on
 * (seed, pass, chain), on the guide's state from earlier passes and on the targets of its own paths, never
 * on the thread or on other chains, so a render is the same at any thread count. begin_pass called again
 * with the last pass's index (a resumed render rebuilding that pass's photons) must give that pass's
 * samples again, and the end_pass that follows must leave the guide's state unchanged.
 *
 * The estimator contract. Every traced path is one of two kinds:
 * - NIMBUS_GUIDE_UNIFORM: u uniform on [0,1)^dims, independent of everything else;
 * - NIMBUS_GUIDE_PROPOSAL: any other u (e.g. a mutation).
 * The guide's states (uniform or proposal paths it keeps) must be distributed, at stationarity, with
 * density T(u) / b where b = integral of T; each state is credited its multiplicity m (the chain steps it
 * was the state for). With N_u = the uniform paths and N_m = the chain steps summed over all chains, and
 * b^ = (sum of T over uniform paths) / N_u, the integrator weights a path by the balance heuristic of the
 * two techniques: (1[uniform] + m) / (N_u + N_m T(u) / b^). A proposal that is never credited weighs 0.
 * A guide that only draws uniform paths (N_m = 0) gives the plain 1 / N_u. The integrator may count the
 * chain technique as N'_m = kappa N_m for a constant kappa in (0, 1] (e.g. distinct states over steps,
 * since a chain's samples are correlated), weighting paths by (1[uniform] + kappa m) / (N_u + N'_m T / b^):
 * any such constant keeps the estimate unbiased. */

/* The kind of a traced path (nimbus_guide_tracer_t.trace). */
#define NIMBUS_GUIDE_UNIFORM 1u
#define NIMBUS_GUIDE_PROPOSAL 2u

/* What the integrator lends a chain: its tracer. */
typedef struct nimbus_guide_tracer {
  uint32_t struct_size;
  uint32_t dims; /* length of every u the chain passes to trace */
  void *user;    /* plugin-owned (the integrator's) until run_chain returns: handed to both callbacks */
  /* [render-thread] user borrowed. Traces the photon path of u (borrowed; dims values in [0,1)) as a path of
   * kind `kind`, keeps its photons until the pass ends and returns its target value T >= 0 (0: it reached
   * nothing the camera needs). *path (out) names the path for credit. */
  double (*trace)(void *user, const float *u, uint32_t kind, uint64_t *path);
  /* [render-thread] user borrowed. Credits path `path` (returned by this chain's trace) with `multiplicity`
   * chain steps. Credits to one path add up. */
  void (*credit)(void *user, uint64_t path, uint64_t multiplicity);
} nimbus_guide_tracer_t;

#define NIMBUS_S_TYPE_GUIDE_PASS 33u
typedef struct nimbus_guide_pass {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_GUIDE_PASS */
  uint64_t seed;                 /* the render's seed */
  uint64_t pass;                 /* 1-based photon pass index */
  uint64_t path_budget;          /* paths to trace in this pass over all chains (uniform and proposals) */
  uint32_t chain_count;          /* run_chain is called for chains [0, chain_count) */
  uint32_t dims;                 /* length of every primary-sample vector */
} nimbus_guide_pass_t;

/* What a chain did (run_chain), or the sums over a pass's chains (end_pass). */
#define NIMBUS_S_TYPE_GUIDE_TOTALS 34u
typedef struct nimbus_guide_totals {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_GUIDE_TOTALS */
  uint64_t uniform_paths;        /* N_u: paths traced as NIMBUS_GUIDE_UNIFORM */
  uint64_t chain_steps;          /* N_m: multiplicities credited */
  double uniform_target_sum;     /* sum of T over the uniform paths (b^ = this / N_u) */
  uint64_t proposals;            /* paths traced as NIMBUS_GUIDE_PROPOSAL */
  uint64_t accepted;             /* proposals that became the chain's state */
} nimbus_guide_totals_t;

typedef struct nimbus_guiding_v2 {
  uint32_t struct_size;
  /* [main-thread, !rendering] info borrowed. */
  nimbus_status_t (*prepare)(const nimbus_plugin_t *plugin, const nimbus_scene_info_t *info);
  /* [main-thread] Starts a photon pass; pass borrowed. */
  nimbus_status_t (*begin_pass)(const nimbus_plugin_t *plugin, const nimbus_guide_pass_t *pass);
  /* [render-thread] Runs chain `chain` of the pass to its share of the budget through tracer (borrowed;
   * calls it on this thread only) and fills totals (out, caller storage; the caller sets header). Calls
   * for different chains may run at once. */
  nimbus_status_t (*run_chain)(const nimbus_plugin_t *plugin, const nimbus_thread_ctx_t *ctx, uint32_t chain,
                               const nimbus_guide_tracer_t *tracer, nimbus_guide_totals_t *totals);
  /* [main-thread] Ends the pass; totals borrowed: the sums over its chains. A guide adapts here (e.g. its
   * mutation size) for the next pass. */
  nimbus_status_t (*end_pass)(const nimbus_plugin_t *plugin, const nimbus_guide_totals_t *totals);
} nimbus_guiding_v2_t;

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_GUIDING_H */
