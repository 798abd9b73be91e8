// The subdivision cage reader: an OBJ cage read by the scene (`shape: subdivision`,
// scene/subdivision_section.cpp), checked there and refined by OpenSubdiv (scene/subdivision.hpp). The
// first input byte chooses the scheme (bit 7), the level (low 3 bits: 0..6, 7 for auto) and whether a
// crease follows in the next two bytes; the rest is cage.obj.
//
// The level is capped so the fuzzer explores cages rather than spending seconds on millions of
// triangles: a level whose triangles exceed kFuzzTriangles is lowered, unless it exceeds the host's own
// kMaxSubdivisionTriangles, which the host must refuse with an error (checked). `level: auto` is asked
// for only when the finest level is within the cap, since auto stops only at the host's limit.
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "scene/obj_loader.hpp"
#include "scene/subdivision.hpp"

namespace {

constexpr uint64_t kFuzzTriangles = uint64_t(1) << 16;

// The cage as the scene will read it, or nullopt when the scene must refuse it before counting.
std::optional<nimbus::SubdivisionCage> cage_of(const std::filesystem::path &obj) {
  nimbus::Expected<nimbus::PolygonMesh> polygons = nimbus::load_obj_polygons(obj, nullptr);
  if (!polygons) return std::nullopt;
  for (uint32_t n : polygons->face_sizes)
    if (n < 3) return std::nullopt;
  return nimbus::SubdivisionCage{
      std::move(polygons->positions), std::move(polygons->face_sizes), std::move(polygons->indices), {}};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  if (size < 3) return 0;
  const uint8_t control = data[0];
  const bool loop = control & 0x80, crease = control & 0x40;
  const std::filesystem::path obj = scratch_dir() / "cage.obj";
  write_file(obj, std::string_view(reinterpret_cast<const char *>(data + 3), size - 3));

  const nimbus::SubdivisionScheme scheme =
      loop ? nimbus::SubdivisionScheme::Loop : nimbus::SubdivisionScheme::CatmullClark;
  int level = control & 7;
  bool must_refuse = false;
  std::string level_text;
  const std::optional<nimbus::SubdivisionCage> cage = cage_of(obj);
  const auto triangles = [&](int l) {
    return cage ? nimbus::subdivision_triangle_count(*cage, scheme, l) : 0;
  };
  if (level == 7 && triangles(nimbus::kMaxSubdivisionLevel) <= kFuzzTriangles) {
    level_text = "auto";
  } else {
    level = std::min(level, nimbus::kMaxSubdivisionLevel);
    must_refuse = triangles(level) > nimbus::kMaxSubdivisionTriangles;
    while (!must_refuse && level > 0 && triangles(level) > kFuzzTriangles) --level;
    level_text = std::to_string(level);
  }

  std::string yaml = "objects:\n  - shape: subdivision\n    file: cage.obj\n    scheme: " +
                     std::string(loop ? "loop" : "catmull-clark") + "\n    level: " + level_text + "\n";
  if (crease)
    yaml += "    creases: [[" + std::to_string(data[1] % 16) + ", " + std::to_string(data[2] % 16) + ", " +
            std::to_string(data[2] / 16) + "]]\n";
  const std::optional<std::string> error = scene_error(yaml);
  require(error || !must_refuse, "the host accepted a level of " + std::to_string(triangles(level)) +
                                     " triangles, more than kMaxSubdivisionTriangles");
  return 0;
}
