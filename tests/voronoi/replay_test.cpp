// Replaying recorded fracture events: exact meshes matched to the simulator's bodies.
#include <gtest/gtest.h>

#include "mesh/check.h"
#include "mesh/properties.h"
#include "synthetic_run.h"
#include "test_support.h"
#include "voronoi/replay.h"

namespace {

using bw::Vec3d;
namespace bv = bw::voronoi;

bv::ReplayResult replay(const bw::RunRecord& run) {
  bv::ReplayOptions options;
  options.source = "run.h5";
  return bv::replay_run(run, options);
}

// Event 0 breaks the U into the cells of a seed in the left arm and one in the base:
// the left arm's cell reaches over the notch into the right arm, so the simulator
// makes three bodies. Event 1 breaks the largest of them again.
struct TwoEvents {
  bw::test::TempDir dir;
  bw::test::SyntheticRun s = bw::test::make_u_run(dir.file("u.h5"), 0.1);
  std::vector<std::int32_t> first = s.fracture(0, {{0.5, 2.5, 0.5}, {1.5, 0.5, 0.5}}, 0.1);
  std::int32_t largest = *std::max_element(first.begin(), first.end(), [&](std::int32_t a, std::int32_t b) {
    return s.run.bodies[static_cast<std::size_t>(a)].voxels < s.run.bodies[static_cast<std::size_t>(b)].voxels;
  });
  std::vector<std::int32_t> second = s.fracture(largest, {{1.2, 0.3, 0.5}, {2.7, 0.6, 0.5}}, 0.2);
};

TEST(Replay, EveryBodyGetsTheExactFragmentOfItsVoxels) {
  TwoEvents t;
  ASSERT_EQ(t.first.size(), 3u);
  ASSERT_EQ(t.second.size(), 2u);
  const bv::ReplayResult r = replay(t.s.run);
  EXPECT_TRUE(r.passed()) << r.text();
  EXPECT_EQ(r.events, 2u);
  EXPECT_EQ(r.unmatched, 0u);
  EXPECT_EQ(r.spare, 0u);
  // The simulator's fragment count, one exact mesh per body.
  ASSERT_EQ(r.fragments.fragments.size(), t.first.size() + t.second.size());
  EXPECT_EQ(r.fragments.seeds.size(), 4u);
  const double s = t.s.reference_spacing;
  double first_generation = 0;
  for (std::size_t i = 0; i < r.fragments.fragments.size(); ++i) {
    const bw::Fragment& f = r.fragments.fragments[i];
    const bv::BodyMatch& m = r.bodies[i];  // every body matched: the same order
    EXPECT_EQ(f.body, m.body);
    EXPECT_TRUE(bw::mesh::check_mesh(f.mesh).bounds_volume());
    const auto& body = t.s.run.bodies[static_cast<std::size_t>(f.body)];
    const double voxel_volume = body.voxels * s * s * s;
    const auto props = bw::mesh::mass_properties(f.mesh);
    // Volume within the voxel resolution; centre of mass within a voxel or so.
    EXPECT_NEAR(props.volume, voxel_volume, props.area * s) << "body " << f.body;
    EXPECT_LT((props.centroid - body.reference_center).norm(), 1.5 * s) << "body " << f.body;
    bw::test::figure("body " + std::to_string(f.body) + " volume error / (area x spacing)",
                     std::abs(props.volume - voxel_volume) / (props.area * s));
    if (m.event == 0) first_generation += props.volume;
    // Seeds index all events' seeds: event 1's start after event 0's two.
    EXPECT_EQ(f.seed, m.seed);
    EXPECT_EQ(f.seed >= 2, m.event == 1);
  }
  // The first event's fragments fill the solid in its reference configuration.
  EXPECT_NEAR(first_generation, 7.0 * 0.125, 1e-12);
  // Fragments of fragments fill their parent.
  double parent = 0, children = 0;
  for (std::size_t i = 0; i < r.bodies.size(); ++i) {
    if (r.bodies[i].body == t.largest) parent = r.bodies[i].volume;
    if (r.bodies[i].event == 1) children += r.bodies[i].volume;
  }
  EXPECT_NEAR(children, parent, 1e-12);
}

TEST(Replay, BodiesWithoutAnExactFragmentAreReportedWithTheReason) {
  TwoEvents t;
  // A body that the exact cut cannot give: a second component of the base's seed.
  bw::RunRecord run = t.s.run;
  bw::BodyRecord ghost = run.bodies[1];
  ghost.reference_center += Vec3d(0, 0, 5);
  run.bodies.push_back(ghost);
  run.fractures[0].child_body.push_back(static_cast<std::int32_t>(run.bodies.size() - 1));
  run.fractures[0].child_seed.push_back(1);
  run.fractures[0].child_component.push_back(1);
  const bv::ReplayResult r = replay(run);
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.unmatched, 1u);
  EXPECT_EQ(r.fragments.fragments.size(), 5u);
  const bv::BodyMatch& m = r.bodies[3];
  EXPECT_EQ(m.body, static_cast<std::int32_t>(run.bodies.size() - 1));
  EXPECT_EQ(m.component, -1);
  EXPECT_NE(m.problem.find("the exact cut gives seed 1 of event 0 1 fragments, all taken"), std::string::npos)
      << m.problem;
  EXPECT_NE(r.text().find("FAIL"), std::string::npos);
}

TEST(Replay, UnreadableSolidAndOrphanEventsAreReported) {
  TwoEvents t;
  bw::RunRecord run = t.s.run;
  run.solids[0].particles = t.dir.file("missing.h5");
  const bv::ReplayResult r = replay(run);
  EXPECT_EQ(r.unmatched, r.bodies.size());
  EXPECT_TRUE(r.fragments.fragments.empty());
  for (const bv::BodyMatch& m : r.bodies) {
    // Event 0 names the file; event 1 names the parent that has no mesh.
    EXPECT_NE(m.problem.find("missing.h5"), std::string::npos) << m.problem;
    if (m.event == 1) {
      EXPECT_NE(m.problem.find("parent body " + std::to_string(t.largest) + " has no exact mesh"), std::string::npos)
          << m.problem;
    }
  }
}

TEST(Replay, RunWithoutFractureGivesNoFragments) {
  bw::test::TempDir dir;
  const bw::test::SyntheticRun s = bw::test::make_u_run(dir.file("u.h5"), 0.25);
  const bv::ReplayResult r = replay(s.run);
  EXPECT_TRUE(r.passed());
  EXPECT_EQ(r.events, 0u);
  EXPECT_TRUE(r.fragments.fragments.empty());
}

}  // namespace
