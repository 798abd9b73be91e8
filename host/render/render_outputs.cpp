#include "render/render_outputs.hpp"

#include <nimbus/film.h>

#include <algorithm>
#include <cctype>

#include "film/partial_exr.hpp"
#include "scene/pixel_filter_type.hpp"

namespace nimbus {

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

Status set_up_film(Film &film, const RenderJob &job, const PluginHandle &integrator,
                   const std::vector<std::string> &light_groups, uint32_t workers,
                   std::vector<int32_t> &lightmix_elements) {
  for (const std::string &e : job.elements) film.request(e);
  if (job.lightmix && !integrator.record().has_feature("lightmix"))
    return Error{"integrator '" + integrator.id() +
                 "' does not produce LightMix layers (no \"lightmix\" feature)"};
  if (job.lightmix) {
    // One layer per light group; the integrator's contributions per light sum to beauty.
    for (const std::string &g : lightmix_layer_names(light_groups)) {
      const int32_t id = film.register_element(g, 3, NIMBUS_ELEMENT_SPLAT);
      if (id < 0) return Error{"cannot create LightMix layer '" + g + "'"};
      film.request(g);
      lightmix_elements.push_back(id);
    }
  }
  if (Status s = film.allocate(); !s) return s.error();
  film.set_worker_count(workers);
  if (job.region[2] > job.region[0] && job.region[3] > job.region[1])
    film.set_region(job.region[0], job.region[1], job.region[2], job.region[3]);
  return Ok{};
}

Status write_outputs(const RenderJob &job, const Film &film, const RenderFacts &facts) {
  std::vector<std::pair<std::string, std::string>> smeta = {
      {"version", NIMBUS_VERSION_STRING},     {"integrator", facts.integrator},
      {"light_sampler", facts.light_sampler}, {"scene", job.scene->path},
      {"seed", std::to_string(job.seed)},  // exact for any 64-bit seed
      {"stopped_by", facts.stopped_by}};
  if (!facts.guide.empty()) smeta.push_back({"guide", facts.guide});
  // How the pixels were made beyond the scene file: a command line may have replaced its filter and region.
  smeta.push_back({"filter", std::string(filter_name(job.filter))});
  if (job.region[2] > job.region[0] && job.region[3] > job.region[1])
    smeta.push_back({"region", std::to_string(job.region[0]) + "," + std::to_string(job.region[1]) + "," +
                                   std::to_string(job.region[2]) + "," + std::to_string(job.region[3])});
  std::vector<std::pair<std::string, double>> nmeta = {{"iterations", double(facts.iterations)},
                                                       {"seconds", facts.seconds},
                                                       {"threads", double(facts.threads)},
                                                       {"nonfinite_samples", double(film.nonfinite_count())},
                                                       {"rays", double(facts.rays)}};
  if (facts.estimated_relmse) {
    nmeta.push_back({"target_error", job.stop.target_error});
    nmeta.push_back({"estimated_relmse", *facts.estimated_relmse});
  }
  if (facts.resumed_from) nmeta.push_back({"resumed_from", double(*facts.resumed_from)});
  if (facts.first_iteration_seconds) {
    nmeta.push_back({"load_seconds", facts.load_seconds});
    nmeta.push_back({"setup_seconds", facts.setup_seconds});
    nmeta.push_back({"first_iteration_seconds", *facts.first_iteration_seconds});
    nmeta.push_back(
        {"time_to_first_pixel", facts.load_seconds + facts.setup_seconds + *facts.first_iteration_seconds});
  }
  for (const auto &[k, v] : facts.stats) nmeta.push_back({"stat:" + k, v});
  if (!job.split.whole()) {
    smeta.push_back({"fingerprint", facts.fingerprint});
    smeta.push_back({"plugins", facts.plugin_versions});
    nmeta.push_back({"task", double(job.split.index)});
    nmeta.push_back({"tasks", double(job.split.count)});
    nmeta.push_back({"frame_iterations", double(job.frame_iterations)});
    return write_partial_exr(film, job.exr_path, smeta, nmeta);
  }
  if (Status s = film.write_exr(job.exr_path, smeta, nmeta); !s) return s.error();
  return film.write_png(job.png_path, job.ocio_config);
}

}  // namespace nimbus
