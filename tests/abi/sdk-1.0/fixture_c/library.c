/* Entry of the pure-C 1.0 fixture library: the one exported symbol and a refcounted init, written out
 * by hand (no wrapper) so the test covers a plugin that sees only the C headers. */
#include <string.h>

#include "fixture_c.h"

static int refcount;

static nimbus_status_t lib_init(const char *library_path) {
  (void)library_path;
  ++refcount; /* [main-thread] only: no atomics needed */
  return NIMBUS_OK;
}

static void lib_deinit(void) { --refcount; }

static uint32_t lib_count(void) { return 2; }

static const nimbus_descriptor_t *lib_descriptor(uint32_t i) {
  return i == 0 ? &abi_direct_descriptor : i == 1 ? &abi_uniform_descriptor : NULL;
}

static nimbus_status_t lib_create(const char *id, const struct nimbus_host *host,
                                  const nimbus_plugin_t **out) {
  if (id == NULL || host == NULL || out == NULL) return NIMBUS_E_INVALID_ARG;
  *out = NULL;
  if (strcmp(id, ABI_DIRECT_ID) == 0) return abi_direct_create(host, out);
  if (strcmp(id, ABI_UNIFORM_ID) == 0) return abi_uniform_create(host, out);
  return NIMBUS_E_INVALID_ARG;
}

const void *abi_service(const nimbus_host_t *host, const char *id, size_t min_size) {
  const uint32_t *table = (const uint32_t *)host->get_service(host, id, 1);
  /* Every table starts with its struct_size: a newer host may hand out a bigger one, never a smaller. */
  return table != NULL && *table >= min_size ? table : NULL;
}

static const nimbus_entry_t entry = {sizeof(nimbus_entry_t),
                                     NIMBUS_ABI_VERSION_INIT,
                                     lib_init,
                                     lib_deinit,
                                     lib_count,
                                     lib_descriptor,
                                     lib_create};

NIMBUS_EXPORT const nimbus_entry_t *nimbus_plugin_entry(void) { return &entry; }
