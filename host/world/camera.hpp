// Perspective camera with an optional thin lens. The horizontal field of view spans the image width. A
// moving camera is the same camera carried rigidly by its motion transform at the path's time.
#pragma once

#include <nimbus/scene.h>

#include <memory>

#include <nimbus/cpp/math.hpp>
#include <nimbus/cpp/sampling.hpp>
#include "scene/scene_desc.hpp"

namespace nimbus {

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc &d, uint32_t width, uint32_t height) : width_(width), height_(height) {
    const Vec3f forward = normalize(d.look_at - d.position);
    const Vec3f right = normalize(cross(forward, d.up));
    const Vec3f up = cross(right, forward);
    frame_ = {right, up, forward};
    origin_ = d.position;
    tan_half_ = std::tan(radians(d.fov_degrees) * 0.5f);
    aperture_ = d.aperture;
    focus_ = d.focus_distance > 0 ? d.focus_distance : length(d.look_at - d.position);
    if (d.motion && d.motion->moves()) motion_ = d.motion;
  }

  bool moves() const { return motion_ != nullptr; }

  // generate_ray with the camera where it is at scene time `time`.
  void generate_ray_at(const nimbus_camera_sample_t &s, float time, nimbus_ray_t &ray) const {
    generate_ray(s, ray);
    if (!motion_) return;
    const Transform m = motion_->at(time);
    m.point(Vec3f::load(ray.org)).store(ray.org);
    m.vector(Vec3f::load(ray.dir)).store(ray.dir);  // rigid: stays unit length
  }

  // connect with the camera where it is at scene time `time`: p is carried into the resting camera's
  // world, where distances and angles are the same (the motion is rigid).
  float connect_at(const Vec3f &p, float time, const float lens_u[2], float raster[2],
                   Vec3f &lens_point) const {
    if (!motion_) return connect(p, lens_u, raster, lens_point);
    const Transform m = motion_->at(time);
    const float w = connect(m.inverse().point(p), lens_u, raster, lens_point);
    lens_point = m.point(lens_point);
    return w;
  }

  // Primary ray through raster position (fx, fy): x to the right, y down, pixel centres at +0.5.
  void generate_ray(const nimbus_camera_sample_t &s, nimbus_ray_t &ray) const {
    const float aspect = float(height_) / float(width_);
    const float sx = (2 * s.film[0] / float(width_) - 1) * tan_half_;
    const float sy = (1 - 2 * s.film[1] / float(height_)) * tan_half_ * aspect;
    Vec3f dir_cam{sx, sy, 1};  // camera space: x right, y up, z forward
    Vec3f org_cam{0, 0, 0};
    if (aperture_ > 0) {
      const Vec2f l = sample_uniform_disk_concentric(s.lens[0], s.lens[1]);
      org_cam = Vec3f{l.x * aperture_, l.y * aperture_, 0};
      dir_cam = dir_cam * focus_ - org_cam;  // through the in-focus point on the plane z = focus
    }
    const Vec3f dir = normalize(frame_.s * dir_cam.x + frame_.t * dir_cam.y + frame_.n * dir_cam.z);
    const Vec3f org = origin_ + frame_.s * org_cam.x + frame_.t * org_cam.y;
    org.store(ray.org);
    dir.store(ray.dir);
    ray.tnear = 0;
    ray.tfar = kInfinity;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
  }

  // Light-tracing connection (see nimbus_host_camera_v1_t::connect).
  float connect(const Vec3f &p, const float lens_u[2], float raster[2], Vec3f &lens_point) const {
    Vec3f lens_cam{0, 0, 0};
    if (aperture_ > 0) {
      const Vec2f l = sample_uniform_disk_concentric(lens_u[0], lens_u[1]);
      lens_cam = Vec3f{l.x * aperture_, l.y * aperture_, 0};
    }
    lens_point = origin_ + frame_.s * lens_cam.x + frame_.t * lens_cam.y;
    const Vec3f d = p - lens_point;
    const float dist2 = length_squared(d);
    const Vec3f dc{dot(d, frame_.s), dot(d, frame_.t), dot(d, frame_.n)};  // camera space
    if (!(dc.z > 0) || !(dist2 > 0)) return 0;
    // The point of the focus plane the ray lens -> p passes through, seen from the lens centre, gives
    // the raster position (for a pinhole: p itself).
    Vec3f q = dc;
    if (aperture_ > 0) q = lens_cam + dc * (focus_ / dc.z);
    const float sx = q.x / q.z, sy = q.y / q.z;  // on the plane z = 1
    const float aspect = float(height_) / float(width_);
    raster[0] = (sx / tan_half_ + 1) * 0.5f * float(width_);
    raster[1] = (1 - sy / (tan_half_ * aspect)) * 0.5f * float(height_);
    if (!(raster[0] >= 0 && raster[0] < float(width_) && raster[1] >= 0 && raster[1] < float(height_)))
      return 0;
    const float cos_theta = dc.z / std::sqrt(dist2);
    const float pixel_area = sqr(2 * tan_half_ / float(width_));
    return cos_theta / (dist2 * pixel_area * sqr(sqr(cos_theta)));
  }

  // Angular width of one pixel at the image centre.
  float pixel_angle() const { return 2 * std::atan(tan_half_ / float(width_)); }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  Vec3f position() const { return origin_; }

 private:
  uint32_t width_ = 1, height_ = 1;
  Frame frame_{};
  Vec3f origin_;
  float tan_half_ = 1, aperture_ = 0, focus_ = 1;
  std::shared_ptr<const MotionTransform> motion_;  // null when the camera holds still
};

}  // namespace nimbus
