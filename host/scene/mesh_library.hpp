// The meshes of a scene that come from files or are shared by name. Each file is read once however many
// objects or `meshes:` entries name it, and each object then takes its own copy to move into world space
// (the geometry module has no instancing yet, so sharing saves loading time, not memory).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/gltf_loader.hpp"
#include "scene/obj_loader.hpp"
#include "scene/scene_desc.hpp"
#include "scene/yaml_value.hpp"

namespace nimbus::scene_yaml {

// A mesh in its own coordinates, with the material a glTF file gives it or the faces and .mtl materials
// of an OBJ file.
struct LoadedMesh {
  MeshData mesh;
  std::optional<GltfMaterial> material;
  std::vector<ObjPart> parts;  // OBJ files only
  ObjMaterials obj_materials;  // OBJ files only
  std::string file;            // absolute path of the file it came from; empty when written inline
  // Whether the OBJ file names .mtl materials (even ones that cannot be used): an object without
  // `material:` then takes them.
  bool has_obj_materials() const { return !obj_materials.materials.empty() || !obj_materials.error.empty(); }
};

class MeshLibrary {
 public:
  // The mesh in the file a `file:` value names (.obj, .gltf or .glb, relative to the file naming it).
  // Failures are reported at `file` with the path and the reason.
  std::shared_ptr<const LoadedMesh> load(const YamlValue &file);

  // `meshes:` entries. Adding a name twice fails at `where`, naming the first definition.
  void add(const std::string &name, std::shared_ptr<const LoadedMesh> mesh, const YamlValue &where);
  // The mesh named `name` (a `mesh:` value); an unknown name fails there, listing the known ones.
  std::shared_ptr<const LoadedMesh> find(const YamlValue &name) const;

 private:
  struct Named {
    std::shared_ptr<const LoadedMesh> mesh;
    SourceLocation where;
  };
  std::map<std::filesystem::path, std::shared_ptr<const LoadedMesh>> files_;
  std::map<std::string, Named> named_;
};

}  // namespace nimbus::scene_yaml
