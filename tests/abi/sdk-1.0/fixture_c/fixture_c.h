/* The pure-C 1.0 fixture library (sdk-idioms.md §4.1): what each plugin file provides to the entry.
 * Built against tests/abi/sdk-1.0/include only, so it is a plugin compiled when 1.0 shipped. */
#ifndef ABI_FIXTURE_C_H
#define ABI_FIXTURE_C_H

#include <nimbus/nimbus.h>

#define ABI_DIRECT_ID "org.nimbus.abi.direct"
#define ABI_UNIFORM_ID "org.nimbus.abi.uniform"

extern const nimbus_descriptor_t abi_direct_descriptor;
extern const nimbus_descriptor_t abi_uniform_descriptor;

/* Each creates one instance for `host`; *out is owned by the instance until its destroy. */
nimbus_status_t abi_direct_create(const nimbus_host_t *host, const nimbus_plugin_t **out);
nimbus_status_t abi_uniform_create(const nimbus_host_t *host, const nimbus_plugin_t **out);

/* The service table `id`@1, or NULL when the host lacks it or its table is smaller than 1.0's. */
const void *abi_service(const nimbus_host_t *host, const char *id, size_t min_size);

#endif
