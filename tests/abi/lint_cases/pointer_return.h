/* expect: returns a pointer */

typedef struct case_return {
  uint32_t struct_size;
  /* [any-thread] Table `id` (borrowed). */
  const void *(*get)(const nimbus_host_t *host, const char *id);
} case_return_t;
