// bw-voronoi as users run it: exit codes, messages, files written and not written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "io/fragments_file.h"
#include "mesh/import.h"
#include "mesh/properties.h"
#include "mesh/shapes.h"
#include "synthetic_run.h"
#include "test_support.h"

namespace {

using bw::test::run;
using bw::test::TempDir;
using bw::test::tool;

const std::string kVoronoi = tool("bw-voronoi");
const std::string kSample = tool("bw-sample");

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

const char* kOctants =
    "0.25 0.25 0.25\n0.75 0.25 0.25\n0.25 0.75 0.25\n0.75 0.75 0.25\n"
    "0.25 0.25 0.75\n0.75 0.25 0.75\n0.25 0.75 0.75\n0.75 0.75 0.75\n";

TEST(BwVoronoi, HelpAndVersion) {
  const auto help = run(kVoronoi + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
  EXPECT_NE(help.out.find("check"), std::string::npos);
  const auto check_help = run(kVoronoi + " check --help");
  EXPECT_EQ(check_help.exit_code, 0);
  for (const char* option : {"--seeds", "--random", "--seed", "--export", "--json", "-o"})
    EXPECT_NE(check_help.out.find(option), std::string::npos) << option;
  const auto version = run(kVoronoi + " --version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.out.find("bw-voronoi "), std::string::npos);
}

TEST(BwVoronoi, CubeWithEightSeedsPassesAndWritesEightFragments) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  write_text(dir.file("seeds.txt"), kOctants);
  const auto r = run(kVoronoi + " check " + dir.file("cube.obj") + " --seeds " + dir.file("seeds.txt") + " -o " +
                     dir.file("cube.h5") + " --export " + dir.file("parts"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("PASS  fragment volumes add up to the mesh volume: relative error "), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("result     pass"), std::string::npos) << r.out;

  const bw::FragmentSet set = bw::read_fragments(dir.file("cube.h5"));
  EXPECT_EQ(set.source, dir.file("cube.obj"));
  EXPECT_NE(set.tool.find("bw-voronoi"), std::string::npos);
  EXPECT_EQ(set.options, "check --seeds " + dir.file("seeds.txt"));
  ASSERT_EQ(set.fragments.size(), 8u);
  EXPECT_EQ(set.seeds.size(), 8u);
  for (const auto& f : set.fragments) EXPECT_NEAR(f.volume, 0.125, 1e-16);

  // One OBJ per fragment, read back by the importer with the same volume.
  EXPECT_EQ(bw::test::list_folder(dir.file("parts")).substr(0, 29), "fragment_0000_seed_0000_0.obj");
  const bw::TriMesh back = bw::mesh::import_mesh(dir.file("parts/fragment_0007_seed_0007_0.obj"));
  // Full precision: the same points (the importer may order them otherwise).
  std::vector<bw::Vec3d> points = back.vertices;
  std::sort(points.begin(), points.end(), [](const bw::Vec3d& a, const bw::Vec3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  EXPECT_EQ(points, set.fragments[7].mesh.vertices);
  EXPECT_NEAR(bw::mesh::mass_properties(back).volume, 0.125, 1e-16);
}

TEST(BwVoronoi, JsonReport) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  write_text(dir.file("seeds.txt"), kOctants);
  const auto r = run(kVoronoi + " check " + dir.file("cube.obj") + " --seeds " + dir.file("seeds.txt") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"result\": \"pass\"", "\"relative_error\": ", "\"fragments_closed\"", "\"given\": 8",
                          "\"status\": \"pass\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing in " << r.out;
}

TEST(BwVoronoi, SeedsOutsideTheMeshAreIgnoredWithAWarning) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  write_text(dir.file("seeds.txt"), std::string(kOctants) + "5 5 5\n");
  const auto r = run(kVoronoi + " check " + dir.file("cube.obj") + " --seeds " + dir.file("seeds.txt"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("bw-voronoi: warning: seed 8 at (5, 5, 5) lies outside the mesh: ignored"), std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("9 given, 8 used, 1 ignored"), std::string::npos) << r.out;
}

TEST(BwVoronoi, OpenMeshIsRejectedAndNothingIsWritten) {
  TempDir dir;
  bw::TriMesh open = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  open.triangles.resize(10);
  bw::mesh::export_mesh(open, dir.file("open.obj"));
  const auto r = run(kVoronoi + " check " + dir.file("open.obj") + " --random 5 -o " + dir.file("out.h5") +
                     " --export " + dir.file("parts"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("open.obj: the mesh does not bound a volume"), std::string::npos) << r.err;
  EXPECT_FALSE(bw::test::exists(dir.file("out.h5")));
  EXPECT_FALSE(bw::test::exists(dir.file("parts")));
  EXPECT_EQ(bw::test::list_folder(dir.path()), "open.obj");
}

TEST(BwVoronoi, SelfIntersectingMeshFailsTheCheckWithExitThree) {
  TempDir dir;
  bw::TriMesh mesh = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  bw::mesh::append(mesh, bw::mesh::box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}));
  bw::mesh::export_mesh(mesh, dir.file("overlap.obj"));
  const auto r = run(kVoronoi + " check " + dir.file("overlap.obj") + " --random 4 --seed 2 --json");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.out.find("\"result\": \"fail\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"status\": \"fail\""), std::string::npos) << r.out;
}

TEST(BwVoronoi, BadUsageAndBadSeedsAreExitTwo) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  const std::string cube = dir.file("cube.obj");
  const auto none = run(kVoronoi + " check " + cube);
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--seeds FILE or --random N"), std::string::npos) << none.err;
  write_text(dir.file("s.txt"), "0.5 0.5 0.5\n");
  EXPECT_EQ(run(kVoronoi + " check " + cube + " --seeds " + dir.file("s.txt") + " --random 3").exit_code, 2);
  EXPECT_EQ(run(kVoronoi + " check " + cube + " --seed 3").exit_code, 2);
  for (const char* count : {"0", "1000001", "1e9"}) {
    const auto r = run(kVoronoi + " check " + cube + " --random " + count);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, fmt::format("bw-voronoi: --random: '{}' must be a number from 1 to 1000000 (see bw-voronoi "
                                 "--help)\n",
                                 count));
  }
  EXPECT_EQ(run(kVoronoi).exit_code, 2);
  write_text(dir.file("bad.txt"), "0.5 0.5 0.5\n0.1 0.2\n");
  const auto bad = run(kVoronoi + " check " + cube + " --seeds " + dir.file("bad.txt"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.txt:2: 2 numbers where a seed needs three"), std::string::npos) << bad.err;
  write_text(dir.file("out.txt"), "3 3 3\n");
  const auto outside = run(kVoronoi + " check " + cube + " --seeds " + dir.file("out.txt"));
  EXPECT_EQ(outside.exit_code, 2);
  EXPECT_NE(outside.err.find("none of the 1 seeds lies inside the mesh"), std::string::npos) << outside.err;
  EXPECT_EQ(run(kVoronoi + " check " + dir.file("missing.obj") + " --random 3").exit_code, 2);
  // The fragments file's folder is checked before the mesh is read and cut.
  const auto nowhere = run(kVoronoi + " check " + dir.file("missing.obj") + " --random 3 -o " + dir.file("no/f.h5"));
  EXPECT_EQ(nowhere.exit_code, 2);
  EXPECT_EQ(nowhere.err, "bw-voronoi: " + dir.file("no/f.h5") + ": folder '" + dir.file("no") + "' does not exist\n");
  const auto folder = run(kVoronoi + " replay " + dir.file("missing.h5") + " -o " + dir.path());
  EXPECT_EQ(folder.exit_code, 2);
  EXPECT_EQ(folder.err, "bw-voronoi: " + dir.path() + ": is a folder, expected a file name\n");
  // An output that is an input, by its name or another, would replace it: refused, the input left whole.
  const std::string mesh = read_text(cube);
  const auto same = run(kVoronoi + " check " + cube + " --random 3 -o " + dir.path() + "/./cube.obj");
  EXPECT_EQ(same.exit_code, 2);
  EXPECT_EQ(same.err, "bw-voronoi: " + dir.path() + "/./cube.obj: is the input file " + cube +
                          " itself; write the output to another file\n");
  EXPECT_EQ(read_text(cube), mesh);
  const auto seeds_file = run(kVoronoi + " check " + cube + " --seeds " + dir.file("s.txt") + " -o " + dir.file("s.txt"));
  EXPECT_EQ(seeds_file.exit_code, 2);
  EXPECT_NE(seeds_file.err.find("is the input file"), std::string::npos) << seeds_file.err;
  std::filesystem::create_symlink(dir.file("s.txt"), dir.file("run.h5"));
  const auto run_file = run(kVoronoi + " replay " + dir.file("s.txt") + " -o " + dir.file("run.h5"));
  EXPECT_EQ(run_file.exit_code, 2);
  EXPECT_NE(run_file.err.find("run.h5: is the input file " + dir.file("s.txt")), std::string::npos) << run_file.err;
  EXPECT_EQ(read_text(dir.file("s.txt")), "0.5 0.5 0.5\n");
}

TEST(BwVoronoi, RandomSeedsAreReproducibleAndTheFileIsTheSame) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::icosphere({0, 0, 0}, 1, 2), dir.file("ball.obj"));
  const std::string base = kVoronoi + " check " + dir.file("ball.obj") + " --random 10 ";
  ASSERT_EQ(run(base + "--seed 4 -o " + dir.file("a.h5")).exit_code, 0);
  ASSERT_EQ(run(base + "--seed 4 --threads 1 -o " + dir.file("b.h5")).exit_code, 0);
  ASSERT_EQ(run(base + "--seed 5 -o " + dir.file("c.h5")).exit_code, 0);
  EXPECT_EQ(run("cmp " + dir.file("a.h5") + " " + dir.file("b.h5")).exit_code, 0);
  EXPECT_NE(run("cmp -s " + dir.file("a.h5") + " " + dir.file("c.h5")).exit_code, 0);
  // The seeds of a fragments file cut the mesh the same way again.
  ASSERT_EQ(run(kVoronoi + " check " + dir.file("ball.obj") + " --seeds " + dir.file("a.h5") + " -o " +
                dir.file("d.h5")).exit_code,
            0);
  const auto a = bw::read_fragments(dir.file("a.h5"));
  const auto d = bw::read_fragments(dir.file("d.h5"));
  EXPECT_EQ(a.seeds, d.seeds);
  ASSERT_EQ(a.fragments.size(), d.fragments.size());
  for (std::size_t i = 0; i < a.fragments.size(); ++i) EXPECT_EQ(a.fragments[i].mesh.vertices, d.fragments[i].mesh.vertices);
}

// A particles file carries its mesh: straight from bw-sample through a pipe, with the
// fragments as PLY files, and the report on stderr when the fragments go to stdout.
TEST(BwVoronoi, ParticlesFileThroughAPipe) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  write_text(dir.file("seeds.txt"), kOctants);
  const auto r = run(kSample + " " + dir.file("cube.obj") + " --spacing 0.25 -o - | " + kVoronoi + " check - --seeds " +
                     dir.file("seeds.txt") + " --export " + dir.file("parts") + " --export-format ply -o - > " +
                     dir.file("f.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("- (particles)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("result     pass"), std::string::npos) << r.err;
  EXPECT_EQ(bw::read_fragments(dir.file("f.h5")).fragments.size(), 8u);
  const bw::TriMesh back = bw::mesh::import_mesh(dir.file("parts/fragment_0003_seed_0003_0.ply"));
  EXPECT_NEAR(bw::mesh::mass_properties(back).volume, 0.125, 1e-6);
}

}  // namespace

namespace {

TEST(BwVoronoiReplay, WritesOneFragmentPerBodyOfTheRun) {
  TempDir dir;
  bw::test::SyntheticRun s = bw::test::make_u_run(dir.file("u.h5"), 0.125);
  s.fracture(0, {{0.5, 2.5, 0.5}, {1.5, 0.5, 0.5}}, 0.1);
  bw::write_run(s.run, dir.file("run.h5"));
  const auto r = run(kVoronoi + " replay " + dir.file("run.h5") + " -o " + dir.file("f.h5") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("\"matched\": 3"), std::string::npos) << r.out;
  const bw::FragmentSet set = bw::read_fragments(dir.file("f.h5"));
  EXPECT_EQ(set.source, dir.file("run.h5"));
  EXPECT_EQ(set.options, "replay");
  ASSERT_EQ(set.fragments.size(), 3u);
  std::vector<std::int32_t> bodies;
  for (const auto& f : set.fragments) bodies.push_back(f.body);
  std::sort(bodies.begin(), bodies.end());
  EXPECT_EQ(bodies, (std::vector<std::int32_t>{1, 2, 3}));
}

TEST(BwVoronoiReplay, UnmatchedBodyIsExitThreeAndNamed) {
  TempDir dir;
  bw::test::SyntheticRun s = bw::test::make_u_run(dir.file("u.h5"), 0.125);
  s.fracture(0, {{0.5, 2.5, 0.5}, {1.5, 0.5, 0.5}}, 0.1);
  s.run.bodies.push_back(s.run.bodies[1]);
  s.run.fractures[0].child_body.push_back(4);
  s.run.fractures[0].child_seed.push_back(1);
  s.run.fractures[0].child_component.push_back(1);
  bw::write_run(s.run, dir.file("run.h5"));
  const auto r = run(kVoronoi + " replay " + dir.file("run.h5") + " -o " + dir.file("f.h5"));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("body 4     event 0, seed 1: the exact cut gives seed 1"), std::string::npos) << r.out;
  EXPECT_EQ(bw::read_fragments(dir.file("f.h5")).fragments.size(), 3u);
  // Not a run file: bad input, nothing written.
  const auto wrong = run(kVoronoi + " replay " + dir.file("u.h5") + " -o " + dir.file("g.h5"));
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("particles"), std::string::npos) << wrong.err;
  EXPECT_FALSE(bw::test::exists(dir.file("g.h5")));
}

}  // namespace
