// Subdivision surfaces through OpenSubdiv: a polygon cage refined once, at load time, into triangles.
// Pure geometry, no YAML (subdivision_section.cpp reads the scene keys).
#pragma once

#include <cstdint>
#include <vector>

#include "core/expected.hpp"
#include "core/transform.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

struct SubdivisionCage {
  std::vector<Vec3f> positions;
  std::vector<uint32_t> face_sizes;  // vertices per face, >= 3
  std::vector<uint32_t> indices;     // the faces' vertices one after the other, counter-clockwise
  struct Crease {
    uint32_t v0, v1;  // the two ends of a cage edge
    float sharpness;  // OpenSubdiv's: 0 smooth ... 10 (kInfinitelySharp) infinitely sharp
  };
  std::vector<Crease> creases;
};

enum class SubdivisionScheme { CatmullClark, Loop };

inline constexpr int kMaxSubdivisionLevel = 6;
inline constexpr float kInfinitelySharp = 10;  // Sdc::Crease::SHARPNESS_INFINITE
// Beyond this a level is refused (explicit) or lowered (auto): about 1 GB of MeshData.
inline constexpr uint64_t kMaxSubdivisionTriangles = uint64_t(1) << 25;

// Triangles subdivide() produces at `level`: Catmull-Clark turns an n-gon into n quads at level 1 and
// every quad into 4 per further level (two triangles each; level 0 fans the cage's polygons); Loop turns
// every triangle into 4 per level.
uint64_t subdivision_triangle_count(const SubdivisionCage &cage, SubdivisionScheme scheme, int level);

// Uniform refinement to `level` (0..kMaxSubdivisionLevel), then every vertex of the finest level moved to
// its limit position with the limit normal (Far::PrimvarRefiner::Limit), so that even a coarse level lies
// on the true surface and shades smoothly. The one exception is Catmull-Clark at level 0 on a cage that is
// not all quads, where limit masks do not apply: there the cage itself is output with smooth
// (area-weighted) normals. Boundaries are sharp at edges and corners (VTX_BOUNDARY_EDGE_AND_CORNER). The
// cage is expected valid (indices in range, faces of >= 3 distinct vertices; Loop: all triangles); what
// OpenSubdiv still rejects comes back as an Error with its reason.
Expected<MeshData> subdivide(const SubdivisionCage &cage, SubdivisionScheme scheme, int level);

// `level: auto`: the smallest level at which no refined edge projects to much more than one pixel. Each
// cage edge (through `to_world`) spans length * f / d pixels, with f = width / (2 tan(fov / 2)) the focal
// length in pixels and d its closest distance to the camera (foreshortening ignored: an upper bound);
// refinement halves edges, so the level is ceil(log2(longest)), clamped to [0, kMaxSubdivisionLevel].
int auto_subdivision_level(const SubdivisionCage &cage, const Transform &to_world, const CameraDesc &camera,
                           uint32_t width);

}  // namespace nimbus
