// Bad textures and bad texture syntax: every error names the file, the reason and the place in the scene,
// in-process and through the CLI (which then exits non-zero and writes nothing).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "e2e/subprocess.hpp"
#include "materials/textured_materials.hpp"
#include "scene/scene_parser.hpp"
#include "texture_fixtures.hpp"
#include "world/world.hpp"

namespace nimbus {
namespace error_test {

using texture_test::has_substr;
using texture_test::ScratchDir;
using texture_test::texture_at;

std::string add_error(const std::string &path, TextureSet::Kind kind = TextureSet::Kind::Color,
                      int channels = 1) {
  TextureSet set;
  auto id = set.add(texture_at(path), kind, channels);
  EXPECT_FALSE(id.ok()) << path << " was accepted";
  return id.ok() ? std::string() : id.error().message;
}

TEST(TextureErrors, MissingFileNamesPathReasonAndSceneLocation) {
  ScratchDir dir;
  const std::string path = dir.file("nowhere.png");
  EXPECT_EQ(add_error(path), "scene.yaml:7:22: error: materials.m.albedo.texture: " + path +
                                 ": cannot read texture: No such file or directory");
}

TEST(TextureErrors, DirectoryIsNotATexture) {
  ScratchDir dir;
  EXPECT_TRUE(has_substr(add_error(dir.path().string()),
                         dir.path().string() + ": cannot read texture: is a directory"));
}

// A path that cannot be read as a file: a directory (unreadable as a file for every user, root too) and,
// for other users than root (who reads any file), a file without read permission.
TEST(TextureErrors, UnreadableFile) {
  ScratchDir dir;
  std::filesystem::create_directory(dir.file("folder.png"));
  const std::string folder = add_error(dir.file("folder.png"));
  EXPECT_TRUE(has_substr(folder, dir.file("folder.png") + ": cannot read texture: ")) << folder;
  EXPECT_EQ(folder.find('\n'), std::string::npos) << "one line: " << folder;
  std::printf("directory: %s\n", folder.c_str());
  if (::geteuid() == 0) return;  // root reads any file: the permission case cannot arise
  texture_test::write_png8(dir.file("locked.png"), 1, 1, 1, {7});
  ::chmod(dir.file("locked.png").c_str(), 0);
  EXPECT_TRUE(
      has_substr(add_error(dir.file("locked.png")), "locked.png: cannot read texture: Permission denied"));
}

TEST(TextureErrors, CorruptFileNamesTheReason) {
  ScratchDir dir;
  texture_test::write_text(dir.file("garbage.png"), "this is not a PNG file at all\n");
  const std::string message = add_error(dir.file("garbage.png"));
  EXPECT_TRUE(has_substr(message, dir.file("garbage.png") + ": cannot read texture: "));
  const std::string reason = message.substr(message.find("cannot read texture: ") + 21);
  EXPECT_GT(reason.size(), 5u) << message;
  EXPECT_EQ(reason.find('\n'), std::string::npos) << "one line: " << message;
  std::printf("corrupt file: %s\n", message.c_str());
}

// Headers that claim more than the file holds (an EXR attribute of 2 GiB, a PNG chunk of 1.7 GiB), a
// 100000-pixel side, or 55 bytes named .exr that OpenImageIO's WebP reader takes for a 7711x14457 image
// (~600 MB decoded): refused before the image library allocates what they claim (inputs the image
// reader's fuzz target found, tests/fuzz/image/regressions).
TEST(TextureErrors, HeadersClaimingHugeSizesAreRefusedBeforeAllocating) {
  const std::string dir = std::string(NIMBUS_SOURCE_DIR) + "/tests/fuzz/image/regressions/";
  for (const char *name : {"attribute_size_2gib.exr", "png_chunk_length_1.7gib.png", "huge_header.png",
                           "webp_bitstream_named_exr.exr"}) {
    const std::string message = add_error(dir + name);
    EXPECT_TRUE(has_substr(message, dir + name + ": cannot read texture: ")) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    std::printf("%s: %s\n", name, message.c_str());
  }
}

// A texture named .png must be a PNG (and .exr an OpenEXR file): OpenImageIO would try every other
// reader on it, and WebP's decodes the size a few stray bytes claim.
TEST(TextureErrors, FileNamedPngMustBePng) {
  ScratchDir dir;
  std::filesystem::copy_file(
      std::string(NIMBUS_SOURCE_DIR) + "/tests/fuzz/image/regressions/webp_bitstream_named_exr.exr",
      dir.file("webp.png"));
  const std::string message = add_error(dir.file("webp.png"));
  EXPECT_TRUE(has_substr(message, dir.file("webp.png") + ": cannot read texture: not a PNG file")) << message;
}

TEST(TextureErrors, TruncatedPixelDataIsFoundAtBuild) {
  // A valid header with half its pixel data: only reading the pixels finds the damage. (EXR rather than
  // PNG: libpng reports a truncated file by longjmp, which skips a destructor inside OIIO and leaks a
  // string, so the same test with a PNG passes but fails under LeakSanitizer.)
  ScratchDir dir;
  const std::string path = dir.file("truncated.exr");
  std::vector<float> px(128 * 128 * 3);
  for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % 251) / 251;
  texture_test::write_exr(path, 128, 128, 3, px);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
  const std::string message = add_error(path);
  EXPECT_TRUE(has_substr(message, path + ": cannot read texture: "));
  std::printf("truncated file: %s\n", message.c_str());
}

TEST(TextureErrors, NormalMapNeedsThreeChannels) {
  ScratchDir dir;
  texture_test::write_png8(dir.file("grey.png"), 1, 1, 1, {128});
  EXPECT_TRUE(has_substr(add_error(dir.file("grey.png"), TextureSet::Kind::Data, 3),
                         "grey.png: cannot read texture: needs 3 channels, the image has 1"));
}

// A scene file in a scratch directory with one material, m, written as `material_yaml`.
std::string write_scene(const ScratchDir &dir, const std::string &material_yaml) {
  const std::string path = dir.file("scene.yaml");
  texture_test::write_text(path,
                           "render: { resolution: [8, 8], iterations: 1 }\n"
                           "materials:\n"
                           "  m: " +
                               material_yaml +
                               "\n"
                               "objects:\n"
                               "  - { shape: rectangle, size: [1, 1], material: m }\n"
                               "lights:\n"
                               "  - { type: point, position: [0, 0, 2], intensity: 1 }\n");
  return path;
}

TEST(TextureErrors, SceneBuildNamesTheResolvedPathAndTheSceneLocation) {
  ScratchDir dir;
  const std::string scene = write_scene(dir, "{ type: diffuse, albedo: { texture: maps/missing.png } }");
  auto desc = parse_scene_file(scene);
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  EXPECT_EQ(desc.value().materials[0].albedo_texture.path, dir.file("maps/missing.png"));
  auto world = World::build(desc.value(), desc->render.filter);
  ASSERT_FALSE(world.ok());
  EXPECT_EQ(world.error().message,
            scene + ":3:42: error: materials.m.albedo.texture: " + dir.file("maps/missing.png") +
                ": cannot read texture: No such file or directory");
}

TEST(TextureErrors, CliExitsNonZeroNamingPathAndReason) {
  ScratchDir dir;
  texture_test::write_text(dir.file("bad.jpg"), "JFIF? no.");
  for (const auto &[material, file, reason] :
       {std::tuple<std::string, std::string, std::string>{
            "{ type: diffuse, albedo: { texture: missing.png } }", "missing.png",
            "No such file or directory"},
        {"{ type: conductor, metal: gold, roughness: { texture: bad.jpg } }", "bad.jpg", "not a JPEG file"},
        {"{ type: dielectric, normal_map: missing_n.png }", "missing_n.png", "No such file or directory"}}) {
    write_scene(dir, material);
    const e2e::ProcessResult r = e2e::run_process(
        {NIMBUS_CLI, "render", "scene.yaml", "-o", "out.exr", "--iterations", "1"}, dir.path());
    EXPECT_TRUE(r.exited && r.exit_code != 0) << r.describe();
    EXPECT_TRUE(has_substr(r.err, dir.file(file) + ": cannot read texture: ")) << r.err;
    EXPECT_TRUE(has_substr(r.err, reason)) << r.err;
    EXPECT_TRUE(has_substr(r.err, "scene.yaml:3:")) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr")));
  }
}

// Syntax: errors at file:line:column, as for every other key.
std::string parse_error(const std::string &material_yaml) {
  auto desc = parse_scene_string("materials:\n  m: " + material_yaml + "\n", "s.yaml");
  EXPECT_FALSE(desc.ok()) << material_yaml;
  return desc.ok() ? std::string() : desc.error().message;
}

TEST(TextureSyntax, Errors) {
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, albedo: [0.5, 0.5, 0.5], uv_scale: 2 }"),
                         "s.yaml:2:48: error: materials.m.uv_scale: needs a texture"));
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, albedo: { file: a.png } }"),
                         "s.yaml:2:33: error: materials.m.albedo.file: unknown key 'file'"));
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, albedo: { texture: '' } }"),
                         "s.yaml:2:42: error: materials.m.albedo.texture: must not be empty"));
  EXPECT_TRUE(has_substr(parse_error("{ type: conductor, metal: gold, albedo: { texture: a.png } }"),
                         "unknown key 'albedo' for a conductor"));
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, roughness: { texture: a.png } }"),
                         "unknown key 'roughness' for a diffuse material"));
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, albedo: { texture: a.png }, uv_scale: [1, 0] }"),
                         "materials.m.uv_scale[1]: must be > 0"));
  EXPECT_TRUE(has_substr(parse_error("{ type: diffuse, normal_map: [1, 2] }"), "materials.m.normal_map"));
}

TEST(TextureSyntax, FormsAndRelativePaths) {
  ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "sub");
  const std::string scene = dir.file("sub/scene.yaml");
  texture_test::write_text(scene,
                           "materials:\n"
                           "  a: { type: diffuse, albedo: { texture: ../wood.png }, normal_map: maps/n.png,"
                           " uv_scale: [2, 3] }\n"
                           "  b: { type: conductor, metal: gold, roughness: { texture: /abs/r.exr },"
                           " normal_map: { texture: n.exr }, uv_scale: 4 }\n"
                           "  c: { type: dielectric, roughness: 0.2 }\n");
  auto desc = parse_scene_file(scene);
  ASSERT_TRUE(desc.ok()) << desc.error().message;
  const MaterialDesc &a = desc.value().materials[0], &b = desc.value().materials[1],
                     &c = desc.value().materials[2];
  EXPECT_EQ(a.albedo_texture.path, dir.file("wood.png"));
  EXPECT_EQ(a.normal_map.path, dir.file("sub/maps/n.png"));
  EXPECT_EQ(a.normal_map.key, "materials.a.normal_map");
  EXPECT_EQ(a.normal_map.where.line, 2);
  EXPECT_EQ(a.uv_scale.x, 2);
  EXPECT_EQ(a.uv_scale.y, 3);
  EXPECT_TRUE(a.roughness_texture.empty());
  EXPECT_EQ(b.roughness_texture.path, "/abs/r.exr");
  EXPECT_EQ(b.normal_map.path, dir.file("sub/n.exr"));
  EXPECT_EQ(b.uv_scale.y, 4);
  EXPECT_FALSE(c.textured());
  EXPECT_EQ(c.roughness, 0.2f);
}

}  // namespace error_test
}  // namespace nimbus
