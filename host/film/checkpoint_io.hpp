// Binary reading and writing of checkpoint files (checkpoint.hpp has the format): little-endian fixed-size
// values, length-prefixed strings and byte blocks, and a running checksum of everything written or read.
// Every read is checked against the bytes left, so a truncated or corrupted file is reported, not trusted.
#pragma once

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/checksum.hpp"

namespace nimbus::checkpoint_io {

// Bounds that no real checkpoint reaches, checked before allocating, so a corrupted length field is
// reported as such instead of attempting a huge allocation.
constexpr uint32_t kMaxStringBytes = 1u << 20;

struct FileCloser {
  void operator()(std::FILE *f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

class Writer {
 public:
  explicit Writer(std::FILE *f) : f_(f) {}

  // An empty block (an empty vector's data() may be null) writes nothing.
  void bytes(const void *data, size_t n) {
    if (n == 0) return;
    sum_.update(static_cast<const uint8_t *>(data), n);
    if (ok_ && std::fwrite(data, 1, n, f_) != n) ok_ = false;
  }
  void u32(uint32_t v) { fixed(v, 4); }
  void u64(uint64_t v) { fixed(v, 8); }
  void f64(double v) { fixed(std::bit_cast<uint64_t>(v), 8); }
  void str(const std::string &s) {
    u32(static_cast<uint32_t>(s.size()));
    bytes(s.data(), s.size());
  }
  // A u64 byte count, then the bytes.
  void blob(std::span<const uint8_t> data) {
    u64(data.size());
    bytes(data.data(), data.size());
  }
  // Staged through a byte buffer so the encoding is little-endian whatever the host's byte order.
  void doubles(std::span<const double> values) {
    constexpr size_t kBatch = 8192;
    std::vector<uint8_t> buffer(std::min(values.size(), kBatch) * 8);
    for (size_t first = 0; first < values.size(); first += kBatch) {
      const size_t n = std::min(kBatch, values.size() - first);
      for (size_t i = 0; i < n; ++i) store_le(&buffer[i * 8], std::bit_cast<uint64_t>(values[first + i]), 8);
      bytes(buffer.data(), n * 8);
    }
  }
  // The checksum itself is not part of what it sums.
  void finish() {
    uint8_t b[8];
    store_le(b, sum_.value(), 8);
    if (ok_ && std::fwrite(b, 1, 8, f_) != 8) ok_ = false;
  }
  bool ok() const { return ok_; }

 private:
  void fixed(uint64_t v, int n) {
    uint8_t b[8];
    store_le(b, v, n);
    bytes(b, size_t(n));
  }

  std::FILE *f_;
  Checksum sum_;
  bool ok_ = true;
};

// Reads the file front to back, checking every read against the bytes left, so a truncated file is
// reported with where it ends instead of as garbage.
class Reader {
 public:
  Reader(std::FILE *f, uint64_t size) : f_(f), size_(size) {}

  // `what` names the field for the error message.
  bool bytes(void *out, size_t n, const std::string &what) {
    if (n > size_ - offset_) return truncated(what);
    if (n > 0 && std::fread(out, 1, n, f_) != n) {
      error_ = std::string("read error inside ") + what + ": " + std::strerror(errno);
      return false;
    }
    sum_.update(static_cast<const uint8_t *>(out), n);
    offset_ += n;
    return true;
  }
  bool u32(uint32_t &v, const std::string &what) { return fixed(v, 4, what); }
  bool u64(uint64_t &v, const std::string &what) { return fixed(v, 8, what); }
  bool f64(double &v, const std::string &what) {
    uint64_t bits = 0;
    if (!fixed(bits, 8, what)) return false;
    v = std::bit_cast<double>(bits);
    return true;
  }
  bool str(std::string &s, const std::string &what) {
    uint32_t n = 0;
    if (!u32(n, what)) return false;
    if (n > kMaxStringBytes) return corrupted(what + " claims " + std::to_string(n) + " bytes");
    s.resize(n);
    return bytes(s.data(), n, what);
  }
  bool blob(std::vector<uint8_t> &out, const std::string &what) {
    uint64_t n = 0;
    if (!u64(n, what)) return false;
    if (n > size_ - offset_) return truncated(what);
    out.resize(n);
    return bytes(out.data(), n, what);
  }
  bool doubles(std::vector<double> &out, uint64_t count, const std::string &what) {
    if (count > (size_ - offset_) / 8) return truncated(what);
    out.resize(count);
    constexpr size_t kBatch = 8192;
    std::vector<uint8_t> buffer(std::min<uint64_t>(count, kBatch) * 8);
    for (size_t first = 0; first < count; first += kBatch) {
      const size_t n = std::min<uint64_t>(kBatch, count - first);
      if (!bytes(buffer.data(), n * 8, what)) return false;
      for (size_t i = 0; i < n; ++i) out[first + i] = std::bit_cast<double>(load_le(&buffer[i * 8], 8));
    }
    return true;
  }
  bool corrupted(const std::string &why) {
    error_ = "corrupted: " + why;
    return false;
  }

  uint64_t checksum_so_far() const { return sum_.value(); }
  uint64_t offset() const { return offset_; }
  uint64_t size() const { return size_; }
  const std::string &error() const { return error_; }

 private:
  template <class T>
  bool fixed(T &v, int n, const std::string &what) {
    uint8_t b[8];
    if (!bytes(b, size_t(n), what)) return false;
    v = static_cast<T>(load_le(b, n));
    return true;
  }
  bool truncated(const std::string &what) {
    error_ = "truncated: the file ends at byte " + std::to_string(size_) + ", inside " + what;
    return false;
  }

  std::FILE *f_;
  uint64_t size_, offset_ = 0;
  Checksum sum_;
  std::string error_;
};

}  // namespace nimbus::checkpoint_io
