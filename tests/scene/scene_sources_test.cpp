// SceneDesc::sources: the parser records the scene and every file it reads for it (includes, meshes,
// subdivision cages; glTF buffers in scene_gltf_test.cpp), each once, with the hash of its bytes and a
// path that does not depend on the directory the renderer runs in.
#include <gtest/gtest.h>

#include "core/checksum.hpp"
#include "scene_test_support.hpp"

namespace nimbus::test {
namespace scene_sources_test {

const std::string kQuadObj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";
const std::string kCubeCage =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

std::vector<std::string> paths_of(const SceneDesc &scene) {
  std::vector<std::string> paths;
  for (const SourceFile &f : scene.sources) paths.push_back(f.path);
  return paths;
}

TEST(SceneSources, EveryFileReadIsRecordedOnceInTheOrderRead) {
  TempDir dir;
  const std::string main_text = R"(include: [parts/materials.yaml, parts/room.yaml, parts/materials.yaml]
materials:
  white: { type: diffuse }
objects:
  - { shape: mesh, file: parts/quad.obj, material: white }
  - { shape: subdivision, file: cage.obj, level: 1, material: white }
)";
  const std::string main = dir.write("scene/main.yaml", main_text);
  const std::string materials = "materials:\n  red: { type: diffuse, albedo: [0.8, 0.1, 0.1] }\n";
  dir.write("scene/parts/materials.yaml", materials);
  dir.write("scene/parts/room.yaml", "objects:\n  - { shape: mesh, file: quad.obj, material: red }\n");
  dir.write("scene/parts/quad.obj", kQuadObj);
  dir.write("scene/cage.obj", kCubeCage);

  const Expected<SceneDesc> scene = parse_scene_file(main);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  // The includes are read before any section; the mesh named twice (main file and room.yaml) once.
  EXPECT_EQ(paths_of(scene.value()),
            (std::vector<std::string>{"main.yaml", "parts/materials.yaml", "parts/room.yaml",
                                      "parts/quad.obj", "cage.obj"}));
  EXPECT_EQ(scene->sources[0].hash, content_hash(main_text));
  EXPECT_EQ(scene->sources[0].bytes, main_text.size());
  EXPECT_EQ(scene->sources[1].hash, content_hash(materials));
  EXPECT_EQ(scene->sources[3].hash, content_hash(kQuadObj));
  EXPECT_EQ(scene->sources[4].hash, content_hash(kCubeCage));
}

TEST(SceneSources, PathsDoNotDependOnTheWorkingDirectory) {
  TempDir dir;
  dir.write("scene/main.yaml", "include: inc.yaml\n");
  dir.write("scene/inc.yaml", "materials:\n  grey: { type: diffuse }\n");
  const std::filesystem::path before = std::filesystem::current_path();
  std::vector<std::vector<std::string>> seen;
  for (const std::filesystem::path &cwd : {dir.path(), dir.path() / "scene"}) {
    std::filesystem::current_path(cwd);
    const std::string relative = (std::filesystem::path(cwd == dir.path() ? "scene" : ".") / "main.yaml");
    const Expected<SceneDesc> scene = parse_scene_file(relative);
    std::filesystem::current_path(before);
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    seen.push_back(paths_of(scene.value()));
    seen.back().erase(seen.back().begin());  // the scene itself goes by the name it was given
  }
  EXPECT_EQ(seen[0], (std::vector<std::string>{"inc.yaml"}));
  EXPECT_EQ(seen[0], seen[1]);
}

TEST(SceneSources, AFileOutsideTheScenesDirectoryGoesByItsAbsolutePath) {
  TempDir dir;
  const std::string obj = dir.write("meshes/quad.obj", kQuadObj);
  const std::string main =
      dir.write("scene/main.yaml",
                "materials:\n  m: { type: diffuse }\nobjects:\n  - { shape: mesh, file: ../meshes/quad.obj, "
                "material: m }\n");
  const Expected<SceneDesc> scene = parse_scene_file(main);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->sources.size(), 2u);
  EXPECT_EQ(scene->sources[1].path, std::filesystem::path(obj).lexically_normal().string());
}

TEST(SceneSources, SceneTextComesFirstUnderItsDisplayName) {
  const std::string text = "render: { seed: 3 }\n";
  const Expected<SceneDesc> scene = parse_scene_string(text, "inline.yaml");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->sources.size(), 1u);
  EXPECT_EQ(scene->sources[0].path, "inline.yaml");
  EXPECT_EQ(scene->sources[0].hash, content_hash(text));
}

}  // namespace scene_sources_test
}  // namespace nimbus::test
