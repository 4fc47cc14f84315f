// PGM images (core/map/pgm.h), the image half of a map_server map: any bytes, read strictly and
// leniently. An image that decodes has width * height pixels, and writing it (P5 and P2) and
// reading that back gives the same image.
#include "core/map/pgm.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {
namespace {

void CheckImage(const core::GrayImage& image) {
  FUZZ_REQUIRE(image.width > 0 && image.height > 0);
  FUZZ_REQUIRE(image.pixels.size() == size_t(image.width) * size_t(image.height));
  for (const core::PgmFormat format : {core::PgmFormat::kBinary, core::PgmFormat::kAscii}) {
    core::PgmReadOptions strict;
    strict.allow_trailing_data = false;
    auto back = core::DecodePgm(core::EncodePgm(image, format), strict);
    FUZZ_REQUIRE(back.ok() && back->width == image.width && back->height == image.height &&
                 back->pixels == image.pixels);
  }
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  core::PgmReadOptions strict;
  strict.allow_trailing_data = false;
  auto lenient = core::DecodePgm(bytes);
  auto exact = core::DecodePgm(bytes, strict);
  if (exact.ok()) FUZZ_REQUIRE(lenient.ok() && lenient->pixels == exact->pixels);
  if (lenient.ok()) fuzz::CheckImage(*lenient);
  return 0;
}
