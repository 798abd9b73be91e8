// Nimbus SDK: optional header-only C++17 wrapper. It compiles entirely into the plugin; only the C
// tables of the other headers cross the boundary, so this file may change freely between releases.
//
//   class MyIntegrator : public nimbus::sdk::Integrator {
//     ... NIMBUS_DESCRIPTOR(...) and overrides of the hooks ...
//   };
//   NIMBUS_PLUGIN_LIBRARY(MyIntegrator)
//
// nimbus::sdk::LightSampler works the same way for light samplers, nimbus::sdk::PhotonGuide
// (nimbus/cpp/photon_guide.hpp) for guides.
//
// Trampolines catch every exception, log its text through the host and return NIMBUS_E_INTERNAL, so no
// exception ever leaves the plugin.
#ifndef NIMBUS_NIMBUS_HPP
#define NIMBUS_NIMBUS_HPP

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "nimbus.h"

namespace nimbus {
namespace sdk {

// The host as seen by a plugin: service lookup and logging.
class Host {
 public:
  explicit Host(const nimbus_host_t *h = nullptr) : h_(h) {}
  const nimbus_host_t *get() const { return h_; }
  // The service table, or nullptr when the host lacks it (an explicit branch for the caller).
  template <class Table>
  const Table *service(const char *id, uint32_t rev = 1) const {
    return h_ ? static_cast<const Table *>(h_->get_service(h_, id, rev)) : nullptr;
  }
  void log(nimbus_log_level_t level, const char *plugin_id, const std::string &msg) const {
    if (h_) h_->log(h_, level, plugin_id, msg.c_str());
  }

 private:
  const nimbus_host_t *h_;
};

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

// Common base of plugin instances: owns the C nimbus_plugin_t that the host sees.
class Plugin {
 public:
  Plugin() = default;
  Plugin(const Plugin &) = delete;
  Plugin &operator=(const Plugin &) = delete;
  virtual ~Plugin() = default;

  // [main-thread] After construction; fetch services here.
  virtual nimbus_status_t init() { return NIMBUS_OK; }
  virtual const void *interface(const char *id, uint32_t rev) = 0;

  const Host &host() const { return host_; }
  const char *id() const { return c_.desc ? c_.desc->id : ""; }
  const nimbus_plugin_t *c_plugin() const { return &c_; }
  void log(nimbus_log_level_t level, const std::string &msg) const { host_.log(level, id(), msg); }

  // Runs f, turning any exception into a logged error status.
  template <class F>
  nimbus_status_t guarded(const char *hook, F &&f) noexcept {
    try {
      return f();
    } catch (const std::exception &e) {
      log(NIMBUS_LOG_ERROR, std::string(hook) + ": " + e.what());
    } catch (...) {
      log(NIMBUS_LOG_ERROR, std::string(hook) + ": unknown exception");
    }
    return NIMBUS_E_INTERNAL;
  }

  static Plugin *from(const nimbus_plugin_t *p) { return static_cast<Plugin *>(p->plugin_data); }

  // Used by the library macro.
  void attach(const nimbus_descriptor_t *desc, const nimbus_host_t *host) {
    host_ = Host(host);
    c_.struct_size = sizeof(nimbus_plugin_t);
    c_.desc = desc;
    c_.plugin_data = this;
    c_.init = [](const nimbus_plugin_t *p) -> nimbus_status_t {
      Plugin *self = from(p);
      return self->guarded("init", [&] { return self->init(); });
    };
    c_.destroy = [](const nimbus_plugin_t *p) { delete from(p); };
    c_.get_interface = [](const nimbus_plugin_t *p, const char *id, uint32_t rev) -> const void * {
      return id ? from(p)->interface(id, rev) : nullptr;
    };
  }

 private:
  nimbus_plugin_t c_{};
  Host host_;
};

// Base class for integrators. Override the hooks; defaults do nothing and succeed.
class Integrator : public Plugin {
 public:
  virtual nimbus_status_t prepare(const nimbus_render_setup_t &) { return NIMBUS_OK; }
  virtual nimbus_status_t begin_render(const nimbus_render_info_t &) { return NIMBUS_OK; }
  virtual nimbus_status_t begin_iteration(uint64_t) { return NIMBUS_OK; }
  virtual nimbus_status_t render_tile(const nimbus_thread_ctx_t &, const nimbus_tile_t &) = 0;
  virtual nimbus_status_t end_iteration(uint64_t) { return NIMBUS_OK; }
  virtual void end_render(nimbus_status_t) {}

  const void *interface(const char *id, uint32_t rev) override {
    return (rev == 1 && std::strcmp(id, NIMBUS_IFACE_INTEGRATOR) == 0) ? &table() : nullptr;
  }

 private:
  static Integrator *self(const nimbus_plugin_t *p) { return static_cast<Integrator *>(from(p)); }
  static const nimbus_integrator_v1_t &table() {
    static const nimbus_integrator_v1_t t = {
        sizeof(nimbus_integrator_v1_t),
        [](const nimbus_plugin_t *p, const nimbus_render_setup_t *s) {
          return self(p)->guarded("prepare", [&] { return self(p)->prepare(*s); });
        },
        [](const nimbus_plugin_t *p, const nimbus_render_info_t *i) {
          return self(p)->guarded("begin_render", [&] { return self(p)->begin_render(*i); });
        },
        [](const nimbus_plugin_t *p, uint64_t it) {
          return self(p)->guarded("begin_iteration", [&] { return self(p)->begin_iteration(it); });
        },
        [](const nimbus_plugin_t *p, const nimbus_thread_ctx_t *c, const nimbus_tile_t *t) {
          return self(p)->guarded("render_tile", [&] { return self(p)->render_tile(*c, *t); });
        },
        [](const nimbus_plugin_t *p, uint64_t it) {
          return self(p)->guarded("end_iteration", [&] { return self(p)->end_iteration(it); });
        },
        [](const nimbus_plugin_t *p, nimbus_status_t r) {
          self(p)->guarded("end_render", [&] {
            self(p)->end_render(r);
            return NIMBUS_OK;
          });
        }};
    return t;
  }
};

// Base class for light samplers.
class LightSampler : public Plugin {
 public:
  virtual nimbus_status_t prepare(const nimbus_scene_info_t &) = 0;
  virtual uint32_t pick(const nimbus_interaction_t &ix, float u, float *pmf) = 0;
  virtual float pmf(const nimbus_interaction_t &ix, uint32_t light) = 0;
  virtual uint32_t pick_emitter(float u, float *pmf) = 0;
  // A sampler that learns from its samples returns true from adapts(): its table then carries record
  // (every NEE outcome, light_sampler.h) and end_iteration; the others leave them NULL, so that the
  // camera-path layer makes no call per sample.
  virtual bool adapts() const { return false; }
  virtual void record(const nimbus_thread_ctx_t &, uint32_t, float) {}
  virtual void end_iteration(uint64_t) {}
  // A sampler whose photon emission follows an integrator's feedback (light_sampler.h, since 1.6)
  // returns true from adapts_emission(): its table then carries update_emission and pmf_emitter, and
  // pick_emitter must sample the table they describe (nimbus/cpp/emitter_selection.hpp implements the
  // solver spec's rule). The others leave both NULL, and integrators keep their own emitter rule.
  virtual bool adapts_emission() const { return false; }
  virtual nimbus_status_t update_emission(const nimbus_emission_feedback_t &) { return NIMBUS_E_UNSUPPORTED; }
  virtual float pmf_emitter(uint32_t) { return 0; }

  const void *interface(const char *id, uint32_t rev) override {
    if (rev != 1 || std::strcmp(id, NIMBUS_IFACE_LIGHT_SAMPLER) != 0) return nullptr;
    if (adapts_emission()) return adapts() ? &table<true, true>() : &table<false, true>();
    return adapts() ? &table<true, false>() : &table<false, false>();
  }

 private:
  static LightSampler *self(const nimbus_plugin_t *p) { return static_cast<LightSampler *>(from(p)); }
  // Hot paths cannot report a status: an exception yields "no light" (pmf 0), and is logged.
  template <class R, class F>
  static R hot(const nimbus_plugin_t *p, R fallback, F &&f) noexcept {
    R r = fallback;
    self(p)->guarded("light sampler", [&] {
      r = f();
      return NIMBUS_OK;
    });
    return r;
  }
  template <bool kAdapts, bool kEmission>
  static const nimbus_light_sampler_v1_t &table() {
    static const nimbus_light_sampler_v1_t t = {
        sizeof(nimbus_light_sampler_v1_t),
        [](const nimbus_plugin_t *p, const nimbus_scene_info_t *i) {
          return self(p)->guarded("prepare", [&] { return self(p)->prepare(*i); });
        },
        [](const nimbus_plugin_t *p, const nimbus_interaction_t *ix, float u, float *pmf) {
          *pmf = 0;
          return hot<uint32_t>(p, NIMBUS_NONE, [&] { return self(p)->pick(*ix, u, pmf); });
        },
        [](const nimbus_plugin_t *p, const nimbus_interaction_t *ix, uint32_t l) {
          return hot<float>(p, 0.0f, [&] { return self(p)->pmf(*ix, l); });
        },
        [](const nimbus_plugin_t *p, float u, float *pmf) {
          *pmf = 0;
          return hot<uint32_t>(p, NIMBUS_NONE, [&] { return self(p)->pick_emitter(u, pmf); });
        },
        kAdapts ? +[](const nimbus_plugin_t *p, const nimbus_thread_ctx_t *ctx, uint32_t light,
                      float v) { hot<int>(p, 0, [&] { return self(p)->record(*ctx, light, v), 0; }); }
                : nullptr,
        kAdapts ? +[](const nimbus_plugin_t *p,
                      uint64_t it) { hot<int>(p, 0, [&] { return self(p)->end_iteration(it), 0; }); }
                : nullptr,
        kEmission ? +[](const nimbus_plugin_t *p, const nimbus_emission_feedback_t *f) {
          return self(p)->guarded("update_emission", [&] { return self(p)->update_emission(*f); });
        }
                  : nullptr,
        kEmission ? +[](const nimbus_plugin_t *p, uint32_t l) {
          return hot<float>(p, 0.0f, [&] { return self(p)->pmf_emitter(l); });
        }
                  : nullptr};
    return t;
  }
};

// The value the host resolved for option `name` of a render (declared options always arrive, SDK 1.2),
// or nullptr when the setup carries no such option.
inline const char *option_value(const nimbus_render_setup_t &setup, const char *name) {
  for (uint32_t i = 0; i < setup.option_count; ++i)
    if (setup.options[i].key && setup.options[i].value && std::strcmp(setup.options[i].key, name) == 0)
      return setup.options[i].value;
  return nullptr;
}

namespace detail {

template <class... Plugins>
struct Library {
  static inline std::atomic<int> refcount{0};
  static const nimbus_descriptor_t *descriptor(uint32_t i) {
    const nimbus_descriptor_t *all[] = {&Plugins::descriptor()...};
    return i < sizeof...(Plugins) ? all[i] : nullptr;
  }
  template <class P>
  static bool try_create(const char *id, const nimbus_host_t *host, const nimbus_plugin_t **out,
                         nimbus_status_t *status) {
    if (*out || std::strcmp(P::descriptor().id, id) != 0) return false;
    try {
      auto *p = new P();
      p->attach(&P::descriptor(), host);
      *out = p->c_plugin();
      *status = NIMBUS_OK;
    } catch (const std::bad_alloc &) {
      *status = NIMBUS_E_NO_MEMORY;
    } catch (...) {
      *status = NIMBUS_E_INTERNAL;
    }
    return true;
  }
  static const nimbus_entry_t &entry() {
    static const nimbus_entry_t e = {
        sizeof(nimbus_entry_t),
        NIMBUS_ABI_VERSION_INIT,
        [](const char *) -> nimbus_status_t {
          refcount.fetch_add(1);
          return NIMBUS_OK;
        },
        [] { refcount.fetch_sub(1); },
        []() -> uint32_t { return sizeof...(Plugins); },
        [](uint32_t i) { return descriptor(i); },
        [](const char *id, const nimbus_host_t *host, const nimbus_plugin_t **out) -> nimbus_status_t {
          if (!id || !out) return NIMBUS_E_INVALID_ARG;
          *out = nullptr;
          nimbus_status_t status = NIMBUS_E_INVALID_ARG;  // unknown id
          (try_create<Plugins>(id, host, out, &status) || ...);
          return status;
        }};
    return e;
  }
};

}  // namespace detail
}  // namespace sdk
}  // namespace nimbus

// Emits the library's one exported entry point for the listed plugin classes.
#define NIMBUS_PLUGIN_LIBRARY(...)                                                                    \
  extern "C" __attribute__((visibility("default"))) const nimbus_entry_t *nimbus_plugin_entry(void) { \
    return &::nimbus::sdk::detail::Library<__VA_ARGS__>::entry();                                     \
  }

// The descriptor's initialiser, its header chained to NEXT (internal to the two macros below).
#define NIMBUS_DESCRIPTOR_VALUE_(ID, NAME, VENDOR, KIND, MAJOR, MINOR, PATCH, FEATURES, REQUIRED, NEXT) \
  {                                                                                                     \
    {sizeof(nimbus_descriptor_t), NIMBUS_S_TYPE_DESCRIPTOR, NEXT}, ID, NAME, VENDOR,                    \
        {MAJOR, MINOR, PATCH, 0}, KIND, 0, FEATURES, REQUIRED                                           \
  }

// A static descriptor: NIMBUS_DESCRIPTOR(id, name, kind, major, minor, patch, features, required).
#define NIMBUS_DESCRIPTOR(ID, NAME, VENDOR, KIND, MAJOR, MINOR, PATCH, FEATURES, REQUIRED)                  \
  static const nimbus_descriptor_t &descriptor() {                                                          \
    static const nimbus_descriptor_t d =                                                                    \
        NIMBUS_DESCRIPTOR_VALUE_(ID, NAME, VENDOR, KIND, MAJOR, MINOR, PATCH, FEATURES, REQUIRED, nullptr); \
    return d;                                                                                               \
  }

// A static descriptor with declared options (SDK 1.2): OPTIONS names a `const nimbus_option_decl_t[]`
// array of static storage, chained to the descriptor as a nimbus_option_list_t.
#define NIMBUS_DESCRIPTOR_WITH_OPTIONS(ID, NAME, VENDOR, KIND, MAJOR, MINOR, PATCH, FEATURES, REQUIRED,   \
                                       OPTIONS)                                                           \
  static const nimbus_descriptor_t &descriptor() {                                                        \
    static const nimbus_option_list_t list = {                                                            \
        {sizeof(nimbus_option_list_t), NIMBUS_S_TYPE_OPTION_LIST, nullptr},                               \
        uint32_t(sizeof(OPTIONS) / sizeof(OPTIONS[0])),                                                   \
        0,                                                                                                \
        OPTIONS};                                                                                         \
    static const nimbus_descriptor_t d =                                                                  \
        NIMBUS_DESCRIPTOR_VALUE_(ID, NAME, VENDOR, KIND, MAJOR, MINOR, PATCH, FEATURES, REQUIRED, &list); \
    return d;                                                                                             \
  }

// The rev-1 guide base class, for sources written against SDK 1.1-1.4.
#include "guide_v1.hpp"

#endif /* NIMBUS_NIMBUS_HPP */
