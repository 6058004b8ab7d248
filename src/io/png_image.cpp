#include "bssrdf/io/png_image.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace bssrdf {

std::uint8_t to_srgb8(double v) {
  v = std::clamp(v, 0.0, 1.0);
  const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(255 * s));
}

std::string encode_png(const RgbImage& image, const std::vector<std::pair<std::string, std::string>>& text) {
  if (image.width <= 0 || image.height <= 0) throw InvalidInput("image", "empty", "at least 1 x 1 pixels");
  std::string out;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, image.width, image.height, 3, image.pixels.data(), image.width * 3))
    throw InvalidInput("PNG encoding failed");
  // tEXt chunks after IHDR (PNG 1.2 section 4.2.3.1; stb_image_write writes none): length, type, keyword NUL text, CRC
  // of type and data. The signature (8 bytes) and IHDR (12 + 13) come first.
  std::string chunks;
  for (const auto& [keyword, value] : text) {
    if (keyword.empty() || keyword.size() > 79 ||
        std::any_of(keyword.begin(), keyword.end(), [](char c) { return c < 32 || c > 126; }))
      throw InvalidInput("PNG text keyword", "'" + keyword + "'", "1 to 79 printable characters");
    std::string chunk = "tEXt" + keyword + '\0' + value;
    const auto length = static_cast<std::uint32_t>(chunk.size() - 4);
    const unsigned crc = stbiw__crc32(reinterpret_cast<unsigned char*>(chunk.data()), static_cast<int>(chunk.size()));
    for (int shift = 24; shift >= 0; shift -= 8) chunks += static_cast<char>((length >> shift) & 0xff);
    chunks += chunk;
    for (int shift = 24; shift >= 0; shift -= 8) chunks += static_cast<char>((crc >> shift) & 0xff);
  }
  out.insert(8 + 12 + 13, chunks);
  return out;
}

}  // namespace bssrdf
