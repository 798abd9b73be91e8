// Wavefront MTL files, the materials an OBJ file names with `mtllib`. Only the statements that Nimbus maps
// to its materials (scene/obj_material.cpp) are read, and whether each was written is kept: a missing `Ns`
// means a smooth surface, not the value a default would give. Every other statement is only named, so that
// the scene can say in one warning what it ignores.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nimbus/cpp/math.hpp>
#include "core/expected.hpp"

namespace nimbus {

struct MtlMaterial {
  std::string name;
  std::optional<Rgb> kd, ks, ke, tf;   // `Kd`, `Ks`, `Ke`, `Tf`: r g b, or one number for grey
  std::optional<float> ns, ni, d, tr;  // `Ns`, `Ni`, `d`, `Tr`
  std::optional<int> illum;
  std::string map_kd;  // `map_Kd`: absolute path, resolved against the .mtl file's directory; empty = none
};

struct MtlFile {
  std::vector<MtlMaterial> materials;  // in the file's order; names unique
  // The statements read but not mapped, each once in the order first seen: keywords ("map_Bump", "Pr"),
  // and forms of mapped ones Nimbus does not support ("Kd spectral", "map_Kd -s"). `Ka`, which has no
  // physical meaning for Nimbus, is dropped without being named.
  std::vector<std::string> ignored;
};

// The statements of the .mtl file at `path` whose bytes are `text`. A malformed value of a mapped statement
// fails with "PATH:LINE: KEYWORD: REASON" (one line; bytes from the file shown safely), as do a `newmtl`
// without a name, a name defined twice, and a mapped statement before the first `newmtl`.
Expected<MtlFile> parse_mtl(std::string_view text, const std::filesystem::path &path);

}  // namespace nimbus
