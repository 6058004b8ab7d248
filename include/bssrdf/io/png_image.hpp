// 8-bit RGB images and their PNG encoding (stb_image_write), in memory so callers write the bytes
// atomically (io/atomic_file.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bssrdf {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, top row first, R G B per pixel

  RgbImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3, 0) {}
  std::uint8_t* at(int x, int y) { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 3; }
  const std::uint8_t* at(int x, int y) const { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 3; }
};

// Linear [0, 1] (clamped) to 8-bit sRGB.
std::uint8_t to_srgb8(double linear);

// Throws InvalidInput for an empty image. `text`: PNG tEXt chunks (keyword, Latin-1 text), e.g. {"Description", ...};
// a keyword is 1-79 printable characters.
std::string encode_png(const RgbImage& image, const std::vector<std::pair<std::string, std::string>>& text = {});

}  // namespace bssrdf
