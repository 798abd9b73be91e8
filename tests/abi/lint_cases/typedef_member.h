/* expect: case_typed_t.hook: needs exactly one thread tag */

/* [render-thread] user borrowed. */
typedef void (*case_hook_fn)(void *user);
typedef struct case_typed {
  uint32_t struct_size;
  case_hook_fn hook; /* called per tile */
} case_typed_t;
