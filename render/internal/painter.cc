// Raster, SVG and PDF painters (see painter.h).
#include "render/internal/painter.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cstdio>
#include <locale>
#include <sstream>
#include <stdexcept>

#include "render/figure.h"

namespace render::internal {
namespace {

// An output stream that writes "0.5" whatever the global C++ locale.
std::ostringstream ClassicStream() {
  std::ostringstream out;
  out.imbue(std::locale::classic());
  return out;
}

class RasterPainter : public Painter {
 public:
  explicit RasterPainter(Image* image) : image_(image) {}
  void Fill(int x0, int y0, int x1, int y1, const Rgb& rgb, const char*) override {
    FillRect(image_, x0, y0, x1, y1, rgb);
  }
  void Stroke(int x0, int y0, int x1, int y1, const Rgb& rgb, int width) override {
    for (int k = 0; k < width; ++k) StrokeRect(image_, x0 + k, y0 + k, x1 - k, y1 - k, rgb);
  }
  void Text(float x, float y, std::string_view text, float px, const Rgb& rgb, Align align,
            bool bold) override {
    (bold ? Font::Bold() : Font::Regular()).Draw(image_, x, y, text, px, rgb, align);
  }
  void VerticalText(float cx, float cy, std::string_view text, float px, const Rgb& rgb) override {
    Font::Regular().DrawVertical(image_, cx, cy, text, px, rgb);
  }

 private:
  Image* image_;
};

std::string Hex(const Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

// Font size (em) of text `px` high: SVG font-size and cairo font size.
double EmSize(float px, bool bold) { return (bold ? Font::Bold() : Font::Regular()).EmSize(px); }

class SvgPainter : public VectorPainter {
 public:
  SvgPainter(int width, int height) {
    out_ << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << width
         << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height << "\">\n"
         << "<rect width=\"" << width << "\" height=\"" << height << "\" fill=\"#ffffff\"/>\n"
         << "<g font-family=\"DejaVu Sans, Verdana, sans-serif\" shape-rendering=\"crispEdges\">\n";
  }
  void Fill(int x0, int y0, int x1, int y1, const Rgb& rgb, const char* tag) override {
    out_ << "<rect";
    if (tag) out_ << " class=\"" << tag << "\"";
    out_ << " x=\"" << x0 << "\" y=\"" << y0 << "\" width=\"" << x1 - x0 << "\" height=\""
         << y1 - y0 << "\" fill=\"" << Hex(rgb) << "\"/>\n";
  }
  void Stroke(int x0, int y0, int x1, int y1, const Rgb& rgb, int width) override {
    const double h = 0.5 * width;
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
                  "stroke=\"%s\" stroke-width=\"%d\"/>\n",
                  x0 + h, y0 + h, x1 - x0 - 2 * h, y1 - y0 - 2 * h, Hex(rgb).c_str(), width);
    out_ << buf;
  }
  void Text(float x, float y, std::string_view text, float px, const Rgb& rgb, Align align,
            bool bold) override {
    const char* anchor = align == Align::kLeft     ? "start"
                         : align == Align::kCenter ? "middle"
                                                   : "end";
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "<text x=\"%.2f\" y=\"%.2f\" font-size=\"%.2f\" text-anchor=\"%s\" fill=\"%s\"%s>", x, y,
        EmSize(px, bold), anchor, Hex(rgb).c_str(), bold ? " font-weight=\"bold\"" : "");
    out_ << buf << XmlEscape(text) << "</text>\n";
  }
  void VerticalText(float cx, float cy, std::string_view text, float px, const Rgb& rgb) override {
    const Font& f = Font::Regular();
    const float baseline = 0.5f * (f.Ascent(px) - f.Descent(px));
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "<text transform=\"translate(%.2f %.2f) rotate(-90)\" x=\"0\" y=\"%.2f\" "
                  "font-size=\"%.2f\" text-anchor=\"middle\" fill=\"%s\">",
                  cx, cy, baseline, EmSize(px, false), Hex(rgb).c_str());
    out_ << buf << XmlEscape(text) << "</text>\n";
  }
  std::string Finish() override { return out_.str() + "</g>\n</svg>\n"; }

 private:
  std::ostringstream out_ = ClassicStream();
};

cairo_status_t AppendPdfBytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

class PdfPainter : public VectorPainter {
 public:
  PdfPainter(int width, int height) {
    surface_ = cairo_pdf_surface_create_for_stream(AppendPdfBytes, &bytes_, width, height);
    cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_CREATE_DATE,
                                   "2000-01-01T00:00:00Z");
    cairo_pdf_surface_set_metadata(surface_, CAIRO_PDF_METADATA_CREATOR, "topoplan");
    cr_ = cairo_create(surface_);
    cairo_set_antialias(cr_, CAIRO_ANTIALIAS_NONE);  // abutting cells without hairline seams
    cairo_set_source_rgb(cr_, 1, 1, 1);
    cairo_paint(cr_);
  }
  ~PdfPainter() override {
    if (cr_) cairo_destroy(cr_);
    if (surface_) cairo_surface_destroy(surface_);
  }
  void Fill(int x0, int y0, int x1, int y1, const Rgb& rgb, const char*) override {
    SetColor(rgb);
    cairo_rectangle(cr_, x0, y0, x1 - x0, y1 - y0);
    cairo_fill(cr_);
  }
  void Stroke(int x0, int y0, int x1, int y1, const Rgb& rgb, int width) override {
    SetColor(rgb);
    const double h = 0.5 * width;
    cairo_set_line_width(cr_, width);
    cairo_rectangle(cr_, x0 + h, y0 + h, x1 - x0 - 2 * h, y1 - y0 - 2 * h);
    cairo_stroke(cr_);
  }
  void Text(float x, float y, std::string_view text, float px, const Rgb& rgb, Align align,
            bool bold) override {
    const std::string s(text);
    const float w = (bold ? Font::Bold() : Font::Regular()).Width(text, px);
    if (align == Align::kCenter) x -= 0.5f * w;
    if (align == Align::kRight) x -= w;
    Select(px, bold);
    SetColor(rgb);
    cairo_move_to(cr_, x, y);
    cairo_show_text(cr_, s.c_str());
  }
  void VerticalText(float cx, float cy, std::string_view text, float px, const Rgb& rgb) override {
    const Font& f = Font::Regular();
    const std::string s(text);
    cairo_save(cr_);
    cairo_translate(cr_, cx, cy);
    cairo_rotate(cr_, -1.5707963267948966);
    Select(px, false);
    SetColor(rgb);
    cairo_move_to(cr_, -0.5 * f.Width(text, px), 0.5 * (f.Ascent(px) - f.Descent(px)));
    cairo_show_text(cr_, s.c_str());
    cairo_restore(cr_);
  }
  std::string Finish() override {
    cairo_destroy(cr_);
    cr_ = nullptr;
    cairo_surface_finish(surface_);
    const cairo_status_t status = cairo_surface_status(surface_);
    cairo_surface_destroy(surface_);
    surface_ = nullptr;
    if (status != CAIRO_STATUS_SUCCESS) {
      throw std::runtime_error(std::string("PDF output: ") + cairo_status_to_string(status));
    }
    return bytes_;
  }

 private:
  void SetColor(const Rgb& c) {
    cairo_set_source_rgb(cr_, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
  }
  void Select(float px, bool bold) {
    cairo_select_font_face(cr_, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, EmSize(px, bold));
  }

  std::string bytes_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

}  // namespace

std::unique_ptr<Painter> MakeRasterPainter(Image* image) {
  return std::make_unique<RasterPainter>(image);
}
std::unique_ptr<VectorPainter> MakeSvgPainter(int width, int height) {
  return std::make_unique<SvgPainter>(width, height);
}
std::unique_ptr<VectorPainter> MakePdfPainter(int width, int height) {
  return std::make_unique<PdfPainter>(width, height);
}

}  // namespace render::internal
