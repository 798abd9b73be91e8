// Reading lat-long environment images through the image I/O module (EXR, HDR, PNG, JPEG...).
#include "core/image_io.hpp"
#include "core/limits.hpp"
#include "lights/light_set.hpp"

namespace nimbus {

Expected<EnvironmentLight> load_environment_map(const std::string &path) {
  auto opened = open_image_file(path);
  if (!opened) {
    const std::string &reason = opened.error().message;
    return Error{path + ": cannot read environment map: " + (reason.empty() ? "cannot open" : reason)};
  }
  ImageFile &in = **opened;
  const ImageDesc &spec = in.desc();
  const int channels = int(spec.channels.size());
  if (spec.width < 2 || spec.height < 1 || channels < 1)
    return Error{path + ": environment map has no pixels"};
  if (std::string big = oversized_input_image(spec.width, spec.height); !big.empty())
    return Error{path + ": cannot read environment map: " + big};
  std::vector<float> pixels(size_t(spec.width) * spec.height * channels);
  if (!in.read_rows(spec.y, spec.y + spec.height, PixelType::Float, pixels.data()))
    return Error{path + ": cannot read environment map: " + in.error()};
  EnvironmentLight env;
  env.width = uint32_t(spec.width);
  env.height = uint32_t(spec.height);
  env.map.resize(size_t(env.width) * env.height);
  const int c = channels;
  for (size_t i = 0; i < env.map.size(); ++i) {
    const float *p = &pixels[i * c];
    Rgb v = c >= 3 ? Rgb{p[0], p[1], p[2]} : Rgb(p[0]);
    // Negative, NaN or infinite texels would poison the sampling distribution: clamp them to zero.
    for (int k = 0; k < 3; ++k)
      if (!(std::isfinite(v[k]) && v[k] > 0)) v[k] = 0;
    env.map[i] = v;
  }
  return env;
}

}  // namespace nimbus
