/* expect: needs exactly one thread tag */

typedef struct case_untagged {
  uint32_t struct_size;
  uint32_t (*count)(const nimbus_host_t *host);
} case_untagged_t;
