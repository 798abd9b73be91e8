// A plugin's learnt state across a resumed render (nimbus/render_state.h) for C++ plugins: a writer and a
// reader of plain values and arrays, and the interface table, which calls the plugin class's
//   nimbus_status_t save_state(uint64_t iterations, sdk::StateWriter &w);
//   nimbus_status_t restore_state(uint64_t iterations, sdk::StateReader &r);
// A plugin serves it from its interface() override:
//   if (const void *t = sdk::render_state_interface<MyPlugin>(id, rev)) return t;
// Values are stored as their bytes (this machine's byte order): the state is read back by the same
// plugin build on the same kind of machine, and the plugin's own version tag guards the format.
#pragma once

#include <nimbus/render_state.h>
#include <nimbus/nimbus.hpp>

#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace nimbus::sdk {

// Writes through the host's writer; the first failure sticks and is what save_state returns.
class StateWriter {
 public:
  explicit StateWriter(const nimbus_state_writer_t *w) : w_(w) {}

  // A value without padding bytes, so that the same state always writes the same bytes.
  template <class T>
  void put(const T &v) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>);
    bytes(&v, sizeof v);
  }
  // A count, then the elements.
  template <class T>
  void put_array(std::span<const T> a) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>);
    put(uint64_t(a.size()));
    bytes(a.data(), a.size_bytes());
  }
  nimbus_status_t status() const { return status_; }

 private:
  void bytes(const void *p, size_t n) {
    if (status_ == NIMBUS_OK && n > 0) status_ = w_->write(w_, p, n);
  }
  const nimbus_state_writer_t *w_;
  nimbus_status_t status_ = NIMBUS_OK;
};

// Reads what StateWriter wrote, checking every read against the bytes left.
class StateReader {
 public:
  StateReader(const void *bytes, uint64_t size) : p_(static_cast<const uint8_t *>(bytes)), left_(size) {}

  template <class T>
  bool get(T &v) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>);
    return take(&v, sizeof v);
  }
  // An array written by put_array, of exactly `count` elements (the reader knows the size it needs).
  template <class T>
  bool get_array(std::vector<T> &a, uint64_t count) {
    uint64_t n = 0;
    if (!get(n) || n != count || n > left_ / sizeof(T)) return ok_ = false;
    a.resize(size_t(n));
    return take(a.data(), n * sizeof(T));
  }
  template <class T>
  bool get_array(std::span<T> a) {
    uint64_t n = 0;
    if (!get(n) || n != a.size()) return ok_ = false;
    return take(a.data(), a.size_bytes());
  }
  // Everything read, nothing left over.
  bool done() const { return ok_ && left_ == 0; }

 private:
  bool take(void *out, uint64_t n) {
    if (!ok_ || n > left_) return ok_ = false;
    if (n > 0) std::memcpy(out, p_, size_t(n));
    p_ += n, left_ -= n;
    return true;
  }
  const uint8_t *p_;
  uint64_t left_;
  bool ok_ = true;
};

// The "nimbus.iface.render-state" rev 1 table of plugin class P (derived from sdk::Plugin), or NULL for
// any other id.
template <class P>
const void *render_state_interface(const char *id, uint32_t rev) {
  static const nimbus_render_state_v1_t table = {
      sizeof(nimbus_render_state_v1_t),
      [](const nimbus_plugin_t *p, uint64_t iterations, const nimbus_state_writer_t *w) {
        P *self = static_cast<P *>(Plugin::from(p));
        return self->guarded("save_state", [&] {
          StateWriter out(w);
          const nimbus_status_t s = self->save_state(iterations, out);
          return s != NIMBUS_OK ? s : out.status();
        });
      },
      [](const nimbus_plugin_t *p, uint64_t iterations, const void *bytes, uint64_t size) {
        P *self = static_cast<P *>(Plugin::from(p));
        return self->guarded("restore_state", [&] {
          StateReader in(bytes, size);
          return self->restore_state(iterations, in);
        });
      }};
  return (rev == 1 && std::strcmp(id, NIMBUS_IFACE_RENDER_STATE) == 0) ? &table : nullptr;
}

}  // namespace nimbus::sdk
