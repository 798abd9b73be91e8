/* Layout of the Nimbus SDK 1.10 structs on x86-64 System V (sdk-idioms.md §4.2), checked
 * against the live headers at compile time: appending members keeps this file compiling; moving,
 * resizing or removing one breaks the build. Generated once by gen_layout.py when the minor shipped;
 * the numbers are literal on purpose: never regenerate it to make a failing build pass.
 * Tables and info structs may grow at the end (sizeof >=); hot-path records are frozen (sizeof ==). */
#include <nimbus/nimbus.h>
#include <stddef.h>

#if defined(__x86_64__) && !defined(_WIN32)
_Static_assert(NIMBUS_ABI_MAJOR == 1 && NIMBUS_ABI_MINOR >= 10, "not a 1.x SDK");

#define NIMBUS_MEMBER(T, m, off, size) \
  _Static_assert(offsetof(T, m) == (off) && sizeof(((T *)0)->m) == (size), #T "." #m " moved")
#define NIMBUS_FROZEN(T, size, align) \
  _Static_assert(sizeof(T) == (size) && _Alignof(T) == (align), #T " changed size")
#define NIMBUS_GROWABLE(T, size, align) \
  _Static_assert(sizeof(T) >= (size) && _Alignof(T) == (align), #T " shrank")

/* base.h */
NIMBUS_FROZEN(nimbus_struct_header_t, 16, 8);
NIMBUS_MEMBER(nimbus_struct_header_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_struct_header_t, s_type, 4, 4);
NIMBUS_MEMBER(nimbus_struct_header_t, next, 8, 8);

/* bsdf.h */
NIMBUS_FROZEN(nimbus_bsdf_sample_t, 40, 4);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, wi, 0, 12);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, f, 12, 12);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, pdf, 24, 4);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, pdf_rev, 28, 4);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, eta, 32, 4);
NIMBUS_MEMBER(nimbus_bsdf_sample_t, lobe, 36, 4);
NIMBUS_GROWABLE(nimbus_host_bsdf_v1_t, 56, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, eval, 8, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, sample, 16, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, pdf, 24, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, lobes, 32, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, min_roughness, 40, 8);
NIMBUS_MEMBER(nimbus_host_bsdf_v1_t, albedo, 48, 8);

/* film.h */
NIMBUS_GROWABLE(nimbus_host_film_v1_t, 40, 8);
NIMBUS_MEMBER(nimbus_host_film_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_film_v1_t, register_element, 8, 8);
NIMBUS_MEMBER(nimbus_host_film_v1_t, is_active, 16, 8);
NIMBUS_MEMBER(nimbus_host_film_v1_t, accumulate, 24, 8);
NIMBUS_MEMBER(nimbus_host_film_v1_t, splat, 32, 8);
NIMBUS_GROWABLE(nimbus_ext_lightmix_v1_t, 40, 8);
NIMBUS_MEMBER(nimbus_ext_lightmix_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_ext_lightmix_v1_t, is_active, 8, 8);
NIMBUS_MEMBER(nimbus_ext_lightmix_v1_t, group_count, 16, 8);
NIMBUS_MEMBER(nimbus_ext_lightmix_v1_t, accumulate, 24, 8);
NIMBUS_MEMBER(nimbus_ext_lightmix_v1_t, splat, 32, 8);

/* guiding.h */
NIMBUS_GROWABLE(nimbus_guide_stats_t, 24, 8);
NIMBUS_MEMBER(nimbus_guide_stats_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_guide_stats_t, reserved, 4, 4);
NIMBUS_MEMBER(nimbus_guide_stats_t, paths_traced, 8, 8);
NIMBUS_MEMBER(nimbus_guide_stats_t, paths_visible, 16, 8);
NIMBUS_GROWABLE(nimbus_guiding_v1_t, 56, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_guiding_v1_t, prepare, 8, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, begin_iteration, 16, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, budget, 24, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, propose, 32, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, report, 40, 8);
NIMBUS_MEMBER(nimbus_guiding_v1_t, end_iteration, 48, 8);
NIMBUS_GROWABLE(nimbus_guide_tracer_t, 32, 8);
NIMBUS_MEMBER(nimbus_guide_tracer_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_guide_tracer_t, dims, 4, 4);
NIMBUS_MEMBER(nimbus_guide_tracer_t, user, 8, 8);
NIMBUS_MEMBER(nimbus_guide_tracer_t, trace, 16, 8);
NIMBUS_MEMBER(nimbus_guide_tracer_t, credit, 24, 8);
NIMBUS_GROWABLE(nimbus_guide_pass_t, 48, 8);
NIMBUS_MEMBER(nimbus_guide_pass_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_guide_pass_t, seed, 16, 8);
NIMBUS_MEMBER(nimbus_guide_pass_t, pass, 24, 8);
NIMBUS_MEMBER(nimbus_guide_pass_t, path_budget, 32, 8);
NIMBUS_MEMBER(nimbus_guide_pass_t, chain_count, 40, 4);
NIMBUS_MEMBER(nimbus_guide_pass_t, dims, 44, 4);
NIMBUS_GROWABLE(nimbus_guide_totals_t, 56, 8);
NIMBUS_MEMBER(nimbus_guide_totals_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_guide_totals_t, uniform_paths, 16, 8);
NIMBUS_MEMBER(nimbus_guide_totals_t, chain_steps, 24, 8);
NIMBUS_MEMBER(nimbus_guide_totals_t, uniform_target_sum, 32, 8);
NIMBUS_MEMBER(nimbus_guide_totals_t, proposals, 40, 8);
NIMBUS_MEMBER(nimbus_guide_totals_t, accepted, 48, 8);
NIMBUS_GROWABLE(nimbus_guiding_v2_t, 40, 8);
NIMBUS_MEMBER(nimbus_guiding_v2_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_guiding_v2_t, prepare, 8, 8);
NIMBUS_MEMBER(nimbus_guiding_v2_t, begin_pass, 16, 8);
NIMBUS_MEMBER(nimbus_guiding_v2_t, run_chain, 24, 8);
NIMBUS_MEMBER(nimbus_guiding_v2_t, end_pass, 32, 8);

/* host.h */
NIMBUS_GROWABLE(nimbus_host_t, 40, 8);
NIMBUS_MEMBER(nimbus_host_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_t, abi, 4, 8);
NIMBUS_MEMBER(nimbus_host_t, host_data, 16, 8);
NIMBUS_MEMBER(nimbus_host_t, get_service, 24, 8);
NIMBUS_MEMBER(nimbus_host_t, log, 32, 8);
NIMBUS_GROWABLE(nimbus_thread_ctx_t, 32, 8);
NIMBUS_MEMBER(nimbus_thread_ctx_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_thread_ctx_t, worker_index, 4, 4);
NIMBUS_MEMBER(nimbus_thread_ctx_t, worker_count, 8, 4);
NIMBUS_MEMBER(nimbus_thread_ctx_t, reserved, 12, 4);
NIMBUS_MEMBER(nimbus_thread_ctx_t, scratch, 16, 8);
NIMBUS_MEMBER(nimbus_thread_ctx_t, scratch_bytes, 24, 8);
NIMBUS_GROWABLE(nimbus_host_memory_v1_t, 24, 8);
NIMBUS_MEMBER(nimbus_host_memory_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_memory_v1_t, alloc, 8, 8);
NIMBUS_MEMBER(nimbus_host_memory_v1_t, free, 16, 8);
NIMBUS_GROWABLE(nimbus_host_progress_v1_t, 32, 8);
NIMBUS_MEMBER(nimbus_host_progress_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_progress_v1_t, report, 8, 8);
NIMBUS_MEMBER(nimbus_host_progress_v1_t, cancelled, 16, 8);
NIMBUS_MEMBER(nimbus_host_progress_v1_t, stat_add, 24, 8);
NIMBUS_GROWABLE(nimbus_host_tasks_v1_t, 24, 8);
NIMBUS_MEMBER(nimbus_host_tasks_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_tasks_v1_t, reserved, 4, 4);
NIMBUS_MEMBER(nimbus_host_tasks_v1_t, parallel_for, 8, 8);
NIMBUS_MEMBER(nimbus_host_tasks_v1_t, worker_count, 16, 8);
NIMBUS_GROWABLE(nimbus_host_thread_check_v1_t, 24, 8);
NIMBUS_MEMBER(nimbus_host_thread_check_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_thread_check_v1_t, is_main_thread, 8, 8);
NIMBUS_MEMBER(nimbus_host_thread_check_v1_t, is_render_thread, 16, 8);

/* integrator.h */
NIMBUS_FROZEN(nimbus_option_t, 16, 8);
NIMBUS_MEMBER(nimbus_option_t, key, 0, 8);
NIMBUS_MEMBER(nimbus_option_t, value, 8, 8);
NIMBUS_GROWABLE(nimbus_render_setup_t, 80, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_render_setup_t, width, 16, 4);
NIMBUS_MEMBER(nimbus_render_setup_t, height, 20, 4);
NIMBUS_MEMBER(nimbus_render_setup_t, max_depth, 24, 4);
NIMBUS_MEMBER(nimbus_render_setup_t, option_count, 28, 4);
NIMBUS_MEMBER(nimbus_render_setup_t, seed, 32, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, options, 40, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, light_sampler, 48, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, light_sampler_iface, 56, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, guide, 64, 8);
NIMBUS_MEMBER(nimbus_render_setup_t, guide_iface, 72, 8);
NIMBUS_GROWABLE(nimbus_render_info_t, 48, 8);
NIMBUS_MEMBER(nimbus_render_info_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_render_info_t, worker_count, 16, 4);
NIMBUS_MEMBER(nimbus_render_info_t, reserved, 20, 4);
NIMBUS_MEMBER(nimbus_render_info_t, first_iteration, 24, 8);
NIMBUS_MEMBER(nimbus_render_info_t, planned_iterations, 32, 8);
NIMBUS_MEMBER(nimbus_render_info_t, task_index, 40, 4);
NIMBUS_MEMBER(nimbus_render_info_t, task_count, 44, 4);
NIMBUS_FROZEN(nimbus_tile_t, 24, 8);
NIMBUS_MEMBER(nimbus_tile_t, x0, 0, 4);
NIMBUS_MEMBER(nimbus_tile_t, y0, 4, 4);
NIMBUS_MEMBER(nimbus_tile_t, x1, 8, 4);
NIMBUS_MEMBER(nimbus_tile_t, y1, 12, 4);
NIMBUS_MEMBER(nimbus_tile_t, iteration, 16, 8);
NIMBUS_GROWABLE(nimbus_integrator_v1_t, 56, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_integrator_v1_t, prepare, 8, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, begin_render, 16, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, begin_iteration, 24, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, render_tile, 32, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, end_iteration, 40, 8);
NIMBUS_MEMBER(nimbus_integrator_v1_t, end_render, 48, 8);

/* light_sampler.h */
NIMBUS_GROWABLE(nimbus_scene_info_t, 40, 8);
NIMBUS_MEMBER(nimbus_scene_info_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_scene_info_t, light_count, 16, 4);
NIMBUS_MEMBER(nimbus_scene_info_t, worker_count, 20, 4);
NIMBUS_MEMBER(nimbus_scene_info_t, scene_center, 24, 12);
NIMBUS_MEMBER(nimbus_scene_info_t, scene_radius, 36, 4);
NIMBUS_GROWABLE(nimbus_emission_feedback_t, 64, 8);
NIMBUS_MEMBER(nimbus_emission_feedback_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_emission_feedback_t, light_count, 16, 4);
NIMBUS_MEMBER(nimbus_emission_feedback_t, flags, 20, 4);
NIMBUS_MEMBER(nimbus_emission_feedback_t, camera, 24, 12);
NIMBUS_MEMBER(nimbus_emission_feedback_t, reserved, 36, 4);
NIMBUS_MEMBER(nimbus_emission_feedback_t, photon_power, 40, 8);
NIMBUS_MEMBER(nimbus_emission_feedback_t, emitted, 48, 8);
NIMBUS_MEMBER(nimbus_emission_feedback_t, contributed, 56, 8);
NIMBUS_GROWABLE(nimbus_light_sampler_v1_t, 72, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, prepare, 8, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, pick, 16, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, pmf, 24, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, pick_emitter, 32, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, record, 40, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, end_iteration, 48, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, update_emission, 56, 8);
NIMBUS_MEMBER(nimbus_light_sampler_v1_t, pmf_emitter, 64, 8);

/* lights.h */
NIMBUS_GROWABLE(nimbus_light_info_t, 80, 8);
NIMBUS_MEMBER(nimbus_light_info_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_light_info_t, flags, 16, 4);
NIMBUS_MEMBER(nimbus_light_info_t, group, 20, 4);
NIMBUS_MEMBER(nimbus_light_info_t, power, 24, 4);
NIMBUS_MEMBER(nimbus_light_info_t, bounds_min, 28, 12);
NIMBUS_MEMBER(nimbus_light_info_t, bounds_max, 40, 12);
NIMBUS_MEMBER(nimbus_light_info_t, axis, 52, 12);
NIMBUS_MEMBER(nimbus_light_info_t, cos_theta_o, 64, 4);
NIMBUS_MEMBER(nimbus_light_info_t, cos_theta_e, 68, 4);
NIMBUS_MEMBER(nimbus_light_info_t, area, 72, 4);
NIMBUS_FROZEN(nimbus_light_incident_t, 64, 4);
NIMBUS_MEMBER(nimbus_light_incident_t, wi, 0, 12);
NIMBUS_MEMBER(nimbus_light_incident_t, dist, 12, 4);
NIMBUS_MEMBER(nimbus_light_incident_t, p, 16, 12);
NIMBUS_MEMBER(nimbus_light_incident_t, n, 28, 12);
NIMBUS_MEMBER(nimbus_light_incident_t, L, 40, 12);
NIMBUS_MEMBER(nimbus_light_incident_t, pdf, 52, 4);
NIMBUS_MEMBER(nimbus_light_incident_t, flags, 56, 4);
NIMBUS_MEMBER(nimbus_light_incident_t, reserved, 60, 4);
NIMBUS_FROZEN(nimbus_light_emission_t, 64, 4);
NIMBUS_MEMBER(nimbus_light_emission_t, org, 0, 12);
NIMBUS_MEMBER(nimbus_light_emission_t, dir, 12, 12);
NIMBUS_MEMBER(nimbus_light_emission_t, n, 24, 12);
NIMBUS_MEMBER(nimbus_light_emission_t, Le, 36, 12);
NIMBUS_MEMBER(nimbus_light_emission_t, pdf_pos, 48, 4);
NIMBUS_MEMBER(nimbus_light_emission_t, pdf_dir, 52, 4);
NIMBUS_MEMBER(nimbus_light_emission_t, flags, 56, 4);
NIMBUS_MEMBER(nimbus_light_emission_t, reserved, 60, 4);
NIMBUS_GROWABLE(nimbus_host_lights_v1_t, 112, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, count, 8, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, info, 16, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, sample_incident, 24, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, pdf_incident, 32, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, eval_emitted, 40, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, eval_infinite, 48, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, sample_emission, 56, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, eval_emission, 64, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, pdf_emission, 72, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, sample_incident_at, 80, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, sample_emission_at, 88, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, eval_emission_at, 96, 8);
NIMBUS_MEMBER(nimbus_host_lights_v1_t, pdf_emission_at, 104, 8);

/* plugin.h */
NIMBUS_GROWABLE(nimbus_descriptor_t, 72, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_descriptor_t, id, 16, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, name, 24, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, vendor, 32, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, version, 40, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, kind, 48, 4);
NIMBUS_MEMBER(nimbus_descriptor_t, reserved, 52, 4);
NIMBUS_MEMBER(nimbus_descriptor_t, features, 56, 8);
NIMBUS_MEMBER(nimbus_descriptor_t, required_services, 64, 8);
NIMBUS_FROZEN(nimbus_option_decl_t, 40, 8);
NIMBUS_MEMBER(nimbus_option_decl_t, name, 0, 8);
NIMBUS_MEMBER(nimbus_option_decl_t, type, 8, 4);
NIMBUS_MEMBER(nimbus_option_decl_t, reserved, 12, 4);
NIMBUS_MEMBER(nimbus_option_decl_t, default_value, 16, 8);
NIMBUS_MEMBER(nimbus_option_decl_t, allowed, 24, 8);
NIMBUS_MEMBER(nimbus_option_decl_t, doc, 32, 8);
NIMBUS_GROWABLE(nimbus_option_list_t, 32, 8);
NIMBUS_MEMBER(nimbus_option_list_t, header, 0, 16);
NIMBUS_MEMBER(nimbus_option_list_t, count, 16, 4);
NIMBUS_MEMBER(nimbus_option_list_t, reserved, 20, 4);
NIMBUS_MEMBER(nimbus_option_list_t, options, 24, 8);
NIMBUS_GROWABLE(nimbus_plugin_t, 48, 8);
NIMBUS_MEMBER(nimbus_plugin_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_plugin_t, reserved, 4, 4);
NIMBUS_MEMBER(nimbus_plugin_t, desc, 8, 8);
NIMBUS_MEMBER(nimbus_plugin_t, plugin_data, 16, 8);
NIMBUS_MEMBER(nimbus_plugin_t, init, 24, 8);
NIMBUS_MEMBER(nimbus_plugin_t, destroy, 32, 8);
NIMBUS_MEMBER(nimbus_plugin_t, get_interface, 40, 8);
NIMBUS_GROWABLE(nimbus_entry_t, 56, 8);
NIMBUS_MEMBER(nimbus_entry_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_entry_t, abi, 4, 8);
NIMBUS_MEMBER(nimbus_entry_t, init, 16, 8);
NIMBUS_MEMBER(nimbus_entry_t, deinit, 24, 8);
NIMBUS_MEMBER(nimbus_entry_t, count, 32, 8);
NIMBUS_MEMBER(nimbus_entry_t, descriptor, 40, 8);
NIMBUS_MEMBER(nimbus_entry_t, create, 48, 8);

/* render_state.h */
NIMBUS_GROWABLE(nimbus_state_writer_t, 24, 8);
NIMBUS_MEMBER(nimbus_state_writer_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_state_writer_t, reserved, 4, 4);
NIMBUS_MEMBER(nimbus_state_writer_t, host_data, 8, 8);
NIMBUS_MEMBER(nimbus_state_writer_t, write, 16, 8);
NIMBUS_GROWABLE(nimbus_render_state_v1_t, 24, 8);
NIMBUS_MEMBER(nimbus_render_state_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_render_state_v1_t, save, 8, 8);
NIMBUS_MEMBER(nimbus_render_state_v1_t, restore, 16, 8);

/* rng.h */
NIMBUS_FROZEN(nimbus_rng_t, 16, 8);
NIMBUS_MEMBER(nimbus_rng_t, state, 0, 8);
NIMBUS_MEMBER(nimbus_rng_t, inc, 8, 8);
NIMBUS_GROWABLE(nimbus_host_rng_v1_t, 16, 8);
NIMBUS_MEMBER(nimbus_host_rng_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_rng_v1_t, derive, 8, 8);

/* scene.h */
NIMBUS_FROZEN(nimbus_ray_t, 40, 4);
NIMBUS_MEMBER(nimbus_ray_t, org, 0, 12);
NIMBUS_MEMBER(nimbus_ray_t, tnear, 12, 4);
NIMBUS_MEMBER(nimbus_ray_t, dir, 16, 12);
NIMBUS_MEMBER(nimbus_ray_t, tfar, 28, 4);
NIMBUS_MEMBER(nimbus_ray_t, mask, 32, 4);
NIMBUS_MEMBER(nimbus_ray_t, flags, 36, 4);
NIMBUS_FROZEN(nimbus_hit_t, 24, 4);
NIMBUS_MEMBER(nimbus_hit_t, t, 0, 4);
NIMBUS_MEMBER(nimbus_hit_t, u, 4, 4);
NIMBUS_MEMBER(nimbus_hit_t, v, 8, 4);
NIMBUS_MEMBER(nimbus_hit_t, geom_id, 12, 4);
NIMBUS_MEMBER(nimbus_hit_t, prim_id, 16, 4);
NIMBUS_MEMBER(nimbus_hit_t, inst_id, 20, 4);
NIMBUS_FROZEN(nimbus_interaction_t, 88, 8);
NIMBUS_MEMBER(nimbus_interaction_t, p, 0, 12);
NIMBUS_MEMBER(nimbus_interaction_t, eps, 12, 4);
NIMBUS_MEMBER(nimbus_interaction_t, ng, 16, 12);
NIMBUS_MEMBER(nimbus_interaction_t, ns, 28, 12);
NIMBUS_MEMBER(nimbus_interaction_t, dpdu, 40, 12);
NIMBUS_MEMBER(nimbus_interaction_t, dpdv, 52, 12);
NIMBUS_MEMBER(nimbus_interaction_t, uv, 64, 8);
NIMBUS_MEMBER(nimbus_interaction_t, material, 72, 8);
NIMBUS_MEMBER(nimbus_interaction_t, light_id, 80, 4);
NIMBUS_MEMBER(nimbus_interaction_t, flags, 84, 4);
NIMBUS_FROZEN(nimbus_object_bounds_t, 40, 4);
NIMBUS_MEMBER(nimbus_object_bounds_t, lo, 0, 12);
NIMBUS_MEMBER(nimbus_object_bounds_t, hi, 12, 12);
NIMBUS_MEMBER(nimbus_object_bounds_t, center, 24, 12);
NIMBUS_MEMBER(nimbus_object_bounds_t, radius, 36, 4);
NIMBUS_GROWABLE(nimbus_host_scene_query_v1_t, 112, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, intersect, 8, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, occluded, 16, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, interaction, 24, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, spawn_ray, 32, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, spawn_ray_to, 40, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, bounding_sphere, 48, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, sharp_bounds, 56, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, intersect_at, 64, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, occluded_at, 72, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, interaction_at, 80, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, moving_bounds, 88, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, trace_from, 96, 8);
NIMBUS_MEMBER(nimbus_host_scene_query_v1_t, occluded_to, 104, 8);
NIMBUS_FROZEN(nimbus_camera_sample_t, 16, 4);
NIMBUS_MEMBER(nimbus_camera_sample_t, film, 0, 8);
NIMBUS_MEMBER(nimbus_camera_sample_t, lens, 8, 8);
NIMBUS_GROWABLE(nimbus_host_camera_v1_t, 72, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, generate_ray, 8, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, resolution, 16, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, connect, 24, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, sample_film, 32, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, shutter, 40, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, sample_time, 48, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, generate_ray_at, 56, 8);
NIMBUS_MEMBER(nimbus_host_camera_v1_t, connect_at, 64, 8);

/* spectral.h */
NIMBUS_GROWABLE(nimbus_host_spectral_v1_t, 40, 8);
NIMBUS_MEMBER(nimbus_host_spectral_v1_t, struct_size, 0, 4);
NIMBUS_MEMBER(nimbus_host_spectral_v1_t, dispersive, 8, 8);
NIMBUS_MEMBER(nimbus_host_spectral_v1_t, uplift, 16, 8);
NIMBUS_MEMBER(nimbus_host_spectral_v1_t, bsdf_sample, 24, 8);
NIMBUS_MEMBER(nimbus_host_spectral_v1_t, bsdf_eval, 32, 8);

/* version.h */
NIMBUS_FROZEN(nimbus_version_t, 8, 2);
NIMBUS_MEMBER(nimbus_version_t, major, 0, 2);
NIMBUS_MEMBER(nimbus_version_t, minor, 2, 2);
NIMBUS_MEMBER(nimbus_version_t, patch, 4, 2);
NIMBUS_MEMBER(nimbus_version_t, reserved, 6, 2);
#else
typedef int nimbus_layout_not_checked; /* another ABI: the numbers above do not apply */
#endif
