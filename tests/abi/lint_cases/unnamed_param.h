/* expect: unnamed pointer parameter */

typedef struct case_unnamed {
  uint32_t struct_size;
  /* [render-thread] Everything borrowed. */
  void (*eval)(const nimbus_host_t *host, const float *);
} case_unnamed_t;
