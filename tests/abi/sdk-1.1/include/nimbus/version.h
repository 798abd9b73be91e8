/* Nimbus SDK: versions, status codes and the conventions every other header relies on.
 *
 * Conventions (sdk-idioms.md):
 * - C only across the boundary; enumerations travel as fixed-width integers.
 * - Every pointer is tagged: `borrowed` (valid during the call only; default for const inputs),
 *   `out` or `caller storage` (the callee writes into the caller's memory), `host-owned until <event>`,
 *   `plugin-owned until <event>`. A parameter's tag follows its name in the same clause of the
 *   function's comment ("ix, wo borrowed; out caller storage"); a member's tag is in its own comment.
 * - Receivers are borrowed without saying so: a `const nimbus_host_t *`, `const nimbus_plugin_t *` or
 *   `const nimbus_thread_ctx_t *` parameter is the host, plugin instance or worker context the call is
 *   made on or for, valid during the call (longer only where a comment says so).
 * - Every function pointer is tagged with the thread it may be called on: [main-thread],
 *   [render-thread] or [any-thread], possibly narrowed, e.g. [main-thread, !rendering].
 * tests/abi/lint_sdk_headers.py enforces both tags; its docstring states the rule exactly. */
#ifndef NIMBUS_VERSION_H
#define NIMBUS_VERSION_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
#define NIMBUS_EXTERN_C extern "C"
#else
#define NIMBUS_EXTERN_C
#endif

#if defined(_WIN32)
#define NIMBUS_EXPORT NIMBUS_EXTERN_C __declspec(dllexport)
#else
#define NIMBUS_EXPORT NIMBUS_EXTERN_C __attribute__((visibility("default")))
#endif

/* The ABI these headers describe. A plugin loads iff its major equals the host's and its minor is not
 * newer; in 0.x the minor must match exactly. Patch never matters.
 * A minor only appends: members marked "Since 1.N" exist in tables built with SDK 1.N or later, so a
 * caller holding a table from an older plugin or host checks NIMBUS_HAS_MEMBER before using them.
 * Changelog: docs/sdk-guide.md. Frozen copies of each minor's headers: tests/abi/sdk-1.N/. */
#define NIMBUS_ABI_MAJOR 1
#define NIMBUS_ABI_MINOR 1
#define NIMBUS_ABI_PATCH 0

typedef struct nimbus_version {
  uint16_t major, minor, patch, reserved;
} nimbus_version_t;

#define NIMBUS_ABI_VERSION_INIT \
  { NIMBUS_ABI_MAJOR, NIMBUS_ABI_MINOR, NIMBUS_ABI_PATCH, 0 }

/* Status of fallible calls. Zero is success; any negative value is a failure, including values this
 * header does not know yet. */
typedef int32_t nimbus_status_t;
#define NIMBUS_OK 0
#define NIMBUS_E_INVALID_ARG (-1)
#define NIMBUS_E_UNSUPPORTED (-2)
#define NIMBUS_E_NO_MEMORY (-3)
#define NIMBUS_E_VERSION (-4)
#define NIMBUS_E_CANCELLED (-5)
#define NIMBUS_E_INTERNAL (-6)

/* "No such index": a missed ray's geom_id, a surface that is not an emitter, and so on. */
#define NIMBUS_NONE 0xFFFFFFFFu

/* Header of configuration and info structs: add-ons hang off `next` (borrowed, read-only), readers skip
 * unknown s_types, writers zero-fill. */
typedef struct nimbus_struct_header {
  uint32_t struct_size;
  uint32_t s_type;
  const void *next; /* borrowed; NULL ends the chain */
} nimbus_struct_header_t;

/* True when a table of `struct_size` bytes contains the member `member` of type `type`. */
#define NIMBUS_HAS_MEMBER(table, type, member) \
  ((table) != NULL && (table)->struct_size >= offsetof(type, member) + sizeof(((const type *)0)->member))

#endif /* NIMBUS_VERSION_H */
