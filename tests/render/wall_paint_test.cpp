// The solids coloured by the wall pressure, on the host: the table gives the field
// that wall_paint.h defines (the brute-force sum over every particle), a uniform
// pressure reads as itself over a face, a linear one within what one spacing of
// smoothing allows; the folder's range is the loaded patches' percentiles; the colour
// bar's colours are the scale's and its ticks are round numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/error.h"
#include "io/frame_file.h"
#include "render/legend.h"
#include "render/wall_paint.h"
#include "test_support.h"

namespace br = bw::render;
using bw::Vec3d;

namespace {

constexpr double kSpacing = 0.05;

// A plate of solid `solid`: two layers of particles on the sampling grid behind the
// face y = 0 (at y = s/2 and 3s/2, as bw-sample puts a volume's surface and the layer
// behind it), x and z in [0, 1]; the surface layer carries `pressure`, the one
// behind it nothing.
void add_plate(bw::FrameData& f, std::int32_t solid, double (*pressure)(double x, double z)) {
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i < 20; ++i)
      for (int k = 0; k < 20; ++k) {
        const double x = (i + 0.5) * kSpacing, z = (k + 0.5) * kSpacing, y = (layer + 0.5) * kSpacing;
        f.bx.push_back(static_cast<float>(x));
        f.by.push_back(static_cast<float>(y));
        f.bz.push_back(static_cast<float>(z));
        f.bp.push_back(layer == 0 ? static_cast<float>(pressure(x, z)) : 0.0f);
        f.bsolid.push_back(solid);
      }
}

// wall_paint.h's p(x), summed over every particle of the frame.
double brute_force(const bw::FrameData& f, const Vec3d& x, std::int32_t solid, double reach) {
  double sum = 0, weight = 0;
  for (std::size_t j = 0; j < f.bp.size(); ++j) {
    if (f.bsolid[j] != solid) continue;
    const double d2 = (Vec3d(f.bx[j], f.by[j], f.bz[j]) - x).squaredNorm();
    if (d2 >= reach * reach) continue;
    const double s = 1 - d2 / (reach * reach), w = s * s * s;
    sum += w * f.bp[j];
    weight += w;
  }
  return weight > 0 ? sum / weight : 0;
}

}  // namespace

TEST(WallPaint, TheTableGivesTheFieldOfEveryParticleNearALoad) {
  bw::FrameData f;
  // Solid 0 loaded on its left half only; solid 1, a second plate beside it (x shifted
  // by 2 m), not loaded at all; solid 2, loaded all over, half a metre behind solid 0.
  add_plate(f, 0, [](double x, double z) { return x < 0.5 ? 1000.0 + 3000.0 * z : 0.0; });
  const std::size_t first = f.bp.size();
  add_plate(f, 1, [](double, double) { return 0.0; });
  for (std::size_t j = first; j < f.bp.size(); ++j) f.bx[j] += 2.0f;
  add_plate(f, 2, [](double, double) { return 50000.0; });
  for (std::size_t j = 2 * first; j < f.bp.size(); ++j) f.by[j] += 0.5f;
  const br::PaintTable table = br::paint_table(f, kSpacing, "frame");
  // Solid 1 and solid 0's far right lie far from every load: they are left out.
  EXPECT_LT(table.size(), 2 * first);
  std::mt19937 random(17);
  std::uniform_real_distribution<double> along(-0.1, 1.1), depth(-0.03, 0.06);
  double worst = 0;
  for (int n = 0; n < 4000; ++n) {
    const Vec3d x(along(random), depth(random), along(random));
    for (std::int32_t solid : {0, 1, 2}) {
      const double expected = brute_force(f, x, solid, kSpacing);
      const double got = table.value(x, solid);
      worst = std::max(worst, std::abs(got - expected));
    }
  }
  bw::test::figure("largest difference from the sum over every particle (Pa)", worst);
  EXPECT_LT(worst, 1e-6 * 4000);
}

TEST(WallPaint, AUniformPressureReadsAsItselfAndALinearOneWithinASpacing) {
  bw::FrameData uniform, linear;
  add_plate(uniform, 0, [](double, double) { return 4321.0; });
  constexpr double kGradient = 10000;  // Pa/m along z
  add_plate(linear, 0, [](double, double z) { return kGradient * z; });
  const br::PaintTable u = br::paint_table(uniform, kSpacing, "uniform");
  const br::PaintTable l = br::paint_table(linear, kSpacing, "linear");
  double worst_uniform = 0, worst_linear = 0;
  for (int i = 0; i <= 40; ++i)
    for (int k = 0; k <= 40; ++k) {
      // On the face, away from its edges by a spacing.
      const Vec3d x(0.05 + 0.9 * i / 40.0, 0.0, 0.05 + 0.9 * k / 40.0);
      worst_uniform = std::max(worst_uniform, std::abs(u.value(x, 0) - 4321.0));
      worst_linear = std::max(worst_linear, std::abs(l.value(x, 0) - kGradient * x.z()));
    }
  bw::test::figure("uniform: largest error (Pa)", worst_uniform);
  bw::test::figure("linear: largest error over the gradient times the spacing", worst_linear / (kGradient * kSpacing));
  EXPECT_LT(worst_uniform, 4321.0 * 1e-6);
  // A weighted mean of values taken within R = s of the point: a linear field within
  // its change over R (0.34 of it here, where the lattice leaves some asymmetry).
  EXPECT_LT(worst_linear, kGradient * kSpacing);
  // Where no particle of the solid is within reach, the face reads 0; another solid's
  // particles never colour it.
  EXPECT_EQ(u.value(Vec3d(0.5, -0.2, 0.5), 0), 0.0);
  EXPECT_EQ(u.value(Vec3d(0.5, 0.0, 0.5), 1), 0.0);
}

TEST(WallPaint, FramesWithoutTheFieldAreNamed) {
  bw::FrameData f;
  f.bx = {0}, f.by = {0}, f.bz = {0};
  EXPECT_THROW(
      try { br::paint_table(f, kSpacing, "frames/000003.h5"); } catch (const bw::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("frames/000003.h5: holds no wall pressure"), std::string::npos)
            << e.what();
        throw;
      },
      bw::InputError);
  f.bp = {1};
  EXPECT_THROW(br::paint_table(f, kSpacing, "f"), bw::InputError);  // no boundary/solid
}

TEST(WallPaint, TheRangeIsThePercentilesOfTheLoadedPatchesOfEveryFrame) {
  bw::test::TempDir dir;
  std::vector<std::string> paths;
  // Two frames: 0 unloaded (frame 0 of a run), then patches at 1..1000 Pa, a spike,
  // and zeros that do not count.
  for (int n = 0; n < 2; ++n) {
    bw::FrameData f;
    f.frame = n;
    f.time = 0.1 * n;
    for (int k = 0; k < 1200; ++k) {
      const float p = n == 0 || k >= 1000 ? 0.0f : static_cast<float>(k + 1);
      f.bx.push_back(0.01f * k), f.by.push_back(0), f.bz.push_back(0), f.bp.push_back(p), f.bsolid.push_back(0);
    }
    if (n == 1) f.bp[1100] = 1e6f;  // one spike
    paths.push_back(bw::frame_file_name(dir.path(), n));
    bw::write_frame(f, paths.back());
  }
  const br::PaintRange r = br::wall_pressure_range(paths);
  EXPECT_EQ(r.frames, 2u);
  EXPECT_EQ(r.samples, 1001u);
  EXPECT_EQ(r.peak, 1e6);
  EXPECT_EQ(r.scale.min, 0.0);
  // The 99th percentile of 1..1000 and the spike: the spike does not set the scale.
  EXPECT_GE(r.scale.max, 985.0);
  EXPECT_LE(r.scale.max, 1000.0);
  // From an even share of at most 100 of the 1001 patches: the same within the
  // share's step (16 patches of 1 Pa apart here), the peak and the count exact.
  const br::PaintRange shared = br::wall_pressure_range(paths, 100);
  EXPECT_EQ(shared.samples, 1001u);
  EXPECT_EQ(shared.peak, 1e6);
  EXPECT_NEAR(shared.scale.max, r.scale.max, 16.0);

  // Suction: a trace of it (a tenth of the patches at -1 Pa) leaves the scale at 0; a
  // fifth at -200 Pa starts it at their 1st percentile.
  for (float suction : {-1.0f, -200.0f}) {
    bw::FrameData f;
    f.frame = 0;
    for (int k = 0; k < 1000; ++k) {
      const float p = k % (suction < -100 ? 5 : 10) == 0 ? suction : static_cast<float>(k + 1);
      f.bx.push_back(0), f.by.push_back(0), f.bz.push_back(0), f.bp.push_back(p), f.bsolid.push_back(0);
    }
    const std::string path = bw::frame_file_name(dir.path(), 7);
    bw::write_frame(f, path);
    const br::PaintRange s = br::wall_pressure_range({path});
    EXPECT_EQ(s.scale.min, suction < -100 ? -200.0 : 0.0) << suction;
  }
}

TEST(Legend, TicksAreRoundNumbersWithinTheRange) {
  EXPECT_EQ(br::legend_ticks(0, 20000), (std::vector<double>{0, 5000, 10000, 15000, 20000}));
  EXPECT_EQ(br::legend_ticks(-1315, 5477), (std::vector<double>{0, 2000, 4000}));
  EXPECT_EQ(br::legend_ticks(0.2, 1.1), (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(br::pressure_unit(0, 999).name, "Pa");
  EXPECT_EQ(br::pressure_unit(-2000, 500).name, "kPa");
  EXPECT_EQ(br::pressure_unit(0, 3e6).name, "MPa");
}

TEST(Legend, TheBarShowsTheScalesColoursAndLeavesTheRestOfTheImage) {
  br::Image image;
  image.width = 640, image.height = 360;
  image.rgb.assign(3 * 640 * 360, 100);
  const br::Image before = image;
  const br::ColorScale scale{0, 20000};
  const br::LegendBar bar = br::draw_legend(image, scale, br::pressure_unit(0, 20000));
  ASSERT_GT(bar.y1 - bar.y0, 100);
  ASSERT_GT(bar.x1 - bar.x0, 3);
  ASSERT_GT(bar.x0, 3 * image.width / 4);
  // Top row the max's colour, bottom row the min's, the middle the middle's, in every
  // column of the bar (8-bit: within 1/255 and a row's step of the scale).
  const auto level = [&](int x, int y) {
    const std::uint8_t* p = image.pixel(x, y);
    Vec3d c;
    for (int k = 0; k < 3; ++k) c[k] = p[k] / 255.0;
    return c;
  };
  const double tolerance = 1.0 / 255 + 3.0 / (bar.y1 - bar.y0);
  for (int x = bar.x0; x < bar.x1; ++x) {
    EXPECT_LT((level(x, bar.y0) - scale.srgb(20000)).cwiseAbs().maxCoeff(), tolerance);
    EXPECT_LT((level(x, bar.y1 - 1) - scale.srgb(0)).cwiseAbs().maxCoeff(), tolerance);
    EXPECT_LT((level(x, (bar.y0 + bar.y1) / 2) - scale.srgb(10000)).cwiseAbs().maxCoeff(), tolerance);
  }
  // The labels' ink left of the bar; nothing drawn in the image's left three quarters.
  int ink = 0, elsewhere = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const bool changed = !std::equal(image.pixel(x, y), image.pixel(x, y) + 3, before.pixel(x, y));
      if (x < 3 * image.width / 4) elsewhere += changed;
      else if (x < bar.x0 - 4 && image.pixel(x, y)[0] > 240) ++ink;
    }
  EXPECT_EQ(elsewhere, 0);
  EXPECT_GT(ink, 50);
}
