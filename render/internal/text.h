// Real text for figures: TrueType glyphs rasterised with stb_truetype (Debian's libstb) from the
// DejaVu fonts (package fonts-dejavu-core), alpha-blended into an Image. Deterministic (pure CPU,
// fixed font file).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "render/image.h"

namespace render::internal {

enum class Align { kLeft, kCenter, kRight };

// Largest font file read (bytes): 32 MiB (DejaVuSans.ttf is 0.7 MB).
inline constexpr std::size_t kMaxFontFileBytes = std::size_t{32} << 20;

class Font {
 public:
  // Loads a TrueType file. Throws render::EnvironmentError naming the path when it is missing,
  // larger than kMaxFontFileBytes (`/dev/zero` is refused after that many bytes) or not a font.
  explicit Font(const std::string& path);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  // DejaVuSans.ttf / DejaVuSans-Bold.ttf from /usr/share/fonts/truetype/dejavu (loaded once).
  static const Font& Regular();
  static const Font& Bold();

  // Advance width in pixels of UTF-8 `text` at pixel height `px` (ascent - descent = px).
  float Width(std::string_view text, float px) const;
  float Ascent(float px) const;   // > 0, pixels above the baseline
  float Descent(float px) const;  // > 0, pixels below the baseline
  // Em size (the font size of SVG and cairo) of text `px` high: px · unitsPerEm / (ascent −
  // descent).
  float EmSize(float px) const;

  // Draws `text` with its baseline at row y; x is the left end, centre or right end per `align`.
  void Draw(Image* image, float x, float y, std::string_view text, float px,
            const std::array<std::uint8_t, 3>& rgb, Align align = Align::kLeft) const;
  // Draws `text` rotated 90 degrees counter-clockwise (reading upwards), centred at (cx, cy).
  void DrawVertical(Image* image, float cx, float cy, std::string_view text, float px,
                    const std::array<std::uint8_t, 3>& rgb) const;

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

// Decodes UTF-8 into code points (invalid bytes become U+FFFD).
std::vector<int> DecodeUtf8(std::string_view text);

}  // namespace render::internal
