// The checkpoint reader (film/checkpoint.hpp): the input is render.exr.ckpt, peeked at, then restored
// into a 4x3 film with beauty and albedo, as a render would resume. So that the fuzzer reaches the sums
// and plugin states rather than stopping at a mismatch, the render continued is the one the header
// describes. Every refusal must be one line naming the path; a refused restore must leave the film
// untouched (checked on its iteration count).
#include <cstdint>
#include <string>

#include "film/checkpoint.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using namespace nimbus::fuzz;
  const std::string path = (scratch_dir() / "render.exr.ckpt").string();
  write_file(path, std::string_view(reinterpret_cast<const char *>(data), size));

  const nimbus::Expected<nimbus::CheckpointInfo> peeked = nimbus::peek_checkpoint(path);
  if (!peeked) check_error_line(peeked.error().message, path);
  nimbus::CheckpointInfo info = peeked ? *peeked : nimbus::CheckpointInfo{};

  nimbus::Film film(4, 3);
  film.register_element("albedo", 3, nimbus::Film::kAverage);
  film.request("albedo");
  require(film.allocate().ok(), "cannot allocate the film");
  constexpr uint64_t kUntouched = 12345;
  film.set_iterations(kUntouched);
  const nimbus::Status read = nimbus::read_checkpoint(film, path, info);
  if (!read) {
    check_error_line(read.error().message, path);
    require(film.iterations() == kUntouched, "a refused checkpoint changed the film");
  }
  return 0;
}
