// The renderer on whatever EGL device the machine has (llvmpipe in CI): fluid shows
// where it projects and nowhere else, smoothing flattens a flat pool's normals,
// solids show where their meshes project. Small images keep it quick.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include <fmt/format.h>

#include "io/frame_file.h"
#include "mesh/shapes.h"
#include "render/camera.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/renderer.h"
#include "render/solids.h"
#include "render/view_fit.h"
#include "render/wall_paint.h"
#include "synthetic.h"
#include "test_support.h"

namespace br = bw::render;
using bw::Vec3d;

namespace {

constexpr int kWidth = 160, kHeight = 120;

// One context for the whole suite: creating one costs more than a small render.
br::GlContext& context() {
  static std::unique_ptr<br::GlContext> c = br::GlContext::create();
  return *c;
}

br::RenderSettings small_settings() {
  br::RenderSettings s;
  s.width = kWidth;
  s.height = kHeight;
  return s;
}

br::RenderInput input_of(const bw::FrameData& f, const br::Camera& camera, double spacing) {
  br::RenderInput in;
  in.x = f.x.data(), in.y = f.y.data(), in.z = f.z.data(), in.count = f.fluid_count();
  in.camera = camera;
  in.particle_radius = 0.8 * spacing;
  in.particle_spacing = spacing;
  in.ground_height = 0;
  return in;
}

// Pixel (column, row from the top) where a world point projects.
Eigen::Vector2d project(const br::Camera& c, const Vec3d& p) {
  const br::Mat4d m = br::perspective(c.fov_degrees, double(kWidth) / kHeight, 0.01, 100) *
                      br::look_at(c.position, c.target, c.up);
  const Eigen::Vector4d clip = m * Eigen::Vector4d(p.x(), p.y(), p.z(), 1);
  return {(clip.x() / clip.w() * 0.5 + 0.5) * kWidth, (0.5 - clip.y() / clip.w() * 0.5) * kHeight};
}

bool same_pixel(const br::Image& a, const br::Image& b, int x, int y) {
  return std::equal(a.pixel(x, y), a.pixel(x, y) + 3, b.pixel(x, y));
}

}  // namespace

TEST(Renderer, ReportsItsDevice) {
  EXPECT_FALSE(context().renderer().empty());
  EXPECT_NE(context().display().find("EGL"), std::string::npos);
  std::printf("[ device   ] %s via %s\n", context().renderer().c_str(), context().display().c_str());
}

// A ball of particles: fluid where the ball projects, the very same pixels as an
// empty frame elsewhere (shadows off, so that the ball changes nothing outside).
TEST(Renderer, BallShowsWhereItProjectsAndNowhereElse) {
  br::RenderSettings s = small_settings();
  s.light.shadows = false;
  br::Renderer renderer(context(), s);
  const Vec3d center(0.2, 0.1, 0.6);
  const double radius = 0.3, spacing = 0.03;
  bw::FrameData ball;
  br::test::add_ball(ball, center, radius, spacing, 0.1, 3);
  br::Camera camera;
  camera.position = Vec3d(0.5, -2.5, 1.2);
  camera.target = center;

  const br::Image empty = renderer.render(input_of(bw::FrameData{}, camera, spacing));
  const br::Image image = renderer.render(input_of(ball, camera, spacing));
  const br::FluidLayers layers = renderer.read_fluid_layers();

  // Projected disc: the centre's pixel and the radius at the centre's distance (the
  // particles reach a particle radius beyond the lattice).
  const Eigen::Vector2d c = project(camera, center);
  const double focal = 0.5 * kHeight / std::tan(camera.fov_degrees * M_PI / 360);
  const double r_px = (radius + 0.8 * spacing) * focal / (center - camera.position).norm();
  int inside = 0, inside_fluid = 0, inside_changed = 0, outside_changed = 0, stray_fluid = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double d = (Eigen::Vector2d(x + 0.5, y + 0.5) - c).norm();
      const bool fluid = layers.depth[y * kWidth + x] > 0;
      if (d < 0.85 * r_px) {
        ++inside;
        inside_fluid += fluid;
        inside_changed += !same_pixel(image, empty, x, y);
      } else if (d > 1.15 * r_px + 2) {
        outside_changed += !same_pixel(image, empty, x, y);
        stray_fluid += fluid;
      }
    }
  bw::test::figure("ball disc pixels", inside);
  bw::test::figure("ball disc pixels showing water", inside_changed);
  ASSERT_GT(inside, 300);
  EXPECT_EQ(inside_fluid, inside);
  EXPECT_GE(inside_changed, 0.98 * inside);
  EXPECT_EQ(outside_changed, 0);
  EXPECT_EQ(stray_fluid, 0);
  // Thickness through the middle is close to the diameter (the thickness is scaled
  // to the particles' volume).
  const int cx = static_cast<int>(c.x()), cy = static_cast<int>(c.y());
  const double middle = layers.thickness[cy * kWidth + cx];
  bw::test::figure("thickness through the middle / diameter", middle / (2 * radius));
  EXPECT_NEAR(middle, 2 * radius, 0.25 * 2 * radius);
}

// A flat, jittered pool seen obliquely: the spread of its normals around the true
// one, for each filter. Smoothing must lower it, the narrow-range filter most.
TEST(Renderer, SmoothingLowersTheNormalNoiseOfAFlatPool) {
  const double spacing = 0.02;
  bw::FrameData pool;
  br::test::add_block(pool, Vec3d(-1, -1, 0), Vec3d(1, 1, 0.1), spacing, 0.15, 5);
  br::Camera camera;
  camera.position = Vec3d(0, -1.2, 1.0);
  camera.target = Vec3d(0, 0, 0.1);
  const Vec3d up_view = (br::look_at(camera.position, camera.target, camera.up).topLeftCorner<3, 3>() *
                         Vec3d::UnitZ()).normalized();
  double noise[3] = {};
  const br::Filter filters[3] = {br::Filter::kNone, br::Filter::kBilateral, br::Filter::kNarrowRange};
  for (int f = 0; f < 3; ++f) {
    br::RenderSettings s = small_settings();
    s.filter = filters[f];
    br::Renderer renderer(context(), s);
    renderer.render(input_of(pool, camera, spacing));
    const br::FluidLayers layers = renderer.read_fluid_layers();
    // Pixels of the top face far from its edges: rows in the middle third.
    double sum = 0;
    int count = 0;
    for (int y = kHeight / 3; y < 2 * kHeight / 3; ++y)
      for (int x = kWidth / 4; x < 3 * kWidth / 4; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * kWidth + x;
        if (layers.depth[i] <= 0) continue;
        const Vec3d n(layers.normals[3 * i], layers.normals[3 * i + 1], layers.normals[3 * i + 2]);
        const double angle = std::acos(std::clamp(n.normalized().dot(up_view), -1.0, 1.0));
        sum += angle * angle;
        ++count;
      }
    ASSERT_GT(count, kWidth * kHeight / 8);
    noise[f] = std::sqrt(sum / count) * 180 / M_PI;
    bw::test::figure(std::string("normal noise (RMS angle), filter ") + br::filter_name(filters[f]), noise[f],
                     "degrees");
  }
  EXPECT_LT(noise[1], 0.7 * noise[0]);
  EXPECT_LT(noise[2], 0.5 * noise[0]);
  EXPECT_LT(noise[2], 5.0);
}

// Solids show where their meshes project: a static wall, and a dynamic box that its
// body's pose moves away from where it started.
TEST(Renderer, SolidsShowWhereTheirMeshesProject) {
  bw::test::TempDir dir;
  const bw::Aabb wall = br::test::write_wall_run(dir.path());
  const auto scene = br::SolidScene::load({dir.file("run.h5"), ""}, {});
  br::Renderer renderer(context(), small_settings());
  br::Camera camera;
  camera.position = Vec3d(0, -3.5, 1.2);
  camera.target = Vec3d(0, 0.5, 0.4);

  const br::TriangleSoup soup = scene.place({});
  br::RenderInput in = input_of(bw::FrameData{}, camera, 0.02);
  const br::Image empty = renderer.render(in);
  in.solids = &soup;
  const br::Image image = renderer.render(in);

  // Every pixel well inside the wall's front face changed; pixels well away from it
  // (above the wall, where only sky can be) did not.
  const Eigen::Vector2d a = project(camera, Vec3d(wall.min.x(), wall.min.y(), wall.max.z()));
  const Eigen::Vector2d b = project(camera, Vec3d(wall.max.x(), wall.min.y(), wall.min.z()));
  int face = 0, face_changed = 0;
  for (int y = int(a.y()) + 3; y < int(b.y()) - 3; ++y)
    for (int x = int(a.x()) + 3; x < int(b.x()) - 3; ++x) ++face, face_changed += !same_pixel(image, empty, x, y);
  bw::test::figure("wall face pixels", face);
  ASSERT_GT(face, 500);
  EXPECT_EQ(face_changed, face);
  int sky = 0, sky_changed = 0;
  for (int y = 0; y < int(a.y()) - 12; ++y)
    for (int x = 0; x < kWidth; ++x) ++sky, sky_changed += !same_pixel(image, empty, x, y);
  ASSERT_GT(sky, 100);
  EXPECT_EQ(sky_changed, 0);

  // A cube in the reference configuration at the origin, moved by its body to x = 1.
  const bw::TriMesh mesh = bw::mesh::box(Vec3d(-0.2, -1.2, 0.0), Vec3d(0.2, -0.8, 0.4));
  const auto place = [&](const Vec3d& shift) {
    br::TriangleSoup s;
    for (const bw::Triangle& t : mesh.triangles) {
      const Vec3d p0 = mesh.vertices[t[0]] + shift, p1 = mesh.vertices[t[1]] + shift,
                  p2 = mesh.vertices[t[2]] + shift;
      const Vec3d n = (p1 - p0).cross(p2 - p0).normalized();
      for (const Vec3d* p : {&p0, &p1, &p2})
        for (double v : {p->x(), p->y(), p->z(), n.x(), n.y(), n.z(), 0.5, 0.3, 0.2})
          s.vertices.push_back(static_cast<float>(v));
    }
    return s;
  };
  const br::TriangleSoup moved = place(Vec3d(1, 0, 0));
  in.solids = &moved;
  const br::Image image_moved = renderer.render(in);
  const Eigen::Vector2d at_new = project(camera, Vec3d(1, -1.2, 0.2));
  const Eigen::Vector2d at_old = project(camera, Vec3d(0, -1.2, 0.2));
  EXPECT_FALSE(same_pixel(image_moved, empty, int(at_new.x()), int(at_new.y())));
  EXPECT_TRUE(same_pixel(image_moved, empty, int(at_old.x()), int(at_old.y())));
}

// The wall coloured by the pressure on its face: every pixel of the front face shows
// the colour of the field wall_paint.h defines at the point it sees (the table on the
// host, PaintTable::value), on the scale, shaded by the face's turn from the camera,
// to 3 levels of 255 (float positions, the map's 256 entries); the pixels above the
// wall, which see only sky, are those of the unpainted render.
TEST(Renderer, SolidsColouredByTheWallPressureShowTheFieldAtEveryPixel) {
  bw::test::TempDir dir;
  br::test::write_wall_run(dir.path());
  const br::TriangleSoup soup = br::SolidScene::load({dir.file("run.h5"), ""}, {}).place({});
  bw::FrameData frame;
  br::test::add_wall_pressure(frame, dir.path(), [](const Vec3d& x) { return 10000.0 * x.z() + 2000.0 * x.x(); });
  const br::PaintTable table = br::paint_table(frame, 0.05, "frame");
  br::RenderSettings s = small_settings();
  s.light.shadows = false;
  s.ground = false;
  br::Renderer shaded(context(), s);
  s.solids = br::SolidColoring::kWallPressure;
  br::Renderer painted(context(), s);
  br::Camera camera;
  camera.position = Vec3d(0.3, -2.2, 0.6);
  camera.target = Vec3d(0, 0.5, 0.45);
  br::RenderInput in = input_of(bw::FrameData{}, camera, 0.05);
  in.solids = &soup;
  const br::Image plain = shaded.render(in);
  in.paint = &table;
  // Values in [-2000, 12000] Pa: the map's colours stay below the tone curve's knee.
  in.paint_scale = {-3000, 14000};
  const br::Image image = painted.render(in);

  // The ray through a pixel's centre, to the face y = 0.5.
  const Vec3d forward = (camera.target - camera.position).normalized();
  const Vec3d right = forward.cross(camera.up).normalized(), up = right.cross(forward);
  const double half = std::tan(camera.fov_degrees * M_PI / 360.0);
  const auto encode = [](double c) {
    c = std::clamp(c, 0.0, 1.0);
    return 255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055);
  };
  int face = 0, sky = 0, sky_changed = 0;
  double worst = 0, low = 1e9, high = -1e9;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const Vec3d ray = (forward + right * ((x + 0.5) / kWidth * 2 - 1) * half * kWidth / kHeight +
                         up * (1 - (y + 0.5) / kHeight * 2) * half)
                            .normalized();
      const double t = (0.5 - camera.position.y()) / ray.y();
      const Vec3d hit = camera.position + t * ray;
      if (hit.z() > 1.1 && std::abs(hit.x()) < 0.9 && ray.z() > 0) {
        ++sky, sky_changed += !same_pixel(image, plain, x, y);
        continue;
      }
      if (std::abs(hit.x()) > 0.9 || hit.z() < 0.1 || hit.z() > 0.9) continue;
      const double value = table.value(hit, 0);
      low = std::min(low, value), high = std::max(high, value);
      const double shade = 0.55 + 0.45 * (camera.position - hit).normalized().dot(Vec3d(0, -1, 0));
      const Vec3d expected = in.paint_scale.linear(value) * shade;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(image.pixel(x, y)[k] - encode(expected[k])));
      ++face;
    }
  bw::test::figure("face pixels", face);
  bw::test::figure("pressure seen (Pa), from", low);
  bw::test::figure("to", high);
  bw::test::figure("largest difference from the host's colour (levels of 255)", worst);
  ASSERT_GT(face, 3000);
  EXPECT_GT(high - low, 8000);  // the face shows the field's range, not one colour
  EXPECT_LE(worst, 3.0);
  ASSERT_GT(sky, 100);
  EXPECT_EQ(sky_changed, 0);
}

// Water behind a solid is hidden exactly where the solid stands in front of it: the
// dam break's column in the example tank, seen over the front wall from three
// heights, against a ray cast on the host (pixel centres against the particles'
// spheres and the tank's triangles). From the lowest camera the wall hides all of
// it; the others see the top of the column, then most of it.
TEST(Renderer, WaterIsHiddenWhereASolidStandsInFront) {
  bw::test::TempDir dir;
  br::test::write_tank_run(dir.path());
  const br::TriangleSoup soup = br::SolidScene::load({dir.file("run.h5"), ""}, {}).place({});
  const br::Occluders occluders(soup);
  const bw::FrameData column = br::test::dambreak_frame(0);
  const double spacing = 0.01, radius = 0.8 * spacing;
  br::RenderSettings s = small_settings();
  s.ground = false;
  s.light.shadows = false;
  br::Renderer renderer(context(), s);
  int seen_before = -1;
  for (double y : {-0.6, -0.3, -0.05}) {
    br::Camera camera;
    camera.position = Vec3d(0.3, y, 1.2);
    camera.target = Vec3d(0.3, 0.075, 0.05);
    camera.fov_degrees = 40;
    br::RenderInput in = input_of(column, camera, spacing);
    in.solids = &soup;
    renderer.render(in);
    const br::FluidLayers layers = renderer.read_fluid_layers();
    // Pixel rays in the world.
    const Eigen::Matrix3d to_world =
        br::look_at(camera.position, camera.target, camera.up).topLeftCorner<3, 3>().transpose();
    const double focal = 0.5 * kHeight / std::tan(camera.fov_degrees * M_PI / 360);
    int gpu = 0, host = 0, differ = 0;
    for (int py = 0; py < kHeight; ++py)
      for (int px = 0; px < kWidth; ++px) {
        const Vec3d d =
            (to_world * Vec3d((px + 0.5 - 0.5 * kWidth) / focal, (0.5 * kHeight - py - 0.5) / focal, -1)).normalized();
        double water = INFINITY;
        for (std::size_t i = 0; i < column.fluid_count(); ++i) {
          const Vec3d c = Vec3d(column.x[i], column.y[i], column.z[i]) - camera.position;
          const double b = d.dot(c), disc = b * b - c.squaredNorm() + radius * radius;
          if (disc >= 0) water = std::min(water, b - std::sqrt(disc));
        }
        const bool on_host = water < occluders.first_hit(camera.position, d, 10.0);
        const bool on_gpu = layers.depth[py * kWidth + px] > 0;
        host += on_host, gpu += on_gpu, differ += on_host != on_gpu;
      }
    bw::test::figure(fmt::format("camera y = {}: water pixels cast on the host", y), host);
    bw::test::figure(fmt::format("camera y = {}: pixels where the drawing differs", y), differ);
    EXPECT_LE(differ, 2 + host / 20) << "camera y = " << y << ": " << gpu << " drawn, " << host << " cast";
    if (y == -0.6) {
      EXPECT_EQ(host, 0);
    }
    EXPECT_GT(host, seen_before);
    seen_before = host;
  }
  EXPECT_GT(seen_before, 300);
}

// Particles with a non-finite coordinate (a blown-up simulation) are left out: the
// image is that of the others.
TEST(Renderer, NonFiniteParticlesAreLeftOut) {
  br::Renderer renderer(context(), small_settings());
  bw::FrameData f;
  br::test::add_ball(f, Vec3d(0, 0, 0.5), 0.2, 0.04, 0.1, 9);
  br::Camera camera;
  camera.position = Vec3d(0.5, -2.5, 1.2);
  camera.target = Vec3d(0, 0, 0.5);
  const br::Image clean = renderer.render(input_of(f, camera, 0.04));
  const float nan = std::nanf(""), inf = INFINITY;
  f.x.insert(f.x.end(), {nan, 0.f, 1.f});
  f.y.insert(f.y.end(), {0.f, inf, 1.f});
  f.z.insert(f.z.end(), {0.f, 0.f, -inf});
  EXPECT_EQ(renderer.render(input_of(f, camera, 0.04)).rgb, clean.rgb);
}

// The same input gives the same bytes, also after rendering something else.
TEST(Renderer, Deterministic) {
  br::Renderer renderer(context(), small_settings());
  const bw::FrameData f = br::test::splash_frame(20000);
  br::Camera camera;
  camera.position = Vec3d(-1.7, -3.1, 1.9);
  camera.target = Vec3d(0, -0.1, 0.45);
  const br::Image first = renderer.render(input_of(f, camera, 0.03));
  renderer.render(input_of(br::test::splash_frame(5000), camera, 0.05));
  const br::Image second = renderer.render(input_of(f, camera, 0.03));
  EXPECT_EQ(first.rgb, second.rgb);
}

// Drops flung out of a pool: with spray on they are small, white, soft dots; with it
// off, refracting spheres of the water's radius. Per drop, the pixels it changes
// (against the pool alone) and their colour.
TEST(Renderer, IsolatedParticlesAreDrawnAsWhiteSpray) {
  const double spacing = 0.05;
  bw::FrameData pool;
  br::test::add_block(pool, Vec3d(-0.6, -0.3, 0), Vec3d(0.6, 0.5, 0.2), spacing, 0.1, 5);
  bw::FrameData splash = pool;
  std::vector<Vec3d> drops;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) drops.emplace_back(-0.36 + 0.24 * i, 0.0, 0.45 + 0.16 * j);
  for (const Vec3d& d : drops)
    splash.x.push_back(float(d.x())), splash.y.push_back(float(d.y())), splash.z.push_back(float(d.z()));
  br::Camera camera;
  // From above, so that the drops are seen against the pool.
  camera.position = Vec3d(0, -1.2, 1.5);
  camera.target = Vec3d(0, 0.05, 0.45);

  struct Look {
    // Per drop: the pixels it changes; over them, the mean of min/max channel and of
    // the darkest channel; and the darkest channel of its brightest pixel.
    double pixels = 0, whiteness = 0, brightness = 0, peak = 0;
  };
  auto look = [&](bool spray) {
    br::RenderSettings s = small_settings();
    s.spray = spray;
    br::Renderer renderer(context(), s);
    const br::Image background = renderer.render(input_of(pool, camera, spacing));
    const br::Image image = renderer.render(input_of(splash, camera, spacing));
    EXPECT_EQ(renderer.render(input_of(splash, camera, spacing)).rgb, image.rgb);  // deterministic
    if (const char* dir = std::getenv("BW_RENDER_TEST_IMAGES"))
      br::write_png(image, fmt::format("{}/spray-{}.png", dir, spray ? "on" : "off"));
    Look l;
    int changed = 0;
    for (const Vec3d& d : drops) {
      const Eigen::Vector2d c = project(camera, d);
      double peak = 0;
      for (int y = int(c.y()) - 8; y <= int(c.y()) + 8; ++y)
        for (int x = int(c.x()) - 8; x <= int(c.x()) + 8; ++x) {
          if (x < 0 || y < 0 || x >= kWidth || y >= kHeight || same_pixel(image, background, x, y)) continue;
          const std::uint8_t* p = image.pixel(x, y);
          const double lo = std::min({p[0], p[1], p[2]}), hi = std::max({p[0], p[1], p[2]});
          ++changed;
          l.whiteness += lo / std::max(hi, 1.0);
          l.brightness += lo;
          peak = std::max(peak, lo);
        }
      l.peak += peak / drops.size();
    }
    l.pixels = double(changed) / drops.size();
    l.whiteness /= std::max(changed, 1);
    l.brightness /= std::max(changed, 1);
    return l;
  };
  const Look spray = look(true), bubbles = look(false);
  bw::test::figure("pixels per drop, spray", spray.pixels);
  bw::test::figure("pixels per drop, bubbles", bubbles.pixels);
  bw::test::figure("whiteness (min/max channel), spray", spray.whiteness);
  bw::test::figure("whiteness (min/max channel), bubbles", bubbles.whiteness);
  bw::test::figure("darkest channel, spray", spray.brightness);
  bw::test::figure("darkest channel, bubbles", bubbles.brightness);
  bw::test::figure("brightest pixel's darkest channel, spray", spray.peak);
  bw::test::figure("brightest pixel's darkest channel, bubbles", bubbles.peak);
  EXPECT_GT(spray.pixels, 2);  // still visible
  EXPECT_LT(spray.pixels, 0.5 * bubbles.pixels);
  EXPECT_GT(spray.whiteness, bubbles.whiteness);
  EXPECT_GT(spray.whiteness, 0.75);
  EXPECT_GT(spray.brightness, bubbles.brightness + 15);
  EXPECT_GT(spray.peak, 200);  // white at the centre (a bubble's glint may be as bright)
}

// A sheet one particle thick and a jet two particles across stay water: their
// pixels of the water's surface are the same with spray on as with it off.
TEST(Renderer, ThinSheetsAndJetsStayWaterWithSpray) {
  const double spacing = 0.03;
  bw::FrameData thin;
  // A sheet (one particle thick) and a jet (2 x 2 particles across).
  br::test::add_block(thin, Vec3d(-0.4, 0, 0.3), Vec3d(0.4, 0.5 * spacing, 0.9), spacing, 0.1, 11);
  br::test::add_block(thin, Vec3d(-0.5, -0.3, 0.1), Vec3d(0.5, -0.3 + 1.5 * spacing, 0.1 + 1.5 * spacing), spacing, 0.1,
                      12);
  br::Camera camera;
  camera.position = Vec3d(0.6, -2.2, 1.0);
  camera.target = Vec3d(0, 0, 0.5);
  int fluid[2] = {0, 0};
  for (bool spray : {false, true}) {
    br::RenderSettings s = small_settings();
    s.spray = spray;
    br::Renderer renderer(context(), s);
    renderer.render(input_of(thin, camera, spacing));
    for (float d : renderer.read_fluid_layers().depth) fluid[spray] += d > 0;
  }
  bw::test::figure("surface pixels of the sheet and jet, spray off", fluid[0]);
  bw::test::figure("surface pixels of the sheet and jet, spray on", fluid[1]);
  ASSERT_GT(fluid[0], 1000);
  EXPECT_GE(fluid[1], 0.99 * fluid[0]);
}
