// Emitters inject the particles their flow rate gives (area x speed x time / spacing^3,
// up to the lattice of the emitter's face), stop at max_particles, and walls stop
// particles shot at them at any speed up to c0.
#include <cmath>
#include <fstream>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "io/frame_file.h"
#include "io/particles_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"
#include "io/run_file.h"
#include "scene/scene.h"
#include "sim/setup.h"
#include "sim_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {

constexpr double kSpacing = 0.01;

std::string emitter_scene(const std::string& emitter, const std::string& fluid_extra = "") {
  return R"(
spacing = 0.01
gravity = [0, 0, 0]
[time]
end = 0.5
frame_rate = 20
[domain]
min = [-0.3, -0.3, -0.1]
max = [0.3, 0.3, 1.0]
[fluid]
c0 = 20
)" + fluid_extra + R"(
[[fluid.emitter]]
)" + emitter;
}

TEST(Emitter, DiscInjectsWhatItsFlowRateGives) {
  test::TempDir dir;
  const double radius = 0.05, speed = 1.0, start = 0.1, stop = 0.4;
  std::ofstream(dir.file("disc.toml")) << emitter_scene(
      "shape = \"disc\"\ncenter = [0, 0, 0]\nnormal = [0, 0, 1]\nradius = 0.05\nspeed = 1.0\nstart = 0.1\nstop = 0.4\n");
  const scene::Scene scene = scene::load_scene(dir.file("disc.toml"));
  const std::size_t per_layer = sim::emitter_points(scene.emitters.at(0), kSpacing).size();
  const sim::RunSummary summary = test::run_scene(dir.file("disc.toml"), dir.file("out"));
  const RunRecord run = read_run(dir.file("out/run.h5"));

  // One layer each time the fluid has moved one spacing.
  const auto layers = static_cast<std::size_t>(std::floor(speed * (stop - start) / kSpacing + 1e-9));
  const double flow = std::numbers::pi * radius * radius * speed * (stop - start) / std::pow(kSpacing, 3);
  test::figure("particles per layer", static_cast<double>(per_layer));
  test::figure("injected", static_cast<double>(summary.fluid_end));
  test::figure("area x speed x time / spacing^3", flow);
  EXPECT_EQ(summary.fluid_end, static_cast<std::int64_t>(layers * per_layer));
  EXPECT_NEAR(static_cast<double>(summary.fluid_end) / flow, 1.0, 0.05) << "the disc's lattice covers its area";
  EXPECT_FALSE(summary.emitters_capped);

  // Over time: nothing before start, the rate in between, nothing after stop.
  for (const FrameStats& s : run.frames) {
    const double active = std::clamp(s.time, start, stop) - start;
    const auto expected = static_cast<std::int64_t>(std::floor(speed * active / kSpacing + 1e-9) * per_layer);
    EXPECT_NEAR(static_cast<double>(s.fluid), static_cast<double>(expected), static_cast<double>(per_layer))
        << "t = " << s.time;
  }
  // Without gravity the jet coasts at the emitter's speed, layers one spacing apart.
  const FrameData last = read_frame(frame_file_name(dir.file("out/frames"), 10));
  float zmax = 0;
  for (std::size_t i = 0; i < last.fluid_count(); ++i) {
    zmax = std::max(zmax, last.z[i]);
    EXPECT_NEAR(last.vz[i], speed, 1e-3 * speed);
  }
  EXPECT_NEAR(zmax, speed * (0.5 - start) - kSpacing, 0.5 * kSpacing) << "first layer left at start + spacing / speed";
}

TEST(Emitter, RectangleAndMaxParticles) {
  test::TempDir dir;
  std::ofstream(dir.file("rect.toml")) << emitter_scene(
      "shape = \"rectangle\"\ncenter = [0, 0, 0.2]\nnormal = [0, 0, 1]\nsize = [0.08, 0.05]\nup = [1, 0, 0]\nspeed = 1.0\n",
      "max_particles = 1000\n");
  const sim::RunSummary summary = test::run_scene(dir.file("rect.toml"), dir.file("out"));
  // 8 x 5 points per layer, 50 layers over 0.5 s at 1 m/s: 2000 wanted, 1000 allowed.
  test::figure("injected (max_particles 1000)", static_cast<double>(summary.fluid_end));
  EXPECT_EQ(summary.fluid_end, 1000);
  EXPECT_TRUE(summary.emitters_capped);
  const FrameData d = read_frame(frame_file_name(dir.file("out/frames"), 2));
  ASSERT_EQ(d.fluid_count(), 8u * 5u * 10u) << "t = 0.1 s: 10 layers of 8 x 5";
  float xmin = 1, xmax = -1, ymin = 1, ymax = -1;
  for (std::size_t i = 0; i < d.fluid_count(); ++i) {
    xmin = std::min(xmin, d.x[i]), xmax = std::max(xmax, d.x[i]);
    ymin = std::min(ymin, d.y[i]), ymax = std::max(ymax, d.y[i]);
  }
  EXPECT_NEAR(ymax - ymin, 0.07, 2e-3) << "size[0] along up x normal";
  EXPECT_NEAR(xmax - xmin, 0.04, 2e-3) << "size[1] along up";
}

// A jet falling from an emitter 0.5 m up, 0.6 m above the domain's floor, for `end`
// seconds (its first layer reaches the floor after 0.27 s).
std::string falling_jet(double end) {
  std::string text = emitter_scene(
      "shape = \"disc\"\ncenter = [0, 0, 0.5]\nnormal = [0, 0, -1]\nradius = 0.03\nspeed = 1.0\n");
  text.replace(text.find("gravity = [0, 0, 0]"), 19, "gravity = [0, 0, -9.81]");
  text.replace(text.find("end = 0.5"), 9, fmt::format("end = {}", end));
  return text;
}

// The largest |kinetic + potential + elastic - emitted + outflow| over the frames: what
// a scene keeps, up to its losses.
double worst_imbalance(const RunRecord& run) {
  double worst = 0;
  for (const FrameStats& s : run.frames)
    worst = std::max(worst, std::abs(s.kinetic_energy + s.potential_energy + s.elastic_energy - s.emitted_energy +
                                     s.outflow_energy));
  return worst;
}

// What the emitters put in is counted (FrameStats::emitted_energy): the kinetic and
// potential energy of the particles they make and the work of holding them at their
// speed. A jet falling freely under gravity then keeps kinetic + potential + elastic
// - emitted at its start, up to the little its pressure and viscosity dissipate.
TEST(Emitter, FallingJetKeepsItsEnergyBeyondWhatTheEmitterPutIn) {
  test::TempDir dir;
  const double speed = 1.0, end = 0.2;  // the first layer falls 0.4 m of the 0.6 m below the emitter
  std::ofstream(dir.file("jet.toml")) << falling_jet(end);
  const sim::RunSummary summary = test::run_scene(dir.file("jet.toml"), dir.file("out"));
  const RunRecord run = read_run(dir.file("out/run.h5"));
  ASSERT_EQ(summary.removed, 0) << "the jet stays in the domain";
  const sim::Setup setup = sim::prepare(scene::load_scene(dir.file("jet.toml")), end);
  const double m = setup.params.mass;
  const FrameStats& last = run.frames.back();
  // What the particles got at birth alone (at z = 0.5, 0.6 m above the domain's
  // floor, the potential's zero), without the work of holding them: the emitter holds
  // each over h = 2 spacings, against gravity and the jet's pressure.
  const double born = static_cast<double>(last.fluid) * m * (0.5 * speed * speed + 9.81 * 0.6);
  const double worst = worst_imbalance(run);
  test::figure("particles", static_cast<double>(last.fluid));
  test::figure("emitted energy", last.emitted_energy, "J");
  test::figure("kinetic and potential energy at birth, no holding", born, "J");
  test::figure("largest |kinetic + potential + elastic - emitted| over the frames / emitted", worst / last.emitted_energy);
  test::figure("energy growth (run summary)", summary.energy_growth());
  test::figure("energy drift (run summary)", summary.energy_drift());
  // Holding the falling particles takes energy from them: without that term the
  // total would read higher than what was put in.
  EXPECT_LT(last.emitted_energy, born);
  EXPECT_EQ(last.outflow_energy, 0);
  EXPECT_LT(worst, 2e-3 * last.emitted_energy);
  EXPECT_LT(summary.energy_growth(), 1e-3);
  EXPECT_NEAR(summary.emitted_energy, last.emitted_energy, 1e-12);
}

// Particles leaving the domain take their energy with them (outflow_energy): the same
// jet, long enough to fall out through the floor, keeps the balance.
TEST(Emitter, JetLeavingTheDomainCarriesItsEnergyOut) {
  test::TempDir dir;
  std::ofstream(dir.file("jet.toml")) << falling_jet(0.45);
  const sim::RunSummary summary = test::run_scene(dir.file("jet.toml"), dir.file("out"));
  const RunRecord run = read_run(dir.file("out/run.h5"));
  const FrameStats& last = run.frames.back();
  const double worst = worst_imbalance(run);
  test::figure("particles left the domain", static_cast<double>(summary.removed));
  test::figure("outflow energy / emitted", last.outflow_energy / last.emitted_energy);
  test::figure("largest imbalance over the frames / emitted", worst / last.emitted_energy);
  test::figure("energy drift (run summary)", summary.energy_drift());
  ASSERT_GT(summary.removed, 100);
  EXPECT_GT(last.outflow_energy, 0.1 * last.emitted_energy);
  EXPECT_LT(worst, 2e-3 * last.emitted_energy);
  EXPECT_LT(summary.energy_growth(), 1e-3);
  EXPECT_NEAR(summary.outflow_energy, last.outflow_energy, 1e-12);
}

// With either density scheme and either wall: with the continuity equation a particle
// that leaves a wall must get back the density it had before it came (a lone particle
// that kept its compression hit the next wall harder and came back faster, until it
// blew up), and the steps must follow the sound speed of the most compressed particle
// (docs/scene.md, "[time]"): steps sized for c0 gave a block fired into a corner
// +161% of its energy with the mirrored wall and +768% with the hydrostatic one.
class Walls : public ::testing::TestWithParam<const char*> {};

TEST_P(Walls, StopParticlesShotAtThemUpToTheSpeedOfSound) {
  const std::string keys = GetParam();
  test::TempDir dir;
  test::write_tank(dir.file("tank.h5"), {10, 10, 10}, kSpacing);
  // Single particles and small blocks aimed at walls, edges and corners, straight
  // onto a wall particle and between them, up to c0 = 30 m/s.
  const char* shots[][2] = {{"[0.05, 0.05, 0.05], [0.06, 0.06, 0.06]", "[0, 0, 30]"},
                            {"[0.045, 0.045, 0.045], [0.055, 0.055, 0.055]", "[0, 0, 29]"},
                            {"[0.045, 0.045, 0.045], [0.055, 0.055, 0.055]", "[-20, -10, 25]"},
                            {"[0.03, 0.03, 0.03], [0.07, 0.07, 0.07]", "[17, 17, 17]"},
                            {"[0.02, 0.02, 0.02], [0.05, 0.08, 0.08]", "[-25, 3, 0]"}};
  int k = 0;
  for (const auto& shot : shots) {
    const std::string name = "shot" + std::to_string(k++);
    std::string box(shot[0]);
    const std::size_t split = box.find("], [");
    std::ofstream(dir.file(name + ".toml"))
        << "spacing = 0.01\ngravity = [0, 0, 0]\n[time]\nend = 0.03\nframe_rate = 100\n[domain]\n"
           "min = [-0.03, -0.03, -0.03]\nmax = [0.14, 0.14, 0.14]\n[fluid]\nc0 = 30\n"
        << keys << "\n[[fluid.block]]\nmin = "
        << box.substr(0, split + 1) << "\nmax = " << box.substr(split + 3) << "\nvelocity = " << shot[1]
        << "\n[[solid]]\nparticles = \"tank.h5\"\n";
    const sim::RunSummary summary = test::run_scene(dir.file(name + ".toml"), dir.file(name));
    EXPECT_EQ(summary.removed, 0) << name << ": block " << shot[0] << " at " << shot[1] << " m/s";
    const RunRecord run = read_run(dir.file(name + "/run.h5"));
    const double kinetic = run.frames.back().kinetic_energy / run.frames.front().kinetic_energy;
    test::figure(name + ": energy at the end / at the start - 1", summary.energy_drift());
    test::figure(name + ": kinetic energy at the end / at the start", kinetic);
    test::figure(name + ": elastic energy at the end / kinetic at the start",
                 run.frames.back().elastic_energy / run.frames.front().kinetic_energy);
    // Walls only take energy: bounces are inelastic (the contact, the friction). With
    // the continuity equation a block that compressed and flew apart keeps some of its
    // density (docs/scene.md, "Density"): its total counts that elastic energy, which
    // no longer moves anything, and still may not grow.
    EXPECT_LT(kinetic, 1) << name;
    EXPECT_LT(summary.energy_drift(), 0) << name;
    const FrameData d = read_frame(frame_file_name(dir.file(name + "/frames"), 3));
    for (std::size_t i = 0; i < d.fluid_count(); ++i) {
      const Vec3d q(d.x[i], d.y[i], d.z[i]);
      EXPECT_TRUE((q.array() > 0.005).all() && (q.array() < 0.105).all()) << name << ": " << q.transpose();
    }
  }
}

// A particle a little behind the plane of a solid's top particles, moving down. A solid
// sampled with its volume has its surface half a spacing above those particles: the
// particle is in the surface's layer and may only leave it upward (a particle pressed
// past the plane used to be held there, and let sink). A box's surface sampled alone
// is a tank's wall, wetted inside: below its top particles the particle is inside the
// tank and falls freely.
class SurfaceLayer : public ::testing::TestWithParam<bool> {};

TEST_P(SurfaceLayer, ParticleBehindATopPatchSinksOnlyIntoATank) {
  const bool volume = GetParam();
  test::TempDir dir;
  SampledSolid box = sample::sample_mesh(mesh::box(Vec3d::Zero(), Vec3d::Constant(0.06)),
                                         {kSpacing, volume, "box", 1.0});
  write_particles(box, dir.file("box.h5"), "emitter test");
  // The top face's particles lie at z = 0.055; the particle starts at 0.0535, 0.15
  // spacings below them, between four of them.
  std::ofstream(dir.file("layer.toml"))
      << "spacing = 0.01\ngravity = [0, 0, 0]\n[time]\nend = 0.02\nframe_rate = 100\n[domain]\n"
         "min = [-0.03, -0.03, -0.03]\nmax = [0.09, 0.09, 0.09]\n[fluid]\nc0 = 20\n"
         "[[fluid.block]]\nmin = [0.025, 0.025, 0.0485]\nmax = [0.035, 0.035, 0.0585]\nvelocity = [0, 0, -1]\n"
         "[[solid]]\nparticles = \"box.h5\"\n";
  test::run_scene(dir.file("layer.toml"), dir.file("layer"));
  const FrameData start = read_frame(frame_file_name(dir.file("layer/frames"), 0));
  const FrameData end = read_frame(frame_file_name(dir.file("layer/frames"), 2));
  ASSERT_EQ(start.fluid_count(), 1u);
  ASSERT_EQ(end.fluid_count(), 1u);
  EXPECT_NEAR(start.z[0], 0.0535, 1e-6);
  test::figure(volume ? "volume: z at 0.02 s" : "surface: z at 0.02 s", end.z[0]);
  if (volume)
    EXPECT_GE(end.z[0], start.z[0] - 1e-5) << "sank into the solid";
  else
    EXPECT_LT(end.z[0], start.z[0] - 0.5 * kSpacing) << "held at the tank's wall from inside";
}

INSTANTIATE_TEST_SUITE_P(Contact, SurfaceLayer, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& param) { return param.param ? "Volume" : "Surface"; });

INSTANTIATE_TEST_SUITE_P(Density, Walls,
                         ::testing::Values("density = \"summation\"", "density = \"continuity\"",
                                           "density = \"continuity\"\nwall_pressure = \"hydrostatic\""));

}  // namespace
}  // namespace bw
