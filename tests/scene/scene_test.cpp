// Scene files: a full scene is read with every key, defaults are those of
// docs/scene.md, and each bad input is an InputError whose one-line message names
// the file and the key's path.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"
#include "scene/scene.h"
#include "test_support.h"

namespace bw::scene {
namespace {

// A folder with a scene file and an (empty) particle file next to it.
struct SceneFolder {
  test::TempDir dir;
  SceneFolder() { std::ofstream(dir.file("wall.h5")) << "x"; }
  std::string write(const std::string& text, const std::string& name = "scene.toml") const {
    const std::string path = dir.file(name);
    std::ofstream(path) << text;
    return path;
  }
};

const std::string kMinimal = R"(
spacing = 0.02
[time]
end = 1.0
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[fluid.block]]
min = [0.1, 0.1, 0.1]
max = [0.5, 0.5, 0.5]
)";

// The error message of loading `text`, or "" when it loads.
std::string error_of(const SceneFolder& f, const std::string& text) {
  try {
    load_scene(f.write(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const SceneFolder& f, const std::string& text, const std::string& expected) {
  const std::string m = error_of(f, text);
  EXPECT_NE(m.find(expected), std::string::npos) << "message: '" << m << "'\nexpected to contain: '" << expected << "'";
  EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
  EXPECT_NE(m.find("scene.toml"), std::string::npos) << "names the file: " << m;
}

TEST(Scene, MinimalSceneHasDocumentedDefaults) {
  SceneFolder f;
  const Scene s = load_scene(f.write(kMinimal));
  EXPECT_DOUBLE_EQ(s.spacing, 0.02);
  EXPECT_DOUBLE_EQ(s.smoothing_length, 0.04);
  EXPECT_EQ(s.gravity, Vec3d(0, 0, -9.81));
  EXPECT_DOUBLE_EQ(s.time.frame_rate, 60);
  EXPECT_DOUBLE_EQ(s.time.dt_min, 1e-6);
  EXPECT_DOUBLE_EQ(s.time.dt_max, 2e-3);
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.4);
  EXPECT_DOUBLE_EQ(s.time.force_factor, 0.25);
  EXPECT_DOUBLE_EQ(s.time.viscous_factor, 0.125);
  EXPECT_DOUBLE_EQ(s.time.diffusion_factor, 1);
  EXPECT_DOUBLE_EQ(s.time.energy_limit, 0.1) << "the guard on energy, on by default";
  EXPECT_DOUBLE_EQ(s.fluid.rho0, 998);
  EXPECT_EQ(s.fluid.k, 0);
  EXPECT_EQ(s.fluid.c0, 0);
  EXPECT_DOUBLE_EQ(s.fluid.gamma, 7);
  EXPECT_DOUBLE_EQ(s.fluid.mu_b, s.fluid.mu);
  EXPECT_LT(s.fluid.gamma1, 0) << "gamma1 defaults to the calibrated value, resolved by the solver";
  EXPECT_LT(s.fluid.gamma2, 0) << "gamma2 defaults to gamma1 (hydrostatic wall), resolved by the solver";
  EXPECT_EQ(s.fluid.max_particles, 0);
  EXPECT_EQ(s.fluid.density, bw::scene::DensityScheme::continuity);
  EXPECT_DOUBLE_EQ(s.fluid.diffusion, 0.1) << "delta of the density diffusion, on by default";
  EXPECT_EQ(s.fluid.wall_pressure, bw::scene::WallPressure::images);
  EXPECT_EQ(s.fluid.seed, 0) << "no draw: the blocks on their lattice";
  EXPECT_DOUBLE_EQ(s.fluid.jitter, 1e-3);
  EXPECT_FALSE(s.loads);
  ASSERT_EQ(s.blocks.size(), 1u);
  EXPECT_TRUE(s.fields.velocity);
  EXPECT_FALSE(s.fields.density || s.fields.pressure || s.fields.id || s.fields.boundary);
  EXPECT_TRUE(s.solids.empty() && s.emitters.empty());
}

TEST(Scene, ReadsEveryKey) {
  SceneFolder f;
  const Scene s = load_scene(f.write(R"(
spacing = 0.01
smoothing_length = 0.025
gravity = [0, 0, -10]
[time]
end = 2
frame_rate = 30
dt_min = 1e-7
dt_max = 1e-3
cfl = 0.3
force_factor = 0.2
viscous_factor = 0.1
diffusion_factor = 0.05
energy_limit = 0
[domain]
min = [-1, -1, 0]
max = [1, 1, 2]
[fluid]
rho0 = 1000
c0 = 40
gamma = 7
mu = 0.02
mu_b = 0.1
gamma1 = 0.8
gamma2 = 0.6
max_particles = 50000
seed = 4
jitter = 0.01
[[fluid.block]]
min = [0, 0, 0]
max = [0.2, 0.2, 0.2]
velocity = [1, 0, 0]
[[fluid.emitter]]
shape = "disc"
center = [0, 0, 1]
normal = [0, 0, -2]
radius = 0.05
speed = 2
start = 0.1
stop = 0.5
[[fluid.emitter]]
shape = "rectangle"
center = [0.5, 0, 1]
normal = [1, 0, 0]
size = [0.1, 0.05]
up = [0, 0, 1]
speed = 1
[[solid]]
name = "wall"
particles = "wall.h5"
translation = [1, 2, 3]
rotation = [0, 0, 90]
scale = 2
[output]
fields = ["velocity", "density", "pressure", "id", "boundary"]
[camera]
position = [1, 2, 3]
anything = "the renderer's"
[light]
direction = [0, 0, -1]
[render]
width = 640
)"));
  EXPECT_DOUBLE_EQ(s.smoothing_length, 0.025);
  EXPECT_EQ(s.gravity, Vec3d(0, 0, -10));
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.3);
  EXPECT_DOUBLE_EQ(s.time.diffusion_factor, 0.05);
  EXPECT_DOUBLE_EQ(s.time.energy_limit, 0);
  EXPECT_DOUBLE_EQ(s.fluid.c0, 40);
  EXPECT_DOUBLE_EQ(s.fluid.mu_b, 0.1);
  EXPECT_DOUBLE_EQ(s.fluid.gamma2, 0.6);
  EXPECT_EQ(s.fluid.max_particles, 50000);
  EXPECT_EQ(s.fluid.seed, 4);
  EXPECT_DOUBLE_EQ(s.fluid.jitter, 0.01);
  ASSERT_EQ(s.emitters.size(), 2u);
  EXPECT_EQ(s.emitters[0].shape, Emitter::Shape::disc);
  EXPECT_NEAR(s.emitters[0].normal.z(), -1, 1e-12) << "normals are normalized";
  EXPECT_DOUBLE_EQ(s.emitters[0].stop, 0.5);
  EXPECT_TRUE(std::isinf(s.emitters[1].stop)) << "stop defaults to the end of the run";
  EXPECT_EQ(s.emitters[1].size, Eigen::Vector2d(0.1, 0.05));
  ASSERT_EQ(s.solids.size(), 1u);
  EXPECT_EQ(s.solids[0].name, "wall");
  EXPECT_EQ(s.solids[0].particles, f.dir.file("wall.h5")) << "relative to the scene file";
  EXPECT_TRUE(s.solids[0].to_world(Vec3d(1, 0, 0)).isApprox(Vec3d(1, 4, 3), 1e-12)) << "scale, rotate about z, translate";
  EXPECT_TRUE(s.fields.velocity && s.fields.density && s.fields.pressure && s.fields.id && s.fields.boundary);
}

TEST(Scene, RotationIsAboutXThenYThenZ) {
  Solid solid;
  solid.rotation_degrees = Vec3d(90, 0, 90);
  // x-rotation first takes y to z; then z-rotation leaves z alone.
  EXPECT_TRUE(solid.to_world(Vec3d(0, 1, 0)).isApprox(Vec3d(0, 0, 1), 1e-12)) << solid.to_world(Vec3d(0, 1, 0)).transpose();
  // x to x, then z-rotation takes x to y.
  EXPECT_TRUE(solid.to_world(Vec3d(1, 0, 0)).isApprox(Vec3d(0, 1, 0), 1e-12));
}

TEST(Scene, NameDefaultsToTheFileStem) {
  SceneFolder f;
  const Scene s = load_scene(f.write(kMinimal + "[[solid]]\nparticles = \"wall.h5\"\n"));
  EXPECT_EQ(s.solids.at(0).name, "wall");
}

// Loads, sensors and bw-measure find solids by name: a name given twice is refused,
// and solids of one file without names are told apart by a number.
TEST(SceneErrors, SolidNamesAreUnique) {
  SceneFolder f;
  const std::string wall = "[[solid]]\nparticles = \"wall.h5\"\n";
  const Scene s = load_scene(f.write(kMinimal + wall + wall + wall));
  ASSERT_EQ(s.solids.size(), 3u);
  EXPECT_EQ(s.solids[0].name, "wall");
  EXPECT_EQ(s.solids[1].name, "wall-2");
  EXPECT_EQ(s.solids[2].name, "wall-3");
  expect_error(f, kMinimal + wall + "[[solid]]\nparticles = \"wall.h5\"\nname = \"wall\"\n",
               "scene.toml: solid[1].name: 'wall' names solid[0] too");
  expect_error(f, kMinimal + wall + wall + "[[solid]]\nparticles = \"wall.h5\"\nname = \"wall-2\"\n",
               "scene.toml: solid[2].name: 'wall-2' names solid[1] too");
  const Scene named = load_scene(f.write(kMinimal + "[[solid]]\nparticles = \"wall.h5\"\nname = \"wall-2\"\n" + wall +
                                         wall));
  EXPECT_EQ(named.solids[1].name, "wall");
  EXPECT_EQ(named.solids[2].name, "wall-3");
}

TEST(SceneErrors, UnknownKeysNameTheirPath) {
  SceneFolder f;
  expect_error(f, "colour = 3\n" + kMinimal, "scene.toml: colour: unknown key");
  expect_error(f, kMinimal + "colour = 3\n", "scene.toml: fluid.block[0].colour: unknown key");
  expect_error(f, kMinimal + "[fluid]\nviscosity = 1\n", "fluid.viscosity: unknown key");
  expect_error(f, kMinimal + "[[solid]]\nparticles = \"wall.h5\"\nscael = 2\n", "solid[0].scael: unknown key (did you mean 'scale'?)");
  expect_error(f, kMinimal + "[[solid]]\nparticles = \"wall.h5\"\nbreakible = true\n",
               "solid[0].breakible: unknown key (did you mean 'breakable'?)");
  expect_error(f, kMinimal + "[fracture]\nwindw = 0.01\n", "fracture.windw: unknown key (did you mean 'window'?)");
  expect_error(f, kMinimal + "[output]\nfields = [\"speed\"]\n", "output.fields: 'speed' is not a field");
}

TEST(Scene, DensitySchemeAndLoads) {
  SceneFolder f;
  const Scene s = load_scene(f.write(kMinimal + "[fluid]\ndensity = \"continuity\"\ndiffusion = 0.05\n[output]\nloads = true\n"));
  EXPECT_EQ(s.fluid.density, bw::scene::DensityScheme::continuity);
  EXPECT_DOUBLE_EQ(s.fluid.diffusion, 0.05);
  EXPECT_TRUE(s.loads);
  expect_error(f, kMinimal + "[fluid]\ndensity = \"riemann\"\n", "fluid.density: \"riemann\" is not a density scheme");
  expect_error(f, kMinimal + "[fluid]\ndensity = \"continuity\"\ndiffusion = 2\n", "fluid.diffusion: 2 must be between 0");
  expect_error(f, kMinimal + "[fluid]\ndensity = \"summation\"\ndiffusion = 0.1\n",
               "fluid.diffusion: density diffusion needs fluid.density = \"continuity\"");
  EXPECT_EQ(s.fluid.wall_pressure, bw::scene::WallPressure::images) << "the continuity's default wall";
  const Scene m = load_scene(f.write(kMinimal + "[fluid]\ndensity = \"summation\"\n"));
  EXPECT_EQ(m.fluid.wall_pressure, bw::scene::WallPressure::mirrored) << "the summation's only wall";
  const Scene w = load_scene(f.write(kMinimal + "[fluid]\nwall_pressure = \"mirrored\"\n"));
  EXPECT_EQ(w.fluid.wall_pressure, bw::scene::WallPressure::mirrored);
  const Scene g = load_scene(f.write(kMinimal + "[fluid]\nwall_pressure = \"images\"\n"));
  EXPECT_EQ(g.fluid.wall_pressure, bw::scene::WallPressure::images);
  const Scene p = load_scene(f.write(kMinimal + "[fluid]\nwall_pressure = \"hydrostatic\"\n"));
  EXPECT_EQ(p.fluid.wall_pressure, bw::scene::WallPressure::hydrostatic) << "every face a wall of particles";
  expect_error(f, kMinimal + "[fluid]\ndensity = \"summation\"\nwall_pressure = \"images\"\n",
               "fluid.wall_pressure: the images wall pressure needs fluid.density = \"continuity\"");
  expect_error(f, kMinimal + "[fluid]\nwall_pressure = \"adami\"\n", "fluid.wall_pressure: \"adami\" is not a wall pressure");
  expect_error(f, kMinimal + "[fluid]\ndensity = \"summation\"\nwall_pressure = \"hydrostatic\"\n",
               "fluid.wall_pressure: the hydrostatic wall pressure needs fluid.density = \"continuity\"");
  expect_error(f, kMinimal + "[output]\nloads = 1\n", "output.loads: expected true or false");
}

TEST(SceneErrors, OutOfRangeValues) {
  SceneFolder f;
  expect_error(f, "spacing = -0.01\n[time]\nend = 1\n", "spacing: -0.01 must be positive");
  expect_error(f, kMinimal + "[[solid]]\nparticles = \"wall.h5\"\n[[solid]]\nparticles = \"wall.h5\"\n[[solid]]\nparticles = \"wall.h5\"\nscale = -1\n",
               "solid[2].scale: -1 must be positive");
  expect_error(f, kMinimal + "[fluid]\nmax_particles = 0\n", "fluid.max_particles: 0 must be at least 1");
  expect_error(f, kMinimal + "[fluid]\nk = 1000\nc0 = 30\n", "fluid.c0: give either k or c0, not both");
  expect_error(f, kMinimal + "[fluid]\ngamma = 0.5\n", "fluid.gamma: 0.5 must be at least 1");
  expect_error(f, kMinimal + "[fluid]\nmu = -1\n", "fluid.mu: -1 must not be negative");
  expect_error(f, kMinimal + "[fluid]\nseed = -2\n", "fluid.seed: -2 must be 0 (the lattice as it is) or a draw's number");
  expect_error(f, kMinimal + "[fluid]\nseed = 1.5\n", "fluid.seed: 1.5 is not a whole number");
  expect_error(f, kMinimal + "[fluid]\nseed = 3\njitter = 0.5\n", "fluid.jitter: 0.5 is outside (0, 0.1] spacings");
  expect_error(f, kMinimal + "[fluid]\njitter = 0.01\n", "fluid.jitter: moves particles only in a draw: set fluid.seed");
  expect_error(f, "spacing = 0.02\nsmoothing_length = 0.2\n[time]\nend = 1\n", "smoothing_length: 0.2 is 10 spacings");
  expect_error(f, "spacing = 0.02\n[time]\nend = 0\n", "time.end: 0 must be positive");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\ncfl = 2\n", "time.cfl: 2 is outside (0, 1]");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\ndiffusion_factor = 0\n", "time.diffusion_factor: 0 is outside (0, 2]");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\nenergy_limit = -0.1\n",
               "time.energy_limit: -0.1 must be a fraction, 0 or more");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\ndt_min = 1e-3\ndt_max = 1e-4\n", "time.dt_max: 0.0001 is smaller than dt_min");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\n[domain]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n", "domain.max: [1, 0, 1] must exceed min");
  expect_error(f, kMinimal + "[[fluid.block]]\nmin = [0.5, 0.5, 0.5]\nmax = [1.5, 0.6, 0.6]\n", "fluid.block[1]: the block reaches outside the domain");
  expect_error(f, kMinimal + "[[fluid.emitter]]\nshape = \"disc\"\ncenter = [0.5, 0.5, 0.9]\nnormal = [0, 0, -1]\nradius = 0.1\nspeed = 1\nstart = 0.5\nstop = 0.2\n",
               "fluid.emitter[0].stop: 0.2 must be later than start (0.5)");
  expect_error(f, kMinimal + "[[fluid.emitter]]\nshape = \"cone\"\n", "fluid.emitter[0].shape: 'cone' is not \"disc\" or \"rectangle\"");
  expect_error(f, kMinimal + "[[fluid.emitter]]\nshape = \"disc\"\ncenter = [0.5, 0.5, 0.9]\nnormal = [0, 0, 0]\n", "fluid.emitter[0].normal: must not be zero");
}

TEST(Scene, BreakableSolidsAndFractureSettings) {
  SceneFolder f;
  const Scene d = load_scene(f.write(kMinimal + "[[solid]]\nparticles = \"wall.h5\"\nbreakable = true\n"));
  const Solid& w = d.solids.at(0);
  EXPECT_TRUE(w.breakable && w.body() && w.anchored && !w.dynamic);
  EXPECT_DOUBLE_EQ(w.frc, 0.5);
  EXPECT_DOUBLE_EQ(w.density, 2400);
  EXPECT_DOUBLE_EQ(d.fracture.window, 0.005);
  EXPECT_DOUBLE_EQ(d.fracture.energy_scale, FractureSettings{}.energy_scale);
  EXPECT_EQ(d.fracture.max_chunks, 64);
  const Scene s = load_scene(f.write(kMinimal + R"(
[[solid]]
particles = "wall.h5"
breakable = true
frc = 0.97
anchored = false
density = 1800
velocity = [1, 0, 0]
[fracture]
window = 0.01
energy_scale = 3.5
max_chunks = 12
)"));
  const Solid& b = s.solids.at(0);
  EXPECT_TRUE(b.breakable && !b.anchored);
  EXPECT_DOUBLE_EQ(b.frc, 0.97);
  EXPECT_DOUBLE_EQ(b.density, 1800);
  EXPECT_DOUBLE_EQ(b.velocity.x(), 1);
  EXPECT_DOUBLE_EQ(s.fracture.window, 0.01);
  EXPECT_DOUBLE_EQ(s.fracture.energy_scale, 3.5);
  EXPECT_EQ(s.fracture.max_chunks, 12);
  // A scene of a breakable solid needs no fluid.
  EXPECT_NO_THROW(load_scene(f.write("spacing = 0.02\n[time]\nend = 1\n[domain]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n"
                                     "[[solid]]\nparticles = \"wall.h5\"\nbreakable = true\n")));
}

// The names a run of the scene may give its bodies: bodies' solids, and fragments of
// breakable ones as the fracture names them; static solids are no bodies.
TEST(Scene, NamesOfTheBodiesARunMayHave) {
  SceneFolder f;
  const Scene s = load_scene(f.write(kMinimal + "[[solid]]\nparticles = \"wall.h5\"\nname = \"plate\"\nbreakable = true\n"
                                                "[[solid]]\nparticles = \"wall.h5\"\nname = \"crate\"\ndynamic = true\n"
                                                "density = 500\n[[solid]]\nparticles = \"wall.h5\"\nname = \"tank\"\n"));
  for (const char* name : {"plate", "crate", "plate.12", "plate.3.0"}) EXPECT_TRUE(may_have_body(s, name)) << name;
  for (const char* name : {"tank", "crate.1", "plate.", "plate.x", "plate..1", "plate.1.", "plat", ""})
    EXPECT_FALSE(may_have_body(s, name)) << name;
  EXPECT_EQ(body_names(s), "plate, crate");
}

TEST(SceneErrors, BreakableKeys) {
  SceneFolder f;
  const std::string solid = kMinimal + "[[solid]]\nparticles = \"wall.h5\"\n";
  expect_error(f, solid + "breakable = true\nfrc = 0\n", "solid[0].frc: 0 is outside (0, 1]");
  expect_error(f, solid + "breakable = true\nfrc = 1.5\n", "solid[0].frc: 1.5 is outside (0, 1]");
  expect_error(f, solid + "frc = 0.5\n", "solid[0].frc: only for a breakable solid");
  expect_error(f, solid + "anchored = true\n", "solid[0].anchored: only for a breakable solid");
  expect_error(f, solid + "breakable = 1\n", "solid[0].breakable: expected true or false");
  expect_error(f, solid + "breakable = true\ndensity = -3\n", "solid[0].density: -3 must be positive");
  expect_error(f, solid + "breakable = true\nvelocity = [1, 0, 0]\n", "solid[0].velocity: an anchored solid starts at rest");
  expect_error(f, solid + "breakable = true\ndynamic = true\n", "solid[0].anchored: an anchored breakable solid");
  expect_error(f, solid + "density = 1000\n", "solid[0].density: only for a dynamic or breakable solid");
  expect_error(f, kMinimal + "[fracture]\nwindow = 0\n", "fracture.window: 0 must be positive");
  expect_error(f, kMinimal + "[fracture]\nenergy_scale = -1\n", "fracture.energy_scale: -1 must be positive");
  expect_error(f, kMinimal + "[fracture]\nmax_chunks = 0\n", "fracture.max_chunks: 0 must be at least 1");
  expect_error(f, kMinimal + "[fracture]\nmax_chunks = 2.5\n", "fracture.max_chunks: 2.5 is not a whole number");
}

// motion = [[t, vx, vy, vz], ...]: a static solid's velocity at times that do not decrease.
TEST(Scene, MovingSolidKeys) {
  SceneFolder f;
  const std::string solid = kMinimal + "[[solid]]\nparticles = \"wall.h5\"\n";
  const Scene s = load_scene(f.write(solid + "motion = [[0, 0, 0, 4], [0.15, 0, 0, 4], [0.15, 0, 0, 0]]\n"));
  const Solid& gate = s.solids.at(0);
  EXPECT_TRUE(gate.moving() && !gate.body());
  EXPECT_EQ(gate.motion_times, (std::vector<double>{0, 0.15, 0.15}));
  ASSERT_EQ(gate.motion_velocities.size(), 3u);
  EXPECT_EQ(gate.motion_velocities[1], Vec3d(0, 0, 4));
  EXPECT_FALSE(load_scene(f.write(solid)).solids.at(0).moving());
  expect_error(f, solid + "motion = [1, 0, 0, 4]\n", "solid[0].motion[0]: expected [t, vx, vy, vz] (s, m/s), found an integer");
  expect_error(f, solid + "motion = []\n",
               "solid[0].motion: expected rows [t, vx, vy, vz] (s, m/s) or the name of a file of them, found an empty array");
  expect_error(f, solid + "motion = [[0, 0, 4]]\n", "solid[0].motion[0]: expected [t, vx, vy, vz] (s, m/s), found 3 values");
  expect_error(f, solid + "motion = [[0, 0, 0, \"up\"]]\n", "solid[0].motion[0][3]: expected a number");
  expect_error(f, solid + "motion = [[-1, 0, 0, 4]]\n", "solid[0].motion[0]: time -1 s is before the start of the run");
  expect_error(f, solid + "motion = [[0.2, 0, 0, 4], [0.1, 0, 0, 0]]\n",
               "solid[0].motion[1]: time 0.1 s is before the key above's 0.2 s (times must not decrease)");
  expect_error(f, solid + "dynamic = true\ndensity = 500\nmotion = [[0, 0, 0, 4]]\n",
               "solid[0].motion: only for a static solid");
}

// The same keys from a file: one a line, commas or spaces, comments, a header line.
TEST(Scene, MovingSolidKeysFromAFile) {
  SceneFolder f;
  const std::string solid = kMinimal + "[[solid]]\nparticles = \"wall.h5\"\n";
  f.write("# a piston\nt, vx, vy, vz\n0, 0, 0, 0\n\n0.5 0.2 0 0  # at speed\n1.0,0.2,0,0\n", "piston.csv");
  const Solid piston = load_scene(f.write(solid + "motion = \"piston.csv\"\n")).solids.at(0);
  EXPECT_EQ(piston.motion_times, (std::vector<double>{0, 0.5, 1.0}));
  ASSERT_EQ(piston.motion_velocities.size(), 3u);
  EXPECT_EQ(piston.motion_velocities[1], Vec3d(0.2, 0, 0));
  f.write("t omega\n0 0\n1 0.5\n", "flap.csv");
  const Solid flap =
      load_scene(f.write(solid + "angular_motion = \"flap.csv\"\naxis = [0, -2, 0]\npivot = [1, 0, 0]\n")).solids.at(0);
  EXPECT_TRUE(flap.moving() && flap.motion_times.empty());
  EXPECT_EQ(flap.angular_times, (std::vector<double>{0, 1}));
  EXPECT_EQ(flap.angular_rates, (std::vector<double>{0, 0.5}));
  EXPECT_EQ(flap.axis, Vec3d(0, -1, 0));
  EXPECT_EQ(flap.pivot, Vec3d(1, 0, 0));
  EXPECT_EQ(load_scene(f.write(solid + "angular_motion = [[0, 1]]\naxis = [0, 0, 1]\npivot = [0, 0, 0]\n"))
                .solids.at(0).angular_rates,
            (std::vector<double>{1}));

  expect_error(f, solid + "motion = \"none.csv\"\n", "solid[0].motion: none.csv: no such file");
  f.write("# nothing\n\n", "empty.csv");
  expect_error(f, solid + "motion = \"empty.csv\"\n",
               "solid[0].motion: empty.csv holds no keys; expected lines [t, vx, vy, vz] (s, m/s)");
  f.write("t vx vy vz\n0 0 0 0\n0.5 0.2 0\n", "short.csv");
  expect_error(f, solid + "motion = \"short.csv\"\n",
               "solid[0].motion (short.csv line 3): expected [t, vx, vy, vz] (s, m/s), found 3 values");
  f.write("0 0 0 0\n0.5 fast 0 0\n", "word.csv");
  expect_error(f, solid + "motion = \"word.csv\"\n",
               "solid[0].motion (word.csv line 2): 'fast' is not a number; expected [t, vx, vy, vz] (s, m/s)");
  f.write("0 0\n0.5 1\n0.4 0\n", "back.csv");
  expect_error(f, solid + "angular_motion = \"back.csv\"\naxis = [0, 1, 0]\npivot = [0, 0, 0]\n",
               "solid[0].angular_motion (back.csv line 3): time 0.4 s is before the key above's 0.5 s");
  expect_error(f, solid + "angular_motion = [[0, 1, 0]]\naxis = [0, 1, 0]\npivot = [0, 0, 0]\n",
               "solid[0].angular_motion[0]: expected [t, omega] (s, rad/s), found 3 values");
  expect_error(f, solid + "angular_motion = [[0, 1]]\npivot = [0, 0, 0]\n", "solid[0].axis: missing (required with angular_motion");
  expect_error(f, solid + "angular_motion = [[0, 1]]\naxis = [0, 1, 0]\n", "solid[0].pivot: missing (required with angular_motion");
  expect_error(f, solid + "angular_motion = [[0, 1]]\naxis = [0, 0, 0]\npivot = [0, 0, 0]\n",
               "solid[0].axis: [0, 0, 0] has no direction");
  expect_error(f, solid + "axis = [0, 1, 0]\n", "solid[0].axis: only with angular_motion");
  expect_error(f, solid + "dynamic = true\ndensity = 500\nangular_motion = [[0, 1]]\n",
               "solid[0].angular_motion: only for a static solid");
}

TEST(SceneErrors, MissingAndMistypedValues) {
  SceneFolder f;
  expect_error(f, "[time]\nend = 1\n", "spacing: missing (required)");
  expect_error(f, "spacing = 0.02\n", "time: missing");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\n", "domain: missing");
  expect_error(f, "spacing = 0.02\n[time]\nend = 1\n[domain]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n", "the scene has no fluid");
  expect_error(f, "spacing = \"small\"\n", "spacing: expected a number, found a string");
  expect_error(f, "gravity = [0, -9.81]\n" + kMinimal, "scene.toml: gravity: expected an array of 3 numbers, found 2 values");
  expect_error(f, kMinimal + "[fluid]\nmax_particles = 1.5\n", "fluid.max_particles: 1.5 is not a whole number");
  expect_error(f, kMinimal + "[[solid]]\nname = \"x\"\n", "solid[0].particles: missing");
  expect_error(f, kMinimal + "[[solid]]\nparticles = \"nowhere.h5\"\n", "solid[0].particles: nowhere.h5: no such file");
  // A relative path says where it was looked for: the scene's folder, not the working one.
  expect_error(f, kMinimal + "[[solid]]\nparticles = \"../nowhere.h5\"\n",
               "solid[0].particles: ../nowhere.h5: no such file (" +
                   std::filesystem::path(f.dir.path()).parent_path().string() +
                   "/nowhere.h5; a relative path starts at the scene's folder)");
  expect_error(f, kMinimal + "[camera]\n[[camera]]\n", "scene.toml:");
}

TEST(SceneErrors, SyntaxErrorsGiveLineAndColumn) {
  SceneFolder f;
  const std::string m = error_of(f, "spacing = 0.02\n[time\nend = 1\n");
  EXPECT_NE(m.find("scene.toml:2:"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(SceneErrors, MissingSceneFile) {
  try {
    load_scene("/nonexistent/scene.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.toml: no such file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bw::scene
