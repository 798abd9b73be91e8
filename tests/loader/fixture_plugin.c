/* One source for every fixture plugin of the loader tests; compile definitions pick the behaviour.
 *
 * Each function the host can reach appends "<event> <detail>" to $NIMBUS_TEST_MARKER_DIR/<FIXTURE_NAME>.log,
 * so a test proves which calls happened, e.g. that an ABI-refused library saw nothing beyond its entry.
 *
 *   FIXTURE_NAME          marker file name (required)
 *   FIXTURE_ABI_MAJOR/MINOR/PATCH   version reported in the entry (default: these headers')
 *   FIXTURE_ENTRY_SIZE    entry struct_size (default: sizeof(nimbus_entry_t))
 *   FIXTURE_ENTRY_NULL    nimbus_plugin_entry returns NULL
 *   FIXTURE_NO_ENTRY      exports an unrelated function instead of nimbus_plugin_entry
 *   FIXTURE_UNRESOLVED    references a symbol nobody defines (only loadable lazily)
 *   FIXTURE_INIT_STATUS   library init result (default NIMBUS_OK)
 *   FIXTURE_COUNT         plugins in the library: 0, 1 (default) or 2
 *   FIXTURE_DESCRIPTOR_NULL   descriptor(0) returns NULL
 *   FIXTURE_ID, FIXTURE_KIND, FIXTURE_REQUIRES   first plugin's id, kind, one required service
 *   FIXTURE_ID2, FIXTURE_KIND2                    second plugin's id and kind
 *   FIXTURE_PLUGIN_INIT_STATUS   instance init result (default NIMBUS_OK) */
#include <nimbus/host.h>
#include <nimbus/plugin.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef FIXTURE_NAME
#error "FIXTURE_NAME must name the marker file"
#endif
#ifndef FIXTURE_ABI_MAJOR
#define FIXTURE_ABI_MAJOR NIMBUS_ABI_MAJOR
#endif
#ifndef FIXTURE_ABI_MINOR
#define FIXTURE_ABI_MINOR NIMBUS_ABI_MINOR
#endif
#ifndef FIXTURE_ABI_PATCH
#define FIXTURE_ABI_PATCH NIMBUS_ABI_PATCH
#endif
#ifndef FIXTURE_ENTRY_SIZE
#define FIXTURE_ENTRY_SIZE sizeof(nimbus_entry_t)
#endif
#ifndef FIXTURE_INIT_STATUS
#define FIXTURE_INIT_STATUS NIMBUS_OK
#endif
#ifndef FIXTURE_COUNT
#define FIXTURE_COUNT 1
#endif
#ifndef FIXTURE_ID
#define FIXTURE_ID "org.nimbus.test.good"
#endif
#ifndef FIXTURE_KIND
#define FIXTURE_KIND NIMBUS_KIND_INTEGRATOR
#endif
#ifndef FIXTURE_REQUIRES
#define FIXTURE_REQUIRES "nimbus.host.film@1"
#endif
#ifndef FIXTURE_ID2
#define FIXTURE_ID2 "org.nimbus.test.second"
#endif
#ifndef FIXTURE_KIND2
#define FIXTURE_KIND2 NIMBUS_KIND_LIGHT_SAMPLER
#endif
#ifndef FIXTURE_PLUGIN_INIT_STATUS
#define FIXTURE_PLUGIN_INIT_STATUS NIMBUS_OK
#endif

static void mark(const char *event, const char *detail) {
  const char *dir = getenv("NIMBUS_TEST_MARKER_DIR");
  if (dir == NULL || dir[0] == '\0') return;
  char path[4096];
  if (snprintf(path, sizeof path, "%s/%s.log", dir, FIXTURE_NAME) >= (int)sizeof path) return;
  FILE *f = fopen(path, "a");
  if (f == NULL) return;
  fprintf(f, "%s %s\n", event, detail != NULL ? detail : "-");
  fclose(f);
}

static const char *const features[] = {"progressive", NULL};
static const char *const required_first[] = {FIXTURE_REQUIRES, NULL};

static const nimbus_descriptor_t descriptors[2] = {
    {{sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
     FIXTURE_ID,
     "Fixture " FIXTURE_NAME,
     "Nimbus tests",
     {1, 2, 3, 0},
     FIXTURE_KIND,
     0,
     features,
     required_first},
    {{sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NULL},
     FIXTURE_ID2,
     "Fixture " FIXTURE_NAME " #2",
     "Nimbus tests",
     {0, 1, 0, 0},
     FIXTURE_KIND2,
     0,
     NULL,
     NULL},
};

/* Refcounted per the entry contract: the host may init more than once. */
static int init_count;

#ifdef FIXTURE_UNRESOLVED
void nimbus_fixture_symbol_nobody_defines(void);
#endif

static nimbus_status_t lib_init(const char *library_path) {
  mark("init", library_path);
#ifdef FIXTURE_UNRESOLVED
  nimbus_fixture_symbol_nobody_defines();
#endif
  if (FIXTURE_INIT_STATUS != NIMBUS_OK) return FIXTURE_INIT_STATUS;
  ++init_count;
  return NIMBUS_OK;
}

static void lib_deinit(void) {
  char count[16];
  snprintf(count, sizeof count, "%d", --init_count);
  mark("deinit", count);
}

static uint32_t lib_count(void) {
  mark("count", NULL);
  return FIXTURE_COUNT;
}

static const nimbus_descriptor_t *lib_descriptor(uint32_t i) {
  mark("descriptor", NULL);
#ifdef FIXTURE_DESCRIPTOR_NULL
  if (i == 0) return NULL;
#endif
  return i < FIXTURE_COUNT ? &descriptors[i] : NULL;
}

static nimbus_status_t plugin_init(const nimbus_plugin_t *plugin) {
  mark("plugin-init", plugin->desc->id);
  /* Fetch what the descriptor declares mandatory, as a real plugin would; the host promised it exists. */
  const nimbus_host_t *host = (const nimbus_host_t *)plugin->plugin_data;
  const char *const *req = plugin->desc->required_services;
  for (; req != NULL && *req != NULL; ++req) {
    char id[256];
    const char *at = strrchr(*req, '@');
    size_t len = at != NULL ? (size_t)(at - *req) : 0;
    if (len == 0 || len >= sizeof id) return NIMBUS_E_INVALID_ARG;
    memcpy(id, *req, len);
    id[len] = '\0';
    if (host == NULL || host->get_service(host, id, (uint32_t)strtoul(at + 1, NULL, 10)) == NULL) {
      return NIMBUS_E_UNSUPPORTED;
    }
  }
  return FIXTURE_PLUGIN_INIT_STATUS;
}

static void plugin_destroy(const nimbus_plugin_t *plugin) {
  mark("destroy", plugin->desc->id);
  free((void *)plugin);
}

static const void *plugin_get_interface(const nimbus_plugin_t *plugin, const char *id, uint32_t rev) {
  (void)plugin, (void)id, (void)rev;
  return NULL; /* the loader tests never render */
}

static nimbus_status_t lib_create(const char *id, const nimbus_host_t *host, const nimbus_plugin_t **out) {
  mark("create", id);
  for (uint32_t i = 0; i < FIXTURE_COUNT; ++i) {
    if (strcmp(id, descriptors[i].id) != 0) continue;
    nimbus_plugin_t *p = (nimbus_plugin_t *)calloc(1, sizeof *p);
    if (p == NULL) return NIMBUS_E_NO_MEMORY;
    p->struct_size = sizeof *p;
    p->desc = &descriptors[i];
    p->plugin_data = (void *)host;
    p->init = plugin_init;
    p->destroy = plugin_destroy;
    p->get_interface = plugin_get_interface;
    *out = p;
    return NIMBUS_OK;
  }
  return NIMBUS_E_INVALID_ARG;
}

static const nimbus_entry_t entry = {
    FIXTURE_ENTRY_SIZE, {FIXTURE_ABI_MAJOR, FIXTURE_ABI_MINOR, FIXTURE_ABI_PATCH, 0},
    lib_init,           lib_deinit,
    lib_count,          lib_descriptor,
    lib_create,
};

#ifdef FIXTURE_NO_ENTRY
/* A shared library that is not a plugin: exports something, just not the entry. */
NIMBUS_EXPORT const nimbus_entry_t *fixture_unrelated_function(void) { return &entry; }
#else
NIMBUS_EXPORT const nimbus_entry_t *nimbus_plugin_entry(void) {
#ifdef FIXTURE_ENTRY_NULL
  return NULL;
#else
  return &entry;
#endif
}
#endif
