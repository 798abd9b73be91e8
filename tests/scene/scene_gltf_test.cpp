// glTF 2.0 meshes: a quad written by the test (JSON with a base64 buffer, or a .glb), node transforms, the
// material made from the glTF material when the object names none, and errors.
#include <gtest/gtest.h>

#include <cstring>

#include "core/checksum.hpp"
#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_gltf_test {

std::string base64(const std::vector<unsigned char> &bytes) {
  static const char *digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    out += digits[n >> 18 & 63];
    out += digits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

template <class T>
void put(std::vector<unsigned char> &bytes, std::initializer_list<T> values) {
  for (T v : values) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    bytes.insert(bytes.end(), b, b + sizeof(T));
  }
}

// The unit quad [0, 1]^2 at z = 0 facing +z, uvs = (x, y) in glTF's convention (v = 0 at the top):
// positions (48 bytes), normals (48), uvs (32), then 6 u16 indices (12).
std::vector<unsigned char> quad_buffer(uint16_t last_index = 3) {
  std::vector<unsigned char> b;
  put<float>(b, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  put<float>(b, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  put<float>(b, {0, 0, 1, 0, 1, 1, 0, 1});
  put<uint16_t>(b, {0, 1, 2, 0, 2, last_index});
  return b;
}

// A glTF document around the quad buffer. `node` is the JSON of the one node holding the mesh (may nest
// children), `material` the JSON of the one material (empty: none), `buffer_uri` where the bytes are.
std::string quad_gltf(const std::string &buffer_uri, const std::string &node = R"({ "mesh": 0 })",
                      const std::string &material = R"({ "name": "Painted", "pbrMetallicRoughness":
        { "baseColorFactor": [0.2, 0.4, 0.6, 1], "metallicFactor": 0, "roughnessFactor": 0.5 } })",
                      const std::string &extra = "") {
  return R"({ "asset": { "version": "2.0" }, "scene": 0, "scenes": [{ "nodes": [0] }],
  "nodes": [)" +
         node + R"(],
  "meshes": [{ "name": "quad", "primitives": [{ "attributes": { "POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2 },
      "indices": 3)" +
         (material.empty() ? "" : R"(, "material": 0)") + R"( }] }],
  "materials": [)" +
         material + R"(],
  "buffers": [{ "byteLength": 140, "uri": ")" +
         buffer_uri + R"(" }],
  "bufferViews": [{ "buffer": 0, "byteOffset": 0, "byteLength": 128 }, { "buffer": 0, "byteOffset": 128, "byteLength": 12 }],
  "accessors": [
    { "bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0] },
    { "bufferView": 0, "byteOffset": 48, "componentType": 5126, "count": 4, "type": "VEC3" },
    { "bufferView": 0, "byteOffset": 96, "componentType": 5126, "count": 4, "type": "VEC2" },
    { "bufferView": 1, "byteOffset": 0, "componentType": 5123, "count": 6, "type": "SCALAR" }]
  )" + extra +
         "}\n";
}

std::string embedded(const std::vector<unsigned char> &buffer = quad_buffer()) {
  return "data:application/octet-stream;base64," + base64(buffer);
}

std::string object_with(const std::string &file, const std::string &extra = "") {
  return "materials:\n  white: { type: diffuse }\nobjects:\n  - { shape: mesh, file: " + file + extra +
         " }\n";
}

TEST(SceneGltf, QuadWithNodeTransformNormalsAndUvs) {
  TempDir dir;
  const std::string file = dir.write(
      "quad.gltf", quad_gltf(embedded(), R"({ "mesh": 0, "translation": [0, 0, 1], "scale": [2, 2, 2] })"));
  const SceneDesc scene = parse_ok(object_with(file, ", material: white"));
  ASSERT_EQ(scene.shapes.size(), 1u);
  const MeshData &m = scene.shapes[0].mesh;
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  expect_vec(m.positions[2], {2, 2, 1});
  ASSERT_EQ(m.normals.size(), 4u);
  for (const Vec3f &n : m.normals) expect_vec(n, {0, 0, 1});
  ASSERT_EQ(m.uvs.size(), 4u);
  // v flipped to Nimbus's convention (v = 0 at the bottom of the image).
  EXPECT_FLOAT_EQ(m.uvs[1].x, 1);
  EXPECT_FLOAT_EQ(m.uvs[1].y, 1);
  EXPECT_FLOAT_EQ(m.uvs[3].y, 0);
  EXPECT_EQ(scene.materials.size(), 1u) << "an object with material: makes no glTF material";
}

TEST(SceneGltf, NodeHierarchyAndMatrices) {
  TempDir dir;
  // Parent: 90 degrees about +z (quaternion); child: column-major matrix translating by (1, 0, 0).
  const std::string nodes =
      R"({ "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476], "children": [1] },
         { "mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1] })";
  const std::string file = dir.write("quad.gltf", quad_gltf(embedded(), nodes));
  const MeshData m = parse_ok(object_with(file, ", material: white")).shapes.at(0).mesh;
  // Vertex (1, 0, 0) -> (2, 0, 0) by the child, -> (0, 2, 0) by the parent.
  expect_vec(m.positions[1], {0, 2, 0});
  expect_vec(m.normals[1], {0, 0, 1});
}

TEST(SceneGltf, MirroringNodeKeepsTheFrontFace) {
  TempDir dir;
  const std::string file =
      dir.write("quad.gltf", quad_gltf(embedded(), R"({ "mesh": 0, "scale": [-1, 1, 1] })"));
  const MeshData m = parse_ok(object_with(file, ", material: white")).shapes.at(0).mesh;
  const Vec3f n = cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                        m.positions[m.indices[2]] - m.positions[m.indices[0]]);
  EXPECT_GT(n.z, 0);
}

// The quad as a binary .glb: header, JSON chunk, BIN chunk.
std::vector<unsigned char> quad_glb() {
  std::string json = quad_gltf("");
  json.replace(json.find(R"(, "uri": "")"), std::strlen(R"(, "uri": "")"), "");
  while (json.size() % 4) json += ' ';
  std::vector<unsigned char> bin = quad_buffer();
  while (bin.size() % 4) bin.push_back(0);
  std::vector<unsigned char> glb;
  put<uint32_t>(glb, {0x46546C67, 2, uint32_t(12 + 8 + json.size() + 8 + bin.size())});
  put<uint32_t>(glb, {uint32_t(json.size()), 0x4E4F534A});
  glb.insert(glb.end(), json.begin(), json.end());
  put<uint32_t>(glb, {uint32_t(bin.size()), 0x004E4942});
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

TEST(SceneGltf, BinaryGlb) {
  TempDir dir;
  const std::vector<unsigned char> glb = quad_glb();
  const std::string file = dir.write("quad.glb", std::string(glb.begin(), glb.end()));
  const SceneDesc scene = parse_ok(object_with(file));
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_EQ(scene.shapes[0].mesh.indices.size(), 6u);
}

// A damaged .glb (cut short in its header, its JSON or its binary chunk; a wrong magic; a chunk length
// past the end of the file) is a load error naming the file, never a read past the data (ASan checks).
TEST(SceneGltfErrors, CorruptGlb) {
  TempDir dir;
  const std::vector<unsigned char> glb = quad_glb();
  const auto variant = [&](const std::string &name, std::vector<unsigned char> bytes) {
    const std::string file = dir.write(name, std::string(bytes.begin(), bytes.end()));
    EXPECT_TRUE(fails_at(object_with(file, ", material: white"), 4, 26, "objects[0].file",
                         "cannot load mesh '" + file + "'"))
        << name;
  };
  for (size_t keep : {size_t(6), size_t(16), size_t(40), glb.size() - 30, glb.size() - 1})
    variant("cut_" + std::to_string(keep) + ".glb",
            std::vector<unsigned char>(glb.begin(), glb.begin() + keep));
  std::vector<unsigned char> magic = glb;
  magic[0] = 'x';
  variant("magic.glb", magic);
  std::vector<unsigned char> json_length = glb;
  json_length[12] = 0xff, json_length[13] = 0xff;  // the JSON chunk's length, far past the file
  variant("json_length.glb", json_length);
  std::vector<unsigned char> total_length = glb;
  total_length[8] = 0xff, total_length[9] = 0xff, total_length[10] = 0xff;  // the header's total length
  variant("total_length.glb", total_length);
}

TEST(SceneGltf, DiffuseMaterialFromTheFile) {
  TempDir dir;
  const std::string file = dir.write("quad.gltf", quad_gltf(embedded()));
  const SceneDesc scene = parse_ok(object_with(file) + "  - { shape: mesh, file: " + file + " }\n");
  ASSERT_EQ(scene.materials.size(), 2u) << "one material, shared by both objects";
  const MaterialDesc &m = scene.materials[1];
  EXPECT_EQ(m.name, "Painted");
  EXPECT_EQ(m.type, MaterialType::Diffuse);
  expect_vec(m.albedo, {0.2f, 0.4f, 0.6f});
  EXPECT_TRUE(m.albedo_texture.empty());
  EXPECT_EQ(scene.shapes.at(0).material, 1u);
  EXPECT_EQ(scene.shapes.at(1).material, 1u);
}

TEST(SceneGltf, MetallicBecomesAConductor) {
  TempDir dir;
  const std::string file =
      dir.write("quad.gltf", quad_gltf(embedded(), R"({ "mesh": 0 })", R"({ "name": "white",
      "pbrMetallicRoughness": { "baseColorFactor": [1, 0.8, 0.3, 1], "metallicFactor": 0.9, "roughnessFactor": 0.25 } })"));
  const SceneDesc scene = parse_ok(object_with(file));
  ASSERT_EQ(scene.materials.size(), 2u);
  const MaterialDesc &m = scene.materials[1];
  EXPECT_EQ(m.name, "white-2") << "made unique against the scene's own 'white'";
  EXPECT_EQ(m.type, MaterialType::Conductor);
  EXPECT_TRUE(m.use_reflectance);
  expect_vec(m.reflectance, {1, 0.8f, 0.3f});
  EXPECT_FLOAT_EQ(m.roughness, 0.25f);
}

TEST(SceneGltf, BaseColorTextureBecomesTheAlbedoTexture) {
  TempDir dir;
  const std::string file = dir.write(
      "models/quad.gltf",
      quad_gltf(embedded(), R"({ "mesh": 0 })",
                R"({ "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 }, "metallicFactor": 0 } })",
                R"(, "textures": [{ "source": 0 }], "images": [{ "uri": "maps/albedo.png" }])"));
  const SceneDesc scene = parse_ok(object_with(file));
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[1].name, "quad.gltf#0") << "an unnamed glTF material";
  EXPECT_EQ(scene.materials[1].albedo_texture.path, (dir.path() / "models/maps/albedo.png").string());
  // Errors about the image (read when the scene is built) point at the file that brought it.
  EXPECT_EQ(scene.materials[1].albedo_texture.key, "objects[0].file");
  EXPECT_EQ(scene.materials[1].albedo_texture.where.line, 4);
}

TEST(SceneGltf, InstanceOfAGltfMesh) {
  TempDir dir;
  const std::string file = dir.write("quad.gltf", quad_gltf(embedded()));
  const SceneDesc scene =
      parse_ok("meshes:\n  quad: { file: " + file +
               " }\nobjects:\n  - { shape: instance, mesh: quad }\n"
               "  - { shape: instance, mesh: quad, transform: { translate: [5, 0, 0] } }\n");
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "Painted");
  ASSERT_EQ(scene.shapes.size(), 2u);
  expect_vec(scene.shapes[1].mesh.positions[0], {5, 0, 0});
}

// The file and the buffer tinygltf reads for it are both in the scene's sources (scene_sources_test.cpp).
TEST(SceneGltf, TheFileAndItsBufferAreRecordedAsRead) {
  TempDir dir;
  const std::vector<unsigned char> bytes = quad_buffer();
  const std::string bin = dir.write("models/quad.bin", std::string(bytes.begin(), bytes.end()));
  const std::string gltf = quad_gltf("quad.bin");
  const std::string file = dir.write("models/quad.gltf", gltf);
  const std::string main = dir.write("main.yaml", object_with("models/quad.gltf"));
  const Expected<SceneDesc> scene = parse_scene_file(main);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->sources.size(), 3u);
  EXPECT_EQ(scene->sources[1].path, "models/quad.gltf");
  EXPECT_EQ(scene->sources[1].hash, content_hash(gltf));
  EXPECT_EQ(scene->sources[2].path, "models/quad.bin");
  EXPECT_EQ(scene->sources[2].bytes, bytes.size());
}

TEST(SceneGltfErrors, NoMaterialAnywhere) {
  TempDir dir;
  const std::string file = dir.write("quad.gltf", quad_gltf(embedded(), R"({ "mesh": 0 })", ""));
  EXPECT_TRUE(fails_at(object_with(file), 4, 5, "objects[0].material", "missing required key 'material'"));
}

TEST(SceneGltfErrors, MalformedFiles) {
  TempDir dir;
  const std::string bad_json = dir.write("bad.gltf", "{ \"asset\": ");
  EXPECT_TRUE(fails_at(object_with(bad_json, ", material: white"), 4, 26, "objects[0].file",
                       "cannot load mesh '" + bad_json + "': malformed glTF"));
  const std::string bad_index = dir.write("index.gltf", quad_gltf(embedded(quad_buffer(7))));
  EXPECT_TRUE(fails_at(object_with(bad_index, ", material: white"), 4, 26, "objects[0].file",
                       "mesh 'quad': index 7 is out of range: the primitive has 4 vertices"));
  // Accessors that reach past the end of their buffer view (positions: 40 VEC3s in a 128-byte view), or
  // whose offset lies past it (uvs at byte 400): an error, never a read past the buffer.
  std::string long_accessor = quad_gltf(embedded());
  long_accessor.replace(long_accessor.find(R"("count": 4, "type": "VEC3", "min")"), 10, R"("count": 40)");
  const std::string past_end = dir.write("past_end.gltf", long_accessor);
  EXPECT_TRUE(fails_at(object_with(past_end, ", material: white"), 4, 26, "objects[0].file",
                       "cannot load mesh '" + past_end + "'"));
  std::string far_offset = quad_gltf(embedded());
  far_offset.replace(far_offset.find(R"("byteOffset": 96)"), 16, R"("byteOffset": 400)");
  const std::string offset_past = dir.write("offset_past.gltf", far_offset);
  EXPECT_TRUE(fails_at(object_with(offset_past, ", material: white"), 4, 26, "objects[0].file",
                       "cannot load mesh '" + offset_past + "'"));
  const std::string missing = (dir.path() / "none.glb").string();
  EXPECT_TRUE(fails_at(object_with(missing, ", material: white"), 4, 26, "objects[0].file",
                       "cannot load mesh '" + missing + "': No such file or directory"));
}

}  // namespace scene_gltf_test
}  // namespace nimbus::test
