// Plugin descriptor validation and what the loader does after dlsym (loader/plugin_library.hpp
// read_entry, loader/plugin_registry.hpp load_opened, loader/plugin_descriptor.hpp). The fixture library
// is in-process: its entry function, entry table, descriptors and option lists are built from the input
// (scalar fields taken from it, strings NUL-terminated slices of it), which is what a dlopen'd fixture
// whose bytes came from the fuzzer would give the loader, without a shared object per input. The
// pointers are always valid (a plugin handing out wild pointers is beyond what a host can check); their
// sizes, types, counts, versions, kinds, strings and missing terminators are the fuzzer's.
// Every refusal must be one warning line "refused PATH: REASON"; every plugin accepted must be findable.
#include <cstdint>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "loader/plugin_registry.hpp"
#include "loader/plugin_version.hpp"

namespace {

using nimbus::fuzz::require;

// Reads the input front to back; past its end every read gives zeros and empty strings.
class Bytes {
 public:
  Bytes(const uint8_t *data, size_t size) : p_(data), end_(data + size) {}
  uint8_t u8() { return p_ < end_ ? *p_++ : 0; }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(u8()) << (8 * i);
    return v;
  }
  // A string up to the next NUL, or NULL when the next byte says so (1 in 16).
  const char *string_or_null() {
    if (u8() % 16 == 0) return nullptr;
    const uint8_t *nul = static_cast<const uint8_t *>(std::memchr(p_, 0, size_t(end_ - p_)));
    const uint8_t *stop = nul ? nul : end_;
    strings_.emplace_back(reinterpret_cast<const char *>(p_), size_t(stop - p_));
    p_ = nul ? nul + 1 : end_;
    return strings_.back().c_str();
  }
  // A NULL-terminated list of up to 6 entries, NULL itself, or (byte 255) 300 entries, past the host's
  // bound of 256.
  const char *const *list() {
    const uint8_t n = u8();
    if (n % 8 == 0) return nullptr;
    const size_t count = n == 255 ? 300 : n % 8 - 1;
    lists_.emplace_back();
    for (size_t i = 0; i < count; ++i) {
      const char *s = string_or_null();
      lists_.back().push_back(s ? s : "");
    }
    lists_.back().push_back(nullptr);
    return lists_.back().data();
  }
  // Mostly the value a well-formed plugin would use, sometimes any value: so that the fuzzer gets past
  // the first check and still tries every value of it.
  uint32_t usually(uint32_t good) { return u8() % 8 == 0 ? u32() : good; }

 private:
  const uint8_t *p_, *end_;
  std::deque<std::string> strings_;
  std::deque<std::vector<const char *>> lists_;
};

struct Fixture {
  nimbus_entry_t entry{};
  nimbus_status_t init_status = NIMBUS_OK;
  uint32_t count = 0;
  std::deque<nimbus_descriptor_t> descriptors;
  std::deque<nimbus_option_list_t> option_lists;
  std::deque<std::vector<nimbus_option_decl_t>> options;
};
Fixture *fixture = nullptr;  // what the entry functions below answer with, for the current input

const nimbus_entry_t *fixture_entry() { return &fixture->entry; }
nimbus_status_t fixture_init(const char *) { return fixture->init_status; }
void fixture_deinit() {}
uint32_t fixture_count() { return fixture->count; }
const nimbus_descriptor_t *fixture_descriptor(uint32_t i) {
  return i < fixture->descriptors.size() ? &fixture->descriptors[i] : nullptr;
}
nimbus_status_t fixture_create(const char *, const nimbus_host_t *, const nimbus_plugin_t **) {
  return NIMBUS_E_INTERNAL;
}

const void *host_get_service(const nimbus_host_t *, const char *id, uint32_t rev) {
  static const int table = 0;
  const bool known = std::strcmp(id, "nimbus.host.film") == 0 || std::strcmp(id, "nimbus.host.rng") == 0;
  return known && rev <= 1 ? &table : nullptr;
}

void build_options(Bytes &in, Fixture &f, nimbus_descriptor_t &d) {
  const uint8_t lists = in.u8() % 4;
  const void **next = &d.header.next;
  for (uint8_t l = 0; l < lists; ++l) {
    std::vector<nimbus_option_decl_t> &decls = f.options.emplace_back(in.u8() % 5);
    for (nimbus_option_decl_t &o : decls) {
      o.name = in.string_or_null();
      o.type = in.usually(1 + in.u8() % 5);
      o.default_value = in.string_or_null();
      o.allowed = in.list();
      o.doc = in.string_or_null();
    }
    nimbus_option_list_t &list = f.option_lists.emplace_back();
    list.header.struct_size = in.usually(sizeof(nimbus_option_list_t));
    list.header.s_type = in.usually(NIMBUS_S_TYPE_OPTION_LIST);
    list.count = uint32_t(decls.size());
    list.options = decls.empty() && in.u8() % 2 ? nullptr : decls.data();
    *next = &list;
    next = &list.header.next;
  }
}

void build(Bytes &in, Fixture &f) {
  f.entry.struct_size = in.usually(sizeof(nimbus_entry_t));
  f.entry.abi = nimbus::kHostAbi;
  if (in.u8() % 8 == 0) f.entry.abi = {in.u8(), in.u8(), in.u8(), 0};
  const uint8_t missing = in.u8();  // bit k set (1 in 8 per input): function k is NULL
  const bool drop = missing % 8 == 0;
  f.entry.init = drop && (missing & 0x08) ? nullptr : fixture_init;
  f.entry.deinit = drop && (missing & 0x10) ? nullptr : fixture_deinit;
  f.entry.count = drop && (missing & 0x20) ? nullptr : fixture_count;
  f.entry.descriptor = drop && (missing & 0x40) ? nullptr : fixture_descriptor;
  f.entry.create = drop && (missing & 0x80) ? nullptr : fixture_create;
  f.init_status = nimbus_status_t(in.usually(NIMBUS_OK));
  const uint8_t built = in.u8() % 4;
  f.count = in.usually(built);
  for (uint8_t i = 0; i < built; ++i) {
    nimbus_descriptor_t &d = f.descriptors.emplace_back();
    d.header.struct_size = in.usually(sizeof(nimbus_descriptor_t));
    d.header.s_type = in.usually(NIMBUS_S_TYPE_DESCRIPTOR);
    d.id = in.string_or_null();
    d.name = in.string_or_null();
    d.vendor = in.string_or_null();
    d.version = {in.u8(), in.u8(), in.u8(), 0};
    d.kind = in.usually(1 + in.u8() % 3);
    d.features = in.list();
    d.required_services = in.list();
    build_options(in, f, d);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  Bytes in(data, size);
  Fixture f;
  build(in, f);
  fixture = &f;
  nimbus_host_t host{};
  host.struct_size = in.usually(sizeof(nimbus_host_t));
  host.abi = nimbus::kHostAbi;
  host.get_service = host_get_service;

  const std::string path = "/fuzz/libfixture.so";
  {
    nimbus::PluginRegistry registry([&](int level, const std::string &line) {
      nimbus::fuzz::check_error_line(line, "");
      if (level >= NIMBUS_LOG_WARNING)
        require(line.rfind("refused " + path + ": ", 0) == 0, "a warning that is not a refusal: " + line);
    });
    registry.load_opened(path, nimbus::read_entry(fixture_entry, nimbus::kHostAbi), &host);
    for (const nimbus::PluginRecord &r : registry.records()) {
      require(!r.status.empty(), "a plugin record without a status");
      if (r.loaded) require(registry.find(r.id) != nullptr, "plugin '" + r.id + "' loaded but not found");
    }
  }  // the registry calls deinit of a library it kept
  fixture = nullptr;
  return 0;
}
