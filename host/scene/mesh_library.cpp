#include "scene/mesh_library.hpp"

#include <vector>

#include "scene/obj_loader.hpp"

namespace nimbus::scene_yaml {

namespace {

std::string lowercase_extension(const std::filesystem::path &path) {
  std::string ext = path.extension().string();
  for (char &c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

std::shared_ptr<const LoadedMesh> MeshLibrary::load(const YamlValue &file) {
  const std::filesystem::path path = file.source().resolve(file.nonempty_string());
  std::error_code ec;
  std::filesystem::path key = std::filesystem::weakly_canonical(path, ec);
  if (ec) key = path.lexically_normal();
  if (auto it = files_.find(key); it != files_.end()) return it->second;

  const std::string ext = lowercase_extension(path);
  auto mesh = std::make_shared<LoadedMesh>();
  mesh->file = key.string();
  std::string reason;
  if (ext == ".obj") {
    Expected<ObjMesh> obj = load_obj_mesh(path, file.source().log);
    if (obj) {
      mesh->mesh = std::move(obj->mesh);
      mesh->parts = std::move(obj->parts);
      mesh->obj_materials = std::move(obj->materials);
    } else {
      reason = obj.error().message;
    }
  } else if (ext == ".gltf" || ext == ".glb") {
    Expected<GltfMesh> gltf = load_gltf_mesh(path, file.source().log);
    if (gltf) {
      mesh->mesh = std::move(gltf->mesh);
      mesh->material = std::move(gltf->material);
    } else {
      reason = gltf.error().message;
    }
  } else {
    file.fail("unknown mesh file type '" + abbreviate(path.extension().string()) +
              "'; supported: .obj, .gltf, .glb");
  }
  if (!reason.empty()) file.fail("cannot load mesh '" + path.string() + "': " + reason);
  files_.emplace(key, mesh);
  return mesh;
}

void MeshLibrary::add(const std::string &name, std::shared_ptr<const LoadedMesh> mesh,
                      const YamlValue &where) {
  const auto [it, inserted] = named_.try_emplace(name, Named{std::move(mesh), where.location()});
  if (!inserted) {
    const SourceLocation &first = it->second.where;
    where.fail("mesh '" + abbreviate(name) + "' is already defined at " + first.file + ":" +
               std::to_string(first.line) + ":" + std::to_string(first.column));
  }
}

std::shared_ptr<const LoadedMesh> MeshLibrary::find(const YamlValue &name) const {
  const std::string n = name.nonempty_string();
  if (auto it = named_.find(n); it != named_.end()) return it->second.mesh;
  if (named_.empty()) name.fail("unknown mesh '" + abbreviate(n) + "': the scene defines no meshes");
  std::vector<std::string_view> names;
  for (const auto &[k, v] : named_) names.push_back(k);
  name.fail("unknown mesh '" + abbreviate(n) + "'; defined: " + join_names(names));
}

}  // namespace nimbus::scene_yaml
