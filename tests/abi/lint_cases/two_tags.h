/* expect: found 2 */

typedef struct case_two_tags {
  uint32_t struct_size;
  /* [main-thread] Counts. */
  uint32_t (*count)(const nimbus_host_t *host); /* [any-thread] */
} case_two_tags_t;
