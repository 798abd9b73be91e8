/* expect: nested struct */

typedef struct case_outer {
  uint32_t struct_size;
  struct inner {
    float x;
  } inner;
} case_outer_t;
