/* expect: case_field_t.vendor: pointer member has no ownership word */

/* Strings are static. */
typedef struct case_field {
  const char *id; /* plugin-owned */
  const char *vendor;
} case_field_t;
