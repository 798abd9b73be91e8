// Readers for the top-level sections of a scene file, one .cpp each. They fail by throwing ParseFailure
// (see yaml_value.hpp); parse_scene_* turns that into an Error value.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/transform.hpp"
#include "scene/mesh_library.hpp"
#include "scene/scene_desc.hpp"
#include "scene/yaml_value.hpp"

namespace nimbus::scene_yaml {

// What objects refer to: materials by name (glTF and OBJ objects without `material:` add their file's
// materials), named and file meshes, and the camera and resolution (for `level: auto` of subdivision
// surfaces); and where warnings go.
struct ObjectContext {
  std::vector<MaterialDesc> &materials;
  MeshLibrary &meshes;
  const CameraDesc &camera;
  const RenderDesc &render;
  std::vector<std::string> &warnings;  // SceneDesc::warnings
  // Materials made from a mesh file's materials, by "<absolute file>#<material>": made once, shared.
  std::map<std::string, uint32_t> file_materials;
  // The files (OBJ and .mtl) already warned about: one warning each however many objects use them.
  std::set<std::string> warned;
};

RenderDesc read_render(const YamlValue &section);                    // render_section.cpp
CameraDesc read_camera(const YamlValue &section);                    // camera_section.cpp
std::vector<MaterialDesc> read_materials(const YamlValue &section);  // materials_section.cpp
// A dielectric's `ior`, `abbe`, `cauchy` or `sellmeier` into ior and dispersion.  // dielectric_section.cpp
void read_dielectric_index(const YamlMap &material, MaterialDesc &mat);
void read_meshes(const YamlValue &section, MeshLibrary &library);                       // mesh_section.cpp
std::vector<ShapeDesc> read_objects(const YamlValue &section, ObjectContext &context);  // objects_section.cpp
std::vector<LightDesc> read_lights(const YamlValue &section, const Shutter &shutter);   // lights_section.cpp
// `lights` are all the scene's lights: a sky takes its sun from them.    // environment_section.cpp
EnvironmentDesc read_environment(const YamlValue &section, const std::vector<LightDesc> &lights);

// `transform:` of an object: {translate, rotate, scale} or {matrix}.      // transform_section.cpp
Transform read_transform(const YamlValue &value);
// The same from a map whose keys the caller checked (a motion key adds `time`).
Transform read_transform(const YamlMap &map);
// `camera.shutter:` {open, close, curve}.                                 // motion_section.cpp
Shutter read_shutter(const YamlValue &value);
// `deform:` of a mesh: its shapes (files of the same triangles, or inline position lists) at evenly spaced
// times over the shutter, into mesh.position_steps (and normal_steps).  // motion_section.cpp
void read_deformation(const YamlValue &value, MeshData &mesh, MeshLibrary &library, const Shutter &shutter);
// `motion:` of an object: keys [{time, translate, rotate, scale} or {time, matrix}] in time order within
// the shutter. `check` is called on each key's transform and the value it came from.  // motion_section.cpp
std::vector<MotionTransform::Key> read_motion(
    const YamlValue &value, const Shutter &shutter,
    const std::function<void(const Transform &, const YamlValue &)> &check);
// read_motion for a camera or a light (`what`, for errors): translations and rotations only, since a
// scale would change its field of view or what it emits.
std::shared_ptr<const MotionTransform> read_rigid_motion(const YamlValue &value, const Shutter &shutter,
                                                         std::string_view what);

// The triangles of a `shape: mesh` object or a `meshes:` entry in its own coordinates: inline arrays or an
// OBJ or glTF file (read once per scene through `library`).                  // mesh_section.cpp
std::shared_ptr<const LoadedMesh> read_mesh(const YamlMap &object, MeshLibrary &library);

// The triangles of a `shape: subdivision` object in object space; `to_world`, the camera and the
// resolution decide `level: auto`.                                           // subdivision_section.cpp
MeshData read_subdivision(const YamlMap &object, const Transform &to_world, const CameraDesc &camera,
                          const RenderDesc &render);

// A material made from a mesh file's, added to context.materials once per `key` ("<absolute
// file>#<material>"; later calls return the first index): its name made unique against the scene's
// names by a "-2", "-3", ... suffix.                                          // file_material.cpp
uint32_t add_file_material(const std::string &key, MaterialDesc material, ObjectContext &context);
// Colours of mesh files are clamped to [0, 1] like written ones.             // file_material.cpp
Rgb unit_clamped(const Rgb &color);

// The scene material for a glTF material (see gltf_material.cpp for the mapping), made once per file and
// material and appended to context.materials; returns its index. `where` is the value that named the mesh
// (`file:` or `mesh:`), which the material's location and texture key refer to.   // gltf_material.cpp
uint32_t gltf_material(const GltfMaterial &material, const LoadedMesh &mesh, const YamlValue &where,
                       ObjectContext &context);

// The shapes of an object without `material:` whose OBJ file names .mtl materials: `shape` (complete, in
// world space) split by material, each part with its scene material (see obj_material.cpp for the mapping;
// made once per file and material) and the emission its `Ke` gives unless the object gives `emission:`.
// `object` is the object's map; `where` the value that named the mesh (`file:` or `mesh:`), at which
// unusable materials fail and the warning about ignored statements (once per file) points.
//                                                                            // obj_material.cpp
std::vector<ShapeDesc> obj_material_shapes(ShapeDesc shape, const LoadedMesh &mesh, const YamlMap &object,
                                           const YamlValue &where, ObjectContext &context);

}  // namespace nimbus::scene_yaml
