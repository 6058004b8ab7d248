// A minimal drawing surface for charts drawn once and written as SVG or PNG: filled rectangles,
// discs and text, in SVG user units (text at its baseline). The PNG form rasterises at `scale`
// pixels a unit with the built-in 5 x 7 font (io/bitmap_text.hpp): text of size <= 9 at one font
// pixel a unit-pixel, larger at two.
//
//   auto canvas = make_canvas(".png", 400, 300);
//   canvas->rect(10, 10, 20, 20, "#1f77b4");
//   canvas->text(10, 50, "albedo", 10, Anchor::middle);
//   std::string bytes = canvas->encode();
#pragma once

#include <memory>
#include <string>

namespace bssrdf {

enum class Anchor { start, middle, end };

class Canvas {
 public:
  virtual ~Canvas() = default;
  // fill: "#rrggbb"; outline: a 1-unit white border (cells of a heatmap).
  virtual void rect(double x, double y, double w, double h, const std::string& fill, bool outline = false) = 0;
  virtual void disc(double cx, double cy, double r, const std::string& fill, double opacity) = 0;
  virtual void text(double x, double y, const std::string& s, double size, Anchor anchor = Anchor::start) = 0;
  virtual std::string encode() const = 0;
};

// extension ".svg" or ".png" (anything else: InvalidInput naming "--map").
std::unique_ptr<Canvas> make_canvas(const std::string& extension, double width, double height);

}  // namespace bssrdf
