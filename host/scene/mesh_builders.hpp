// Triangle meshes for the built-in flat shapes, moving meshes into world space and cutting parts out of
// them. Pure geometry, no YAML.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/transform.hpp"
#include "scene/scene_desc.hpp"

namespace nimbus {

// w x h rectangle centred at the origin in the xy plane; 2 triangles whose geometric normal
// cross(p1 - p0, p2 - p0) is +z; uvs span [0, 1]^2.
MeshData rectangle_mesh(float width, float height);

// Axis-aligned box of the given size centred at the origin; 12 triangles (4 vertices per face, so each face
// is flat and has its own uvs) whose geometric normals point outward.
MeshData box_mesh(const Vec3f &size);

// Positions by the transform, normals by its inverse transpose (renormalised). A mirroring transform
// (negative determinant) would turn every triangle's geometric normal inward, so the winding is reversed
// to keep "outward stays outward".
void transform_mesh(MeshData &mesh, const Transform &transform);

// Triangles `triangles` of `mesh` (triangle i: indices 3i .. 3i + 2) as a mesh of their own, with only
// the vertices they use and those vertices' normals, uvs and deformation steps; order kept.
MeshData submesh(const MeshData &mesh, const std::vector<uint32_t> &triangles);

// The uniform scale factor if the linear part is a scaled rotation (possibly mirrored), else nothing.
// Spheres and disks stay spheres and disks only under such similarities.
std::optional<float> similarity_scale(const Transform &transform);

}  // namespace nimbus
