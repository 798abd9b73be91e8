/* expect: pointer parameter 'dir' */

typedef struct case_array {
  uint32_t struct_size;
  /* [render-thread] Radiance L (out) along dir. */
  void (*eval)(const nimbus_host_t *host, const float dir[3], float L[3]);
} case_array_t;
