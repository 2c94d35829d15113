// Overrides of scene keys (bw-sim --set KEY=VALUE): they change exactly the key
// they name, create what is missing on the way, are checked like the file's own
// values with the same messages, and the scene's text records the effective scene.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "scene/scene.h"
#include "test_support.h"

namespace bw::scene {
namespace {

const std::string kScene = R"(
spacing = 0.02
[time]
end = 1.0
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[fluid.block]]
min = [0.1, 0.1, 0.1]
max = [0.5, 0.5, 0.5]
[[solid]]
particles = "wall.h5"
)";

struct Folder {
  test::TempDir dir;
  std::string scene;
  Folder() {
    std::ofstream(dir.file("wall.h5")) << "x";
    std::ofstream(dir.file("tank.h5")) << "x";
    scene = dir.file("scene.toml");
    std::ofstream(scene) << kScene;
  }
  Scene load(const std::vector<std::string>& overrides) const { return load_scene(scene, overrides); }
  std::string error(const std::vector<std::string>& overrides) const {
    try {
      load(overrides);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

void expect_error(const Folder& f, const std::vector<std::string>& overrides, const std::string& expected) {
  const std::string m = f.error(overrides);
  EXPECT_NE(m.find(expected), std::string::npos) << "message: '" << m << "'\nexpected to contain: '" << expected << "'";
  EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
  EXPECT_NE(m.find("scene.toml"), std::string::npos) << "names the file: " << m;
}

TEST(SceneOverrides, ReplaceTheKeysTheyName) {
  Folder f;
  const Scene s = f.load({"spacing=0.01", "time.cfl=0.2", "domain.max[2]=1.5", "fluid.block[0].velocity=[0, 0, -3]",
                          "solid[0].particles=tank.h5", "solid[0].name=\"box\""});
  EXPECT_DOUBLE_EQ(s.spacing, 0.01);
  EXPECT_DOUBLE_EQ(s.smoothing_length, 0.02) << "derived defaults follow the overridden value";
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.2);
  EXPECT_DOUBLE_EQ(s.time.end, 1.0) << "keys not named keep their values";
  EXPECT_EQ(s.domain.max, Vec3d(1, 1, 1.5));
  EXPECT_EQ(s.blocks.at(0).velocity, Vec3d(0, 0, -3));
  EXPECT_EQ(s.blocks.at(0).min, Vec3d(0.1, 0.1, 0.1));
  EXPECT_EQ(s.solids.at(0).particles, f.dir.file("tank.h5")) << "a bare string, relative to the scene file";
  EXPECT_EQ(s.solids.at(0).name, "box");
}

TEST(SceneOverrides, CreateMissingTablesAndAppendElements) {
  Folder f;
  // The scene has no [fluid] table of its own besides the block array, no [output].
  const Scene s = f.load({"fluid.c0=40", "output.fields=[\"density\"]", "fluid.block[1].min=[0.6, 0.6, 0.6]",
                          "fluid.block[1].max=[0.8, 0.8, 0.8]", "fluid.emitter[0]={shape = \"disc\", center = [0.5, 0.5, "
                          "0.9], normal = [0, 0, -1], radius = 0.05, speed = 1}"});
  EXPECT_DOUBLE_EQ(s.fluid.c0, 40);
  EXPECT_TRUE(s.fields.density && !s.fields.velocity);
  ASSERT_EQ(s.blocks.size(), 2u);
  EXPECT_EQ(s.blocks[1].max, Vec3d(0.8, 0.8, 0.8));
  ASSERT_EQ(s.emitters.size(), 1u);
  EXPECT_DOUBLE_EQ(s.emitters[0].radius, 0.05);
}

// KEY+=VALUE appends to an array: an array value's elements, or the value itself; a
// missing array starts with them; a table value appends to an array of tables.
TEST(SceneOverrides, AppendToArrays) {
  Folder f;
  const Scene s = f.load({"output.fields=[\"velocity\"]", "output.fields+=[\"density\", \"pressure\"]",
                          "output.fields += \"wall_pressure\"",
                          "fluid.block+={min = [0.6, 0.6, 0.6], max = [0.8, 0.8, 0.8]}"});
  EXPECT_EQ(s.field_names, (std::vector<std::string>{"velocity", "density", "pressure", "wall_pressure"}));
  EXPECT_TRUE(s.fields.velocity && s.fields.density && s.fields.pressure && s.fields.wall_pressure);
  ASSERT_EQ(s.blocks.size(), 2u);
  EXPECT_EQ(s.blocks[1].min, Vec3d(0.6, 0.6, 0.6));
  // No [output] in the scene: the array starts with the appended values.
  EXPECT_EQ(f.load({"output.fields+=[\"id\"]"}).field_names, (std::vector<std::string>{"id"}));
  expect_error(f, {"spacing+=0.01"}, "--set spacing+=0.01: spacing is a number; += appends to an array");
  expect_error(f, {"domain.max[2]+=1"}, "domain.max[2]: += appends to an array: name the array, domain.max");
  expect_error(f, {"output.fields+=[\"colour\"]"}, "output.fields: 'colour' is not a field");
}

TEST(SceneOverrides, LaterOverridesWin) {
  Folder f;
  EXPECT_DOUBLE_EQ(f.load({"time.cfl=0.2", "time.cfl=0.3"}).time.cfl, 0.3);
}

TEST(SceneOverrides, ValuesAreCheckedLikeTheFilesOwn) {
  Folder f;
  expect_error(f, {"fluid.c0=-1"}, "scene.toml: fluid.c0: -1 must be positive");
  expect_error(f, {"time.cfl=2"}, "scene.toml: time.cfl: 2 is outside (0, 1]");
  expect_error(f, {"fluid.cc0=3"}, "scene.toml: fluid.cc0: unknown key (did you mean 'c0'?)");
  expect_error(f, {"colour=3"}, "scene.toml: colour: unknown key");
  expect_error(f, {"spacing=abc"}, "scene.toml: spacing: expected a number, found a string");
  expect_error(f, {"solid[0].particles=nope.h5"}, "scene.toml: solid[0].particles: nope.h5: no such file");
  expect_error(f, {"fluid.block[0].max=[1, 2]"}, "fluid.block[0].max: expected an array of 3 numbers, found 2 values");
  expect_error(f, {"fluid.block[1].min=[0.6, 0.6, 0.6]"}, "fluid.block[1].max: missing (required)");
}

TEST(SceneOverrides, MalformedOverridesNameThemselves) {
  Folder f;
  expect_error(f, {"fluid.c0"}, "--set fluid.c0: expected KEY=VALUE");
  expect_error(f, {"=3"}, "--set =3: '' is not a key path");
  expect_error(f, {"fluid..c0=3"}, "is not a key path");
  expect_error(f, {"fluid.block[x].min=3"}, "is not a key path");
  expect_error(f, {"spacing="}, "--set spacing=: no value after '='");
  expect_error(f, {"spacing=1e"}, "--set spacing=1e: '1e' is not a TOML value");
  expect_error(f, {"fluid.block[0].min=[0, 0"}, "is not a TOML value");
  expect_error(f, {"fluid.block[3].min=[0, 0, 0]"}, "--set fluid.block[3].min=[0, 0, 0]: fluid.block[3]: the scene has 1");
  expect_error(f, {"fluid.block.min=[0, 0, 0]"}, "fluid.block is an array of tables ([[fluid.block]]); give an index");
  expect_error(f, {"spacing.x=1"}, "--set spacing.x=1: spacing is a number, not a table");
  expect_error(f, {"time[0].end=1"}, "time is a table, not an array");
  expect_error(f, {"fluid.emitter[2].speed=1"}, "the scene has no fluid.emitter; only fluid.emitter[0] can start it");
}

TEST(SceneOverrides, TextIsTheEffectiveScene) {
  Folder f;
  const std::vector<std::string> overrides = {"spacing=0.01", "fluid.c0=33.3", "domain.max[0]=0.7"};
  const Scene s = f.load(overrides);
  EXPECT_EQ(s.text.rfind("# " + f.scene + " with --set spacing=0.01 --set fluid.c0=33.3 --set domain.max[0]=0.7\n", 0),
            0u)
      << s.text;
  // The text alone gives the same scene, to the last bit.
  std::ofstream(f.dir.file("effective.toml")) << s.text;
  const Scene again = load_scene(f.dir.file("effective.toml"));
  EXPECT_EQ(again.spacing, s.spacing);
  EXPECT_EQ(again.fluid.c0, s.fluid.c0);
  EXPECT_EQ(again.domain.max, s.domain.max);
  EXPECT_EQ(again.blocks.at(0).min, s.blocks.at(0).min);
  EXPECT_EQ(again.solids.at(0).particles, s.solids.at(0).particles);
  // Without overrides the text is the file's, comments and all.
  EXPECT_EQ(f.load({}).text, kScene);
}

}  // namespace
}  // namespace bw::scene
