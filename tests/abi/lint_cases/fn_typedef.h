/* expect: case_cb_fn: pointer parameter 'user' */

/* [render-thread] A callback; nothing says who owns user. */
typedef void (*case_cb_fn)(const nimbus_thread_ctx_t *ctx, void *user);
