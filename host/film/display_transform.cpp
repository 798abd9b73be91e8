#include "film/display_transform.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/install_layout.hpp"
#include "film/film.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace nimbus {

Status apply_display_transform(const std::string &config_path, std::vector<float> &rgb, uint32_t width,
                               uint32_t height) {
  const auto fail = [&](const std::string &reason) {
    return Error{"OCIO config '" + config_path + "': " + reason};
  };
  std::error_code ec;
  if (config_path.empty()) return Error{"no OCIO config given (set NIMBUS_OCIO_CONFIG)"};
  if (!std::filesystem::is_regular_file(config_path, ec)) return fail("no such file");
  if (rgb.empty()) return Ok{};
  try {
    const OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(config_path.c_str());
    config->validate();
    const char *display = config->getDefaultDisplay();
    if (!display || !*display) return fail("defines no display");
    const char *view = config->getDefaultView(display);
    if (!view || !*view) return fail(std::string("display '") + display + "' has no view");
    const OCIO::ConstProcessorRcPtr processor =
        config->getProcessor(OCIO::ROLE_SCENE_LINEAR, display, view, OCIO::TRANSFORM_DIR_FORWARD);
    OCIO::PackedImageDesc image(rgb.data(), width, height, 3);
    processor->getDefaultCPUProcessor()->apply(image);
  } catch (const OCIO::Exception &e) {
    return fail(e.what());
  }
  return Ok{};
}

namespace {

std::string existing_or_empty(const std::filesystem::path &p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) ? p.lexically_normal().string() : std::string();
}

}  // namespace

std::string default_ocio_config_path() {
  // An explicit choice wins even when it names a missing file: the error then names what the user set.
  if (const char *env = std::getenv("NIMBUS_OCIO_CONFIG"); env && *env) return env;
  if (const std::filesystem::path share = installed_data_dir(); !share.empty())
    if (std::string found = existing_or_empty(share / "ocio" / "config.ocio"); !found.empty()) return found;
  return NIMBUS_OCIO_SOURCE_CONFIG;
}

}  // namespace nimbus
