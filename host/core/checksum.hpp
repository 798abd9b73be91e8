// Content checksums: a 64-bit checksum over a byte stream fed in pieces of any size, and the 16-hex-digit
// content_hash of a whole buffer. Checkpoints use it to detect corruption; the scene parser to fingerprint
// every file it reads, so a checkpoint resumes only into the render it was made for.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include <nimbus/cpp/rng.hpp>

namespace nimbus {

inline void store_le(uint8_t *p, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline uint64_t load_le(const uint8_t *p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}

// Little-endian 8-byte words chained through the splitmix64 finaliser (bijective, so any single changed
// word changes the result), the zero-padded tail and the length last, so truncation and appended bytes
// change it too.
class Checksum {
 public:
  void update(const uint8_t *p, size_t n) {
    length_ += n;
    while (n > 0) {
      if (fill_ == 0) {
        for (; n >= 8; p += 8, n -= 8) word(load_le(p, 8));
        if (n == 0) break;
      }
      pending_[fill_++] = *p++;
      --n;
      if (fill_ == 8) {
        word(load_le(pending_.data(), 8));
        fill_ = 0;
      }
    }
  }
  uint64_t value() const {
    Checksum c = *this;
    if (c.fill_ > 0) {
      std::fill(c.pending_.begin() + c.fill_, c.pending_.end(), uint8_t(0));
      c.word(load_le(c.pending_.data(), 8));
    }
    return mix64(c.h_ ^ c.length_);
  }

 private:
  void word(uint64_t w) { h_ = mix64(h_ ^ w); }

  uint64_t h_ = 0x4e494d4255534b31ULL, length_ = 0;
  std::array<uint8_t, 8> pending_{};
  size_t fill_ = 0;
};

// 16 hex digits of the Checksum of `bytes`.
inline std::string content_hash(std::string_view bytes) {
  Checksum c;
  c.update(reinterpret_cast<const uint8_t *>(bytes.data()), bytes.size());
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(c.value()));
  return hex;
}

}  // namespace nimbus
