// bw-sample and bw-info as users run them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/frame_file.h"
#include "io/h5.h"
#include "io/particles_file.h"
#include "mesh/import.h"
#include "mesh/shapes.h"
#include "test_support.h"

namespace {

using bw::test::run;
using bw::test::TempDir;
using bw::test::tool;

const std::string kSample = tool("bw-sample");
const std::string kInfo = tool("bw-info");

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(BwSample, HelpAndVersion) {
  const auto help = run(kSample + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("Examples:"), std::string::npos);
  EXPECT_NE(help.out.find("--spacing"), std::string::npos);
  const auto version = run(kSample + " --version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.out.find("bw-sample "), std::string::npos);
}

TEST(BwSample, SamplesAndDescribesThroughAPipe) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  const auto piped = run(kSample + " " + dir.file("cube.obj") + " --spacing 0.125 --volume -o - | " + kInfo + " - --json");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_NE(piped.out.find("\"kind\": \"particles\""), std::string::npos) << piped.out;
  EXPECT_NE(piped.out.find("\"surface_particles\": 296"), std::string::npos) << piped.out;
  EXPECT_NE(piped.out.find("\"voxels\": 512"), std::string::npos) << piped.out;

  // The same bytes as a file written directly.
  const auto to_file = run(kSample + " " + dir.file("cube.obj") + " --spacing 0.125 --volume -o " + dir.file("a.h5"));
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  EXPECT_TRUE(to_file.err.empty()) << "quiet without -v: " << to_file.err;
  const auto to_stdout = run(kSample + " " + dir.file("cube.obj") + " --spacing 0.125 --volume -o - > " + dir.file("b.h5"));
  ASSERT_EQ(to_stdout.exit_code, 0);
  EXPECT_EQ(run("cmp " + dir.file("a.h5") + " " + dir.file("b.h5")).exit_code, 0);
  const auto solid = bw::read_particles(dir.file("b.h5"));
  EXPECT_EQ(solid.voxels.size(), 512u);
}

// A file system that takes no more ends a tool with one line and exit 1: no crash, no
// temporary file. A file size limit stands in for a full disk (it needs no root; the
// write fails with EFBIG where a full disk gives ENOSPC). HDF5's clean-up at exit
// crashed here, closing again a file whose close had failed.
TEST(BwSample, AFullDiskIsOneLineAndLeavesNothing) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  const auto r = run("bash -c 'ulimit -f 100; trap \"\" XFSZ; exec " + kSample + " " + dir.file("cube.obj") +
                     " --spacing 0.02 --volume -o " + dir.file("out.h5") + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(bw::test::list_folder(dir.path()), "cube.obj");
}

// Process substitution hands a tool a pipe by name (/dev/fd/N), which HDF5 and assimp
// cannot seek in: the tools read it through a temporary copy, which they remove.
TEST(BwSample, ReadsMeshesAndParticleFilesFromPipesByName) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  const std::string tmp = "TMPDIR=" + dir.file("tmp") + " ";
  std::filesystem::create_directories(dir.file("tmp"));
  const auto piped = run("bash -c '" + tmp + kSample + " <(cat " + dir.file("cube.obj") + ") --spacing 0.125 --volume -o " +
                         dir.file("a.h5") + " && " + tmp + kInfo + " <(cat " + dir.file("a.h5") + ") --json'");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_NE(piped.out.find("\"kind\": \"particles\""), std::string::npos) << piped.out;
  EXPECT_NE(piped.out.find("\"voxels\": 512"), std::string::npos) << piped.out;
  EXPECT_EQ(bw::test::list_folder(dir.file("tmp")), "");
  // Stopped by a signal while it reads the pipe, a tool leaves no copy behind either.
  const auto stopped = run("bash -c '" + tmp + "timeout -s INT 1 " + kInfo + " <(cat " + dir.file("a.h5") +
                           "; exec sleep 3 2> /dev/null)'");
  EXPECT_EQ(stopped.exit_code, 124) << stopped.err;
  EXPECT_EQ(bw::test::list_folder(dir.file("tmp")), "");
  const auto garbage = run("bash -c '" + kInfo + " <(echo not hdf5)'");
  EXPECT_EQ(garbage.exit_code, 2);
  EXPECT_NE(garbage.err.find(": not an HDF5 file"), std::string::npos) << garbage.err;
  EXPECT_EQ(bw::test::line_count(garbage.err), 1) << garbage.err;
}

TEST(BwSample, VerbosePrintsCountsBoundsAndVolumes) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::icosphere({0, 0, 0}, 0.5, 3), dir.file("ball.ply"));
  const auto r = run(kSample + " " + dir.file("ball.ply") + " --spacing 0.05 --volume --scale 2 -v -o " + dir.file("ball.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* word : {"surface", "voxels", "mesh volume", "bounds", "grid", "spacing 0.05", "scale 2"}) {
    EXPECT_NE(r.err.find(word), std::string::npos) << word << " missing in: " << r.err;
  }
  EXPECT_NE(r.err.find("[-1, -1, -1]"), std::string::npos) << "scaled bounds: " << r.err;
}

TEST(BwInfo, DescribesEveryKindAndRefusesForeignFiles) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 2, 3}), dir.file("box.stl"));
  ASSERT_EQ(run(kSample + " " + dir.file("box.stl") + " --spacing 0.5 -o " + dir.file("box.h5")).exit_code, 0);
  const auto text = run(kInfo + " " + dir.file("box.h5"));
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_NE(text.out.find("kind: particles"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("/surface/position"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("not sampled"), std::string::npos) << text.out;

  // A frame: the water's fields, and the boundary's count and what it holds (the wall
  // pressure bw-render colours the solids by).
  bw::FrameData frame;
  frame.x = frame.y = frame.z = {0.5f, 0.6f};
  frame.p = {10, 20};
  frame.bx = frame.by = frame.bz = {0, 1, 2};
  frame.bp = {0, 5, 0};
  frame.bsolid = {0, 0, 1};
  bw::write_frame(frame, dir.file("frame.h5"));
  const auto described = run(kInfo + " " + dir.file("frame.h5"));
  EXPECT_EQ(described.exit_code, 0) << described.err;
  EXPECT_NE(described.out.find("fields: p x y z\n"), std::string::npos) << described.out;
  EXPECT_NE(described.out.find("boundary_count: 3\n"), std::string::npos) << described.out;
  EXPECT_NE(described.out.find("boundary_fields: p solid x y z\n"), std::string::npos) << described.out;

  write_text(dir.file("notes.txt"), "hello\n");
  const auto foreign = run(kInfo + " " + dir.file("notes.txt"));
  EXPECT_EQ(foreign.exit_code, 2);
  EXPECT_EQ(bw::test::line_count(foreign.err), 1) << foreign.err;
  EXPECT_NE(foreign.err.find("not an HDF5 file"), std::string::npos);
}

// Every bad input: exit code 2, one line naming the file and the problem, and no
// output file (nor a temporary one) left behind; an existing output stays as it was.
struct BadInput {
  std::string name;
  std::string args;       // after the tool name; {dir} is replaced by the folder
  std::string expected;   // a part of the message
};

// Test names and failure messages show the case's name, not its bytes.
void PrintTo(const BadInput& input, std::ostream* os) { *os << input.name; }

class BwSampleBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(BwSampleBadInput, OneLineExitTwoNoOutput) {
  TempDir dir;
  bw::mesh::export_mesh(bw::mesh::box({0, 0, 0}, {1, 1, 1}), dir.file("cube.obj"));
  auto open = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  open.triangles.resize(open.triangles.size() - 2);
  bw::mesh::export_mesh(open, dir.file("open.obj"));
  auto misoriented = bw::mesh::box({0, 0, 0}, {1, 1, 1});
  std::swap(misoriented.triangles[0][1], misoriented.triangles[0][2]);
  bw::mesh::export_mesh(misoriented, dir.file("flipped.obj"));
  write_text(dir.file("empty.obj"), "");
  write_text(dir.file("malformed.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2\n");
  write_text(dir.file("nan.obj"), "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n");
  {
    bw::h5::File f = bw::h5::File::create(dir.file("frame.h5"), "frame");
    f.commit();
  }
  write_text(dir.file("out.h5"), "previous");

  std::string args = GetParam().args;
  for (std::size_t at; (at = args.find("{dir}")) != std::string::npos;) args.replace(at, 5, dir.path());
  const auto r = run(kSample + " " + args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(bw::test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().expected), std::string::npos) << r.err;
  EXPECT_EQ(r.err.rfind("bw-sample: ", 0), 0u) << r.err;
  const std::string files = bw::test::list_folder(dir.path());
  EXPECT_EQ(files, "cube.obj empty.obj flipped.obj frame.h5 malformed.ply nan.obj open.obj out.h5") << files;
  std::ifstream in(dir.file("out.h5"));
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), "previous");
}

INSTANTIATE_TEST_SUITE_P(
    Inputs, BwSampleBadInput,
    ::testing::Values(
        BadInput{"missing", "{dir}/missing.obj -o {dir}/out.h5 --spacing 0.1", "missing.obj: cannot open"},
        BadInput{"empty", "{dir}/empty.obj -o {dir}/out.h5 --spacing 0.1", "empty.obj: empty file"},
        BadInput{"malformed", "{dir}/malformed.ply -o {dir}/out.h5 --spacing 0.1", "malformed.ply"},
        BadInput{"nonfinite", "{dir}/nan.obj -o {dir}/out.h5 --spacing 0.1", "non-finite"},
        BadInput{"hdf5_instead_of_mesh", "{dir}/frame.h5 -o {dir}/out.h5 --spacing 0.1", "frame.h5"},
        BadInput{"zero_spacing", "{dir}/cube.obj -o {dir}/out.h5 --spacing 0", "--spacing"},
        BadInput{"negative_spacing", "{dir}/cube.obj -o {dir}/out.h5 --spacing -0.5", "--spacing"},
        BadInput{"text_spacing", "{dir}/cube.obj -o {dir}/out.h5 --spacing abc", "--spacing"},
        BadInput{"too_small_spacing", "{dir}/cube.obj -o {dir}/out.h5 --spacing 1e-6 --volume", "would need"},
        BadInput{"open_volume", "{dir}/open.obj -o {dir}/out.h5 --spacing 0.1 --volume", "4 boundary edges"},
        BadInput{"flipped_volume", "{dir}/flipped.obj -o {dir}/out.h5 --spacing 0.1 --volume",
                 "3 inconsistently oriented edges"},
        BadInput{"missing_output_folder", "{dir}/cube.obj -o {dir}/no/such/out.h5 --spacing 0.1", "does not exist"},
        // The output is checked before the mesh is read, not after the sampling.
        BadInput{"missing_output_folder_first", "{dir}/missing.obj -o {dir}/no/such/out.h5 --spacing 0.1",
                 "/no/such/out.h5: folder '"},
        BadInput{"output_is_a_folder", "{dir}/missing.obj -o {dir} --spacing 0.1", "is a folder, expected a file name"},
        // The mesh itself, under another name: refused before it is read, so it stays whole.
        BadInput{"output_is_the_mesh", "{dir}/cube.obj -o {dir}/./cube.obj --spacing 0.1",
                 "cube.obj itself; write the output to another file"},
        BadInput{"unknown_option", "{dir}/cube.obj -o {dir}/out.h5 --spacing 0.1 --bogus", "--bogus"},
        BadInput{"no_spacing", "{dir}/cube.obj -o {dir}/out.h5", "--spacing"}),
    [](const auto& test) { return test.param.name; });

}  // namespace
