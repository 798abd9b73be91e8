/* org.nimbus.abi.direct: direct lighting only. Camera ray, first hit, its emission, and one
 * next-event-estimation sample of the light the bound light sampler picks (no MIS: the BSDF is never
 * sampled). It registers a `caustics` element and writes zero into it, as a photon-mapping integrator
 * with no caustic paths would, so the test covers element registration through the 1.0 film table. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fixture_c.h"

static const char *const required[] = {"nimbus.host.scene-query@1",
                                       "nimbus.host.camera@1",
                                       "nimbus.host.bsdf@1",
                                       "nimbus.host.lights@1",
                                       "nimbus.host.film@1",
                                       "nimbus.host.rng@1",
                                       NULL};
static const char *const features[] = {"progressive", NULL};

const nimbus_descriptor_t abi_direct_descriptor = {
    {sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
    ABI_DIRECT_ID,
    "ABI 1.0 fixture: direct lighting",
    "Nimbus tests",
    {1, 0, 0, 0},
    NIMBUS_KIND_INTEGRATOR,
    0,
    features,
    required};

typedef struct direct {
  nimbus_plugin_t plugin;
  const nimbus_host_t *host;
  const nimbus_host_scene_query_v1_t *scene;
  const nimbus_host_camera_v1_t *camera;
  const nimbus_host_bsdf_v1_t *bsdf;
  const nimbus_host_lights_v1_t *lights;
  const nimbus_host_film_v1_t *film;
  const nimbus_host_rng_v1_t *rng;
  const nimbus_plugin_t *sampler;
  const nimbus_light_sampler_v1_t *sampler_iface;
  nimbus_element_t caustics; /* NIMBUS_ELEMENT_INVALID unless requested */
  uint32_t width;
} direct;

static direct *self(const nimbus_plugin_t *p) { return (direct *)p->plugin_data; }
static float next(nimbus_rng_t *rng) { return nimbus_rng_next_float(rng); }
static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static nimbus_status_t init(const nimbus_plugin_t *p) {
  direct *d = self(p);
  d->scene = abi_service(d->host, NIMBUS_SERVICE_SCENE_QUERY, sizeof(nimbus_host_scene_query_v1_t));
  d->camera = abi_service(d->host, NIMBUS_SERVICE_CAMERA, sizeof(nimbus_host_camera_v1_t));
  d->bsdf = abi_service(d->host, NIMBUS_SERVICE_BSDF, sizeof(nimbus_host_bsdf_v1_t));
  d->lights = abi_service(d->host, NIMBUS_SERVICE_LIGHTS, sizeof(nimbus_host_lights_v1_t));
  d->film = abi_service(d->host, NIMBUS_SERVICE_FILM, sizeof(nimbus_host_film_v1_t));
  d->rng = abi_service(d->host, NIMBUS_SERVICE_RNG, sizeof(nimbus_host_rng_v1_t));
  return d->scene && d->camera && d->bsdf && d->lights && d->film && d->rng ? NIMBUS_OK
                                                                            : NIMBUS_E_UNSUPPORTED;
}

static nimbus_status_t prepare(const nimbus_plugin_t *p, const nimbus_render_setup_t *setup) {
  direct *d = self(p);
  if (setup->header.struct_size < sizeof(nimbus_render_setup_t)) return NIMBUS_E_INVALID_ARG;
  d->sampler = setup->light_sampler;
  d->sampler_iface = setup->light_sampler_iface;
  if (d->sampler == NULL || d->sampler_iface == NULL) return NIMBUS_E_INVALID_ARG;
  d->caustics = d->film->register_element(d->host, "caustics", 3, NIMBUS_ELEMENT_AVERAGE);
  return d->caustics >= 1 ? NIMBUS_OK : NIMBUS_E_INTERNAL;
}

static nimbus_status_t begin_render(const nimbus_plugin_t *p, const nimbus_render_info_t *info) {
  direct *d = self(p);
  uint32_t height = 0;
  (void)info;
  d->camera->resolution(d->host, &d->width, &height);
  if (!d->film->is_active(d->host, d->caustics)) d->caustics = NIMBUS_ELEMENT_INVALID;
  return NIMBUS_OK;
}

static nimbus_status_t no_op(const nimbus_plugin_t *p, uint64_t iteration) {
  (void)p, (void)iteration;
  return NIMBUS_OK;
}

/* One light sample towards the surface point ix seen along -wo_dir, added to L. */
static void next_event(const direct *d, const nimbus_thread_ctx_t *ctx, const nimbus_interaction_t *ix,
                       const float wo[3], nimbus_rng_t *rng, float weight, float L[3]) {
  const float u_pick = next(rng);
  const float u[2] = {next(rng), next(rng)};
  float pmf = 0, f[3], bsdf_pdf = 0;
  const uint32_t light = d->sampler_iface->pick(d->sampler, ix, u_pick, &pmf);
  if (light == NIMBUS_NONE || !(pmf > 0)) return;
  nimbus_light_incident_t ls;
  d->lights->sample_incident(d->host, light, ix, u, &ls);
  if (!(ls.pdf > 0)) return;
  d->bsdf->eval(d->host, ix, wo, ls.wi, NIMBUS_MODE_RADIANCE, f, &bsdf_pdf, NULL);
  const float cos_i = fabsf(dot3(ls.wi, ix->ns));
  if (f[0] + f[1] + f[2] <= 0 || cos_i <= 0) return;
  nimbus_ray_t shadow;
  uint8_t blocked = 0;
  d->scene->spawn_ray_to(d->host, ix, ls.p, &shadow);
  if (ls.flags & NIMBUS_LIGHT_INFINITE) shadow.tfar = INFINITY;
  d->scene->occluded(d->host, ctx, &shadow, &blocked, 1);
  if (blocked) return;
  const float w = weight * cos_i / (pmf * ls.pdf);
  for (int c = 0; c < 3; ++c) L[c] += w * f[c] * ls.L[c];
}

static void shade(const direct *d, const nimbus_thread_ctx_t *ctx, uint32_t x, uint32_t y, uint64_t iteration,
                  float L[3]) {
  nimbus_rng_t rng;
  d->rng->derive(d->host, (uint64_t)y * d->width + x, iteration, 0, &rng);
  nimbus_camera_sample_t cs;
  cs.film[0] = (float)x + next(&rng);
  cs.film[1] = (float)y + next(&rng);
  cs.lens[0] = next(&rng);
  cs.lens[1] = next(&rng);
  nimbus_ray_t ray;
  const float weight = d->camera->generate_ray(d->host, &cs, &ray);
  if (!(weight > 0)) return;
  nimbus_hit_t hit;
  d->scene->intersect(d->host, ctx, &ray, &hit, 1);
  if (hit.geom_id == NIMBUS_NONE) return;
  nimbus_interaction_t ix;
  d->scene->interaction(d->host, &ray, &hit, &ix);
  const float wo[3] = {-ray.dir[0], -ray.dir[1], -ray.dir[2]};
  if (ix.flags & NIMBUS_IX_EMISSIVE) {
    float le[3];
    d->lights->eval_emitted(d->host, &ix, wo, le);
    for (int c = 0; c < 3; ++c) L[c] += weight * le[c];
  }
  next_event(d, ctx, &ix, wo, &rng, weight, L);
}

static nimbus_status_t render_tile(const nimbus_plugin_t *p, const nimbus_thread_ctx_t *ctx,
                                   const nimbus_tile_t *tile) {
  const direct *d = self(p);
  static const float zero[3] = {0, 0, 0};
  for (uint32_t y = tile->y0; y < tile->y1; ++y)
    for (uint32_t x = tile->x0; x < tile->x1; ++x) {
      float L[3] = {0, 0, 0};
      shade(d, ctx, x, y, tile->iteration, L);
      d->film->accumulate(d->host, ctx, NIMBUS_ELEMENT_BEAUTY, x, y, L);
      if (d->caustics != NIMBUS_ELEMENT_INVALID) d->film->accumulate(d->host, ctx, d->caustics, x, y, zero);
    }
  return NIMBUS_OK;
}

static void end_render(const nimbus_plugin_t *p, nimbus_status_t reason) { (void)p, (void)reason; }

static const nimbus_integrator_v1_t table = {
    sizeof(nimbus_integrator_v1_t), prepare, begin_render, no_op, render_tile, no_op, end_render};

static void destroy(const nimbus_plugin_t *p) { free(self(p)); }

static const void *get_interface(const nimbus_plugin_t *p, const char *id, uint32_t rev) {
  (void)p;
  return id != NULL && rev == 1 && strcmp(id, NIMBUS_IFACE_INTEGRATOR) == 0 ? &table : NULL;
}

nimbus_status_t abi_direct_create(const nimbus_host_t *host, const nimbus_plugin_t **out) {
  direct *d = (direct *)calloc(1, sizeof *d);
  if (d == NULL) return NIMBUS_E_NO_MEMORY;
  d->host = host;
  d->caustics = NIMBUS_ELEMENT_INVALID;
  d->plugin.struct_size = sizeof(nimbus_plugin_t);
  d->plugin.desc = &abi_direct_descriptor;
  d->plugin.plugin_data = d;
  d->plugin.init = init;
  d->plugin.destroy = destroy;
  d->plugin.get_interface = get_interface;
  *out = &d->plugin;
  return NIMBUS_OK;
}
