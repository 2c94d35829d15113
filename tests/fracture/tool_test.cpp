// bw-sim with a breakable wall end to end: the run file's /bodies and /fracture, and
// bw-voronoi replay rebuilding one exact mesh per fragment with the simulator's
// volumes (within the voxel resolution); bad inputs are refused with one line.
#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "fracture_fixtures.h"
#include "io/fragments_file.h"
#include "io/run_file.h"
#include "test_support.h"

namespace bw {
namespace {

TEST(FractureTool, RunRecordsFracturesThatReplayRebuilds) {
  test::TempDir dir;
  test::write_fracture_solids(dir.file(""));
  std::ofstream(dir.file("scene.toml")) << test::fracture_scene(10.0, 0.45, 0.03, "[fracture]\nmax_chunks = 8\n");
  const auto sim = test::run(test::tool("bw-sim") + " " + dir.file("scene.toml") + " -o " + dir.file("run") + " --quiet");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const RunRecord run = read_run(dir.file("run/run.h5"));
  ASSERT_FALSE(run.fractures.empty());
  EXPECT_EQ(run.solids.at(1).kind, "breakable");
  EXPECT_EQ(run.solids.at(1).body, 0);
  std::size_t children = 0;
  for (const FractureEvent& e : run.fractures) children += e.child_body.size();
  const auto replay = test::run(test::tool("bw-voronoi") + " replay " + dir.file("run/run.h5") + " -o " +
                                dir.file("fragments.h5"));
  EXPECT_EQ(replay.exit_code, 0) << replay.out << replay.err;
  const FragmentSet set = read_fragments(dir.file("fragments.h5"));
  // One exact fragment per body fracture made, each with its body's volume within
  // the voxel resolution (bw-voronoi replay checks it and fails otherwise).
  EXPECT_EQ(set.fragments.size(), children);
  double volume = 0;
  for (const Fragment& f : set.fragments) {
    const auto& body = run.bodies.at(static_cast<std::size_t>(f.body));
    if (body.parent >= 0 && std::none_of(run.fractures.begin(), run.fractures.end(),
                                         [&](const FractureEvent& e) { return e.parent == f.body; }))
      volume += f.volume;
  }
  // The fragments that are left fill the wall (0.06 x 0.3 x 0.3 m).
  EXPECT_NEAR(volume, 0.06 * 0.3 * 0.3, 1e-8);
}

TEST(FractureTool, BadInputsAreRefusedWithOneLine) {
  test::TempDir dir;
  test::write_fracture_solids(dir.file(""), false);
  std::ofstream(dir.file("novoxels.toml")) << test::fracture_scene(10.0, 0.5, 0.03);
  auto r = test::run(test::tool("bw-sim") + " " + dir.file("novoxels.toml") + " -o " + dir.file("a") + " --quiet");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("solid[1].particles: wall.h5 has no voxels; a breakable solid needs its volume"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  r = test::run(test::tool("bw-sim") + " " + dir.file("novoxels.toml") + " -o " + dir.file("b") +
                " --quiet --set solid[1].frc=1.5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("solid[1].frc: 1.5 is outside (0, 1]"), std::string::npos) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  r = test::run(test::tool("bw-sim") + " " + dir.file("novoxels.toml") + " -o " + dir.file("c") +
                " --quiet --set fracture.max_chunks=0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("fracture.max_chunks: 0 must be at least 1"), std::string::npos) << r.err;
  EXPECT_FALSE(test::exists(dir.file("a/run.h5")));
}

}  // namespace
}  // namespace bw
