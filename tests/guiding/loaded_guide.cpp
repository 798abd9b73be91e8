#include "loaded_guide.hpp"

#include <algorithm>
#include <utility>

namespace nimbus::guide_test {

LoadedGuide::LoadedGuide(std::string id, const std::string &dir)
    : id_(std::move(id)), registry_([](int, const std::string &) {}) {
  // A host with no services: the guide needs none, and logs through it.
  host_ = {sizeof(nimbus_host_t), NIMBUS_ABI_VERSION_INIT, messages_.get(),
           [](const nimbus_host_t *, const char *, uint32_t) -> const void * { return nullptr; },
           [](const nimbus_host_t *h, nimbus_log_level_t, const char *id, const char *msg) {
             auto &m = *static_cast<Messages *>(h->host_data);
             const std::lock_guard lock(m.mutex);
             m.lines.push_back(std::string(id ? id : "") + ": " + msg);
           }};
  registry_.discover({dir}, &host_);
  auto created = registry_.create(id_, NIMBUS_KIND_GUIDING, &host_);
  if (!created) {
    ADD_FAILURE() << created.error().message;
    return;
  }
  plugin_ = created.value();
  guide_ = static_cast<const nimbus_guiding_v2_t *>(plugin_->get_interface(plugin_, NIMBUS_IFACE_GUIDING, 2));
  state_ = static_cast<const nimbus_render_state_v1_t *>(
      plugin_->get_interface(plugin_, NIMBUS_IFACE_RENDER_STATE, 1));
  if (!guide_) ADD_FAILURE() << id_ << " does not serve " << NIMBUS_IFACE_GUIDING << "@2";
}

PassRun LoadedGuide::run_pass(const nimbus_guide_pass_t &pass, const Target &target, ChainOrder order) const {
  PassRun run;
  if ((run.status = guide_->begin_pass(plugin_, &pass)) != NIMBUS_OK) return run;
  run.chains.assign(pass.chain_count, ChainLog{&target, pass.dims});
  run.totals.assign(pass.chain_count, {});
  std::vector<nimbus_status_t> status(pass.chain_count, NIMBUS_OK);
  const auto run_chain = [&](uint32_t c, uint32_t worker) {
    const nimbus_thread_ctx_t ctx{sizeof ctx, worker, 2, 0, nullptr, 0};
    const nimbus_guide_tracer_t tracer{sizeof tracer, pass.dims, &run.chains[c], log_trace, log_credit};
    run.totals[c].header = {sizeof(nimbus_guide_totals_t), NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr};
    status[c] = guide_->run_chain(plugin_, &ctx, c, &tracer, &run.totals[c]);
  };
  if (order == ChainOrder::serial) {
    for (uint32_t c = 0; c < pass.chain_count; ++c) run_chain(c, 0);
  } else {
    // Two workers taking chains from the top down, interleaved: another order, and concurrent calls.
    std::thread other([&] {
      for (uint32_t c = pass.chain_count; c-- > 0;)
        if (c % 2 == 0) run_chain(c, 1);
    });
    for (uint32_t c = pass.chain_count; c-- > 0;)
      if (c % 2 == 1) run_chain(c, 0);
    other.join();
  }
  for (uint32_t c = 0; c < pass.chain_count; ++c) {
    if (status[c] != NIMBUS_OK && run.status == NIMBUS_OK) run.status = status[c];
    const nimbus_guide_totals_t &t = run.totals[c];
    run.sum += {t.uniform_paths, t.chain_steps, t.uniform_target_sum, t.proposals, t.accepted};
  }
  nimbus_guide_totals_t sum{{sizeof sum, NIMBUS_S_TYPE_GUIDE_TOTALS, nullptr},
                            run.sum.uniform_paths,
                            run.sum.chain_steps,
                            run.sum.uniform_target_sum,
                            run.sum.proposals,
                            run.sum.accepted};
  const nimbus_status_t end = guide_->end_pass(plugin_, &sum);
  if (run.status == NIMBUS_OK) run.status = end;
  return run;
}

std::vector<uint8_t> LoadedGuide::save() const {
  std::vector<uint8_t> bytes;
  if (!state_) {
    ADD_FAILURE() << id_ << " has no render state";
    return bytes;
  }
  nimbus_state_writer_t writer{
      sizeof writer, 0, &bytes,
      [](const nimbus_state_writer_t *w, const void *p, uint64_t n) -> nimbus_status_t {
        auto &out = *static_cast<std::vector<uint8_t> *>(w->host_data);
        const auto *b = static_cast<const uint8_t *>(p);
        out.insert(out.end(), b, b + n);
        return NIMBUS_OK;
      }};
  EXPECT_EQ(state_->save(plugin_, 1, &writer), NIMBUS_OK);
  return bytes;
}

}  // namespace nimbus::guide_test
