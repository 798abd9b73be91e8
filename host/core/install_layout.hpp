// Where an installed (or built) Nimbus keeps its data: <prefix>/bin/nimbus reads <prefix>/share/nimbus,
// found from the running executable, so a package or a relocated tarball needs no environment variable.
// The build tree mirrors the layout (build/bin, build/tests -> build/share/nimbus).
#pragma once

#include <filesystem>

namespace nimbus {

// <dir of the running executable>/../share/nimbus (NIMBUS_INSTALL_DATA_DIR; an absolute install data
// directory is taken as it is). Empty when the executable's path cannot be read.
std::filesystem::path installed_data_dir();

}  // namespace nimbus
