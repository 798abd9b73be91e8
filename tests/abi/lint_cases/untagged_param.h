/* expect: pointer parameter 'value' */

typedef struct case_param {
  uint32_t struct_size;
  /* [render-thread] Adds value to the pixel. */
  void (*add)(const nimbus_host_t *host, uint32_t x, const float *value);
} case_param_t;
