#include "render/render_session.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include <tbb/parallel_for.h>

#include "abi/host_services.hpp"
#include "core/checksum.hpp"
#include "film/checkpoint.hpp"
#include "loader/plugin_interface.hpp"
#include "loader/plugin_registry.hpp"
#include "loader/plugin_status.hpp"
#include "render/render_context.hpp"

namespace nimbus {
namespace {

constexpr uint32_t kTileSize = 32;
constexpr uint64_t kDefaultIterations = 64;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Film element names of the LightMix groups: "lightmix." + the group name in [a-z0-9_], unique.
std::vector<std::string> lightmix_layer_names(const std::vector<std::string> &groups) {
  std::vector<std::string> names;
  for (const std::string &g : groups) {
    std::string n;
    for (char c : g) n += (std::isalnum(static_cast<unsigned char>(c)) ? char(std::tolower(c)) : '_');
    if (n.empty()) n = "group";
    std::string unique = "lightmix." + n;
    for (int k = 2; std::find(names.begin(), names.end(), unique) != names.end(); ++k)
      unique = "lightmix." + n + "_" + std::to_string(k);
    names.push_back(unique);
  }
  return names;
}

std::string png_path_for(const std::string &exr) {
  std::filesystem::path p(exr);
  p.replace_extension(".png");
  return p.string();
}

// What the film's sums depend on, one "key=value" per line; a checkpoint resumes only into a render with
// the same lines (read_checkpoint names those that differ). The scene file is hashed whole, so any edit
// to it counts; the files it references (meshes, maps) are not hashed. The other lines catch what the
// CLI can override without editing the file.
std::string render_fingerprint(const SceneDesc &desc, const RenderOptions &options,
                               const std::string &integrator, const std::string &sampler,
                               const std::vector<std::pair<std::string, std::string>> &integrator_options) {
  std::string scene_hash = "none";
  if (std::ifstream in(desc.path, std::ios::binary); in)
    scene_hash = content_hash(std::string(std::istreambuf_iterator<char>(in), {}));
  std::set<std::string> elements(desc.render.elements.begin(), desc.render.elements.end());
  elements.insert(options.elements.begin(), options.elements.end());
  std::string element_list, option_list;
  for (const std::string &e : elements) element_list += (element_list.empty() ? "" : ",") + e;
  for (const auto &[k, v] : integrator_options) option_list += (option_list.empty() ? "" : ",") + k + ":" + v;
  const uint32_t *r = desc.render.region;
  std::string lines = "scene_hash=" + scene_hash;
  lines += "\nresolution=" + std::to_string(desc.render.width) + "x" + std::to_string(desc.render.height);
  lines += "\nregion=" + std::to_string(r[0]) + "," + std::to_string(r[1]) + "," + std::to_string(r[2]) +
           "," + std::to_string(r[3]);
  lines += "\nseed=" + std::to_string(desc.render.seed);
  lines += "\nintegrator=" + integrator + "\nlight_sampler=" + sampler + "\nfilter=" + desc.render.filter;
  lines += "\nmax_depth=" + std::to_string(desc.render.max_depth);
  lines += "\noptions=" + option_list + "\nelements=" + element_list + "\n";
  return lines;
}

}  // namespace

Expected<RenderResult> render(const SceneDesc &desc_in, const RenderOptions &options,
                              PluginRegistry &registry, std::atomic<bool> &cancel, const ProgressFn &progress,
                              const MessageFn &message) {
  SceneDesc desc_copy;  // only when the CLI overrides the seed
  const SceneDesc *desc = &desc_in;
  if (options.seed) {
    desc_copy = desc_in;
    desc_copy.render.seed = *options.seed;
    desc = &desc_copy;
  }
  auto built = RenderContext::build(*desc, options.threads);
  if (!built) return built.error();
  RenderContext &ctx = *built.value();
  ctx.cancel = &cancel;
  ctx.log = [&](int level, const std::string &id, const std::string &msg) {
    if (message) message(level, id.empty() ? msg : id + ": " + msg);
  };
  HostServices services(&ctx);
  const nimbus_host_t *host = services.host();

  // Plugins: the integrator the scene names and the light sampler.
  auto ip = registry.instantiate(desc->render.integrator, NIMBUS_KIND_INTEGRATOR, host);
  if (!ip) return Error{desc->path + ": integrator: " + ip.error().message};
  PluginHandle integrator = std::move(ip).value();
  const std::string sampler_id = !options.light_sampler.empty()             ? options.light_sampler
                                 : !desc->render.light_sampler.empty()      ? desc->render.light_sampler
                                 : ctx.lights.count() > kTreeLightThreshold ? "nimbus.lights.tree"
                                                                            : "nimbus.lights.power";
  auto sp = registry.instantiate(sampler_id, NIMBUS_KIND_LIGHT_SAMPLER, host);
  if (!sp) return Error{"light sampler: " + sp.error().message};
  PluginHandle sampler = std::move(sp).value();
  auto iface = interface_of<nimbus_integrator_v1_t>(integrator, NIMBUS_IFACE_INTEGRATOR, kIntegratorSize10);
  if (!iface) return iface.error();
  auto siface =
      interface_of<nimbus_light_sampler_v1_t>(sampler, NIMBUS_IFACE_LIGHT_SAMPLER, kLightSamplerMinSize);
  if (!siface) return siface.error();
  const nimbus_integrator_v1_t &it = *iface.value();
  const nimbus_light_sampler_v1_t &ls = *siface.value();
  const std::string integrator_id = integrator.id();

  // Prepare: the sampler builds its tables, the integrator registers its elements; then the film
  // allocates exactly what was requested.
  nimbus_scene_info_t scene_info{};
  scene_info.header = {sizeof(scene_info), NIMBUS_S_TYPE_SCENE_INFO, nullptr};
  scene_info.light_count = ctx.lights.count();
  scene_info.worker_count = ctx.worker_count;
  ctx.geometry->sphere_center().store(scene_info.scene_center);
  scene_info.scene_radius = ctx.geometry->sphere_radius();
  if (nimbus_status_t s = ls.prepare(sampler.get(), &scene_info); s != NIMBUS_OK)
    return Error{"light sampler '" + sampler.id() + "' failed to prepare: " + status_text(s)};

  // The integrator's declared options, each with the scene's or command line's value or its default.
  std::vector<OptionRequest> requests;
  for (const auto &o : desc->render.options) requests.push_back({o.name, o.value, o.where, o.hint});
  auto resolved = resolve_options(integrator_id, integrator.record().options, requests);
  if (!resolved) return Error{resolved.error().message};
  std::vector<nimbus_option_t> opts;
  for (const auto &[k, v] : *resolved) opts.push_back({k.c_str(), v.c_str()});
  nimbus_render_setup_t setup{};
  setup.header = {sizeof(setup), NIMBUS_S_TYPE_RENDER_SETUP, nullptr};
  setup.width = desc->render.width;
  setup.height = desc->render.height;
  setup.max_depth = desc->render.max_depth;
  setup.option_count = uint32_t(opts.size());
  setup.seed = desc->render.seed;
  setup.options = opts.data();
  setup.light_sampler = sampler.get();
  setup.light_sampler_iface = &ls;
  if (nimbus_status_t s = it.prepare(integrator.get(), &setup); s != NIMBUS_OK)
    return Error{"integrator '" + integrator_id + "' failed to prepare: " + status_text(s)};

  Film &film = *ctx.film;
  bool lightmix = false;
  for (const auto *list : {&desc->render.elements, &options.elements})
    for (const std::string &e : *list) {
      if (e == "lightmix")
        lightmix = true;
      else
        film.request(e);
    }
  if (lightmix && !integrator.record().has_feature("lightmix"))
    return Error{"integrator '" + integrator_id +
                 "' does not produce LightMix layers (no \"lightmix\" feature)"};
  if (lightmix) {
    // One layer per light group, "lightmix.<group>"; the integrator's contributions per light sum to beauty.
    for (const std::string &g : lightmix_layer_names(ctx.lights.group_names())) {
      const int32_t id = film.register_element(g, 3, NIMBUS_ELEMENT_SPLAT);
      if (id < 0) return Error{"cannot create LightMix layer '" + g + "'"};
      film.request(g);
      ctx.lightmix_elements.push_back(id);
    }
  }
  if (Status s = film.allocate(); !s) return s.error();
  film.set_worker_count(ctx.worker_count);

  // Checkpoint: restore the sums before the first iteration, or warn before replacing someone's work.
  const std::string checkpoint_path =
      options.checkpoint_path.empty() ? options.output_exr + ".ckpt" : options.checkpoint_path;
  CheckpointInfo checkpoint;
  checkpoint.seed = desc->render.seed;
  checkpoint.integrator = integrator_id;
  checkpoint.fingerprint = render_fingerprint(*desc, options, integrator_id, sampler.id(), *resolved);
  if (options.resume) {
    if (Status s = read_checkpoint(film, checkpoint_path, checkpoint); !s)
      return Error{"cannot resume: " + s.error().message};
  } else if (std::error_code ec; std::filesystem::exists(checkpoint_path, ec) && message) {
    const auto old = peek_checkpoint(checkpoint_path);
    const std::string held = old ? " (" + std::to_string(old->iterations) + " iterations)" : "";
    message(NIMBUS_LOG_WARNING,
            "checkpoint '" + checkpoint_path + "'" + held +
                " will be replaced by this render's; to continue it instead, stop now and "
                "rerun with --resume");
  }
  const double previous_seconds = checkpoint.seconds;

  // The command line's stop conditions replace the scene's: `--time 60` on a scene that says
  // `iterations: 64` renders for 60 seconds, not until whichever comes first. Within one source, the
  // conditions combine (the first reached stops); a time budget or an error target alone means no
  // iteration limit.
  const bool cli_stops = options.iterations || options.time_seconds || options.target_error;
  const RenderDesc &scene_stops = desc->render;
  const uint64_t iterations = cli_stops                ? options.iterations.value_or(0)
                              : scene_stops.iterations ? scene_stops.iterations
                              : (scene_stops.time_seconds > 0 || scene_stops.target_error > 0)
                                  ? 0
                                  : kDefaultIterations;
  const double budget = cli_stops ? options.time_seconds.value_or(0) : scene_stops.time_seconds;
  const double target_error = cli_stops ? options.target_error.value_or(0) : scene_stops.target_error;
  if (target_error > 0) {
    if (film.iterations() > 0)
      return Error{
          "an error target (--target-error or render.target_error) cannot resume a checkpoint "
          "(the odd/even halves were not saved)"};
    ctx.error_estimate =
        std::make_unique<ErrorEstimate>(desc->render.width, desc->render.height, ctx.worker_count);
  }
  double estimated_error = -1;

  nimbus_render_info_t info{};
  info.header = {sizeof(info), NIMBUS_S_TYPE_RENDER_INFO, nullptr};
  info.worker_count = ctx.worker_count;
  info.first_iteration = film.iterations() + 1;
  info.planned_iterations = iterations;
  if (nimbus_status_t s = it.begin_render(integrator.get(), &info); s != NIMBUS_OK)
    return Error{"integrator '" + integrator_id + "' failed to begin the render: " + status_text(s)};

  // Tiles in row-major order over the render region; each is rendered by one worker per iteration.
  const uint32_t w = desc->render.width, h = desc->render.height;
  const uint32_t *reg = desc->render.region;
  const bool has_region = reg[2] > reg[0] && reg[3] > reg[1];
  const uint32_t rx0 = has_region ? std::min(reg[0], w) : 0, ry0 = has_region ? std::min(reg[1], h) : 0;
  const uint32_t rx1 = has_region ? std::min(reg[2], w) : w, ry1 = has_region ? std::min(reg[3], h) : h;
  std::vector<nimbus_tile_t> tiles;
  for (uint32_t y = ry0; y < ry1; y += kTileSize)
    for (uint32_t x = rx0; x < rx1; x += kTileSize)
      tiles.push_back({x, y, std::min(rx1, x + kTileSize), std::min(ry1, y + kTileSize), 0});
  const uint64_t region_pixels = uint64_t(rx1 - rx0) * (ry1 - ry0);

  const auto t0 = Clock::now();
  nimbus_status_t failure = NIMBUS_OK;
  std::string failure_hook;
  const uint64_t resumed_from = film.iterations();
  uint64_t done = resumed_from;
  // Iterations the checkpoint on disk holds from this render (or the one resumed).
  uint64_t saved = resumed_from;
  std::string saved_path = options.resume ? checkpoint_path : "";
  auto save_checkpoint = [&]() -> Status {
    checkpoint.seconds = previous_seconds + seconds_since(t0);
    Status s = write_checkpoint(film, checkpoint_path, checkpoint);
    if (s) saved = done, saved_path = checkpoint_path;
    return s;
  };
  auto last_save = t0;
  bool reached_target = false;
  while (!cancel.load() && !reached_target) {
    if (iterations && done >= iterations) break;
    if (budget > 0 && done > resumed_from) {
      // Stop when another iteration would overrun the budget (estimated from this session's mean).
      const double elapsed = seconds_since(t0);
      if (elapsed + elapsed / double(done - resumed_from) > budget) break;
    }
    // Between iterations the sums are complete (splats merged): the only safe moment to save them.
    if (options.checkpoint_interval_seconds > 0 && done > saved &&
        seconds_since(last_save) >= options.checkpoint_interval_seconds) {
      // A failed periodic checkpoint costs only protection, not the render: warn and carry on.
      if (Status s = save_checkpoint(); !s && message) message(NIMBUS_LOG_WARNING, s.error().message);
      last_save = Clock::now();
    }
    const uint64_t i = done + 1;
    ctx.iteration = i;
    if (nimbus_status_t s = it.begin_iteration(integrator.get(), i); s != NIMBUS_OK) {
      failure = s, failure_hook = "begin_iteration";
      break;
    }
    std::atomic<nimbus_status_t> tile_status{NIMBUS_OK};
    ctx.arena->execute([&] {
      tbb::parallel_for(size_t(0), tiles.size(), [&](size_t t) {
        const int wi = tbb::this_task_arena::current_thread_index();
        nimbus_thread_ctx_t tc{
            sizeof(nimbus_thread_ctx_t), uint32_t(wi < 0 ? 0 : wi), ctx.worker_count, 0, nullptr, 0};
        nimbus_tile_t tile = tiles[t];
        tile.iteration = i;
        if (nimbus_status_t s = it.render_tile(integrator.get(), &tc, &tile); s != NIMBUS_OK) {
          nimbus_status_t expected = NIMBUS_OK;
          tile_status.compare_exchange_strong(expected, s);
        }
      });
    });
    if (tile_status.load() != NIMBUS_OK) {
      failure = tile_status.load(), failure_hook = "render_tile";
      break;
    }
    film.merge_splats();
    // Optional: a sampler's table may end before end_iteration (kLightSamplerMinSize).
    if (NIMBUS_HAS_MEMBER(&ls, nimbus_light_sampler_v1_t, end_iteration) && ls.end_iteration)
      ls.end_iteration(sampler.get(), i);
    if (nimbus_status_t s = it.end_iteration(integrator.get(), i); s != NIMBUS_OK) {
      failure = s, failure_hook = "end_iteration";
      break;
    }
    film.end_iteration();
    done = i;
    if (ctx.error_estimate) {
      ctx.error_estimate->end_iteration(i);
      if (i % 2 == 0) {
        estimated_error = ctx.error_estimate->relmse(film);
        if (estimated_error < target_error) reached_target = true;
      }
    }
    if (progress) {
      RenderProgress p;
      p.iteration = done;
      p.total_iterations = iterations;
      p.elapsed_seconds = seconds_since(t0);
      p.time_budget = budget;
      p.samples_per_second =
          double(region_pixels) * (done - resumed_from) / std::max(p.elapsed_seconds, 1e-9);
      std::lock_guard lock(ctx.phase_mutex);
      p.phase = ctx.phase;
      progress(p);
    }
  }
  const double seconds = seconds_since(t0);
  const bool was_cancelled = cancel.load();
  it.end_render(integrator.get(),
                failure != NIMBUS_OK ? failure : (was_cancelled ? NIMBUS_E_CANCELLED : NIMBUS_OK));

  // Write what we have, whatever ended the loop. The checkpoint goes first, so that an image write that
  // fails still leaves a way to recover the render; after a plugin failure the sums hold a partial
  // iteration, so the last periodic checkpoint is kept instead.
  Status checkpointed = Ok{};
  if (failure == NIMBUS_OK && done > saved) checkpointed = save_checkpoint();
  RenderResult result;
  result.iterations = done;
  result.seconds = seconds;
  result.cancelled = was_cancelled;
  result.nonfinite_samples = film.nonfinite_count();
  result.rays = ctx.rays_traced();
  result.resumed_from = options.resume ? resumed_from : 0;
  result.checkpoint_path = saved_path;
  result.exr_path = options.output_exr;
  result.png_path = png_path_for(options.output_exr);
  std::vector<std::pair<std::string, std::string>> smeta = {
      {"version", NIMBUS_VERSION_STRING},
      {"integrator", integrator_id},
      {"light_sampler", sampler.id()},
      {"scene", desc->path},
      {"seed", std::to_string(desc->render.seed)},  // exact for any 64-bit seed
      {"stopped_by", failure != NIMBUS_OK                 ? "error"
                     : was_cancelled                      ? "cancel"
                     : reached_target                     ? "target_error"
                     : (iterations && done >= iterations) ? "iterations"
                                                          : "time"}};
  // "seconds" is the render time of all the iterations in the image, over every resumed session.
  std::vector<std::pair<std::string, double>> nmeta = {{"iterations", double(done)},
                                                       {"seconds", previous_seconds + seconds},
                                                       {"threads", double(ctx.worker_count)},
                                                       {"nonfinite_samples", double(film.nonfinite_count())},
                                                       {"rays", double(result.rays)}};
  if (ctx.error_estimate) {
    nmeta.push_back({"target_error", target_error});
    nmeta.push_back({"estimated_relmse", estimated_error});
  }
  if (options.resume) nmeta.push_back({"resumed_from", double(resumed_from)});
  {
    std::lock_guard lock(ctx.stats_mutex);
    for (const auto &[k, v] : ctx.stats) nmeta.push_back({"stat:" + k, v});
  }
  if (Status s = film.write_exr(result.exr_path, smeta, nmeta); !s) return s.error();
  const std::string ocio = options.ocio_config.empty() ? default_ocio_config_path() : options.ocio_config;
  if (Status s = film.write_png(result.png_path, ocio); !s) return s.error();
  if (!checkpointed)
    return Error{checkpointed.error().message + " (the image was written to " + result.exr_path + ")"};
  if (failure != NIMBUS_OK)
    return Error{"integrator '" + integrator_id + "' failed in " + failure_hook + ": " +
                 status_text(failure) + "; the image so far (" + std::to_string(done) +
                 " iterations) was written to " + result.exr_path};
  return result;
}

}  // namespace nimbus
