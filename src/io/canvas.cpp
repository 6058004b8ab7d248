#include "canvas.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/io/bitmap_text.hpp"
#include "bssrdf/io/png_image.hpp"

namespace bssrdf {
namespace {

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(double width, double height) {
    svg_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
         << "\" font-family=\"sans-serif\" font-size=\"10\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& fill, bool outline) override {
    svg_ << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << w << "\" height=\"" << h << "\" fill=\"" << fill
         << "\"" << (outline ? " stroke=\"white\"" : "") << "/>\n";
  }
  void disc(double cx, double cy, double r, const std::string& fill, double opacity) override {
    svg_ << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << r << "\" fill=\"" << fill << "\" fill-opacity=\""
         << opacity << "\"/>\n";
  }
  void text(double x, double y, const std::string& s, double size, Anchor anchor) override {
    svg_ << "<text x=\"" << x << "\" y=\"" << y << "\" font-size=\"" << size << "\""
         << (anchor == Anchor::middle ? " text-anchor=\"middle\""
             : anchor == Anchor::end  ? " text-anchor=\"end\""
                                      : "")
         << ">" << escaped(s) << "</text>\n";
  }
  std::string encode() const override { return svg_.str() + "</svg>\n"; }

 private:
  std::ostringstream svg_;
};

std::array<std::uint8_t, 3> parse_colour(const std::string& hex) {
  const auto byte = [&](std::size_t at) {
    return static_cast<std::uint8_t>(std::stoi(hex.substr(at, 2), nullptr, 16));
  };
  return {byte(1), byte(3), byte(5)};
}

class PngCanvas : public Canvas {
 public:
  static constexpr int kScale = 2;  // pixels a unit
  PngCanvas(double width, double height)
      : image_(static_cast<int>(std::ceil(width * kScale)), static_cast<int>(std::ceil(height * kScale))) {
    std::fill(image_.pixels.begin(), image_.pixels.end(), std::uint8_t{255});
  }
  void rect(double x, double y, double w, double h, const std::string& fill, bool outline) override {
    const auto colour = parse_colour(fill);
    const int inset = outline ? 1 : 0;
    const int x0 = px(x) + inset, y0 = px(y) + inset, x1 = px(x + w) - inset, y1 = px(y + h) - inset;
    for (int j = std::max(0, y0); j < std::min(image_.height, y1); ++j)
      for (int i = std::max(0, x0); i < std::min(image_.width, x1); ++i)
        std::copy(colour.begin(), colour.end(), image_.at(i, j));
  }
  void disc(double cx, double cy, double r, const std::string& fill, double opacity) override {
    const auto colour = parse_colour(fill);
    const double R = r * kScale, X = cx * kScale, Y = cy * kScale;
    for (int j = static_cast<int>(std::floor(Y - R)); j <= static_cast<int>(std::ceil(Y + R)); ++j)
      for (int i = static_cast<int>(std::floor(X - R)); i <= static_cast<int>(std::ceil(X + R)); ++i) {
        if (i < 0 || j < 0 || i >= image_.width || j >= image_.height) continue;
        if ((i + 0.5 - X) * (i + 0.5 - X) + (j + 0.5 - Y) * (j + 0.5 - Y) > R * R) continue;
        auto* p = image_.at(i, j);
        for (int c = 0; c < 3; ++c)
          p[c] = static_cast<std::uint8_t>(std::lround((1 - opacity) * p[c] + opacity * colour[c]));
      }
  }
  void text(double x, double y, const std::string& s, double size, Anchor anchor) override {
    const int scale = size <= 9 ? 1 : 2;
    const int w = text_width(s, scale);
    int left = px(x);
    if (anchor == Anchor::middle) left -= w / 2;
    if (anchor == Anchor::end) left -= w;
    draw_text(image_, left, px(y) - text_height(scale), s, {0, 0, 0}, scale);
  }
  std::string encode() const override { return encode_png(image_); }

 private:
  RgbImage image_;
  static int px(double v) { return static_cast<int>(std::lround(v * kScale)); }
};

}  // namespace

std::unique_ptr<Canvas> make_canvas(const std::string& extension, double width, double height) {
  if (extension == ".svg") return std::make_unique<SvgCanvas>(width, height);
  if (extension == ".png") return std::make_unique<PngCanvas>(width, height);
  throw InvalidInput("--map", "'" + extension + "'", "a file ending in .svg or .png");
}

}  // namespace bssrdf
