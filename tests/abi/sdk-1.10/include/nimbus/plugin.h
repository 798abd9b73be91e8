/* Nimbus SDK: the one exported entry point, plugin descriptors and plugin instances. */
#ifndef NIMBUS_PLUGIN_H
#define NIMBUS_PLUGIN_H

#include "version.h"

#ifdef __cplusplus
extern "C" {
#endif

struct nimbus_host;

/* Plugin kinds, as found in nimbus_descriptor_t.kind. Only gains values. */
typedef uint32_t nimbus_plugin_kind_t;
#define NIMBUS_KIND_INTEGRATOR 1u
#define NIMBUS_KIND_LIGHT_SAMPLER 2u
#define NIMBUS_KIND_GUIDING 3u

#define NIMBUS_S_TYPE_DESCRIPTOR 1u

/* Static description of one plugin. Everything it points to is plugin-owned until the library's deinit. */
typedef struct nimbus_descriptor {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_DESCRIPTOR */
  const char *id;                /* plugin-owned: ASCII, no spaces; third parties use reverse DNS */
  const char *name;              /* plugin-owned: human-readable name */
  const char *vendor;            /* plugin-owned */
  nimbus_version_t version;      /* the plugin's own semantic version */
  nimbus_plugin_kind_t kind;
  uint32_t reserved;
  const char *const *features;          /* plugin-owned: NULL-terminated, e.g. "progressive", may be NULL */
  const char *const *required_services; /* plugin-owned: NULL-terminated "id@rev", may be NULL */
} nimbus_descriptor_t;

/* Since 1.2: the options a plugin declares, chained to its descriptor through header.next (a struct of
 * s_type NIMBUS_S_TYPE_OPTION_LIST). The host validates the scene's option keys and the command line's
 * flags against them (unknown keys and bad values are errors naming file:line:column), fills in the
 * defaults, and passes every declared option to the plugin as a resolved {name, value} pair
 * (nimbus_render_setup_t.options). It never knows a plugin's option by name. */
typedef uint32_t nimbus_option_type_t;
#define NIMBUS_OPTION_SWITCH 1u /* "on" or "off" (the host also reads true/false, yes/no, 1/0) */
#define NIMBUS_OPTION_CHOICE 2u /* one of `allowed` */
#define NIMBUS_OPTION_INT 3u    /* a decimal integer (int64) */
#define NIMBUS_OPTION_FLOAT 4u  /* a finite decimal number */
#define NIMBUS_OPTION_STRING 5u /* any text */

/* One declared option. Everything it points to is plugin-owned until the library's deinit. */
typedef struct nimbus_option_decl {
  const char *name; /* plugin-owned: [a-z][a-z0-9_]*, unique in the plugin; scene key and --name flag */
  nimbus_option_type_t type;
  uint32_t reserved;
  const char *default_value;  /* plugin-owned: a valid value of the type, as the host passes it */
  const char *const *allowed; /* plugin-owned: NULL-terminated values of a CHOICE; NULL otherwise */
  const char *doc;            /* plugin-owned: one line for `nimbus plugins --options ID` */
} nimbus_option_decl_t;

#define NIMBUS_S_TYPE_OPTION_LIST 2u
typedef struct nimbus_option_list {
  nimbus_struct_header_t header; /* s_type = NIMBUS_S_TYPE_OPTION_LIST; chained from a descriptor */
  uint32_t count;
  uint32_t reserved;
  const nimbus_option_decl_t *options; /* plugin-owned until deinit; count entries */
} nimbus_option_list_t;

/* A live plugin instance, created by nimbus_entry_t.create. */
typedef struct nimbus_plugin {
  uint32_t struct_size;
  uint32_t reserved;
  const nimbus_descriptor_t *desc; /* plugin-owned until destroy */
  void *plugin_data;               /* plugin-owned, opaque to the host */
  /* [main-thread] Called once after create; fetch host services here. */
  nimbus_status_t (*init)(const struct nimbus_plugin *plugin);
  /* [main-thread, !rendering] Frees the instance; `plugin` is invalid afterwards. */
  void (*destroy)(const struct nimbus_plugin *plugin);
  /* [any-thread] Returns the interface table `id` at revision `rev`, or NULL. The same pointer every
   * time; plugin-owned until destroy. `id` borrowed. */
  const void *(*get_interface)(const struct nimbus_plugin *plugin, const char *id, uint32_t rev);
} nimbus_plugin_t;

/* The library's entry table. `struct_size` and `abi` sit at frozen offsets (0 and 4) in every major, so
 * a host can refuse an incompatible library before calling anything. */
typedef struct nimbus_entry {
  uint32_t struct_size;
  nimbus_version_t abi; /* the SDK version the library was built against */
  /* [main-thread] Refcounted: the host may call init more than once; each successful init is matched by
   * one deinit. `library_path` borrowed. */
  nimbus_status_t (*init)(const char *library_path);
  /* [main-thread] Once per successful init. */
  void (*deinit)(void);
  /* [any-thread] Number of plugins in this library (valid after init). */
  uint32_t (*count)(void);
  /* [any-thread] Descriptor i < count(); plugin-owned until deinit. NULL if i is out of range. */
  const nimbus_descriptor_t *(*descriptor)(uint32_t i);
  /* [main-thread] Creates plugin `id` (borrowed). `host` is host-owned and outlives the instance.
   * *out is plugin-owned until its destroy. */
  nimbus_status_t (*create)(const char *id, const struct nimbus_host *host, const nimbus_plugin_t **out);
} nimbus_entry_t;

/* The one symbol a plugin library exports. Returns its entry table (never NULL): static storage,
 * plugin-owned for the life of the process (1.x hosts never unload a library). [main-thread] */
typedef const nimbus_entry_t *(*nimbus_plugin_entry_fn)(void);
#define NIMBUS_PLUGIN_ENTRY_SYMBOL "nimbus_plugin_entry"

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_PLUGIN_H */
