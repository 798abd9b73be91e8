// The parsed scene: plain data, validated, in world space, with no renderer state. The parser
// (scene_parser.hpp) produces it from YAML; the world (world/world.hpp) is built from it: Embree geometry,
// materials, lights, camera and pixel filter.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "core/ior_curve.hpp"
#include "core/motion_transform.hpp"
#include "core/shutter.hpp"
#include "core/transform.hpp"
#include "scene/pixel_filter_type.hpp"
#include "scene/source_log.hpp"

namespace nimbus {

// Where a value came from, for errors found after parsing (e.g. while loading a mesh).
struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based; 0 = unknown
  int column = 0;  // 1-based
  // "file:line:column", as errors name a place.
  std::string text() const { return file + ":" + std::to_string(line) + ":" + std::to_string(column); }
};

struct RenderDesc {
  uint32_t width = 512, height = 512;
  uint64_t iterations = 0;  // 0 = not set (then time or the CLI decides; default 64)
  double time_seconds = 0;  // 0 = no time budget
  double target_error = 0;  // relMSE estimate to stop at; 0 = no error target
  uint64_t seed = 1;
  uint32_t max_depth = 16;              // path length in segments: a camera ray that hits a light is 1
  std::string integrator = "caustics";  // short name (pt, lt, caustics) or full plugin id
  // Options for the bound integrator (render keys the host does not know, e.g. caustics: off, and
  // --<name> flags), as written: the integrator's declarations decide, once it is bound, whether a key
  // exists and whether its value is valid. Later settings of one name win.
  struct OptionSetting {
    std::string name, value;
    std::string where;  // for errors: "scene.yaml:12:3: render.caustics" or "--caustics"
    std::string hint;   // for an unknown name: what else the user may have meant (the host's own keys)
  };
  std::vector<OptionSetting> options;
  std::vector<std::string> elements;  // requested render elements besides beauty
  FilterType filter = FilterType::Box;
  // Render region (crop window) in pixels, [x0, x1) x [y0, y1); empty (all zero) = the whole image.
  uint32_t region[4] = {0, 0, 0, 0};
  std::string light_sampler;  // empty: the host's choice
  std::string guide;          // a guiding plugin id, "none", or empty: the integrator's default guide
  std::string guide_where;    // for errors: "scene.yaml:12:3: render.guide"
};

struct CameraDesc {
  Vec3f position{0, -4, 1};
  Vec3f look_at{0, 0, 0};
  Vec3f up{0, 0, 1};
  float fov_degrees = 45;    // horizontal field of view
  float aperture = 0;        // thin-lens radius; 0 = pinhole
  float focus_distance = 0;  // 0 = distance to look_at
  Shutter shutter;           // instantaneous unless something moves
  // Rigid motion over the shutter applied to the pose above (null: the camera holds still).
  std::shared_ptr<const MotionTransform> motion;
};

enum class MaterialType { Diffuse, Conductor, Dielectric };

// An image a material reads at every surface point. The file is opened when the scene is built, so its
// errors come after parsing: `key` and `where` let them still name the place in the scene.
struct TextureDesc {
  std::string path;  // absolute after parsing; empty = no texture
  std::string key;   // e.g. "materials.floor.albedo.texture"
  SourceLocation where;
  bool empty() const { return path.empty(); }
};

struct MaterialDesc {
  std::string name;
  MaterialType type = MaterialType::Diffuse;
  Rgb albedo{0.8f, 0.8f, 0.8f};  // diffuse
  // Conductor: complex IOR per RGB channel (from `metal:` or `eta:`/`k:`), or an ideal mirror with
  // `reflectance:` (use_reflectance = true: no Fresnel, reflects `reflectance`).
  Rgb eta{0.2f, 0.92f, 1.1f};
  Rgb k{3.9f, 2.45f, 2.14f};
  bool use_reflectance = false;
  Rgb reflectance{1, 1, 1};
  float ior = 1.5f;  // dielectric: the index RGB transport uses (n_d, at 587.56 nm, for a dispersive one)
  // Dielectric given `abbe`, `cauchy` or `sellmeier`: its index over wavelength, which paths that carry a
  // wavelength use; empty for an index that `ior` alone gives (and for the other types).
  std::optional<IorCurve> dispersion;
  float roughness = 0;  // conductor and dielectric: user-facing roughness in [0, 1]; GGX alpha = r^2
  // Textures replace the constant above them where present (host/scene/materials_section.cpp has the
  // syntax and conventions). Lookups use (u, v) * uv_scale with v = 0 at the bottom of the image.
  TextureDesc albedo_texture;     // diffuse; colour (8/16-bit files are sRGB-decoded)
  TextureDesc roughness_texture;  // conductor, dielectric; first channel, as data
  TextureDesc normal_map;         // any type; tangent space, OpenGL convention (green = +v)
  Vec2f uv_scale{1, 1};
  // The index over wavelength: the curve the scene gave, or the constant `ior`.
  IorCurve ior_curve() const { return dispersion ? *dispersion : IorCurve::constant(ior); }
  // Whether paths through this material must carry a wavelength.
  bool dispersive() const {
    return type == MaterialType::Dielectric && dispersion && dispersion->dispersive();
  }
  bool textured() const {
    return !albedo_texture.empty() || !roughness_texture.empty() || !normal_map.empty();
  }
  SourceLocation where;
};

enum class ShapeType { Sphere, Rectangle, Box, Disk, Mesh };

struct MeshData {
  std::vector<Vec3f> positions;   // world space
  std::vector<Vec3f> normals;     // per vertex, world space; empty = flat shading
  std::vector<Vec2f> uvs;         // per vertex; may be empty
  std::vector<uint32_t> indices;  // 3 per triangle
  // Deformation blur: the positions (and normals, when the mesh has them) at evenly spaced times over the
  // shutter [steps_open, steps_close], each set as long as `positions`; empty when the mesh keeps its shape.
  std::vector<std::vector<Vec3f>> position_steps, normal_steps;
  float steps_open = 0, steps_close = 0;
  bool deforms() const { return position_steps.size() > 1; }
};

struct ShapeDesc {
  ShapeType type = ShapeType::Sphere;
  // Sphere and disk, world space after the transform (which must be a similarity for them), or object
  // space when `motion` moves them.
  Vec3f center{0, 0, 0};
  float radius = 1;
  Vec3f normal{0, 0, 1};  // disk
  // Rectangle, box and mesh: triangles already in world space (rectangle: 2, box: 12), or in object space
  // when `motion` moves them.
  MeshData mesh;
  // A shape that moves over the shutter: its transform at each time; null for a static shape.
  std::shared_ptr<const MotionTransform> motion;
  uint32_t material = 0;  // index into SceneDesc::materials
  // Area emission: radiance in W/(m^2 sr) per channel; black = not an emitter.
  Rgb emission{0, 0, 0};
  bool two_sided = false;  // emission leaves both sides
  std::string group;       // LightMix group; empty = its own group
  SourceLocation where;
};

enum class LightType { Point, Spot, Sun };

struct LightDesc {
  LightType type = LightType::Point;
  Vec3f position{0, 0, 0};
  Rgb intensity{1, 1, 1};  // point and spot: W/sr (from `intensity:`, or `power:` in W converted)
  // Spot: the axis it points along; sun: the direction its light travels (from the sun to the scene).
  Vec3f direction{0, 0, -1};
  float cone_degrees = 30;                 // spot: half angle of the cone
  float softness_degrees = 5;              // spot: width of the smooth fall-off inside the cone's edge
  Rgb irradiance{1, 1, 1};                 // sun: W/m^2 on a surface facing it
  float angular_diameter_degrees = 0.53f;  // sun: 0 = a delta direction
  std::string group;
  // Rigid motion over the shutter applied to position and direction (null: the light holds still).
  std::shared_ptr<const MotionTransform> motion;
  SourceLocation where;
};

enum class EnvironmentType { None, Color, Map, Sky };

// The environment: radiance arriving from infinitely far away along directions no geometry blocks.
struct EnvironmentDesc {
  EnvironmentType type = EnvironmentType::None;
  Rgb color{0, 0, 0};        // uniform: radiance W/(m^2 sr)
  std::string map;           // lat-long image path (absolute after parsing)
  float scale = 1;           // multiplies the radiance of map, color and sky
  float rotate_degrees = 0;  // rotation about the up (+z) axis
  float turbidity = 3;       // sky: Preetham turbidity in [1.7, 10]
  // Sky: direction towards the sun (unit); taken from the scene's sun light when it has one.
  Vec3f sun_direction{0, 0, 1};
  std::string group;
  SourceLocation where;
};

struct SceneDesc {
  std::string path;  // the scene file
  // The scene's text and every file the parser read for it, with a hash of each (scene/source_log.hpp).
  std::vector<SourceFile> sources;
  RenderDesc render;
  CameraDesc camera;
  std::vector<MaterialDesc> materials;
  std::vector<ShapeDesc> shapes;
  std::vector<LightDesc> lights;
  EnvironmentDesc environment;
  // What the scene asks for that Nimbus does not do but can leave out, one line each, formatted like the
  // parser's errors with "warning" in place of "error" (e.g. the .mtl statements it ignores).
  std::vector<std::string> warnings;
};

}  // namespace nimbus
