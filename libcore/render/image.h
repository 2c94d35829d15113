// An 8-bit RGB image and its PNG file (libpng, written through a temporary file).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace bw::render {

struct Image {
  int width = 0;
  int height = 0;
  // width * height * 3 bytes, rows from the top, RGB.
  std::vector<std::uint8_t> rgb;

  const std::uint8_t* pixel(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};

// Text chunks of a PNG (tEXt): keyword (1 to 79 Latin-1 characters) and text.
using PngText = std::vector<std::pair<std::string, std::string>>;

// PNG bytes of the image with optional text chunks (deterministic: no time stamps,
// fixed compression level).
std::vector<std::uint8_t> encode_png(const Image& image, const PngText& text = {});
// Writes the image through a temporary file renamed into place.
void write_png(const Image& image, const std::string& path, const PngText& text = {});
// Reads an 8-bit RGB or RGBA PNG (alpha dropped). Throws InputError.
Image read_png(const std::string& path);

}  // namespace bw::render
