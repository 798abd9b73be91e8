/* expect: pointer parameter 'u' */

typedef struct case_order {
  uint32_t struct_size;
  /* [render-thread] Samples from ix (borrowed) with u. out caller storage. */
  void (*sample)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float u[2], float *out);
} case_order_t;
