// Replacing an output file without ever exposing a truncated one.
#pragma once

#include <functional>
#include <string>

#include "core/expected.hpp"

namespace nimbus {

// Calls `write(tmp_path)` with `<path>.tmp-<pid>` (same directory, so the rename cannot cross file
// systems), flushes it to disk and renames it over `path`: readers, and a crash at any point, see the
// old file or the complete new one. On failure the temporary file is removed and the error reads
// "cannot write '<path>': <reason>", where the reason is what `write` returned.
Status write_atomically(const std::string &path,
                        const std::function<Status(const std::string &tmp_path)> &write);

}  // namespace nimbus
