// `objects:` — a list of shapes with a material, an optional transform and optional emission. Transforms
// are applied here, so every ShapeDesc leaves the parser in world space. Meshes, instances of named meshes
// and subdivision surfaces all become ShapeType::Mesh: triangles, each object with its own copy (an OBJ
// mesh that takes its .mtl materials: one per material).
#include <cmath>
#include <string>
#include <vector>

#include "scene/mesh_builders.hpp"
#include "scene/sections.hpp"

namespace nimbus::scene_yaml {

namespace {

const char *const kShapes = "sphere, rectangle, box, disk, mesh, instance, subdivision";

// The keys every shape accepts plus those specific to it.
std::vector<std::string_view> keys_with(std::initializer_list<std::string_view> specific) {
  std::vector<std::string_view> keys{"shape",    "material",  "transform", "motion",
                                     "emission", "two_sided", "group"};
  keys.insert(keys.end(), specific);
  return keys;
}

uint32_t find_material(const YamlValue &v, const std::vector<MaterialDesc> &materials) {
  const std::string name = v.nonempty_string();
  std::vector<std::string_view> names;
  for (size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return uint32_t(i);
    names.push_back(materials[i].name);
  }
  if (names.empty()) v.fail("unknown material '" + abbreviate(name) + "': the scene defines no materials");
  v.fail("unknown material '" + abbreviate(name) + "'; defined: " + join_names(names));
}

std::vector<float> positive_sizes(const YamlValue &v, size_t n, std::string_view shape) {
  std::vector<float> sizes;
  for (const YamlValue &item : v.sequence_of(n, shape)) sizes.push_back(item.real(Range::greater_than(0)));
  return sizes;
}

// Spheres and disks are kept analytic, so their transform may only rotate, translate, mirror and scale
// uniformly; anything else would turn them into ellipsoids and ellipses.
float uniform_scale(const Transform &t, const YamlValue &transform, std::string_view shape) {
  if (const std::optional<float> s = similarity_scale(t)) return *s;
  const Vec3f scales = t.axis_scales();
  transform.fail(
      "a " + std::string(shape) + " allows only rotation, translation and uniform scale (axis scales " +
      format_number(scales.x) + ", " + format_number(scales.y) + ", " + format_number(scales.z) + ")");
}

// One shape, or several for an OBJ file whose .mtl materials give its faces different materials.
std::vector<ShapeDesc> read_object(const YamlValue &object, ObjectContext &context) {
  const YamlMap m = object.map();
  const YamlValue shape_value = m.require("shape");
  const std::string shape = shape_value.string();
  ShapeDesc s;
  s.where = object.location();
  if (shape == "sphere") {
    s.type = ShapeType::Sphere;
    m.check_keys(keys_with({"center", "radius"}), "a sphere");
  } else if (shape == "rectangle") {
    s.type = ShapeType::Rectangle;
    m.check_keys(keys_with({"size"}), "a rectangle");
  } else if (shape == "box") {
    s.type = ShapeType::Box;
    m.check_keys(keys_with({"size"}), "a box");
  } else if (shape == "disk") {
    s.type = ShapeType::Disk;
    m.check_keys(keys_with({"radius"}), "a disk");
  } else if (shape == "mesh") {
    s.type = ShapeType::Mesh;
    m.check_keys(keys_with({"file", "positions", "indices", "normals", "uvs", "deform"}), "a mesh");
  } else if (shape == "instance") {
    s.type = ShapeType::Mesh;
    m.check_keys(keys_with({"mesh"}), "an instance");
  } else if (shape == "subdivision") {
    s.type = ShapeType::Mesh;
    m.check_keys(keys_with({"file", "positions", "faces", "scheme", "level", "creases"}),
                 "a subdivision surface");
  } else {
    shape_value.fail("unknown shape '" + abbreviate(shape) + "'; known: " + kShapes);
  }

  if (auto v = m.get("emission"))
    s.emission = v->map({"radiance"}).require("radiance").rgb(Range::at_least(0));
  if (auto v = m.get("two_sided")) s.two_sided = v->boolean();
  if (auto v = m.get("group")) s.group = v->string();

  // `motion:` keys the transform in time (object space stays object space: the instance moves it);
  // `transform:` is baked into world space here.
  const std::optional<YamlValue> motion_value = m.get("motion");
  if (motion_value && m.has("transform")) m.key("transform").fail("cannot be combined with 'motion'");
  if (motion_value && m.has("emission"))
    m.key("motion").fail("an emitting object cannot move yet (its light would stay where the shutter opens)");
  if (motion_value && s.type == ShapeType::Mesh && shape == "subdivision")
    m.key("motion").fail("a subdivision surface cannot move yet (its tessellation follows the camera)");
  const std::optional<YamlValue> transform_value = m.get("transform");
  const Transform transform = transform_value ? read_transform(*transform_value) : Transform();

  // Meshes from files and names first: a glTF or OBJ mesh brings materials for objects that name none.
  std::shared_ptr<const LoadedMesh> loaded;
  if (shape == "mesh") loaded = read_mesh(m, context.meshes);
  if (shape == "instance") loaded = context.meshes.find(m.require("mesh"));
  const std::optional<YamlValue> named_by = loaded ? m.get(shape == "mesh" ? "file" : "mesh") : std::nullopt;
  const bool obj_materials = !m.has("material") && named_by && loaded->has_obj_materials();
  if (auto v = m.get("material"))
    s.material = find_material(*v, context.materials);
  else if (loaded && loaded->material)
    s.material = gltf_material(*loaded->material, *loaded, *named_by, context);
  else if (!obj_materials)
    s.material = find_material(
        m.require("material", named_by && !loaded->parts.empty()
                                  ? "'" + loaded->file + "' names no .mtl materials (mtllib) to take instead"
                                  : ""),
        context.materials);

  if (motion_value) {
    const bool analytic = s.type == ShapeType::Sphere || s.type == ShapeType::Disk;
    const auto keys =
        read_motion(*motion_value, context.camera.shutter, [&](const Transform &t, const YamlValue &at) {
          if (analytic) uniform_scale(t, at, shape);
        });
    s.motion = std::make_shared<const MotionTransform>(keys, context.camera.shutter.open(),
                                                       context.camera.shutter.close());
  }
  switch (s.type) {
    case ShapeType::Sphere:
    case ShapeType::Disk: {
      const Vec3f center =
          s.type == ShapeType::Sphere && m.has("center") ? m.get("center")->vec3() : Vec3f(0.0f);
      const float radius = m.require("radius").real(Range::greater_than(0));
      const float scale = transform_value ? uniform_scale(transform, *transform_value, shape) : 1.0f;
      s.center = transform.point(center);
      s.radius = radius * scale;
      if (s.type == ShapeType::Disk) s.normal = normalize(transform.normal({0, 0, 1}));
      break;
    }
    case ShapeType::Rectangle: {
      const std::vector<float> size = positive_sizes(m.require("size"), 2, "[width, height]");
      s.mesh = rectangle_mesh(size[0], size[1]);
      break;
    }
    case ShapeType::Box: {
      const std::vector<float> size = positive_sizes(m.require("size"), 3, "[x, y, z]");
      s.mesh = box_mesh({size[0], size[1], size[2]});
      break;
    }
    case ShapeType::Mesh:
      s.mesh = loaded ? loaded->mesh : read_subdivision(m, transform, context.camera, context.render);
      break;
  }
  if (auto deform = m.get("deform")) {
    if (motion_value) deform->fail("cannot be combined with 'motion'");
    if (m.has("emission")) deform->fail("an emitting mesh cannot deform yet");
    read_deformation(*deform, s.mesh, context.meshes, context.camera.shutter);
  }

  if (!s.mesh.positions.empty()) {
    transform_mesh(s.mesh, transform);
    for (const Vec3f &p : s.mesh.positions)
      if (!is_finite(p)) (transform_value ? *transform_value : object).fail("vertex positions overflow");
  }
  if (!is_finite(s.center) || !std::isfinite(s.radius))
    (transform_value ? *transform_value : object).fail("the transformed shape overflows");
  if (obj_materials) return obj_material_shapes(std::move(s), *loaded, m, *named_by, context);
  return {std::move(s)};
}

}  // namespace

std::vector<ShapeDesc> read_objects(const YamlValue &section, ObjectContext &context) {
  std::vector<ShapeDesc> out;
  if (section.is_null()) return out;
  for (const YamlValue &object : section.sequence())
    for (ShapeDesc &s : read_object(object, context)) out.push_back(std::move(s));
  return out;
}

}  // namespace nimbus::scene_yaml
