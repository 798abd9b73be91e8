/* org.nimbus.abi.uniform: picks every light with the same probability. The simplest sampler that still
 * exercises the whole 1.0 light-sampler table; the optional hooks are left NULL, as 1.0 allows. */
#include <stdlib.h>
#include <string.h>

#include "fixture_c.h"

static const char *const required[] = {"nimbus.host.lights@1", NULL};

const nimbus_descriptor_t abi_uniform_descriptor = {
    {sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
    ABI_UNIFORM_ID,
    "ABI 1.0 fixture: uniform light sampler",
    "Nimbus tests",
    {1, 0, 0, 0},
    NIMBUS_KIND_LIGHT_SAMPLER,
    0,
    NULL,
    required};

typedef struct uniform_sampler {
  nimbus_plugin_t plugin; /* first, so the host's pointer is also ours */
  uint32_t count;
} uniform_sampler;

static uniform_sampler *self(const nimbus_plugin_t *p) { return (uniform_sampler *)p->plugin_data; }

static nimbus_status_t prepare(const nimbus_plugin_t *p, const nimbus_scene_info_t *info) {
  if (info == NULL || info->header.struct_size < sizeof(nimbus_scene_info_t)) return NIMBUS_E_INVALID_ARG;
  self(p)->count = info->light_count;
  return NIMBUS_OK;
}

static uint32_t pick_any(const nimbus_plugin_t *p, float u, float *pmf) {
  const uint32_t n = self(p)->count;
  *pmf = 0;
  if (n == 0 || !(u >= 0.0f)) return NIMBUS_NONE;
  uint32_t i = (uint32_t)(u * (float)n);
  if (i >= n) i = n - 1; /* u just below 1 may round up */
  *pmf = 1.0f / (float)n;
  return i;
}

static uint32_t pick(const nimbus_plugin_t *p, const nimbus_interaction_t *ix, float u, float *pmf) {
  (void)ix;
  return pick_any(p, u, pmf);
}

static float pmf(const nimbus_plugin_t *p, const nimbus_interaction_t *ix, uint32_t light) {
  (void)ix;
  return light < self(p)->count ? 1.0f / (float)self(p)->count : 0.0f;
}

static const nimbus_light_sampler_v1_t table = {
    sizeof(nimbus_light_sampler_v1_t), prepare, pick, pmf, pick_any, NULL, NULL};

static nimbus_status_t init(const nimbus_plugin_t *p) {
  (void)p;
  return NIMBUS_OK;
}

static void destroy(const nimbus_plugin_t *p) { free(self(p)); }

static const void *get_interface(const nimbus_plugin_t *p, const char *id, uint32_t rev) {
  (void)p;
  return id != NULL && rev == 1 && strcmp(id, NIMBUS_IFACE_LIGHT_SAMPLER) == 0 ? &table : NULL;
}

nimbus_status_t abi_uniform_create(const nimbus_host_t *host, const nimbus_plugin_t **out) {
  (void)host;
  uniform_sampler *s = (uniform_sampler *)calloc(1, sizeof *s);
  if (s == NULL) return NIMBUS_E_NO_MEMORY;
  s->plugin.struct_size = sizeof(nimbus_plugin_t);
  s->plugin.desc = &abi_uniform_descriptor;
  s->plugin.plugin_data = s;
  s->plugin.init = init;
  s->plugin.destroy = destroy;
  s->plugin.get_interface = get_interface;
  *out = &s->plugin;
  return NIMBUS_OK;
}
