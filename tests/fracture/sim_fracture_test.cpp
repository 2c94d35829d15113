// Fracture in the simulator (docs/scene.md "Fracture"): a breakable wall on a floor
// hit by a block of water. A gentle stream never breaks it, a strong impact does;
// a weaker material breaks at least as much and no later; voxels and mass are
// conserved exactly; fragments near the impact are smaller; max_chunks holds; the
// anchored remainder stays put; the same scene gives the same fractures.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "common/error.h"
#include "fracture/fracture.h"
#include "fracture_fixtures.h"
#include "sim/solver.h"
#include "test_support.h"

namespace bw {
namespace {

using Outcome = test::FractureOutcome;
using test::fragments;
const auto run_scene = test::run_fracture_scene;

constexpr double kStrong = 10.0;   // m/s
constexpr double kGentle = 1.0;
constexpr double kEnd = 0.04;      // s: the block hits the wall at 8 ms

const Outcome& strong_wall() {
  static const Outcome o = run_scene(test::fracture_scene(kStrong, 0.97, kEnd), kEnd);
  return o;
}

TEST(Fracture, GentleStreamNeverBreaksTheWall) {
  // 1 m/s, started 2 cm before the wall: it runs against it for 80 ms.
  const Outcome o = run_scene(test::fracture_scene(kGentle, 0.97, 0.1, "", 0.02), 0.1);
  EXPECT_TRUE(o.events.empty());
  EXPECT_EQ(o.infos.size(), 1u);
}

TEST(Fracture, StrongImpactBreaksTheWallIntoFragments) {
  const Outcome& o = strong_wall();
  ASSERT_FALSE(o.events.empty());
  EXPECT_GE(fragments(o), 2u);
  EXPECT_GT(o.first, 0.005);
  for (const FractureEvent& e : o.events) {
    EXPECT_GE(e.seeds.size(), 2u);
    EXPECT_EQ(e.child_body.size(), e.child_seed.size());
    EXPECT_GE(e.child_body.size(), 2u);
  }
}

TEST(Fracture, VoxelsAndMassAreConservedExactly) {
  const Outcome& o = strong_wall();
  const double voxel_mass = rigid::voxel_mass_properties({Vec3d::Zero()}, test::kWallSpacing, test::kWallDensity).mass;
  std::int64_t voxels = 0;
  for (std::size_t b = 0; b < o.infos.size(); ++b) {
    // Every body's mass is its voxels' (voxel_mass_properties: count x voxel mass).
    EXPECT_EQ(o.masses[b].mass, voxel_mass * o.infos[b].voxels);
    if (o.infos[b].active) voxels += o.infos[b].voxels;
  }
  EXPECT_EQ(voxels, test::kWallVoxels);
  // Each event hands all of its parent's voxels to its children.
  for (const FractureEvent& e : o.events) {
    std::int64_t children = 0;
    for (const std::int32_t c : e.child_body) children += o.infos[static_cast<std::size_t>(c)].voxels;
    EXPECT_EQ(children, o.infos[static_cast<std::size_t>(e.parent)].voxels);
  }
}

TEST(Fracture, FragmentsNearTheImpactAreSmaller) {
  const Outcome& o = strong_wall();
  struct Piece {
    double distance;
    int voxels;
  };
  std::vector<Piece> pieces;
  for (std::size_t b = 0; b < o.infos.size(); ++b)
    if (o.infos[b].active && o.infos[b].parent >= 0)
      pieces.push_back({(o.masses[b].center - test::impact_point()).norm(), o.infos[b].voxels});
  ASSERT_GE(pieces.size(), 4u);
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.distance < b.distance; });
  const std::size_t half = pieces.size() / 2;
  double near = 0, far = 0;
  for (std::size_t i = 0; i < half; ++i) near += pieces[i].voxels;
  for (std::size_t i = pieces.size() - half; i < pieces.size(); ++i) far += pieces[i].voxels;
  EXPECT_LT(near / half, far / half) << pieces.size() << " fragments";
}

TEST(Fracture, AnchoredRemainderStaysFixed) {
  const Outcome& o = strong_wall();
  int fixed = 0;
  for (std::size_t k = 0; k < o.states.id.size(); ++k) {
    const auto b = static_cast<std::size_t>(o.states.id[k]);
    if (!o.infos[b].fixed) continue;
    ++fixed;
    // Where it was made: its reference configuration.
    EXPECT_LT((o.states.position[k] - o.masses[b].center).norm(), 1e-12);
    EXPECT_EQ(o.states.linear_velocity[k], Vec3d::Zero());
  }
  EXPECT_GE(fixed, 1);
  // And some fragments are free.
  int free = 0;
  for (const sim::BodyInfo& i : o.infos) free += i.active && !i.fixed ? 1 : 0;
  EXPECT_GE(free, 1);
}

TEST(Fracture, WeakerMaterialBreaksAtLeastAsMuchAndNoLater) {
  const Outcome& strong = strong_wall();
  const Outcome weak = run_scene(test::fracture_scene(kStrong, 0.45, kEnd), kEnd);
  ASSERT_GE(weak.first, 0);
  EXPECT_LE(weak.first, strong.first);
  EXPECT_GE(fragments(weak), fragments(strong));
}

TEST(Fracture, CalibrationFragilePlateBreaksWhereTheWallHolds) {
  // docs/scene.md "Fracture": at 0.02 m the wall (frc 0.97) holds up to 4 m/s and
  // breaks from 5 m/s; the fragile plate's material (0.45) breaks at 4 m/s.
  const Outcome wall = run_scene(test::fracture_scene(4.0, 0.97, 0.05), 0.05);
  const Outcome plate = run_scene(test::fracture_scene(4.0, 0.45, 0.05), 0.05);
  EXPECT_TRUE(wall.events.empty());
  EXPECT_FALSE(plate.events.empty());
}

TEST(Fracture, MaxChunksIsNeverExceeded) {
  const Outcome o = run_scene(test::fracture_scene(kStrong, 0.45, kEnd, "[fracture]\nmax_chunks = 3\n"), kEnd);
  EXPECT_FALSE(o.events.empty());
  EXPECT_LE(o.most_active, 3);
  EXPECT_LE(strong_wall().most_active, 64);
}

// The wall alone on its floor, no water: the solver breaks it at given seeds.
struct DryWall {
  test::TempDir dir;
  sim::Setup setup;
  fracture::Piece piece;  // the wall as the solver holds it
  DryWall() {
    test::write_fracture_solids(dir.file(""));
    std::string text = test::fracture_scene(kGentle, 0.97, kEnd, "[fracture]\nmax_chunks = 500\n");
    text.erase(text.find("[[fluid.block]]"), text.find("[[solid]]") - text.find("[[fluid.block]]"));
    setup = test::prepare_text(dir.file(""), text);
    piece = sim::breakable_piece(setup.bodies.at(0));
  }
};

// The fragments a solver made of the wall at its event's seeds against the host's
// split at the same seeds, fragment by fragment.
void expect_host_split(const sim::Solver& solver, const fracture::Piece& piece) {
  ASSERT_EQ(solver.fracture_events().size(), 1u);
  const FractureEvent& e = solver.fracture_events().front();
  const std::vector<fracture::Fragment> host = fracture::split(piece, e.seeds, test::kWallSpacing, test::kWallDensity);
  ASSERT_EQ(e.child_body.size(), host.size());
  for (std::size_t c = 0; c < host.size(); ++c) {
    EXPECT_EQ(e.child_seed[c], host[c].seed);
    EXPECT_EQ(e.child_component[c], host[c].component);
    const auto body = e.child_body[c];
    EXPECT_EQ(solver.body_info(body).voxels, static_cast<std::int32_t>(host[c].piece.size())) << "fragment " << c;
    EXPECT_EQ(solver.body(body).mass().center, host[c].mass.center) << "fragment " << c;
  }
}

TEST(Fracture, DevicePartitionIsTheHostsNearestSeed) {
  // 40 seeds anywhere in the wall (ties are improbable): the device decides almost
  // every voxel, and the fragments are the host's.
  DryWall w;
  sim::Solver solver(w.setup, test::shared_context());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ux(0.3, 0.36), uy(0.02, 0.32), uz(0.0, 0.3);
  std::vector<Vec3d> seeds;
  for (int k = 0; k < 40; ++k) seeds.push_back({ux(rng), uy(rng), uz(rng)});
  const int made = solver.break_body(0, seeds);
  test::figure("fragments", made);
  test::figure("voxels decided on the host", static_cast<double>(solver.fracture_host_decided_voxels()));
  EXPECT_GE(made, 10);
  expect_host_split(solver, w.piece);
}

TEST(Fracture, DevicePartitionLeavesNearTiesToTheHost) {
  // Seeds in mirror pairs about planes through voxel centres: whole layers of voxels
  // are as near to two seeds as rounding lets them be; float cannot order those, and
  // the device leaves them to the host, which decides in double.
  DryWall w;
  sim::Solver solver(w.setup, test::shared_context());
  const Vec3d c = w.piece.centers[w.piece.size() / 2];
  const double s = test::kWallSpacing;
  const std::vector<Vec3d> seeds = {c + Vec3d(0, 3 * s, 0), c - Vec3d(0, 3 * s, 0), c + Vec3d(0, 0, 4 * s),
                                    c - Vec3d(0, 0, 4 * s)};
  EXPECT_EQ(solver.break_body(0, seeds), 4);
  test::figure("voxels decided on the host", static_cast<double>(solver.fracture_host_decided_voxels()));
  EXPECT_GT(solver.fracture_host_decided_voxels(), 0);
  expect_host_split(solver, w.piece);
}

TEST(Fracture, BreakingRefusesWhatCannotBreak) {
  DryWall w;
  sim::Solver solver(w.setup, test::shared_context());
  const Vec3d c = w.piece.centers[w.piece.size() / 2];
  EXPECT_EQ(solver.break_body(0, {c}), 0) << "one seed splits nothing";
  EXPECT_EQ(solver.break_body(0, {c, c + Vec3d(0, 0, 5)}), 0) << "a seed whose cell holds no voxel";
  EXPECT_TRUE(solver.fracture_events().empty());
  EXPECT_THROW(solver.break_body(5, {c, c + Vec3d(0, 0.1, 0)}), RunError);
}

TEST(Fracture, SameSceneSameFractures) {
  const Outcome& a = strong_wall();
  const Outcome b = run_scene(test::fracture_scene(kStrong, 0.97, kEnd), kEnd);
  ASSERT_EQ(a.events.size(), b.events.size());
  for (std::size_t e = 0; e < a.events.size(); ++e) {
    EXPECT_EQ(a.events[e].time, b.events[e].time);
    EXPECT_EQ(a.events[e].seeds, b.events[e].seeds);
    EXPECT_EQ(a.events[e].child_body, b.events[e].child_body);
  }
  ASSERT_EQ(a.states.id, b.states.id);
  for (std::size_t k = 0; k < a.states.id.size(); ++k) {
    EXPECT_EQ(a.states.position[k], b.states.position[k]);
    EXPECT_EQ(a.states.linear_velocity[k], b.states.linear_velocity[k]);
  }
}

}  // namespace
}  // namespace bw
