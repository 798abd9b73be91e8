// Readers for the top-level sections of a scene file, one .cpp each. They fail by throwing ParseFailure
// (see yaml_value.hpp); parse_scene_* turns that into an Error value.
#pragma once

#include <vector>

#include "core/transform.hpp"
#include "scene/scene_desc.hpp"
#include "scene/yaml_value.hpp"

namespace nimbus::scene_yaml {

RenderDesc read_render(const YamlValue &section);                    // render_section.cpp
CameraDesc read_camera(const YamlValue &section);                    // camera_section.cpp
std::vector<MaterialDesc> read_materials(const YamlValue &section);  // materials_section.cpp
std::vector<ShapeDesc> read_objects(const YamlValue &section,        // objects_section.cpp
                                    const std::vector<MaterialDesc> &materials);
std::vector<LightDesc> read_lights(const YamlValue &section);  // lights_section.cpp

// `transform:` of an object: {translate, rotate, scale} or {matrix}.      // transform_section.cpp
Transform read_transform(const YamlValue &value);

// The triangles of a `shape: mesh` object in object space: inline arrays or an OBJ file.  // mesh_section.cpp
MeshData read_mesh(const YamlMap &object);

}  // namespace nimbus::scene_yaml
