// CPU drawing helpers (see canvas.h).
#include "render/internal/canvas.h"

#include <algorithm>
#include <cmath>

namespace render::internal {

void BlendPixel(Image* image, int x, int y, const Rgb& rgb, float alpha) {
  if (x < 0 || y < 0 || x >= image->width || y >= image->height || alpha <= 0.0f) return;
  std::uint8_t* p = image->at(x, y);
  const float a = std::min(alpha, 1.0f);
  for (int c = 0; c < 3; ++c) {
    p[c] = static_cast<std::uint8_t>(std::lround(p[c] + a * (static_cast<float>(rgb[c]) - p[c])));
  }
  p[3] = static_cast<std::uint8_t>(std::lround(p[3] + a * (255.0f - p[3])));
}

void FillRect(Image* image, int x0, int y0, int x1, int y1, const Rgb& rgb) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image->width);
  y1 = std::min(y1, image->height);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = image->at(x, y);
      p[0] = rgb[0];
      p[1] = rgb[1];
      p[2] = rgb[2];
      p[3] = 255;
    }
  }
}

void StrokeRect(Image* image, int x0, int y0, int x1, int y1, const Rgb& rgb) {
  FillRect(image, x0, y0, x1, y0 + 1, rgb);
  FillRect(image, x0, y1 - 1, x1, y1, rgb);
  FillRect(image, x0, y0, x0 + 1, y1, rgb);
  FillRect(image, x1 - 1, y0, x1, y1, rgb);
}

void Blit(Image* image, const Image& src, int x, int y) {
  for (int sy = 0; sy < src.height; ++sy) {
    const int ty = y + sy;
    if (ty < 0 || ty >= image->height) continue;
    for (int sx = 0; sx < src.width; ++sx) {
      const int tx = x + sx;
      if (tx < 0 || tx >= image->width) continue;
      std::copy_n(src.at(sx, sy), 4, image->at(tx, ty));
    }
  }
}

}  // namespace render::internal
