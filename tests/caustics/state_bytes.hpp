// A byte buffer with the StateWriter/StateReader calls (put, get) that the solver's save and restore
// templates use, so tests can round-trip a state without a host.
#pragma once

#include <cstring>
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
};

}  // namespace nimbus::caustics
