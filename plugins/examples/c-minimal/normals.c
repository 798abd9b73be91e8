/* org.example.normals: shades each pixel with the shading normal of the first surface its centre sees,
 * mapped from [-1, 1] to [0, 1]. The smallest useful integrator, written against the C headers only:
 * the entry table, the descriptor and the integrator interface are filled in by hand. */
#include <nimbus/nimbus.h>
#include <stdlib.h>
#include <string.h>

static const char *const required[] = {"nimbus.host.scene-query@1", "nimbus.host.camera@1",
                                       "nimbus.host.film@1", NULL};

static const nimbus_descriptor_t descriptor = {{sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
                                               "org.example.normals",
                                               "Example: shading normals (C)",
                                               "Example Inc.",
                                               {1, 0, 0, 0},
                                               NIMBUS_KIND_INTEGRATOR,
                                               0,
                                               NULL,
                                               required};

typedef struct normals {
  nimbus_plugin_t plugin;
  const nimbus_host_t *host;
  const nimbus_host_scene_query_v1_t *scene;
  const nimbus_host_camera_v1_t *camera;
  const nimbus_host_film_v1_t *film;
} normals;

static normals *self(const nimbus_plugin_t *p) { return (normals *)p->plugin_data; }

static nimbus_status_t init(const nimbus_plugin_t *p) {
  normals *n = self(p);
  n->scene = n->host->get_service(n->host, NIMBUS_SERVICE_SCENE_QUERY, 1);
  n->camera = n->host->get_service(n->host, NIMBUS_SERVICE_CAMERA, 1);
  n->film = n->host->get_service(n->host, NIMBUS_SERVICE_FILM, 1);
  return n->scene && n->camera && n->film ? NIMBUS_OK : NIMBUS_E_UNSUPPORTED;
}

static nimbus_status_t render_tile(const nimbus_plugin_t *p, const nimbus_thread_ctx_t *ctx,
                                   const nimbus_tile_t *tile) {
  const normals *n = self(p);
  for (uint32_t y = tile->y0; y < tile->y1; ++y)
    for (uint32_t x = tile->x0; x < tile->x1; ++x) {
      const nimbus_camera_sample_t cs = {{(float)x + 0.5f, (float)y + 0.5f}, {0.5f, 0.5f}};
      float rgb[3] = {0, 0, 0};
      nimbus_ray_t ray;
      nimbus_hit_t hit;
      if (n->camera->generate_ray(n->host, &cs, &ray) > 0) {
        n->scene->intersect(n->host, ctx, &ray, &hit, 1);
        if (hit.geom_id != NIMBUS_NONE) {
          nimbus_interaction_t ix;
          n->scene->interaction(n->host, &ray, &hit, &ix);
          for (int c = 0; c < 3; ++c) rgb[c] = 0.5f * (ix.ns[c] + 1.0f);
        }
      }
      n->film->accumulate(n->host, ctx, NIMBUS_ELEMENT_BEAUTY, x, y, rgb);
    }
  return NIMBUS_OK;
}

/* The hooks this integrator does not need still get a function: the host calls every one of them. */
static nimbus_status_t prepare(const nimbus_plugin_t *p, const nimbus_render_setup_t *s) {
  (void)p, (void)s;
  return NIMBUS_OK;
}
static nimbus_status_t begin_render(const nimbus_plugin_t *p, const nimbus_render_info_t *i) {
  (void)p, (void)i;
  return NIMBUS_OK;
}
static nimbus_status_t iteration(const nimbus_plugin_t *p, uint64_t it) {
  (void)p, (void)it;
  return NIMBUS_OK;
}
static void end_render(const nimbus_plugin_t *p, nimbus_status_t reason) { (void)p, (void)reason; }

static const nimbus_integrator_v1_t integrator = {
    sizeof(nimbus_integrator_v1_t), prepare, begin_render, iteration, render_tile, iteration, end_render};

static void destroy(const nimbus_plugin_t *p) { free(self(p)); }

static const void *get_interface(const nimbus_plugin_t *p, const char *id, uint32_t rev) {
  (void)p;
  return id && rev == 1 && strcmp(id, NIMBUS_IFACE_INTEGRATOR) == 0 ? &integrator : NULL;
}

/* ---- the library: one plugin, created on demand --------------------------------------------------- */
static nimbus_status_t lib_init(const char *path) {
  (void)path;
  return NIMBUS_OK; /* no library-wide state, so nothing to count */
}
static void lib_deinit(void) {}
static uint32_t lib_count(void) { return 1; }
static const nimbus_descriptor_t *lib_descriptor(uint32_t i) { return i == 0 ? &descriptor : NULL; }

static nimbus_status_t lib_create(const char *id, const struct nimbus_host *host,
                                  const nimbus_plugin_t **out) {
  if (!id || !host || !out || strcmp(id, descriptor.id) != 0) return NIMBUS_E_INVALID_ARG;
  normals *n = calloc(1, sizeof *n);
  if (!n) return NIMBUS_E_NO_MEMORY;
  n->host = host;
  n->plugin.struct_size = sizeof(nimbus_plugin_t);
  n->plugin.desc = &descriptor;
  n->plugin.plugin_data = n;
  n->plugin.init = init;
  n->plugin.destroy = destroy;
  n->plugin.get_interface = get_interface;
  *out = &n->plugin;
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
