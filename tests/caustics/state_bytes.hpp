// A byte buffer with the StateWriter/StateReader calls (put, get) that the solver's save and restore
// templates use, so tests can round-trip a state without a host.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace nimbus::caustics {

struct Bytes {
  std::vector<unsigned char> data;
  size_t read = 0;
  template <class T>
  void put(const T &v) {
    const auto *p = reinterpret_cast<const unsigned char *>(&v);
    data.insert(data.end(), p, p + sizeof v);
  }
  template <class T>
  bool get(T &v) {
    if (data.size() - read < sizeof v) return false;
    std::memcpy(&v, data.data() + read, sizeof v);
    read += sizeof v;
    return true;
  }
  // An array's length, then its elements, as sdk::StateWriter::put_array writes them.
  template <class T>
  void put_array(std::span<const T> a) {
    put(uint64_t(a.size()));
    for (const T &v : a) put(v);
  }
  template <class T>
  bool get_array(std::vector<T> &a, uint64_t count) {
    uint64_t n = 0;
    if (!get(n) || n != count || n > (data.size() - read) / sizeof(T)) return false;
    a.resize(size_t(n));
    for (T &v : a) get(v);
    return true;
  }
};

}  // namespace nimbus::caustics
