/* Nimbus SDK: the conventions every other header relies on, the export macros and the header of
 * growing structs.
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
#ifndef NIMBUS_BASE_H
#define NIMBUS_BASE_H

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

#endif /* NIMBUS_BASE_H */
