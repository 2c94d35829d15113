// A colour bar with its scale, drawn into a finished image: what the colours of the
// solids coloured by a field mean (render/wall_paint.h). On the host, after the image
// is read back, in a built-in 5 x 7 pixel font (digits, '.', '-', and the units' letters),
// so that no font file is needed where bw-render runs.
#pragma once

#include <string>
#include <vector>

#include "render/image.h"
#include "render/wall_paint.h"

namespace bw::render {

// Tick values of [min, max]: multiples of 1, 2, 2.5 or 5 times a power of ten, about
// five of them, every one within the range.
std::vector<double> legend_ticks(double min, double max);

// The unit for a pressure range and its factor: "Pa" 1, "kPa" 1e3 or "MPa" 1e6.
struct LegendUnit {
  std::string name;
  double factor = 1;
};
LegendUnit pressure_unit(double min, double max);

// The bar (its top the scale's max) at the image's right edge, vertically centred, 40%
// of the image's height, with the ticks' labels at its left in `unit` and the unit's
// name above it; light text with a dark outline, readable on sky, water and ground.
// Returns where the bar's colours are: columns [x0, x1), rows [y0, y1) from the top.
struct LegendBar {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
LegendBar draw_legend(Image& image, const ColorScale& scale, const LegendUnit& unit);

}  // namespace bw::render
