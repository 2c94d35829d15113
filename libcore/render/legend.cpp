#include "render/legend.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace bw::render {
namespace {

// 5 x 7 glyphs, a row a byte, the leftmost pixel the bit 0x10.
struct Glyph {
  char c;
  std::uint8_t rows[7];
};
constexpr Glyph kGlyphs[] = {
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}}, {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}}, {'3', {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}}, {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}}, {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}}, {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}}, {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}},
    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}}, {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}}, {'a', {0x00, 0x00, 0x0e, 0x01, 0x0f, 0x11, 0x0f}},
};

const Glyph* glyph(char c) {
  for (const Glyph& g : kGlyphs)
    if (g.c == c) return &g;
  return nullptr;  // a space
}

struct Canvas {
  Image& image;
  void put(int x, int y, const Vec3d& srgb) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
    for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(srgb[k], 0.0, 1.0)));
  }
  void fill(int x0, int y0, int x1, int y1, const Vec3d& srgb) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) put(x, y, srgb);
  }
};

const Vec3d kInk(0.97, 0.97, 0.97), kOutline(0.05, 0.05, 0.05);
constexpr int kAdvance = 6;  // glyph width and a column between glyphs, in font pixels

int text_width(const std::string& s, int scale) { return static_cast<int>(s.size()) * kAdvance * scale - scale; }

// Text with its top-left at (x, y), each font pixel `scale` image pixels, outlined.
void draw_text(Canvas& canvas, const std::string& s, int x, int y, int scale) {
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Glyph* g = glyph(s[i]);
      if (!g) continue;
      const int gx = x + static_cast<int>(i) * kAdvance * scale;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          if (!(g->rows[row] & (0x10 >> col))) continue;
          const int px = gx + col * scale, py = y + row * scale;
          if (pass == 0)
            canvas.fill(px - scale, py - scale, px + 2 * scale, py + 2 * scale, kOutline);
          else
            canvas.fill(px, py, px + scale, py + scale, kInk);
        }
    }
}

}  // namespace

std::vector<double> legend_ticks(double min, double max) {
  std::vector<double> ticks;
  if (!(max > min) || !std::isfinite(min) || !std::isfinite(max)) return {min};
  const double raw = (max - min) / 4;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * power;
  for (double m : {1.0, 2.0, 2.5, 5.0})
    if (m * power >= raw * (1 - 1e-9)) {
      step = m * power;
      break;
    }
  for (double k = std::ceil(min / step - 1e-9); k * step <= max * (1 + 1e-12) + 1e-300; k += 1)
    ticks.push_back(std::abs(k) < 1e-12 ? 0.0 : k * step);
  return ticks;
}

LegendUnit pressure_unit(double min, double max) {
  const double big = std::max(std::abs(min), std::abs(max));
  if (big >= 1e6) return {"MPa", 1e6};
  if (big >= 1e3) return {"kPa", 1e3};
  return {"Pa", 1};
}

LegendBar draw_legend(Image& image, const ColorScale& scale, const LegendUnit& unit) {
  Canvas canvas{image};
  const int s = std::max(1, image.height / 360);      // font pixel
  const int bar_h = std::max(16, image.height * 2 / 5);
  const int bar_w = std::max(6, 6 * s);
  const int margin = std::max(8, 10 * s);
  const int x1 = image.width - margin, x0 = x1 - bar_w;
  const int y0 = (image.height - bar_h) / 2, y1 = y0 + bar_h;
  const double span = scale.max - scale.min;

  // The bar in a dark frame, the scale's max at the top.
  canvas.fill(x0 - s, y0 - s, x1 + s, y1 + s, kOutline);
  for (int y = y0; y < y1; ++y) {
    const double t = 1 - (y - y0 + 0.5) / bar_h;
    canvas.fill(x0, y, x1, y + 1, scale.srgb(scale.min + t * span));
  }

  // Ticks and their labels, as many decimals as the step needs.
  const std::vector<double> ticks = legend_ticks(scale.min, scale.max);
  double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1;
  int decimals = 0;
  const double step_in_unit = step / unit.factor;
  while (decimals < 6 && std::abs(step_in_unit * std::pow(10.0, decimals) -
                                  std::round(step_in_unit * std::pow(10.0, decimals))) > 1e-6)
    ++decimals;
  for (double v : ticks) {
    const double t = span > 0 ? (v - scale.min) / span : 0;
    const int y = y1 - static_cast<int>(std::lround(t * bar_h));
    canvas.fill(x0 - 4 * s, y - (s + 1) / 2, x0 - s, y + s / 2 + 1, kInk);
    const std::string label = fmt::format("{:.{}f}", v / unit.factor, decimals);
    draw_text(canvas, label, x0 - 6 * s - text_width(label, s), y - 7 * s / 2, s);
  }
  draw_text(canvas, unit.name, x1 - text_width(unit.name, s), y0 - 12 * s, s);
  return {x0, y0, x1, y1};
}

}  // namespace bw::render
