// tinygltf comes from Debian as a shared library (libtinygltf.so, built with its stb and JSON
// dependencies), so no translation unit here defines TINYGLTF_IMPLEMENTATION.
#include "scene/gltf_loader.hpp"

#include <tiny_gltf.h>

#include <array>
#include <cmath>
#include <cstring>
#include <functional>

#include "core/one_line.hpp"
#include "core/transform.hpp"
#include "scene/mesh_builders.hpp"

namespace nimbus {

namespace {

// Images are only named, never decoded: the scene builder reads textures itself, and a missing image
// must not make the geometry unreadable.
bool skip_image(tinygltf::Image *, const int, std::string *, std::string *, int, int, const unsigned char *,
                int, void *) {
  return true;
}

// tinygltf's own file reading (so its messages stay as they are), with what it read recorded.
bool read_and_record(std::vector<unsigned char> *out, std::string *err, const std::string &path, void *log) {
  if (!tinygltf::ReadWholeFile(out, err, path, nullptr)) return false;
  if (log)
    static_cast<SourceLog *>(log)->record(
        path, std::string_view(reinterpret_cast<const char *>(out->data()), out->size()));
  return true;
}

// The bytes of element i of an accessor, bounds-checked against its buffer: a malformed file must give an
// error, not a read past the end.
class AccessorView {
 public:
  static Expected<AccessorView> open(const tinygltf::Model &model, int index, int type, const char *what) {
    if (index < 0 || size_t(index) >= model.accessors.size())
      return Error{std::string(what) + " accessor " + std::to_string(index) + " does not exist"};
    const tinygltf::Accessor &a = model.accessors[size_t(index)];
    if (a.sparse.isSparse) return Error{std::string(what) + " accessor uses sparse storage (not supported)"};
    if (a.type != type) return Error{std::string(what) + " accessor has the wrong type"};
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size())
      return Error{std::string(what) + " accessor has no buffer view"};
    const tinygltf::BufferView &view = model.bufferViews[size_t(a.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
      return Error{std::string(what) + " buffer view refers to a missing buffer"};
    const std::vector<unsigned char> &data = model.buffers[size_t(view.buffer)].data;
    // Sizes come from the file: bound them before any arithmetic on them can wrap around.
    if (view.byteOffset > data.size() || view.byteLength > data.size() || a.byteOffset > data.size() ||
        a.count > data.size())
      return Error{std::string(what) + " accessor reaches past the end of its buffer"};
    const int stride = a.ByteStride(view);
    const int component = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (stride <= 0 || component <= 0 || components <= 0)
      return Error{std::string(what) + " accessor has an invalid layout"};
    AccessorView v;
    v.begin_ = view.byteOffset + a.byteOffset;
    v.stride_ = size_t(stride);
    v.count_ = a.count;
    v.component_type_ = a.componentType;
    v.normalized_ = a.normalized;
    const size_t element = size_t(component) * size_t(components);
    const size_t view_end = view.byteOffset + view.byteLength;
    if (a.count > 0 && (view_end > data.size() || v.begin_ + v.stride_ * (a.count - 1) + element > view_end))
      return Error{std::string(what) + " accessor reaches past the end of its buffer"};
    v.data_ = data.data();
    return v;
  }

  size_t count() const { return count_; }
  int component_type() const { return component_type_; }

  // Component c of element i as a float; integer components only when normalized (e.g. uvs as u8/u16).
  float real(size_t i, int c) const {
    const unsigned char *p = data_ + begin_ + stride_ * i;
    switch (component_type_) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float x;
        std::memcpy(&x, p + 4 * c, 4);
        return x;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return float(p[c]) / 255.0f;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t x;
        std::memcpy(&x, p + 2 * c, 2);
        return float(x) / 65535.0f;
      }
      default:
        return 0;
    }
  }
  bool reals_ok(bool allow_normalized) const {
    return component_type_ == TINYGLTF_COMPONENT_TYPE_FLOAT ||
           (allow_normalized && normalized_ &&
            (component_type_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
             component_type_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
  }

  uint32_t index(size_t i) const {
    const unsigned char *p = data_ + begin_ + stride_ * i;
    switch (component_type_) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return p[0];
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t x;
        std::memcpy(&x, p, 2);
        return x;
      }
      default: {
        uint32_t x;
        std::memcpy(&x, p, 4);
        return x;
      }
    }
  }
  bool indices_ok() const {
    return component_type_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           component_type_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
           component_type_ == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }

 private:
  const unsigned char *data_ = nullptr;
  size_t begin_ = 0, stride_ = 0, count_ = 0;
  int component_type_ = 0;
  bool normalized_ = false;
};

// A node's local transform: its matrix (column-major in glTF) or translation * rotation * scale.
Transform local_transform(const tinygltf::Node &node) {
  if (node.matrix.size() == 16) {
    std::array<float, 16> m{};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m[size_t(4 * r + c)] = float(node.matrix[size_t(4 * c + r)]);
    return Transform(m);
  }
  Transform t, r, s;
  if (node.translation.size() == 3)
    t = Transform::translate(
        {float(node.translation[0]), float(node.translation[1]), float(node.translation[2])});
  if (node.rotation.size() == 4) {  // unit quaternion (x, y, z, w)
    const float x = float(node.rotation[0]), y = float(node.rotation[1]), z = float(node.rotation[2]),
                w = float(node.rotation[3]);
    r = Transform({1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0,  //
                   2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0,  //
                   2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0,  //
                   0, 0, 0, 1});
  }
  if (node.scale.size() == 3)
    s = Transform::scale({float(node.scale[0]), float(node.scale[1]), float(node.scale[2])});
  return t * r * s;
}

struct Collector {
  const tinygltf::Model &model;
  GltfMesh out;
  bool all_normals = true, all_uvs = true;
  int first_material = -2;  // -2: no triangle primitive seen yet

  // The triangles (as index triples into the primitive's vertices) of a primitive's mode.
  static Expected<std::vector<uint32_t>> triangles(int mode, const std::vector<uint32_t> &v) {
    std::vector<uint32_t> t;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      if (v.size() % 3 != 0) return Error{"a triangle list has " + std::to_string(v.size()) + " indices"};
      return v;
    }
    for (size_t i = 2; i < v.size(); ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
        t.insert(t.end(), {v[0], v[i - 1], v[i]});
      else if (i % 2 == 0)  // strips alternate winding
        t.insert(t.end(), {v[i - 2], v[i - 1], v[i]});
      else
        t.insert(t.end(), {v[i - 1], v[i - 2], v[i]});
    }
    return t;
  }

  Status add_primitive(const tinygltf::Primitive &p, const Transform &world, const std::string &mesh_name) {
    const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return Ok{};  // points and lines have no area: nothing to render
    const std::string where = "mesh '" + mesh_name + "': ";
    const auto attribute = [&](const char *name) {
      const auto it = p.attributes.find(name);
      return it == p.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) return Error{where + "a primitive has no POSITION"};
    auto pos = AccessorView::open(model, attribute("POSITION"), TINYGLTF_TYPE_VEC3, "POSITION");
    if (!pos) return Error{where + pos.error().message};
    if (!pos->reals_ok(false)) return Error{where + "POSITION must be float"};

    MeshData prim;
    for (size_t i = 0; i < pos->count(); ++i) {
      const Vec3f p3{pos->real(i, 0), pos->real(i, 1), pos->real(i, 2)};
      if (!is_finite(p3)) return Error{where + "a position is not finite"};
      prim.positions.push_back(p3);
    }
    if (attribute("NORMAL") >= 0) {
      auto n = AccessorView::open(model, attribute("NORMAL"), TINYGLTF_TYPE_VEC3, "NORMAL");
      if (!n) return Error{where + n.error().message};
      if (!n->reals_ok(false) || n->count() != pos->count())
        return Error{where + "NORMAL must be float with one per position"};
      for (size_t i = 0; i < n->count(); ++i) {
        const Vec3f v{n->real(i, 0), n->real(i, 1), n->real(i, 2)};
        prim.normals.push_back(is_finite(v) && length(v) > 0 ? normalize(v) : Vec3f(0, 0, 1));
      }
    } else {
      all_normals = false;
    }
    if (attribute("TEXCOORD_0") >= 0) {
      auto uv = AccessorView::open(model, attribute("TEXCOORD_0"), TINYGLTF_TYPE_VEC2, "TEXCOORD_0");
      if (!uv) return Error{where + uv.error().message};
      if (!uv->reals_ok(true) || uv->count() != pos->count())
        return Error{where + "TEXCOORD_0 must be float or normalized with one per position"};
      for (size_t i = 0; i < uv->count(); ++i) prim.uvs.push_back({uv->real(i, 0), 1 - uv->real(i, 1)});
    } else {
      all_uvs = false;
    }

    std::vector<uint32_t> vertices;
    if (p.indices >= 0) {
      auto idx = AccessorView::open(model, p.indices, TINYGLTF_TYPE_SCALAR, "indices");
      if (!idx) return Error{where + idx.error().message};
      if (!idx->indices_ok()) return Error{where + "indices must be unsigned integers"};
      for (size_t i = 0; i < idx->count(); ++i) {
        const uint32_t k = idx->index(i);
        if (k >= pos->count())
          return Error{where + "index " + std::to_string(k) + " is out of range: the primitive has " +
                       std::to_string(pos->count()) + " vertices"};
        vertices.push_back(k);
      }
    } else {
      for (size_t i = 0; i < pos->count(); ++i) vertices.push_back(uint32_t(i));
    }
    auto tris = triangles(mode, vertices);
    if (!tris) return Error{where + tris.error().message};
    prim.indices = std::move(tris.value());
    if (first_material == -2) first_material = p.material;
    transform_mesh(prim, world);  // also restores counter-clockwise winding under mirroring nodes

    const auto base = uint32_t(out.mesh.positions.size());
    out.mesh.positions.insert(out.mesh.positions.end(), prim.positions.begin(), prim.positions.end());
    out.mesh.normals.insert(out.mesh.normals.end(), prim.normals.begin(), prim.normals.end());
    out.mesh.uvs.insert(out.mesh.uvs.end(), prim.uvs.begin(), prim.uvs.end());
    for (uint32_t i : prim.indices) out.mesh.indices.push_back(base + i);
    return Ok{};
  }

  Status add_mesh(int index, const Transform &world) {
    if (index < 0 || size_t(index) >= model.meshes.size())
      return Error{"a node refers to mesh " + std::to_string(index) + ", which does not exist"};
    const tinygltf::Mesh &mesh = model.meshes[size_t(index)];
    const std::string name = mesh.name.empty() ? std::to_string(index) : mesh.name;
    for (const tinygltf::Primitive &p : mesh.primitives)
      if (Status s = add_primitive(p, world, name); !s) return s;
    return Ok{};
  }

  // Depth is bounded by the node count: glTF forbids cycles, but a malformed file must not recurse forever.
  Status add_node(int index, const Transform &parent, size_t depth) {
    if (index < 0 || size_t(index) >= model.nodes.size())
      return Error{"node " + std::to_string(index) + " does not exist"};
    if (depth > model.nodes.size()) return Error{"the node hierarchy has a cycle"};
    const tinygltf::Node &node = model.nodes[size_t(index)];
    const Transform world = parent * local_transform(node);
    if (node.mesh >= 0)
      if (Status s = add_mesh(node.mesh, world); !s) return s;
    for (int child : node.children)
      if (Status s = add_node(child, world, depth + 1); !s) return s;
    return Ok{};
  }
};

std::optional<GltfMaterial> material_of(const tinygltf::Model &model, int index,
                                        const std::filesystem::path &dir) {
  if (index < 0 || size_t(index) >= model.materials.size()) return std::nullopt;
  const tinygltf::Material &m = model.materials[size_t(index)];
  const tinygltf::PbrMetallicRoughness &pbr = m.pbrMetallicRoughness;
  GltfMaterial g;
  g.index = index;
  g.name = m.name;
  if (pbr.baseColorFactor.size() >= 3)
    g.base_color = {float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                    float(pbr.baseColorFactor[2])};
  g.metallic = float(pbr.metallicFactor);
  g.roughness = float(pbr.roughnessFactor);
  const int tex = pbr.baseColorTexture.index;
  if (tex >= 0 && size_t(tex) < model.textures.size()) {
    const int source = model.textures[size_t(tex)].source;
    if (source >= 0 && size_t(source) < model.images.size()) {
      const std::string &uri = model.images[size_t(source)].uri;
      // Embedded images (data: URIs, buffer views) have no file the texture loader could open.
      if (!uri.empty() && uri.rfind("data:", 0) != 0)
        g.base_color_texture = std::filesystem::absolute(dir / uri).lexically_normal().string();
    }
  }
  return g;
}

}  // namespace

Expected<GltfMesh> load_gltf_mesh(const std::filesystem::path &path, SourceLog *log) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Error{"No such file or directory"};
  if (std::filesystem::is_directory(path, ec)) return Error{"is a directory"};

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  loader.SetFsCallbacks(
      {&tinygltf::FileExists, &tinygltf::ExpandFilePath, &read_and_record, &tinygltf::WriteWholeFile, log});
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = path.extension() == ".glb" || path.extension() == ".GLB";
  const bool loaded = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                             : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  if (!loaded) return Error{"malformed glTF: " + one_line(err.empty() ? warn : err)};

  Collector c{model, {}};
  if (!model.nodes.empty()) {
    std::vector<int> roots;
    const int scene = model.defaultScene >= 0 ? model.defaultScene : (model.scenes.empty() ? -1 : 0);
    if (scene >= 0 && size_t(scene) < model.scenes.size()) {
      roots = model.scenes[size_t(scene)].nodes;
    } else {  // no scene: every node that is nobody's child
      std::vector<bool> child(model.nodes.size(), false);
      for (const tinygltf::Node &n : model.nodes)
        for (int k : n.children)
          if (k >= 0 && size_t(k) < child.size()) child[size_t(k)] = true;
      for (size_t i = 0; i < child.size(); ++i)
        if (!child[i]) roots.push_back(int(i));
    }
    for (int root : roots)
      if (Status s = c.add_node(root, Transform(), 0); !s) return s.error();
  } else {
    for (size_t i = 0; i < model.meshes.size(); ++i)
      if (Status s = c.add_mesh(int(i), Transform()); !s) return s.error();
  }
  if (c.out.mesh.indices.empty()) return Error{"the file has no triangles"};
  if (!c.all_normals) c.out.mesh.normals.clear();
  if (!c.all_uvs) c.out.mesh.uvs.clear();
  c.out.material = material_of(model, c.first_material, path.parent_path());
  return std::move(c.out);
}

}  // namespace nimbus
