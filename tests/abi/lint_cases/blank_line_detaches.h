/* expect: needs exactly one thread tag */

typedef struct case_detached {
  uint32_t struct_size;
  /* [main-thread] A comment separated by a blank line does not belong to the member below. */

  uint32_t (*count)(const nimbus_host_t *host);
} case_detached_t;
