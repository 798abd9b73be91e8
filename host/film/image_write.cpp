#include "film/image_write.hpp"

namespace nimbus {

Status write_oiio_image(const std::string &format, const std::string &file, const OIIO::ImageSpec &spec,
                        const void *pixels) {
  auto out = OIIO::ImageOutput::create(format);
  if (!out) return Error{"OpenImageIO has no '" + format + "' writer: " + OIIO::geterror()};
  // Every failure branch fetches the pending message: OIIO complains at exit about unread errors.
  if (!out->open(file, spec)) return Error{out->geterror()};
  if (!out->write_image(spec.format, pixels)) {
    const std::string reason = out->geterror();
    out->close();
    return Error{reason};
  }
  if (!out->close()) return Error{out->geterror()};
  return Ok{};
}

}  // namespace nimbus
