// Text on an RgbImage from a built-in 5 x 7 pixel font (printable ASCII; anything else is drawn as
// '?'), so previews can carry their scale and material without a font file or library.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "bssrdf/io/png_image.hpp"

namespace bssrdf {

// Width in pixels of `text` at integer `scale` (6 x scale per character, less the last gap).
int text_width(std::string_view text, int scale = 1);
inline int text_height(int scale = 1) { return 7 * scale; }

// Draws `text` with its top-left corner at (x, y); pixels outside the image are skipped.
void draw_text(RgbImage& image, int x, int y, std::string_view text, std::array<std::uint8_t, 3> colour, int scale = 1);

}  // namespace bssrdf
