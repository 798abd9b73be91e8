#include "render/render_checkpoint.hpp"

#include <nimbus/host.h>

#include <filesystem>

namespace nimbus {

RenderCheckpoint::RenderCheckpoint(const RenderJob &job, const std::string &integrator_id,
                                   const std::string &sampler_id, const std::string &guide_id,
                                   const std::vector<std::pair<std::string, std::string>> &integrator_options)
    : path_(job.checkpoint_path), interval_(job.checkpoint_interval_seconds), resume_(job.resume) {
  info_.seed = job.seed;
  info_.integrator = integrator_id;
  info_.fingerprint =
      job.fingerprint(integrator_id, sampler_id, integrator_options, guide_id) + job.task_line();
}

Status RenderCheckpoint::restore_or_warn(Film &film, const MessageFn &warn) {
  if (resume_) {
    if (Status s = read_checkpoint(film, path_, info_); !s)
      return Error{"cannot resume: " + s.error().message};
    previous_seconds_ = info_.seconds;
  } else if (std::error_code ec; std::filesystem::exists(path_, ec) && warn) {
    const auto old = peek_checkpoint(path_);
    const std::string held = old ? " (" + std::to_string(old->iterations) + " iterations)" : "";
    warn(NIMBUS_LOG_WARNING, "checkpoint '" + path_ + "'" + held +
                                 " will be replaced by this render's; to continue it instead, stop now and "
                                 "rerun with --resume");
  }
  return Ok{};
}

void RenderCheckpoint::start(uint64_t done, Clock::time_point t0) {
  t0_ = last_save_ = t0;
  saved_ = done;
  saved_path_ = resume_ ? path_ : "";
}

Status RenderCheckpoint::save(const Film &film, uint64_t done) {
  info_.seconds = previous_seconds_ + session_seconds();
  if (states_) {
    auto states = states_->save(done);
    if (!states) return Error{"checkpoint '" + path_ + "' not written: " + states.error().message};
    info_.states = std::move(states.value());
  }
  Status s = write_checkpoint(film, path_, info_);
  if (s) saved_ = done, saved_path_ = path_;
  return s;
}

void RenderCheckpoint::save_if_due(const Film &film, uint64_t done, const MessageFn &warn) {
  if (interval_ <= 0 || done <= saved_ ||
      std::chrono::duration<double>(Clock::now() - last_save_).count() < interval_)
    return;
  if (Status s = save(film, done); !s && warn) warn(NIMBUS_LOG_WARNING, s.error().message);
  last_save_ = Clock::now();
}

Status RenderCheckpoint::save_if_behind(const Film &film, uint64_t done) {
  return done > saved_ ? save(film, done) : Status(Ok{});
}

}  // namespace nimbus
