/* expect: bitfield */

typedef struct case_bits {
  uint32_t flags : 4;
} case_bits_t;
