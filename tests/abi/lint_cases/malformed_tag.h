/* expect: malformed thread tag '[main thread]' */

typedef struct case_malformed {
  uint32_t struct_size;
  /* [main-thread] Counts; see also [main thread] in the design. */
  uint32_t (*count)(const nimbus_host_t *host);
} case_malformed_t;
