// Fuzz targets of the files read by render/: PNG.
#include <stdexcept>
#include <string>

#include "render/image.h"
#include "tests/fuzz/fuzz_targets.h"

namespace topoplan_fuzz {

int Png(const uint8_t* data, size_t size) {
  try {
    const render::Image image = render::DecodePng(Text(data, size), "fuzz.png");
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4) {
      throw std::logic_error("DecodePng returned an image outside its contract");
    }
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

}  // namespace topoplan_fuzz
