// Minimal CPU drawing into an Image for figures (heatmaps, colour bars, contact sheets): filled
// rectangles on whole pixels, alpha-blended pixels, and 1-pixel axis-aligned lines.
#pragma once

#include <array>
#include <cstdint>

#include "render/image.h"

namespace render::internal {

using Rgb = std::array<std::uint8_t, 3>;

// Blends colour `rgb` with coverage `alpha` (0..1) over pixel (x, y); ignores pixels outside.
void BlendPixel(Image* image, int x, int y, const Rgb& rgb, float alpha);
// Fills the half-open pixel rectangle [x0, x1) x [y0, y1) (clipped to the image).
void FillRect(Image* image, int x0, int y0, int x1, int y1, const Rgb& rgb);
// 1-pixel outline of the rectangle [x0, x1) x [y0, y1).
void StrokeRect(Image* image, int x0, int y0, int x1, int y1, const Rgb& rgb);
// Copies `src` with its top-left corner at (x, y) (clipped).
void Blit(Image* image, const Image& src, int x, int y);

}  // namespace render::internal
