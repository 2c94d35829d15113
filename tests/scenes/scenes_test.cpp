// The example scenes end to end through Makefile.scenes, each at a reduced size (a
// coarse spacing, a short run, small images), with the tools of this build
// (NO_BUILD=1): every step a scene needs runs and leaves its files, and the run is
// complete.
#include <filesystem>
#include <ostream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/run_file.h"
#include "scenes_support.h"
#include "test_support.h"

namespace bw {
namespace {

namespace fs = std::filesystem;

struct Reduced {
  std::string name;      // examples/NAME.toml
  std::string spacing;   // SPACING
  std::string end;       // END (s)
};

void PrintTo(const Reduced& r, std::ostream* os) { *os << r.name; }

int count_files(const std::string& folder, const std::string& extension) {
  if (!fs::is_directory(folder)) return 0;
  int n = 0;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.path().extension() == extension) ++n;
  return n;
}

class Scene : public testing::TestWithParam<Reduced> {};

TEST_P(Scene, RunsEndToEnd) {
  const Reduced& r = GetParam();
  test::TempDir out;
  const auto made = test::make_scenes(r.name, out.path(),
                         "SPACING=" + r.spacing + " END=" + r.end + " WIDTH=160 HEIGHT=90 RENDER_CHUNK=4 CHECK_SEEDS=16");
  ASSERT_EQ(made.exit_code, 0) << made.out << made.err;
  const std::string dir = out.path() + "/scenes/" + r.name + "/" + r.spacing + "-end" + r.end;
  const std::string video = dir + "/" + r.name + "-160x90.mp4";
  EXPECT_NE(made.out.find(video), std::string::npos) << "names its video: " << made.out;

  // The run: complete, to the end asked for, with water in it.
  const RunRecord run = read_run(dir + "/run.h5");
  EXPECT_EQ(run.status, "complete");
  ASSERT_FALSE(run.frames.empty());
  EXPECT_NEAR(run.frames.back().time, std::stod(r.end), 1e-9);
  EXPECT_GT(run.frames.back().fluid, 0);
  const auto frames = static_cast<int>(run.frames.size());
  EXPECT_EQ(count_files(dir + "/frames", ".h5"), frames);

  // One image per frame (rendered in chunks of 4), and the video of them.
  EXPECT_EQ(count_files(dir + "/images-160x90", ".png"), frames);
  ASSERT_TRUE(test::exists(video));
  EXPECT_GT(fs::file_size(video), 1000u);

  // The Voronoi steps exactly when the scene has breakable solids.
  const bool breakable = test::has_breakable(r.name);
  EXPECT_EQ(test::exists(dir + "/fragments.h5"), breakable);
  int checks = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("check-", 0) == 0) ++checks;
  EXPECT_EQ(checks > 0, breakable);

  // Made again, nothing is left to do.
  const auto again = test::make_scenes(video, out.path(),
                          "SPACING=" + r.spacing + " END=" + r.end + " WIDTH=160 HEIGHT=90 RENDER_CHUNK=4 CHECK_SEEDS=16 -q");
  EXPECT_EQ(again.exit_code, 0) << "make -q: something would be remade\n" << again.out << again.err;
}

// Coarse spacings whose lattices fit the scenes' solids (docs in each scene file),
// and runs of a few frames.
INSTANTIATE_TEST_SUITE_P(Reduced, Scene,
                         testing::Values(Reduced{"wall", "0.05", "0.2"}, Reduced{"plate", "0.05", "0.2"},
                                         Reduced{"valley", "0.1", "0.2"}, Reduced{"houses", "0.1", "0.2"},
                                         Reduced{"dambreak", "0.01", "0.1"},
                                         Reduced{"floating_box", "0.01", "0.1"}),
                         [](const testing::TestParamInfo<Reduced>& p) { return p.param.name; });

// LOADS=1: the run records the loads and the wall pressure, into a folder of its own,
// and the images colour the solids by it. The jet of scene 1 (5 m/s, 0.15 m in radius)
// reaches the wall by 0.5 s: the water's impulse on the wall points downstream (+x),
// and the wall's face is loaded in the last frame.
TEST(Scenes, LoadsAreRecordedAndShown) {
  test::TempDir out;
  const std::string options = "SPACING=0.05 END=0.5 WIDTH=160 HEIGHT=90 RENDER_CHUNK=4 CHECK_SEEDS=16 LOADS=1";
  const auto made = test::make_scenes("wall", out.path(), options);
  ASSERT_EQ(made.exit_code, 0) << made.out << made.err;
  const std::string dir = out.path() + "/scenes/wall/0.05-end0.5-loads";
  const RunRecord run = read_run(dir + "/run.h5");
  EXPECT_EQ(run.status, "complete");
  ASSERT_EQ(run.loads.size(), run.frames.size());
  ASSERT_EQ(run.solids.size(), 2u);
  const Vec3d impulse = run.loads.back()[1];  // the wall, the scene's second solid
  test::figure("the water's impulse on the wall at 0.5 s, x (N s)", impulse.x());
  EXPECT_GT(impulse.x(), 0.0);
  const FrameData last = read_frame_boundary(dir + "/frames/" + fmt::format("{:06d}.h5", run.frames.back().frame));
  ASSERT_FALSE(last.bp.empty());
  int loaded = 0;
  for (std::size_t k = 0; k < last.bp.size(); ++k) loaded += last.bsolid[k] == 1 && last.bp[k] > 0;
  test::figure("the wall's loaded patches in the last frame", loaded);
  EXPECT_GT(loaded, 0);
  EXPECT_EQ(count_files(dir + "/images-160x90", ".png"), static_cast<int>(run.frames.size()));
  EXPECT_TRUE(test::exists(dir + "/wall-160x90.mp4"));
}

// A target that is neither a scene nor a file of one fails.
TEST(Scenes, UnknownTargetFails) {
  test::TempDir out;
  const auto made = test::make_scenes("no-such-scene", out.path(), "");
  EXPECT_NE(made.exit_code, 0);
  EXPECT_NE(made.err.find("no-such-scene"), std::string::npos) << made.err;
}

}  // namespace
}  // namespace bw
