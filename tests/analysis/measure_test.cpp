#include <gtest/gtest.h>

#include <cmath>

#include "analysis/dambreak.h"
#include "analysis/measure.h"
#include "common/error.h"
#include "io/frame_file.h"
#include "test_support.h"

namespace {

using bw::FrameData;
namespace an = bw::analysis;

// A block of particles on a lattice filling [lo, hi].
FrameData block(const bw::Vec3d& lo, const bw::Vec3d& hi, double spacing, double time) {
  FrameData f;
  f.time = time;
  for (double z = lo.z() + spacing / 2; z < hi.z(); z += spacing)
    for (double y = lo.y() + spacing / 2; y < hi.y(); y += spacing)
      for (double x = lo.x() + spacing / 2; x < hi.x(); x += spacing) {
        f.x.push_back(static_cast<float>(x));
        f.y.push_back(static_cast<float>(y));
        f.z.push_back(static_cast<float>(z));
      }
  return f;
}

TEST(DamBreak, MeasuresFrontAndResidualOfABlock) {
  const FrameData f = block({0, 0, 0}, {0.3, 0.1, 0.12}, 0.01, 0.25);
  const an::DamBreakSetup setup{.column_width = 0.1, .wall = 0, .floor = 0, .band = 0.02};
  const auto s = an::measure_dambreak(f, setup);
  EXPECT_NEAR(s.front, 0.295, 1e-6);
  EXPECT_NEAR(s.residual, 0.115, 1e-6);
  EXPECT_EQ(s.time, 0.25);
}

// A synthetic run that follows the experiment exactly compares with zero error; a
// run 10 % too fast shows an error of the right size.
TEST(DamBreak, ComparisonAgainstTheReference) {
  const auto ref = an::read_dambreak_reference(std::string(BW_SOURCE_DIR) + "/examples/data/martin-moyce-1952.csv");
  ASSERT_EQ(ref.front.size(), 15u);
  ASSERT_EQ(ref.residual.size(), 17u);
  const an::DamBreakSetup setup{.column_width = 0.05715, .wall = 0, .floor = 0, .band = 0.005};
  const double a = setup.column_width, g = setup.gravity;
  // Front and residual sampled on the experimental times of each series.
  auto run_with = [&](double front_factor) {
    std::vector<an::DamBreakSample> samples;
    for (std::size_t i = 0; i < ref.front.size(); ++i) {
      an::DamBreakSample s;
      s.time = ref.front[i].T / std::sqrt(2 * g / a);
      s.front = front_factor * ref.front[i].value * a;
      // Residual at the same time, from the residual series (piecewise linear).
      const double T = s.time * std::sqrt(g / a);
      double H = ref.residual.front().value;
      for (std::size_t k = 1; k < ref.residual.size(); ++k)
        if (ref.residual[k].T >= T) {
          const auto& p = ref.residual[k - 1];
          const auto& q = ref.residual[k];
          H = T <= p.T ? p.value : p.value + (q.value - p.value) * (T - p.T) / (q.T - p.T);
          break;
        }
      s.residual = H * 2 * a;
      samples.push_back(s);
    }
    return an::compare_dambreak(samples, setup, ref);
  };
  const auto exact = run_with(1.0);
  EXPECT_LT(exact.front.rms, 1e-12);
  EXPECT_EQ(exact.front.points, 15);
  EXPECT_GT(exact.residual.points, 5);
  EXPECT_GT(exact.residual.skipped, 0) << "the run ends before the last residual points";
  const auto fast = run_with(1.1);
  // 10 % of Z, whose RMS over the series is about 2.5.
  EXPECT_NEAR(fast.front.rms, 0.1 * 2.6, 0.05);
}

TEST(Probe, AveragesAFieldAndGaugesTheSurface) {
  FrameData f = block({0, 0, 0}, {0.2, 0.2, 0.1}, 0.01, 0);
  for (float z : f.z) f.p.push_back(1000.0f * 9.81f * (0.1f - z));  // hydrostatic
  const double p = an::probe(f, an::Field::pressure, {0.1, 0.1, 0.05}, 0.02);
  EXPECT_NEAR(p, 1000 * 9.81 * 0.05, 5.0);
  EXPECT_TRUE(std::isnan(an::probe(f, an::Field::pressure, {1, 1, 1}, 0.02)));
  EXPECT_NEAR(an::surface_elevation(f, 0.1, 0.1, 0.01), 0.095, 1e-6);
  EXPECT_TRUE(std::isnan(an::surface_elevation(f, 1, 1, 0.01)));
}

// A wave gauge reads the water it stands in: a drop flying 0.2 m over the pool (the
// splash off a structure) is not its surface, and over a dry floor it reads nothing.
TEST(Probe, AGaugeReadsTheWaterNotTheSprayOverIt) {
  FrameData f = block({0, 0, 0}, {0.2, 0.2, 0.1}, 0.01, 0);
  for (float z : {0.3f, 0.31f}) {  // a drop over the pool's middle and one over a dry floor
    f.x.push_back(0.105f), f.y.push_back(0.105f), f.z.push_back(z);
    f.x.push_back(0.5f), f.y.push_back(0.5f), f.z.push_back(z);
  }
  EXPECT_NEAR(an::surface_elevation(f, 0.1, 0.1, 0.01), 0.31, 1e-6) << "the highest particle";
  EXPECT_NEAR(an::surface_elevation(f, 0.1, 0.1, 0.01, 0.02), 0.095, 1e-6);
  EXPECT_NEAR(an::surface_elevation(f, 0.1, 0.1, 0.01, 0.02, 0.0), 0.095, 1e-6);
  EXPECT_NEAR(an::surface_elevation(f, 0.5, 0.5, 0.01, 0.02), 0.31, 1e-6) << "without a bottom: the drop";
  EXPECT_TRUE(std::isnan(an::surface_elevation(f, 0.5, 0.5, 0.01, 0.02, 0.0))) << "over a dry floor";
  // A column with a gap of one missing particle still reads its top.
  FrameData g = block({0, 0, 0}, {0.01, 0.01, 0.1}, 0.01, 0);
  g.z.erase(g.z.begin() + 5), g.x.erase(g.x.begin() + 5), g.y.erase(g.y.begin() + 5);
  EXPECT_NEAR(an::surface_elevation(g, 0.005, 0.005, 0.01, 0.025, 0.0), 0.095, 1e-6);
  EXPECT_NEAR(an::surface_elevation(g, 0.005, 0.005, 0.01, 0.015, 0.0), 0.045, 1e-6) << "a gap wider than --gap";
  EXPECT_THROW(an::probe(f, an::Field::density, {0.1, 0.1, 0.05}, 0.02), bw::InputError);
}

// A hydrostatic pool against a wall (x = 0) and on a floor (z = 0): the sensor on the
// wall reads rho g times its depth, and so does the one on the floor, whose pressure is
// read h / 2 up and corrected by rho0 g (h / 2). Shepard averages of a linear field
// are off by the gradient times the weights' centroid offset, under a few percent
// within a spacing of a face; the discs' symmetric rings cancel most of it.
TEST(Sensor, ReadsTheHydrostaticPressureOnAWallAndTheFloor) {
  const double rho = 998, g = 9.81, top = 0.3, h = 0.02;
  FrameData f = block({0, 0, 0}, {0.2, 0.2, top}, 0.01, 0);
  for (float z : f.z) f.p.push_back(static_cast<float>(rho * g * (top - z)));
  an::Sensor wall;
  wall.point = {0, 0.1, 0.1};
  wall.normal = {1, 0, 0};
  wall.radius = 0.01;
  wall.h = h;
  wall.rho0 = rho;
  EXPECT_EQ(wall.samples().size(), 19u);
  EXPECT_NEAR(an::sensor_pressure(f, wall) / (rho * g * (top - 0.1)), 1.0, 0.02);
  an::Sensor floor = wall;
  floor.point = {0.1, 0.1, 0};
  floor.normal = {0, 0, 1};
  EXPECT_NEAR(an::sensor_pressure(f, floor) / (rho * g * top), 1.0, 0.02);
  an::Sensor point = floor;
  point.radius = 0;
  EXPECT_EQ(point.samples().size(), 1u);
  EXPECT_NEAR(an::sensor_pressure(f, point) / (rho * g * top), 1.0, 0.02);
  an::Sensor dry = wall;
  dry.point = {0, 0.1, 0.5};  // above the water
  EXPECT_TRUE(std::isnan(an::sensor_pressure(f, dry)));
}

TEST(BwMeasure, SensorThroughTheTool) {
  bw::test::TempDir dir;
  for (int k = 0; k < 2; ++k) {
    FrameData f = block({0, 0, 0}, {0.2, 0.2, 0.2}, 0.01, 0.1 * k);
    f.frame = k;
    for (float z : f.z) f.p.push_back(static_cast<float>(998 * 9.81 * (0.2 - z) * (1 + k)));
    bw::write_frame(f, bw::frame_file_name(dir.path(), k));
  }
  const std::string tool = bw::test::tool("bw-measure");
  const auto csv = bw::test::run(tool + " sensor " + dir.path() +
                                 " --at P1=0,0.1,0.1 --at 0,0.1,0.05 --normal 1,0,0 --radius 0.01 --h 0.02");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out.rfind("time,P1,S2\n", 0), 0u) << csv.out;
  EXPECT_EQ(bw::test::line_count(csv.out), 3) << csv.out;
  const auto bad = bw::test::run(tool + " sensor " + dir.path() + " --at P1=0,0.1 --h 0.02");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("P1=0,0.1"), std::string::npos) << bad.err;
  EXPECT_EQ(bw::test::line_count(bad.err), 1) << bad.err;
}

TEST(BwMeasure, DambreakThroughTheTool) {
  bw::test::TempDir dir;
  for (int k = 0; k < 3; ++k) {
    FrameData f = block({0, 0, 0}, {0.1 + 0.05 * k, 0.05, 0.2 - 0.03 * k}, 0.01, 0.05 * k);
    f.frame = k;
    bw::write_frame(f, bw::frame_file_name(dir.path(), k));
  }
  const std::string tool = bw::test::tool("bw-measure");
  const auto csv = bw::test::run(tool + " dambreak " + dir.path() + " --width 0.1 --band 0.02");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(bw::test::line_count(csv.out), 4) << csv.out;
  EXPECT_EQ(csv.out.rfind("time,front,residual", 0), 0u) << csv.out;
  const auto json = bw::test::run(tool + " dambreak " + dir.path() + " --width 0.1 --band 0.02 --json --reference " +
                                  BW_SOURCE_DIR + "/examples/data/martin-moyce-1952.csv");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"rms\""), std::string::npos) << json.out;
  const auto missing = bw::test::run(tool + " dambreak " + dir.file("nothere") + " --width 0.1 --band 0.02");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(bw::test::line_count(missing.err), 1) << missing.err;
}

// The tool's gauge: by default the column stops at a gap of twice the radius, so the
// drop over the pool does not count; --bottom makes a line over a dry floor read NaN.
TEST(BwMeasure, GaugeThroughTheTool) {
  bw::test::TempDir dir;
  FrameData f = block({0, 0, 0}, {0.2, 0.2, 0.1}, 0.01, 0);
  f.x.push_back(0.105f), f.y.push_back(0.105f), f.z.push_back(0.3f);
  bw::write_frame(f, bw::frame_file_name(dir.path(), 0));
  const std::string tool = bw::test::tool("bw-measure");
  const auto pool = bw::test::run(tool + " gauge " + dir.path() + " --at 0.1,0.1 --radius 0.01");
  ASSERT_EQ(pool.exit_code, 0) << pool.err;
  EXPECT_EQ(pool.out.rfind("time,elevation\n", 0), 0u) << pool.out;
  EXPECT_NEAR(std::stod(pool.out.substr(pool.out.find(',', 15) + 1)), 0.095, 1e-6) << pool.out;
  const auto spray = bw::test::run(tool + " gauge " + dir.path() + " --at 0.1,0.1 --radius 0.01 --gap 1");
  ASSERT_EQ(spray.exit_code, 0) << spray.err;
  EXPECT_NEAR(std::stod(spray.out.substr(spray.out.find(',', 15) + 1)), 0.3, 1e-6) << spray.out;
  const auto dry = bw::test::run(tool + " gauge " + dir.path() + " --at 0.5,0.5 --radius 0.01 --bottom 0");
  ASSERT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("nan"), std::string::npos) << dry.out;
  const auto bad = bw::test::run(tool + " gauge " + dir.path() + " --at 0.1,0.1 --radius 0.01 --gap -1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bw::test::line_count(bad.err), 1) << bad.err;
  // Several gauges in one pass, one column each, named or numbered.
  const auto both = bw::test::run(tool + " gauge " + dir.path() + " --at pool=0.1,0.1 --at 0.5,0.5 --radius 0.01 --bottom 0");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(both.out.rfind("time,pool,G2\n0,0.0949999", 0), 0u) << both.out;
  EXPECT_NE(both.out.find(",nan"), std::string::npos) << both.out;
  const auto typo = bw::test::run(tool + " gauge " + dir.path() + " --at H2=0.992 --radius 0.01");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("H2=0.992"), std::string::npos) << typo.err;
  EXPECT_EQ(bw::test::line_count(typo.err), 1) << typo.err;
}

// Numbers CLI11 and scanf take but no measurement can use (nan, inf), and two columns
// of one name, are bad input that names the option.
TEST(BwMeasure, NonFiniteNumbersAndTwiceUsedNamesAreRefused) {
  bw::test::TempDir dir;
  bw::write_frame(block({0, 0, 0}, {0.2, 0.2, 0.1}, 0.01, 0), bw::frame_file_name(dir.path(), 0));
  const std::string tool = bw::test::tool("bw-measure") + " ";
  const std::string frames = dir.path();
  const std::pair<std::string, std::string> cases[] = {
      {"probe " + frames + " --point nan,0,0 --radius 0.02", "--point: 'nan' must be a finite number"},
      {"probe " + frames + " --point 0,inf,0 --radius 0.02", "--point: 'inf' must be a finite number"},
      {"gauge " + frames + " --at 0.1,0.1 --radius 0.01 --bottom -inf", "--bottom: '-inf' must be a finite number"},
      {"gauge " + frames + " --at H=0.1,nan --radius 0.01", "--at 'H=0.1,nan': expected NAME=x,y or x,y (m), finite"},
      {"gauge " + frames + " --at H=0.1,0.1 --at H=0.2,0.1 --radius 0.01", "--at 'H=0.2,0.1': a second gauge named H"},
      {"sensor " + frames + " --at P=0,0.1,0.05 --at P=0,0.1,0.06 --normal 1,0,0 --h 0.02",
       "--at 'P=0,0.1,0.06': a second sensor named P"},
      {"sensor " + frames + " --at P=0,0.1,inf --normal 1,0,0 --h 0.02", "--at 'P=0,0.1,inf': expected NAME=x,y,z"},
      {"sensor " + frames + " --at P=0,0.1,0.05 --normal 1,0,nan --h 0.02", "--normal: 'nan' must be a finite number"},
      {"dambreak " + frames + " --width 0.1 --band 0.02 --wall inf", "--wall: 'inf' must be a finite number"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = bw::test::run(tool + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
}

// A folder or a missing file where a run file or a CSV belongs is named as such, in
// the tools' words (not CLI11's "File is actually a directory").
TEST(BwMeasure, FoldersAndMissingFilesAreNamedAsSuch) {
  bw::test::TempDir dir;
  bw::write_frame(block({0, 0, 0}, {0.2, 0.2, 0.1}, 0.01, 0), bw::frame_file_name(dir.path(), 0));
  const std::string tool = bw::test::tool("bw-measure") + " ";
  const std::pair<std::string, std::string> cases[] = {
      {"loads " + dir.path() + " --solid wall", dir.path() + ": is a folder, not an HDF5 file (a folder of frames"},
      {"sensors " + dir.file("run.h5"), dir.file("run.h5") + ": cannot open: No such file or directory"},
      {"dambreak " + dir.path() + " --width 0.1 --band 0.02 --reference " + dir.path(),
       dir.path() + ": is a folder, not a reference CSV"},
      {"dambreak " + dir.path() + " --width 0.1 --band 0.02 --reference " + dir.file("mm.csv"),
       dir.file("mm.csv") + ": no such file"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = bw::test::run(tool + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
  }
}

}  // namespace
