/* org.example.independence: a photon guide written against the C headers only, serving
 * "nimbus.iface.guiding" rev 2 (SDK 1.5) by hand. Each chain is an independence sampler: every step traces
 * a uniform u (NIMBUS_GUIDE_UNIFORM), which becomes the chain's state with probability min(1, T(u) /
 * T(state)), and the state counts once more. A proposal drawn independently of the state and accepted with
 * the target ratio is a Metropolis-Hastings move that keeps T / b, so the states satisfy nimbus/guiding.h's
 * estimator contract without any mutation; finding a small bright region is left to luck, which local
 * mutations (nimbus.guide.metropolis) improve on. A guide renders nothing itself: an integrator binds and
 * drives it. */
#include <float.h>
#include <nimbus/nimbus.h>
#include <stdlib.h>
#include <string.h>

static const nimbus_descriptor_t descriptor = {{sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
                                               "org.example.independence",
                                               "Example: independence-sampler photon guide (C)",
                                               "Example Inc.",
                                               {1, 0, 0, 0},
                                               NIMBUS_KIND_GUIDING,
                                               0,
                                               NULL,
                                               NULL};

typedef struct independence {
  nimbus_plugin_t plugin;
  nimbus_guide_pass_t pass; /* the current pass, copied in begin_pass; chains only read it */
  int pass_open;
} independence;

static independence *self(const nimbus_plugin_t *p) { return (independence *)p->plugin_data; }

/* splitmix64's finaliser: turns the keys of a chain into well-mixed bits. */
static uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/* Chain `chain` of pass `pass` draws from a PCG32 stream keyed by (seed, pass, chain) alone, never by the
 * thread it runs on, so the render is the same at any thread count. */
static nimbus_rng_t chain_stream(uint64_t seed, uint64_t pass, uint32_t chain) {
  const uint64_t key = mix64(mix64(mix64(seed) ^ pass) ^ chain);
  nimbus_rng_t r;
  r.state = 0;
  r.inc = (mix64(key) << 1) | 1u;
  nimbus_rng_next_u32(&r);
  r.state += key;
  nimbus_rng_next_u32(&r);
  return r;
}

static nimbus_status_t prepare(const nimbus_plugin_t *p, const nimbus_scene_info_t *info) {
  (void)info;
  self(p)->pass_open = 0;
  return NIMBUS_OK;
}

static nimbus_status_t begin_pass(const nimbus_plugin_t *p, const nimbus_guide_pass_t *pass) {
  if (!pass || pass->header.struct_size < sizeof *pass || pass->chain_count == 0 || pass->dims == 0)
    return NIMBUS_E_INVALID_ARG;
  self(p)->pass = *pass;
  self(p)->pass_open = 1;
  return NIMBUS_OK;
}

/* Runs on render threads, several chains at once: it writes only its own locals, u and totals. */
static nimbus_status_t run_chain(const nimbus_plugin_t *p, const nimbus_thread_ctx_t *ctx, uint32_t chain,
                                 const nimbus_guide_tracer_t *tracer, nimbus_guide_totals_t *totals) {
  const independence *g = self(p);
  const nimbus_guide_pass_t *pass = &g->pass;
  uint64_t budget, i, state_path = 0, multiplicity = 0;
  double state_target = 0; /* 0: no state yet (no path has hit) */
  nimbus_rng_t rng;
  float *u;
  uint32_t k;
  (void)ctx;
  if (!g->pass_open || chain >= pass->chain_count || !tracer || tracer->struct_size < sizeof *tracer ||
      !tracer->trace || !tracer->credit || tracer->dims != pass->dims || !totals)
    return NIMBUS_E_INVALID_ARG;
  /* Every traced path counts against the budget: an equal share, the remainder to the lowest chains. */
  budget = pass->path_budget / pass->chain_count + (chain < pass->path_budget % pass->chain_count ? 1 : 0);
  u = malloc(pass->dims * sizeof *u);
  if (!u) return NIMBUS_E_NO_MEMORY;
  rng = chain_stream(pass->seed, pass->pass, chain);
  totals->uniform_paths = totals->chain_steps = totals->proposals = totals->accepted = 0;
  totals->uniform_target_sum = 0;
  for (i = 0; i < budget; ++i) {
    uint64_t path = 0;
    double t, r;
    for (k = 0; k < pass->dims; ++k) u[k] = nimbus_rng_next_float(&rng);
    t = tracer->trace(tracer->user, u, NIMBUS_GUIDE_UNIFORM, &path);
    if (!(t > 0 && t <= DBL_MAX)) t = 0; /* negative, NaN and infinite targets count as 0 */
    ++totals->uniform_paths;
    totals->uniform_target_sum += t;
    /* Accept with probability min(1, t / state_target); the first hit is always taken. */
    r = nimbus_rng_next_float(&rng);
    if (t > 0 && r * state_target < t) {
      if (multiplicity > 0) tracer->credit(tracer->user, state_path, multiplicity);
      state_target = t, state_path = path, multiplicity = 0;
    }
    /* A chain step counts only once there is a state: the states must follow T / b, which is 0 where T is. */
    if (state_target > 0) ++multiplicity, ++totals->chain_steps;
  }
  if (multiplicity > 0) tracer->credit(tracer->user, state_path, multiplicity);
  free(u);
  return NIMBUS_OK;
}

static nimbus_status_t end_pass(const nimbus_plugin_t *p, const nimbus_guide_totals_t *totals) {
  (void)totals; /* nothing to adapt: the proposal is always uniform */
  if (!self(p)->pass_open) return NIMBUS_E_INVALID_ARG;
  self(p)->pass_open = 0;
  return NIMBUS_OK;
}

static const nimbus_guiding_v2_t guide = {sizeof(nimbus_guiding_v2_t), prepare, begin_pass, run_chain,
                                          end_pass};

static void destroy(const nimbus_plugin_t *p) { free(self(p)); }

static nimbus_status_t init(const nimbus_plugin_t *p) {
  (void)p;
  return NIMBUS_OK; /* no host services needed */
}

static const void *get_interface(const nimbus_plugin_t *p, const char *id, uint32_t rev) {
  (void)p;
  return id && rev == 2 && strcmp(id, NIMBUS_IFACE_GUIDING) == 0 ? &guide : NULL;
}

/* ---- the library: one plugin, created on demand --------------------------------------------------- */
static nimbus_status_t lib_init(const char *path) {
  (void)path;
  return NIMBUS_OK;
}
static void lib_deinit(void) {}
static uint32_t lib_count(void) { return 1; }
static const nimbus_descriptor_t *lib_descriptor(uint32_t i) { return i == 0 ? &descriptor : NULL; }

static nimbus_status_t lib_create(const char *id, const struct nimbus_host *host,
                                  const nimbus_plugin_t **out) {
  independence *g;
  if (!id || !host || !out || strcmp(id, descriptor.id) != 0) return NIMBUS_E_INVALID_ARG;
  g = calloc(1, sizeof *g);
  if (!g) return NIMBUS_E_NO_MEMORY;
  g->plugin.struct_size = sizeof(nimbus_plugin_t);
  g->plugin.desc = &descriptor;
  g->plugin.plugin_data = g;
  g->plugin.init = init;
  g->plugin.destroy = destroy;
  g->plugin.get_interface = get_interface;
  *out = &g->plugin;
  return NIMBUS_OK;
}

static const nimbus_entry_t entry = {sizeof(nimbus_entry_t),
                                     NIMBUS_ABI_VERSION_INIT,
                                     lib_init,
                                     lib_deinit,
                                     lib_count,
                                     lib_descriptor,
                                     lib_create};

NIMBUS_EXPORT const nimbus_entry_t *nimbus_plugin_entry(void) { return &entry; }
