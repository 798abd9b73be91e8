/* expect: ok */

/* [render-thread] user borrowed. */
typedef void (*case_fn)(void *user);

/* Pointers of this struct are covered by name here: names borrowed; the table is host-owned. */
typedef struct case_good {
  uint32_t struct_size;
  const char *name; /* plugin-owned until destroy */
  const char *const *names;
  void *data; /* host-owned */
  /* [main-thread, !rendering] Fills out (caller storage) from ix and u (ix, u borrowed). */
  void (*fill)(const nimbus_host_t *host, const struct nimbus_plugin *plugin, const nimbus_thread_ctx_t *ctx,
               const nimbus_interaction_t *ix, const float u[2], float *out);
  /* [any-thread] Service `id` (borrowed): host-owned until the host is destroyed. */
  const void *(*find)(const nimbus_host_t *host, const char *id);
  case_fn callback;                                   /* [render-thread] */
  void (*run)(const nimbus_host_t *host, case_fn fn); /* [main-thread] fn: code, exempt */
} case_good_t;
