#include "render/image.h"

#include <png.h>

#include <csetjmp>
#include <cstring>

#include "common/atomic_file.h"
#include "common/error.h"

namespace bw::render {

namespace {

// zlib level 2 with the "up" filter: a third of the time of libpng's defaults for
// rendered images, at files a few percent larger.
constexpr int kCompressionLevel = 2;

void append_bytes(png_structp png, png_bytep data, png_size_t size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + size);
}
void flush_nothing(png_structp) {}
void on_warning(png_structp, png_const_charp) {}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image, const PngText& text) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    fail_run("encode_png: image of {} x {} holds {} bytes", image.width, image.height, image.rgb.size());
  std::vector<std::uint8_t> bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, on_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    fail_run("PNG encoding failed: out of memory");
  }
  // libpng reports errors by longjmp to here; nothing between here and the jump
  // owns resources but `bytes`, which outlives it.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    fail_run("PNG encoding failed");
  }
  {
    png_set_write_fn(png, &bytes, append_bytes, flush_nothing);
    png_set_compression_level(png, kCompressionLevel);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    std::vector<png_text> chunks(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
      chunks[i].compression = PNG_TEXT_COMPRESSION_NONE;
      chunks[i].key = const_cast<char*>(text[i].first.c_str());
      chunks[i].text = const_cast<char*>(text[i].second.c_str());
      chunks[i].text_length = text[i].second.size();
    }
    if (!chunks.empty()) png_set_text(png, info, chunks.data(), static_cast<int>(chunks.size()));
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y)
      png_write_row(png, const_cast<png_bytep>(&image.rgb[3 * static_cast<std::size_t>(y) * image.width]));
    png_write_end(png, nullptr);
  }
  png_destroy_write_struct(&png, &info);
  return bytes;
}

void write_png(const Image& image, const std::string& path, const PngText& text) {
  const std::vector<std::uint8_t> bytes = encode_png(image, text);
  write_file_atomically(path, bytes.data(), bytes.size());
}

Image read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) fail_input("{}: not a PNG file: {}", path, png.message);
  png.format = PNG_FORMAT_RGB;
  Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    fail_input("{}: cannot decode: {}", path, png.message);
  }
  return image;
}

}  // namespace bw::render
