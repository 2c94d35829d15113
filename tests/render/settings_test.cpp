// The renderer's host-side parts: scene tables, command-line values, camera fit,
// particle spacing, and where solids and bodies are placed. No OpenGL needed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/error.h"
#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "mesh/shapes.h"
#include "render/camera.h"
#include "render/particle_classes.h"
#include "render/particle_spacing.h"
#include "render/render_settings.h"
#include "render/sequence.h"
#include "render/solids.h"
#include "render/view_fit.h"
#include "sample/sampler.h"
#include "synthetic.h"
#include "test_support.h"

namespace br = bw::render;
using bw::Vec3d;

namespace {

std::string error_of(const std::function<void()>& f) { return bw::test::input_error_of(f); }

// Triangles of meshes as the renderer draws them (grey, flat normals).
br::TriangleSoup soup_of(std::initializer_list<bw::TriMesh> meshes) {
  br::TriangleSoup soup;
  for (const bw::TriMesh& mesh : meshes)
    for (const bw::Triangle& t : mesh.triangles) {
      const Vec3d& a = mesh.vertices[t[0]];
      const Vec3d n = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).normalized();
      for (int k = 0; k < 3; ++k) {
        const Vec3d& p = mesh.vertices[t[k]];
        for (double v : {p.x(), p.y(), p.z(), n.x(), n.y(), n.z(), 0.5, 0.5, 0.5})
          soup.vertices.push_back(static_cast<float>(v));
      }
    }
  return soup;
}

std::vector<Vec3d> points_of(const bw::FrameData& f) {
  std::vector<Vec3d> out;
  for (std::size_t i = 0; i < f.fluid_count(); ++i) out.emplace_back(f.x[i], f.y[i], f.z[i]);
  return out;
}

}  // namespace

TEST(RenderSettings, ReadsItsTablesAndIgnoresTheOthers) {
  const auto s = br::parse_render_settings(R"(
[fluid]
anything = "the simulator's business"
[[solid]]
mesh = "wall.obj"
[camera]
position = [1, -3, 2]
target = [0, 0, 0.5]
fov = 50
[light]
direction = [0, 0, -1]
shadows = false
[render]
width = 320
height = 200
filter = "bilateral"
absorption = [1, 0.5, 0.25]
ground_height = -0.5
)",
                                           "scene.toml");
  ASSERT_TRUE(s.camera);
  EXPECT_FALSE(s.camera->animated());
  EXPECT_EQ(s.camera->at(0).position, Vec3d(1, -3, 2));
  EXPECT_EQ(s.camera->at(0).fov_degrees, 50);
  EXPECT_FALSE(s.light.shadows);
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 200);
  EXPECT_EQ(s.filter, br::Filter::kBilateral);
  EXPECT_EQ(s.absorption, Vec3d(1, 0.5, 0.25));
  ASSERT_TRUE(s.ground_height);
  EXPECT_EQ(*s.ground_height, -0.5);
}

TEST(RenderSettings, DefaultsWithoutTables) {
  const auto s = br::parse_render_settings("[fluid]\nrho0 = 998\n", "scene.toml");
  EXPECT_FALSE(s.camera);
  EXPECT_EQ(s.width, 1280);
  EXPECT_EQ(s.height, 720);
  EXPECT_EQ(s.filter, br::Filter::kNarrowRange);
}

TEST(RenderSettings, RejectsUnknownKeysWithTheirPath) {
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nwidht = 3\n", "s.toml"); }),
            "s.toml: render.widht: unknown key (see docs/rendering.md)");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[camera]\nposition=[0,0,1]\ntarget=[0,1,1]\nzoom=2\n", "s.toml"); }),
            "s.toml: camera.zoom: unknown key (see docs/rendering.md)");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[light]\ncolour = [1,1,1]\n", "s.toml"); }),
            "s.toml: light.colour: unknown key (see docs/rendering.md)");
}

TEST(RenderSettings, RejectsBadValues) {
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nwidth = 0\n", "s.toml"); }),
            "s.toml: render.width: 0 is outside [1, 16384]");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nwidth = \"wide\"\n", "s.toml"); }),
            "s.toml: render.width: expected an integer");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nfilter = \"gauss\"\n", "s.toml"); }),
            "s.toml: render.filter: 'gauss' is not one of narrow-range, bilateral, none");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nfluid_color = [1, 2]\n", "s.toml"); }),
            "s.toml: render.fluid_color: expected an array of 3 numbers");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[camera]\nposition = [0, 0, 1]\n", "s.toml"); }),
            "s.toml: camera.target: required when a [camera] table is given");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[camera]\nposition=[0,0,1]\ntarget=[0,0,0]\n", "s.toml"); }),
            "s.toml: camera.up: is parallel to the viewing direction");
  EXPECT_NE(error_of([] { br::parse_render_settings("[render\nwidth = 3\n", "s.toml"); }).find("s.toml:1:"),
            std::string::npos);
}

TEST(RenderSettings, SolidsColouredByTheWallPressure) {
  const auto s = br::parse_render_settings(
      "[render]\nsolids = \"wall_pressure\"\npressure_range = [-500, 2e4]\nlegend = false\nwater = false\n", "s.toml");
  EXPECT_EQ(s.solids, br::SolidColoring::kWallPressure);
  ASSERT_TRUE(s.pressure_range);
  EXPECT_EQ(s.pressure_range->min, -500);
  EXPECT_EQ(s.pressure_range->max, 2e4);
  EXPECT_FALSE(s.legend);
  EXPECT_FALSE(s.water);
  const auto d = br::parse_render_settings("", "s.toml");
  EXPECT_EQ(d.solids, br::SolidColoring::kShaded);
  EXPECT_FALSE(d.pressure_range);
  EXPECT_TRUE(d.legend);
  EXPECT_TRUE(d.water);
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nsolids = \"pressure\"\n", "s.toml"); }),
            "s.toml: render.solids: 'pressure' is not one of shaded, wall_pressure");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\npressure_range = [0]\n", "s.toml"); }),
            "s.toml: render.pressure_range: expected an array of 2 numbers [min, max] (Pa)");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\npressure_range = [10, 10]\n", "s.toml"); }),
            "s.toml: render.pressure_range: [10, 10]: the second value must be above the first");
}

TEST(RenderSettings, FrameRanges) {
  auto r = br::parse_frame_range("3:9:2");
  EXPECT_EQ(*r.first, 3);
  EXPECT_EQ(*r.last, 9);
  EXPECT_EQ(r.step, 2);
  r = br::parse_frame_range("5");
  EXPECT_EQ(*r.first, 5);
  EXPECT_EQ(*r.last, 5);
  r = br::parse_frame_range("4:");
  EXPECT_EQ(*r.first, 4);
  EXPECT_FALSE(r.last);
  r = br::parse_frame_range("::3");
  EXPECT_FALSE(r.first);
  EXPECT_EQ(r.step, 3);
  EXPECT_THROW(br::parse_frame_range("9:3"), bw::InputError);
  EXPECT_THROW(br::parse_frame_range("1:2:0"), bw::InputError);
  EXPECT_THROW(br::parse_frame_range("a:b"), bw::InputError);
  EXPECT_THROW(br::parse_frame_range("-1:4"), bw::InputError);
  EXPECT_THROW(br::parse_frame_range("1:2:3:4"), bw::InputError);
}

TEST(RenderSettings, CameraOption) {
  const br::Camera c = br::parse_camera("1,2,3:0,0,0.5:30");
  EXPECT_EQ(c.position, Vec3d(1, 2, 3));
  EXPECT_EQ(c.target, Vec3d(0, 0, 0.5));
  EXPECT_EQ(c.fov_degrees, 30);
  EXPECT_EQ(br::parse_camera("1,2,3:0,0,0").fov_degrees, 45);
  EXPECT_THROW(br::parse_camera("1,2:0,0,0"), bw::InputError);
  EXPECT_THROW(br::parse_camera("1,2,3:0,0,x"), bw::InputError);
  EXPECT_THROW(br::parse_camera("1,2,3:0,0,0:200"), bw::InputError);
  EXPECT_THROW(br::parse_camera("0,0,5:0,0,0"), bw::InputError);  // looking along up
}

TEST(Camera, FittedViewHoldsEveryCorner) {
  bw::Aabb box;
  box.add(Vec3d(-1, -0.5, 0));
  box.add(Vec3d(3, 1.5, 0.7));
  for (double aspect : {16.0 / 9.0, 1.0, 0.5}) {
    const br::Camera c = br::fit_camera(box, 40, aspect);
    const br::Mat4d m = br::perspective(c.fov_degrees, aspect, 0.01, 100) * br::look_at(c.position, c.target, c.up);
    for (int i = 0; i < 8; ++i) {
      const Vec3d corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                         (i & 4) ? box.max.z() : box.min.z());
      const Eigen::Vector4d clip = m * Eigen::Vector4d(corner.x(), corner.y(), corner.z(), 1);
      EXPECT_LE(std::abs(clip.x() / clip.w()), 1.0) << "aspect " << aspect << " corner " << i;
      EXPECT_LE(std::abs(clip.y() / clip.w()), 1.0) << "aspect " << aspect << " corner " << i;
      EXPECT_GT(clip.w(), 0);
    }
  }
}

// Segments and rays against triangles: a segment through a box is blocked, one
// beside it or leaving from its surface is not, a ray down meets its top; and the
// hierarchy over many boxes answers as the boxes one by one do.
TEST(ViewFit, OccludersBlockWhatCrossesTheirTriangles) {
  const br::Occluders cube(soup_of({bw::mesh::box(Vec3d(0, 0, 0), Vec3d(1, 1, 1))}));
  EXPECT_EQ(cube.size(), 12u);
  EXPECT_TRUE(cube.blocks(Vec3d(-1, 0.5, 0.5), Vec3d(2, 0.5, 0.5)));
  EXPECT_TRUE(cube.blocks(Vec3d(0.5, 0.5, 0.5), Vec3d(0.5, 0.5, 3)));
  EXPECT_FALSE(cube.blocks(Vec3d(-1, 0.5, 1.5), Vec3d(2, 0.5, 1.5)));
  EXPECT_FALSE(cube.blocks(Vec3d(0.5, 0.5, 1), Vec3d(0.5, 0.5, 3)));
  EXPECT_FALSE(cube.blocks(Vec3d(-1, 0.5, 0.5), Vec3d(-0.5, 0.5, 0.5)));
  EXPECT_NEAR(cube.first_hit(Vec3d(0.3, 0.6, 5), Vec3d(0, 0, -1), 10), 4, 1e-12);
  EXPECT_EQ(cube.first_hit(Vec3d(3, 0.6, 5), Vec3d(0, 0, -1), 10), 10);
  EXPECT_FALSE(br::Occluders().blocks(Vec3d(-1, 0.5, 0.5), Vec3d(2, 0.5, 0.5)));

  std::vector<bw::TriMesh> boxes;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      boxes.push_back(bw::mesh::box(Vec3d(i, j, 0), Vec3d(i + 0.5, j + 0.5, 0.3 + 0.05 * ((i * 7 + j * 3) % 11))));
  br::TriangleSoup all;
  std::vector<br::Occluders> each;
  for (const bw::TriMesh& b : boxes) {
    const br::TriangleSoup one = soup_of({b});
    all.vertices.insert(all.vertices.end(), one.vertices.begin(), one.vertices.end());
    each.emplace_back(one);
  }
  const br::Occluders city(all);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 13), h(0, 1.2);
  int blocked = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3d a(u(rng), u(rng), h(rng)), b(u(rng), u(rng), h(rng));
    bool any = false;
    for (const br::Occluders& o : each) any = any || o.blocks(a, b);
    ASSERT_EQ(city.blocks(a, b), any) << a.transpose() << " -> " << b.transpose();
    blocked += any;
    double nearest = 1;
    for (const br::Occluders& o : each) nearest = std::min(nearest, o.first_hit(a, b - a, 1));
    ASSERT_EQ(city.first_hit(a, b - a, 1), nearest);
  }
  EXPECT_GT(blocked, 500);
  EXPECT_LT(blocked, 1900);
}

// Water inside a tank, the dam break of examples/dambreak.toml: walls twice as high
// as the water column and more than twice the cavity's width. The usual
// three-quarter view sees the outside of the walls only; the fitted view looks over
// them at the column, at the floor the water floods next, and at the surge there.
TEST(ViewFit, LooksOverTheWallsOfATank) {
  bw::test::TempDir dir;
  br::test::write_tank_run(dir.path());
  const br::TriangleSoup soup = br::SolidScene::load({dir.file("run.h5"), ""}, {}).place({});
  const br::Occluders occluders(soup);
  br::ViewFitInput in;
  in.solids = soup.bounds();
  in.occluders = &occluders;
  in.water = points_of(br::test::dambreak_frame(0));
  in.particle_radius = 0.008;
  in.ground_height = -0.03;
  const double aspect = 16.0 / 9.0;
  const br::FittedView view = br::fit_view(in, 45, aspect);
  const br::Camera usual = br::fit_camera(view.framed, 45, aspect);
  EXPECT_EQ(br::fraction_seen(usual, aspect, in.water, &occluders), 0);
  EXPECT_GT(view.elevation, br::kFitElevation);
  EXPECT_GE(view.water_seen, 0.9);
  EXPECT_GE(view.surface_seen, 0.8);
  EXPECT_GE(view.floor_seen, 0.8);
  const double surge = br::fraction_seen(view.camera, aspect, points_of(br::test::dambreak_frame(1)), &occluders);
  bw::test::figure("fitted view: elevation", view.elevation, "degrees");
  bw::test::figure("fitted view: azimuth", view.azimuth, "degrees");
  bw::test::figure("fitted view: surge particles seen", surge);
  EXPECT_GE(surge, 0.8);
  // The framed box is the tank and its water.
  EXPECT_TRUE(view.framed.min.isApprox(Vec3d(-0.03, -0.03, -0.03), 1e-6)) << view.framed.min.transpose();
  EXPECT_TRUE(view.framed.max.isApprox(Vec3d(0.63, 0.18, 0.4), 1e-6)) << view.framed.max.transpose();
}

// Where the usual view sees the water, the fitted camera keeps it: water with no
// solids, and the synthetic splash (a pool in a low tank, a ball above, a wall
// behind), whose walls hide a little of the pool only.
TEST(ViewFit, KeepsTheUsualViewWhenItSeesTheWater) {
  const double aspect = 16.0 / 9.0;
  br::ViewFitInput bare;
  bw::FrameData ball;
  br::test::add_ball(ball, Vec3d(0, 0, 0.5), 0.3, 0.03, 0.1, 3);
  bare.water = points_of(ball);
  bare.particle_radius = 0.024;
  bare.ground_height = 0.2;
  br::FittedView view = br::fit_view(bare, 45, aspect);
  EXPECT_EQ(view.azimuth, br::kFitAzimuth);
  EXPECT_EQ(view.elevation, br::kFitElevation);
  EXPECT_EQ(view.water_seen, 1);

  bw::test::TempDir dir;
  br::test::write_wall_run(dir.path(), Vec3d::Zero(), true);
  const br::TriangleSoup soup = br::SolidScene::load({dir.file("run.h5"), ""}, {}).place({});
  const br::Occluders occluders(soup);
  br::ViewFitInput splash;
  splash.solids = soup.bounds();
  splash.occluders = &occluders;
  splash.water = points_of(br::test::splash_frame(20000));
  splash.particle_radius = 0.8 * 0.03;
  splash.ground_height = -0.05;
  view = br::fit_view(splash, 45, aspect);
  EXPECT_EQ(view.azimuth, br::kFitAzimuth);
  EXPECT_EQ(view.elevation, br::kFitElevation);
  EXPECT_GE(view.surface_seen, 0.8);
  EXPECT_TRUE(view.framed.min.isApprox(splash.solids.min, 1e-9));  // the whole scene
}

// A little water on a large ground slab: the camera frames the water and its
// surroundings, not the whole slab.
TEST(ViewFit, FramesTheWaterInALargeScene) {
  const br::TriangleSoup soup = soup_of({bw::mesh::box(Vec3d(-10, -10, -0.2), Vec3d(10, 10, 0))});
  const br::Occluders occluders(soup);
  br::ViewFitInput in;
  in.solids = soup.bounds();
  in.occluders = &occluders;
  bw::FrameData drop;
  br::test::add_ball(drop, Vec3d(2, 1, 0.3), 0.2, 0.02, 0.1, 3);
  in.water = points_of(drop);
  in.particle_radius = 0.016;
  const br::FittedView view = br::fit_view(in, 45, 16.0 / 9.0);
  EXPECT_LT(view.framed.extent().maxCoeff(), 2.0);
  EXPECT_LE(view.framed.min.x(), 1.8);
  EXPECT_GE(view.framed.max.x(), 2.2);
  EXPECT_EQ(view.water_seen, 1);
  EXPECT_LT((view.camera.target - Vec3d(2, 1, 0.3)).norm(), 0.5);
  EXPECT_LT((view.camera.position - view.camera.target).norm(), 5.0);
}

TEST(ParticleSpacing, MedianNearestNeighbourOfALattice) {
  for (double spacing : {0.01, 0.05}) {
    bw::FrameData f;
    br::test::add_block(f, Vec3d(0, 0, 0), Vec3d(0.5, 0.3, 0.2), spacing, 0.0, 1);
    const double s = br::estimate_particle_spacing(f.x.data(), f.y.data(), f.z.data(), f.fluid_count());
    bw::test::figure("estimated spacing / true spacing", s / spacing);
    EXPECT_NEAR(s, spacing, 1e-3 * spacing);
    // A few far-flung drops do not change the median.
    f.x.push_back(30), f.y.push_back(30), f.z.push_back(30);
    EXPECT_NEAR(br::estimate_particle_spacing(f.x.data(), f.y.data(), f.z.data(), f.fluid_count()), spacing,
                1e-3 * spacing);
  }
  const float one = 1;
  EXPECT_EQ(br::estimate_particle_spacing(&one, &one, &one, 1), 0);
  // Non-finite positions are left out.
  bw::FrameData g;
  br::test::add_block(g, Vec3d(0, 0, 0), Vec3d(0.3, 0.3, 0.3), 0.03, 0.0, 1);
  const double before = br::estimate_particle_spacing(g.x.data(), g.y.data(), g.z.data(), g.fluid_count());
  g.x.insert(g.x.begin(), std::nanf("")), g.y.insert(g.y.begin(), 0.f), g.z.insert(g.z.begin(), INFINITY);
  EXPECT_EQ(br::estimate_particle_spacing(g.x.data(), g.y.data(), g.z.data(), g.fluid_count()), before);
}

namespace {

// Positions on a lattice of `spacing` over i < ni, j < nj, k < nk, each moved by up
// to `jitter` spacings (seeded), appended to f.
void add_lattice(bw::FrameData& f, int ni, int nj, int nk, double spacing, double jitter, unsigned seed,
                 const Vec3d& origin = Vec3d::Zero()) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) {
        f.x.push_back(static_cast<float>(origin.x() + (i + u(rng)) * spacing));
        f.y.push_back(static_cast<float>(origin.y() + (j + u(rng)) * spacing));
        f.z.push_back(static_cast<float>(origin.z() + (k + u(rng)) * spacing));
      }
}

std::vector<br::ParticleClass> classes_of(const bw::FrameData& f, double spacing) {
  br::ClassifyParams p;
  p.spacing = spacing;
  return br::classify_particles(f.x.data(), f.y.data(), f.z.data(), f.x.size(), p);
}

}  // namespace

// The grid finds exactly the neighbours a search over all pairs finds.
TEST(RenderSpray, NeighbourCountsMatchAllPairs) {
  bw::FrameData f;
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-0.3f, 0.3f);
  for (int n = 0; n < 1500; ++n) f.x.push_back(u(rng)), f.y.push_back(u(rng)), f.z.push_back(0.2f * u(rng));
  f.x.push_back(40.f), f.y.push_back(-7.f), f.z.push_back(3.f);  // far away: a sparse box
  const double radius = 0.05;
  const std::vector<int> counts = br::count_neighbours(f.x.data(), f.y.data(), f.z.data(), f.x.size(), radius);
  for (std::size_t a = 0; a < f.x.size(); ++a) {
    int expected = 0;
    for (std::size_t b = 0; b < f.x.size(); ++b) {
      const double dx = f.x[b] - f.x[a], dy = f.y[b] - f.y[a], dz = f.z[b] - f.z[a];
      expected += b != a && dx * dx + dy * dy + dz * dz <= radius * radius;
    }
    ASSERT_EQ(counts[a], expected) << "particle " << a;
  }
  EXPECT_EQ(counts.back(), 0);
}

// A block's interior is water, a lone particle and a pair are spray, a sheet one
// particle thick and a jet two particles across are not spray.
TEST(RenderSpray, BlockSheetJetAndDrops) {
  const double h = 0.02;
  bw::FrameData block;
  add_lattice(block, 12, 12, 12, h, 0.1, 1);
  const auto blocks = classes_of(block, h);
  int interior = 0, interior_water = 0;
  for (int k = 2; k < 10; ++k)
    for (int j = 2; j < 10; ++j)
      for (int i = 2; i < 10; ++i) {
        ++interior;
        interior_water += blocks[(k * 12 + j) * 12 + i] == br::ParticleClass::kWater;
      }
  EXPECT_EQ(interior_water, interior);

  bw::FrameData sheet;
  add_lattice(sheet, 20, 20, 1, h, 0.1, 2);
  int sheet_spray = 0;
  for (br::ParticleClass c : classes_of(sheet, h)) sheet_spray += c == br::ParticleClass::kSpray;
  EXPECT_EQ(sheet_spray, 0);

  bw::FrameData jet;
  add_lattice(jet, 40, 2, 2, h, 0.1, 3);
  int jet_spray = 0;
  for (br::ParticleClass c : classes_of(jet, h)) jet_spray += c == br::ParticleClass::kSpray;
  EXPECT_EQ(jet_spray, 0);

  bw::FrameData drops;  // a lone drop and a pair, far from each other
  drops.x = {0.f, 1.f, 1.02f};
  drops.y = {0.f, 0.f, 0.f};
  drops.z = {0.f, 0.f, 0.01f};
  for (br::ParticleClass c : classes_of(drops, h)) EXPECT_EQ(c, br::ParticleClass::kSpray);

  // The same particles in another order get the same classes.
  bw::FrameData reversed = sheet;
  add_lattice(reversed, 1, 1, 1, h, 0, 0, Vec3d(3, 3, 3));
  std::reverse(reversed.x.begin(), reversed.x.end());
  std::reverse(reversed.y.begin(), reversed.y.end());
  std::reverse(reversed.z.begin(), reversed.z.end());
  const auto forward = classes_of(sheet, h), backward = classes_of(reversed, h);
  EXPECT_EQ(backward.front(), br::ParticleClass::kSpray);
  for (std::size_t n = 0; n < forward.size(); ++n) EXPECT_EQ(backward[backward.size() - 1 - n], forward[n]);
}

TEST(RenderSettings, SprayKeys) {
  const auto d = br::parse_render_settings("", "s.toml");
  EXPECT_TRUE(d.spray);
  EXPECT_EQ(d.spray_neighbours, 3);
  EXPECT_EQ(d.foam_neighbours, 8);
  const auto s = br::parse_render_settings(
      "[render]\nspray = false\nspray_neighbours = 2\nfoam_neighbours = 6\nspray_size = 0.4\n"
      "spray_opacity = 0.5\nfoam = 0\n",
      "s.toml");
  EXPECT_FALSE(s.spray);
  EXPECT_EQ(s.spray_neighbours, 2);
  EXPECT_EQ(s.foam_neighbours, 6);
  EXPECT_EQ(s.spray_size, 0.4);
  EXPECT_EQ(s.spray_opacity, 0.5);
  EXPECT_EQ(s.foam, 0);
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nspray_neighbours = 5\nfoam_neighbours = 4\n", "s.toml"); }),
            "s.toml: render.foam_neighbours: 4 is outside [render.spray_neighbours = 5, 1000]");
  EXPECT_EQ(error_of([] { br::parse_render_settings("[render]\nspray_opacity = 2\n", "s.toml"); }),
            "s.toml: render.spray_opacity: must lie in [0, 1]");
}

// A dynamic solid's mesh is placed by x_world = R(q) (x_ref - c_ref) + position, where
// x_ref = translation + R(rotation) (scale x_mesh); static solids stay put.
TEST(Solids, PlacedByScaleRotationTranslationAndBodyPose) {
  bw::test::TempDir dir;
  const bw::SampledSolid cube =
      bw::sample::sample_mesh(bw::mesh::box(Vec3d(0, 0, 0), Vec3d(1, 1, 1)), {0.25, false, "cube", 1.0});
  bw::write_particles(cube, dir.file("cube.h5"), "test");
  bw::RunRecord run;
  bw::SolidRecord fixed;
  fixed.name = "fixed";
  fixed.particles = dir.file("cube.h5");
  fixed.kind = "static";
  fixed.scale = 2;
  fixed.translation = Vec3d(10, 0, 0);
  run.solids.push_back(fixed);
  bw::SolidRecord moving = fixed;
  moving.name = "moving";
  moving.kind = "dynamic";
  moving.scale = 1;
  moving.translation = Vec3d(0, 0, 0);
  // A quarter turn about z: the unit cube [0,1]^3 goes to [-1,0] x [0,1] x [0,1].
  moving.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3d::UnitZ()));
  moving.body = 0;
  run.solids.push_back(moving);
  bw::BodyRecord body;
  body.solid = 1;
  body.reference_center = Vec3d(-0.5, 0.5, 0.5);
  run.bodies.push_back(body);
  bw::write_run(run, dir.file("run.h5"));

  const auto scene = br::SolidScene::load({dir.file("run.h5"), ""}, {});
  EXPECT_EQ(scene.solid_count(), 2u);

  // No poses (time 0): the reference configuration.
  bw::Aabb at_rest = scene.place({}).bounds();
  EXPECT_TRUE(at_rest.min.isApprox(Vec3d(-1, 0, 0), 1e-9));
  EXPECT_TRUE(at_rest.max.isApprox(Vec3d(12, 2, 2), 1e-9));

  // The body's centre moves to (0, 0, 5) and turns half a turn about x.
  bw::BodyStates states;
  states.id = {0};
  states.position = {Vec3d(0, 0, 5)};
  states.orientation = {Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Vec3d::UnitX()))};
  states.linear_velocity = states.angular_velocity = {Vec3d::Zero()};
  std::size_t missing = 99;
  const br::TriangleSoup soup = scene.place(states, &missing);
  EXPECT_EQ(missing, 0u);
  bw::Aabb moved;
  for (std::size_t v = 0; v < soup.vertices.size(); v += 9)
    if (soup.vertices[v] < 5) moved.add(Vec3d(soup.vertices[v], soup.vertices[v + 1], soup.vertices[v + 2]));
  EXPECT_TRUE(moved.min.isApprox(Vec3d(-0.5, -0.5, 4.5), 1e-6)) << moved.min.transpose();
  EXPECT_TRUE(moved.max.isApprox(Vec3d(0.5, 0.5, 5.5), 1e-6)) << moved.max.transpose();
  // Normals are unit and the colour is the body colour's shade, within [0, 1].
  for (std::size_t v = 0; v < soup.vertices.size(); v += 9) {
    EXPECT_NEAR(Vec3d(soup.vertices[v + 3], soup.vertices[v + 4], soup.vertices[v + 5]).norm(), 1.0, 1e-5);
    for (int k = 6; k < 9; ++k) EXPECT_LE(soup.vertices[v + k], 1.0f);
  }
}

TEST(Solids, FragmentsReplaceTheirBodysMeshAndUnknownBodiesAreCounted) {
  bw::test::TempDir dir;
  br::test::write_wall_run(dir.path());
  // A run with the wall as a breakable solid of body 0, and a fragments file with
  // two fragments of body 1 (a child body).
  bw::RunRecord run = bw::read_run(dir.file("run.h5"));
  run.solids[0].kind = "breakable";
  run.solids[0].body = 0;
  bw::BodyRecord root, child;
  root.reference_center = Vec3d(0, 0.575, 0.5);
  child.parent = 0;
  child.reference_center = Vec3d(0.5, 0.575, 0.5);
  root.solid = child.solid = 0;  // the wall, whose boundary particles colour them
  run.bodies = {root, child};
  bw::write_run(run, dir.file("run.h5"));
  bw::FragmentSet set;
  for (int k = 0; k < 2; ++k) {
    bw::Fragment f;
    f.mesh = bw::mesh::box(Vec3d(k * 0.5, 0.5, 0), Vec3d(k * 0.5 + 0.5, 0.65, 1));
    f.body = 1;
    f.seed = k;
    set.fragments.push_back(f);
  }
  bw::write_fragments(set, dir.file("fragments.h5"));
  const auto scene = br::SolidScene::load({dir.file("run.h5"), dir.file("fragments.h5")}, {});
  EXPECT_EQ(scene.fragment_count(), 2u);

  bw::BodyStates states;
  states.id = {1, 7};
  states.position = {Vec3d(0.5, 0.575, 3.5), Vec3d::Zero()};
  states.orientation = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()};
  states.linear_velocity = states.angular_velocity = {Vec3d::Zero(), Vec3d::Zero()};
  std::size_t missing = 0;
  const br::TriangleSoup soup = scene.place(states, &missing);
  const bw::Aabb box = soup.bounds();
  EXPECT_EQ(missing, 1u);  // body 7 is not in the run
  // Every vertex of the fragments belongs to the wall's row of the run.
  ASSERT_EQ(soup.solid.size(), soup.vertices.size() / 9);
  EXPECT_EQ(std::count(soup.solid.begin(), soup.solid.end(), 0), static_cast<std::ptrdiff_t>(soup.solid.size()));
  // Only body 1's fragments, lifted by 3 m; the wall's own body is not in the frame.
  EXPECT_TRUE(box.min.isApprox(Vec3d(0, 0.5, 3), 1e-6)) << box.min.transpose();
  EXPECT_TRUE(box.max.isApprox(Vec3d(1, 0.65, 4), 1e-6)) << box.max.transpose();
}
