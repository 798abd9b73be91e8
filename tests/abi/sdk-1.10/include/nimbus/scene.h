/* Nimbus SDK: ray queries against the host's scene (nimbus.host.scene-query@1) and the camera
 * (nimbus.host.camera@1). Rays, hits and interactions are hot-path records: no header, layout frozen
 * for the whole major. */
#ifndef NIMBUS_SCENE_H
#define NIMBUS_SCENE_H

#include "host.h"

#ifdef __cplusplus
extern "C" {
#endif

/* tnear > tfar marks an inactive ray (skipped by batched queries). */
typedef struct nimbus_ray {
  float org[3], tnear;
  float dir[3], tfar;
  uint32_t mask, flags;
} nimbus_ray_t;

/* A miss has geom_id == NIMBUS_NONE. */
typedef struct nimbus_hit {
  float t, u, v;
  uint32_t geom_id, prim_id, inst_id;
} nimbus_hit_t;

/* nimbus_interaction_t.flags */
#define NIMBUS_IX_FRONT_FACE 1u /* the ray arrived on the side the geometric normal points to */
#define NIMBUS_IX_EMISSIVE 2u   /* the surface emits: light_id names the light */
#define NIMBUS_IX_TWO_SIDED 4u  /* the surface's emission (if any) leaves both sides */

/* A surface point. ng and ns are unit length and point to the same side (the outside of closed shapes,
 * not flipped towards the ray); dpdu is the shading tangent. `eps` is the distance to offset new rays
 * along ng to leave the surface robustly. `material` is opaque, host-owned until end_render. */
typedef struct nimbus_interaction {
  float p[3], eps;
  float ng[3], ns[3];
  float dpdu[3], dpdv[3];
  float uv[2];
  uint64_t material;
  uint32_t light_id; /* NIMBUS_NONE unless emissive */
  uint32_t flags;
} nimbus_interaction_t;

/* Since 1.3: the bounds of one object, as a box and an enclosing sphere (each may be the tighter one). */
typedef struct nimbus_object_bounds {
  float lo[3], hi[3]; /* axis-aligned box */
  float center[3];    /* enclosing sphere */
  float radius;
} nimbus_object_bounds_t;

#define NIMBUS_SERVICE_SCENE_QUERY "nimbus.host.scene-query"
typedef struct nimbus_host_scene_query_v1 {
  uint32_t struct_size;
  /* [render-thread] Closest hits of n rays. rays borrowed; hits out (n records). */
  void (*intersect)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, const nimbus_ray_t *rays,
                    nimbus_hit_t *hits, uint32_t n);
  /* [render-thread] Any-hit test of n rays over (tnear, tfar): blocked[i] = 1 if something lies between.
   * rays borrowed; blocked out. */
  void (*occluded)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, const nimbus_ray_t *rays,
                   uint8_t *blocked, uint32_t n);
  /* [render-thread] Surface details of a hit (not a miss). ray, hit borrowed; out is caller storage. */
  void (*interaction)(const nimbus_host_t *host, const nimbus_ray_t *ray, const nimbus_hit_t *hit,
                      nimbus_interaction_t *out);
  /* [any-thread] Ray leaving `ix` (borrowed) in direction `dir` (borrowed, unit) up to distance tfar,
   * with its origin offset to the side dir points to. out is caller storage. */
  void (*spawn_ray)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float dir[3], float tfar,
                    nimbus_ray_t *out);
  /* [any-thread] Shadow ray from `ix` to point `p` (borrowed), both ends offset so neither surface
   * occludes it. out is caller storage. */
  void (*spawn_ray_to)(const nimbus_host_t *host, const nimbus_interaction_t *ix, const float p[3],
                       nimbus_ray_t *out);
  /* [any-thread] Bounding sphere of the whole scene: center (out) and radius (returned). */
  float (*bounding_sphere)(const nimbus_host_t *host, float center[3]);
  /* Since 1.3 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] Bounds of the geometry that can form caustics: one record per object with positive
   * area whose material has no diffuse lobe and, somewhere on its surface, only delta lobes or GGX lobes
   * with alpha below alpha_max (a textured roughness counts by its smallest possible value), in the
   * host's object order. Writes the first min(count, capacity) records into out (caller storage; may be
   * NULL when capacity is 0) and returns count. Constant between prepare and end_render. */
  uint32_t (*sharp_bounds)(const nimbus_host_t *host, float alpha_max, nimbus_object_bounds_t *out,
                           uint32_t capacity);
  /* Since 1.7 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling).
   * [render-thread] intersect at scene times: ray i meets the scene as it is at times[i] (moving objects
   * where they are then; a time outside the shutter sees the shutter's nearer end). rays, times
   * borrowed; hits out (n records). The same hits as intersect when nothing in the scene moves. */
  void (*intersect_at)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, const nimbus_ray_t *rays,
                       const float *times, nimbus_hit_t *hits, uint32_t n);
  /* Since 1.7. [render-thread] occluded at scene times, as intersect_at. rays, times borrowed; blocked
   * out. */
  void (*occluded_at)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx, const nimbus_ray_t *rays,
                      const float *times, uint8_t *blocked, uint32_t n);
  /* Since 1.7. [render-thread] Surface details of a hit that intersect_at found at `time`. ray, hit
   * borrowed; out is caller storage. */
  void (*interaction_at)(const nimbus_host_t *host, const nimbus_ray_t *ray, const nimbus_hit_t *hit,
                         float time, nimbus_interaction_t *out);
  /* Since 1.9 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] Bounds of what moves while the shutter is open: one record per object that moves
   * rigidly or deforms, its box and sphere enclosing every place it takes during the shutter, in the
   * host's object order. A segment that meets none of them meets the same surfaces at every time of the
   * shutter. Writes the first min(count, capacity) records into out (caller storage; may be NULL when
   * capacity is 0) and returns count (0 when nothing moves or the shutter is instantaneous). Constant
   * between prepare and end_render. */
  uint32_t (*moving_bounds)(const nimbus_host_t *host, nimbus_object_bounds_t *out, uint32_t capacity);
  /* Since 1.10 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling).
   * [render-thread] A path's next segment in one call: spawn_ray(from, dir, infinity), intersect_at of
   * that ray at `time`, and for a hit interaction_at, with the same ray, hit and interaction as those
   * calls, bit for bit. from, dir borrowed; hit out; ray out unless NULL; ix out unless NULL, written only
   * for a hit, and may be `from` itself (read before it is written). */
  void (*trace_from)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx,
                     const nimbus_interaction_t *from, const float dir[3], float time, nimbus_ray_t *ray,
                     nimbus_hit_t *hit, nimbus_interaction_t *ix);
  /* Since 1.10. [render-thread] spawn_ray_to(ix, p), its tfar made infinite when to_infinity is non-zero
   * (p a point along the direction to a light at infinity), then occluded_at at `time`, in one call:
   * 1 if something blocks the segment, as those calls would say. ix, p borrowed. */
  uint8_t (*occluded_to)(const nimbus_host_t *host, const nimbus_thread_ctx_t *ctx,
                         const nimbus_interaction_t *ix, const float p[3], uint32_t to_infinity, float time);
} nimbus_host_scene_query_v1_t;

/* ---- nimbus.host.camera@1 ---------------------------------------------------------------------- */
typedef struct nimbus_camera_sample {
  float film[2]; /* continuous raster position in pixels: (x + 0.5, y + 0.5) is a pixel centre */
  float lens[2]; /* uniform [0,1)^2 point for the lens (ignored by pinholes) */
} nimbus_camera_sample_t;

#define NIMBUS_SERVICE_CAMERA "nimbus.host.camera"
typedef struct nimbus_host_camera_v1 {
  uint32_t struct_size;
  /* [any-thread] Primary ray through a film position. sample borrowed; ray out. Returns the sample's
   * weight (0 if the sample produced no ray). */
  float (*generate_ray)(const nimbus_host_t *host, const nimbus_camera_sample_t *sample, nimbus_ray_t *ray);
  /* [any-thread] Image width and height in pixels (out) and the angular width of one pixel at the
   * image centre, in radians (returned). */
  float (*resolution)(const nimbus_host_t *host, uint32_t *width, uint32_t *height);
  /* Since 1.1 (absent from a 1.0 host's table: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] Connects world point p (borrowed) to the lens, for light tracing. lens_u (borrowed)
   * picks the lens point (ignored by pinholes). Fills raster (out: continuous pixel position) and
   * lens_point (out: where a visibility ray from p must arrive). Returns the importance factor
   * W = cos(theta) / (d^2 * A_pixel * cos^4(theta)) (d: distance p-lens, theta: angle to the view axis,
   * A_pixel: one pixel's area on the image plane at distance 1), so that radiance L leaving p towards
   * the lens adds L * W to the pixel's mean; 0 when p does not project onto the image. */
  float (*connect)(const nimbus_host_t *host, const float p[3], const float lens_u[2], float raster[2],
                   float lens_point[3]);
  /* Since 1.1 (absent from a 1.0 host's table: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] Film position (film: out, raster pixels) of a camera sample of pixel (x, y) drawn with u
   * (borrowed, 2 numbers) from the scene's pixel filter; returns the sample's weight (multiply the
   * sample's radiance by it). The position always lies in pixel (x, y)'s filter support, and the
   * sample is accumulated into pixel (x, y). */
  float (*sample_film)(const nimbus_host_t *host, uint32_t x, uint32_t y, const float u[2], float film[2]);
  /* Since 1.7 (absent from older hosts' tables: check NIMBUS_HAS_MEMBER before calling).
   * [any-thread] The shutter in scene time: open and close (out). Returns what moves while it is open
   * (NIMBUS_MOTION_* bits); 0 means nothing does, and a path needs no time. */
  uint32_t (*shutter)(const nimbus_host_t *host, float *open, float *close);
  /* Since 1.7. [any-thread] A scene time drawn with u in [0,1) from the shutter's curve (the film's
   * relative exposure over the shutter); *pdf (out) its density per unit time. Camera paths draw one
   * each; a photon path draws its own and carries 1 / pdf in its power. The shutter's open time (pdf 1)
   * when it opens and closes at once. */
  float (*sample_time)(const nimbus_host_t *host, float u, float *pdf);
  /* Since 1.7. [any-thread] generate_ray with the camera where it is at scene time `time` (the same ray
   * as generate_ray when the camera holds still). sample borrowed; ray out. Returns the sample's weight. */
  float (*generate_ray_at)(const nimbus_host_t *host, const nimbus_camera_sample_t *sample, float time,
                           nimbus_ray_t *ray);
  /* Since 1.7. [any-thread] connect with the camera where it is at scene time `time`; arguments and
   * result as connect's (p, lens_u borrowed; raster, lens_point out). */
  float (*connect_at)(const nimbus_host_t *host, const float p[3], float time, const float lens_u[2],
                      float raster[2], float lens_point[3]);
} nimbus_host_camera_v1_t;

/* Since 1.7: what moves while the shutter is open (nimbus_host_camera_v1_t.shutter). */
#define NIMBUS_MOTION_CAMERA 1u   /* the camera: camera paths need a time, photons do not */
#define NIMBUS_MOTION_GEOMETRY 2u /* objects or their vertices */
#define NIMBUS_MOTION_LIGHTS 4u   /* lights */

#ifdef __cplusplus
}
#endif

#endif /* NIMBUS_SCENE_H */
