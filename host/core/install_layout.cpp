#include "core/install_layout.hpp"

namespace nimbus {

std::filesystem::path installed_data_dir() {
  const std::filesystem::path data = NIMBUS_INSTALL_DATA_DIR;
  if (data.is_absolute()) return data;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return (exe.parent_path() / ".." / data).lexically_normal();
}

}  // namespace nimbus
