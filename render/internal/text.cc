// stb_truetype text rendering (see text.h). libstb.so holds the implementation: no
// STB_TRUETYPE_IMPLEMENTATION here.
#include "render/internal/text.h"

#include <stb_truetype.h>

#include <algorithm>
#include <cmath>

#include "render/internal/canvas.h"
#include "base/file_read.h"
#include "render/offscreen_context.h"

namespace render::internal {

struct Font::Data {
  std::vector<unsigned char> bytes;
  stbtt_fontinfo info;
};

namespace {

// Moves the pen *x past code point cps[i]: its advance width, then the kerning towards the next
// code point (if any), both in pixels at `scale`.
void AdvancePen(const stbtt_fontinfo& info, float scale, const std::vector<int>& cps, size_t i,
                float* x) {
  int advance = 0, lsb = 0;
  stbtt_GetCodepointHMetrics(&info, cps[i], &advance, &lsb);
  *x += scale * static_cast<float>(advance);
  if (i + 1 < cps.size()) {
    *x += scale * static_cast<float>(stbtt_GetCodepointKernAdvance(&info, cps[i], cps[i + 1]));
  }
}

}  // namespace

std::vector<int> DecodeUtf8(std::string_view text) {
  std::vector<int> out;
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    int n = 0, cp = 0;
    if (c < 0x80) {
      cp = c;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3, cp = c & 0x07;
    } else {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    bool ok = true;
    for (int k = 1; k <= n; ++k) {
      if (i + k >= text.size() || (static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) {
        ok = false;
        break;
      }
      cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
    }
    out.push_back(ok ? cp : 0xFFFD);
    i += ok ? static_cast<size_t>(n) + 1 : 1;
  }
  return out;
}

Font::Font(const std::string& path) : data_(std::make_unique<Data>()) {
  const base::FileBytes file = base::ReadFileLimited(path, kMaxFontFileBytes);
  if (file.status == base::ReadStatus::kTooLarge) {
    throw EnvironmentError(path + ": font file is larger than " +
                           std::to_string(kMaxFontFileBytes) + " bytes (limit)");
  }
  if (file.status != base::ReadStatus::kOk) {
    throw EnvironmentError(path +
                           ": font not found (install the Debian package fonts-dejavu-core)");
  }
  const std::string& bytes = file.bytes;
  data_->bytes.assign(bytes.begin(), bytes.end());
  // stb_truetype reads the 12-byte header without checking the length.
  const int offset = bytes.size() < 12 ? -1 : stbtt_GetFontOffsetForIndex(data_->bytes.data(), 0);
  if (offset < 0 || !stbtt_InitFont(&data_->info, data_->bytes.data(), offset)) {
    throw EnvironmentError(path + ": not a TrueType font");
  }
}

Font::~Font() = default;

const Font& Font::Regular() {
  static const Font font("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
  return font;
}

const Font& Font::Bold() {
  static const Font font("/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf");
  return font;
}

float Font::Width(std::string_view text, float px) const {
  const float scale = stbtt_ScaleForPixelHeight(&data_->info, px);
  const std::vector<int> cps = DecodeUtf8(text);
  float x = 0.0f;
  for (size_t i = 0; i < cps.size(); ++i) {
    AdvancePen(data_->info, scale, cps, i, &x);
  }
  return x;
}

float Font::Ascent(float px) const {
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&data_->info, &ascent, &descent, &gap);
  return stbtt_ScaleForPixelHeight(&data_->info, px) * static_cast<float>(ascent);
}

float Font::Descent(float px) const {
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&data_->info, &ascent, &descent, &gap);
  return -stbtt_ScaleForPixelHeight(&data_->info, px) * static_cast<float>(descent);
}

float Font::EmSize(float px) const {
  return stbtt_ScaleForPixelHeight(&data_->info, px) /
         stbtt_ScaleForMappingEmToPixels(&data_->info, 1.0f);
}

void Font::Draw(Image* image, float x, float y, std::string_view text, float px,
                const std::array<std::uint8_t, 3>& rgb, Align align) const {
  if (align == Align::kCenter) x -= 0.5f * Width(text, px);
  if (align == Align::kRight) x -= Width(text, px);
  // Snap the start to whole pixels so a label looks the same wherever it is placed; glyphs keep
  // their sub-pixel advances within the string.
  x = std::round(x);
  y = std::round(y);
  const float scale = stbtt_ScaleForPixelHeight(&data_->info, px);
  const std::vector<int> cps = DecodeUtf8(text);
  std::vector<unsigned char> glyph;
  for (size_t i = 0; i < cps.size(); ++i) {
    const float shift = x - std::floor(x);
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    stbtt_GetCodepointBitmapBoxSubpixel(&data_->info, cps[i], scale, scale, shift, 0.0f, &x0, &y0,
                                        &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w > 0 && h > 0) {
      glyph.assign(static_cast<size_t>(w) * h, 0);
      stbtt_MakeCodepointBitmapSubpixel(&data_->info, glyph.data(), w, h, w, scale, scale, shift,
                                        0.0f, cps[i]);
      const int ox = static_cast<int>(std::floor(x)) + x0;
      const int oy = static_cast<int>(y) + y0;
      for (int gy = 0; gy < h; ++gy) {
        for (int gx = 0; gx < w; ++gx) {
          const unsigned char a = glyph[static_cast<size_t>(gy) * w + gx];
          if (a) BlendPixel(image, ox + gx, oy + gy, rgb, a / 255.0f);
        }
      }
    }
    AdvancePen(data_->info, scale, cps, i, &x);
  }
}

void Font::DrawVertical(Image* image, float cx, float cy, std::string_view text, float px,
                        const std::array<std::uint8_t, 3>& rgb) const {
  // Draw horizontally into a transparent scratch image, then rotate it into place.
  const int w = static_cast<int>(std::ceil(Width(text, px))) + 2;
  const int h = static_cast<int>(std::ceil(Ascent(px) + Descent(px))) + 2;
  Image scratch(w, h, 0, 0, 0, 0);
  Draw(&scratch, 1.0f, 1.0f + Ascent(px), text, px, {255, 255, 255}, Align::kLeft);
  // Pixel (sx, sy) of the scratch goes to (left + sy, top + (w - 1 - sx)).
  const int left = static_cast<int>(std::round(cx - 0.5f * h));
  const int top = static_cast<int>(std::round(cy - 0.5f * w));
  for (int sy = 0; sy < h; ++sy) {
    for (int sx = 0; sx < w; ++sx) {
      const std::uint8_t a = scratch.at(sx, sy)[0];
      if (a) BlendPixel(image, left + sy, top + (w - 1 - sx), rgb, a / 255.0f);
    }
  }
}

}  // namespace render::internal
