#include "render/render_job.hpp"

#include <filesystem>
#include <set>

#include "film/film.hpp"

namespace nimbus {
namespace {

// A source file's line of the fingerprint: "file:<path>=<hash>", the path kept on one line and clear of
// the '=' that ends the key.
std::string source_line(const SourceFile &f) {
  std::string path = f.path;
  for (char &c : path)
    if (c == '=' || c == '\n') c = '_';
  return "\nfile:" + path + "=" + f.hash;
}

// The command line's stop conditions replace the scene's: `--time 60` on a scene that says
// `iterations: 64` renders for 60 seconds, not until whichever comes first. Within one source, the
// conditions combine (the first reached stops); a time budget or an error target alone means no
// iteration limit.
StopRules stop_rules(const RenderDesc &scene, const RenderOptions &options) {
  if (options.iterations || options.time_seconds || options.target_error)
    return {options.iterations.value_or(0), options.time_seconds.value_or(0),
            options.target_error.value_or(0)};
  const bool other_rule = scene.time_seconds > 0 || scene.target_error > 0;
  return {scene.iterations ? scene.iterations
          : other_rule     ? 0
                           : kDefaultIterations,
          scene.time_seconds, scene.target_error};
}

}  // namespace

std::string RenderJob::light_sampler_for(uint32_t light_count) const {
  if (!light_sampler.empty()) return light_sampler;
  return light_count > kTreeLightThreshold ? "nimbus.lights.tree" : "nimbus.lights.power";
}

std::string RenderJob::guide_for(const std::vector<std::string> &features) const {
  if (guide == "none") return {};
  if (!guide.empty()) return guide;
  constexpr std::string_view kDefaultGuide = "default-guide=";
  for (const std::string &f : features)
    if (f.starts_with(kDefaultGuide)) return f.substr(kDefaultGuide.size());
  return {};
}

std::string RenderJob::fingerprint(const std::string &integrator_id, const std::string &light_sampler_id,
                                   const std::vector<std::pair<std::string, std::string>> &options,
                                   const std::string &guide_id) const {
  std::set<std::string> element_set(elements.begin(), elements.end());
  if (lightmix) element_set.insert("lightmix");
  std::string element_list, option_list;
  for (const std::string &e : element_set) element_list += (element_list.empty() ? "" : ",") + e;
  for (const auto &[k, v] : options) option_list += (option_list.empty() ? "" : ",") + k + ":" + v;
  const std::vector<SourceFile> &sources = scene->sources;
  std::string lines = "scene_hash=" + (sources.empty() ? std::string("none") : sources.front().hash);
  for (size_t i = 1; i < sources.size(); ++i) lines += source_line(sources[i]);
  lines += "\nresolution=" + std::to_string(width) + "x" + std::to_string(height);
  lines += "\nregion=" + std::to_string(region[0]) + "," + std::to_string(region[1]) + "," +
           std::to_string(region[2]) + "," + std::to_string(region[3]);
  lines += "\nseed=" + std::to_string(seed);
  lines += "\nintegrator=" + integrator_id + "\nlight_sampler=" + light_sampler_id +
           "\nfilter=" + std::string(filter_name(filter));
  if (!guide_id.empty()) lines += "\nguide=" + guide_id;
  lines += "\nmax_depth=" + std::to_string(max_depth);
  lines += "\noptions=" + option_list + "\nelements=" + element_list + "\n";
  return lines;
}

std::string RenderJob::task_line() const {
  if (split.whole()) return {};
  return "task=" + std::to_string(split.index) + "/" + std::to_string(split.count) + "\n";
}

Expected<RenderJob> resolve_job(const SceneDesc &scene, const RenderOptions &options) {
  const RenderDesc &r = scene.render;
  RenderJob job;
  job.scene = &scene;
  job.width = r.width;
  job.height = r.height;
  std::copy(r.region, r.region + 4, job.region);
  job.seed = options.seed.value_or(r.seed);
  job.threads = options.threads;
  job.load_seconds = options.load_seconds;
  job.max_depth = r.max_depth;
  job.filter = options.filter.value_or(r.filter);
  job.stop = stop_rules(r, options);
  job.integrator = options.integrator.value_or(r.integrator);
  job.integrator_options = r.options;
  job.light_sampler = !options.light_sampler.empty() ? options.light_sampler : r.light_sampler;
  job.guide = !options.guide.empty() ? options.guide : r.guide;
  job.guide_where = !options.guide.empty() ? "--guide" : r.guide_where;
  for (const auto *list : {&r.elements, &options.elements})
    for (const std::string &e : *list) {
      if (e == "lightmix")
        job.lightmix = true;
      else
        job.elements.push_back(e);
    }

  job.exr_path = options.output_exr;
  job.png_path = std::filesystem::path(options.output_exr).replace_extension(".png").string();
  job.ocio_config = options.ocio_config.empty() ? default_ocio_config_path() : options.ocio_config;
  job.checkpoint_path =
      options.checkpoint_path.empty() ? options.output_exr + ".ckpt" : options.checkpoint_path;
  job.checkpoint_interval_seconds = options.checkpoint_interval_seconds;
  job.resume = options.resume;

  if (options.tasks == 0 || options.task >= options.tasks)
    return Error{"--task " + std::to_string(options.task) + " --tasks " + std::to_string(options.tasks) +
                 ": the task must be in [0, tasks)"};
  job.split = {options.task, options.tasks};
  job.frame_iterations = job.stop.iterations;
  if (job.stop.iterations) {
    job.stop.iterations = job.split.share_of(job.frame_iterations);
    if (job.stop.iterations == 0)
      return Error{"--task " + std::to_string(options.task) + " --tasks " + std::to_string(options.tasks) +
                   ": the frame's " + std::to_string(job.frame_iterations) +
                   " iterations leave this task none (use at most " + std::to_string(job.frame_iterations) +
                   " tasks)"};
  }
  if (job.resume && job.stop.target_error > 0)
    return Error{
        "an error target (--target-error or render.target_error) cannot resume a checkpoint "
        "(the odd/even halves were not saved)"};
  return job;
}

}  // namespace nimbus
