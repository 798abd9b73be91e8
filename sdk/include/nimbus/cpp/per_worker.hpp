// Per-worker state for plugin code, sized in begin_render and indexed by the worker of a callback (never
// thread_local, sdk-idioms.md 1.7). Requires C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <nimbus/host.h>

namespace nimbus {
namespace sdk {

// Bytes of a cache line on the x86-64 and AArch64 machines Nimbus runs on: data two workers write must
// not share one.
inline constexpr size_t kCacheLineBytes = 64;

// Per-worker state, sized in begin_render (never thread_local). Each worker's item starts a cache line of
// its own: items written on every sample by different workers must not share a line, or the workers
// stall on each other's writes (false sharing).
template <class T>
class PerWorker {
  struct alignas(kCacheLineBytes) Slot {
    T item{};
  };

 public:
  class iterator {
   public:
    explicit iterator(typename std::vector<Slot>::iterator it) : it_(it) {}
    T &operator*() const { return it_->item; }
    iterator &operator++() {
      ++it_;
      return *this;
    }
    bool operator==(const iterator &o) const { return it_ == o.it_; }
    bool operator!=(const iterator &o) const { return it_ != o.it_; }

   private:
    typename std::vector<Slot>::iterator it_;
  };

  void resize(uint32_t workers) { items_.assign(workers, Slot{}); }
  T &operator[](const nimbus_thread_ctx_t &ctx) { return items_[ctx.worker_index].item; }
  T &operator[](uint32_t i) { return items_[i].item; }
  size_t size() const { return items_.size(); }
  iterator begin() { return iterator(items_.begin()); }
  iterator end() { return iterator(items_.end()); }

 private:
  std::vector<Slot> items_;
};

}  // namespace sdk
}  // namespace nimbus
