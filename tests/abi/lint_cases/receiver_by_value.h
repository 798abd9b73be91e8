/* expect: pointer parameter 'other' */

typedef struct case_receiver {
  uint32_t struct_size;
  /* [main-thread] Only the receiver is exempt; another plugin pointer is not. */
  void (*bind)(const nimbus_plugin_t *plugin, nimbus_plugin_t *other);
} case_receiver_t;
