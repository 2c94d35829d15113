// ParaView opens a run as it is: a small bw-sim run with a falling box, read by the
// real pvpython (Debian's python3-paraview) through the index bw-sim writes
// (OUTDIR/run.xdmf2) and then through the index with meshes (bw-voronoi index), every
// time step against the frames as libcore reads them; and a frame file alone through
// ParaView's H5Part reader. Without pvpython the test fails: install-deps installs it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "rigid_fixtures.h"
#include "test_support.h"

namespace bw {
namespace {
namespace fs = std::filesystem;

constexpr int kFrames = 5;  // 0.1 s at 40 frames per second

// What pvpython printed (read_run.py): facts by key, each a list of words.
struct Seen {
  std::vector<double> times;
  std::map<std::string, std::vector<std::string>> facts;  // "kind time block [array]" -> the rest
  std::vector<std::vector<std::string>> frames;           // "frame" lines
  std::string reader;
  std::string text;

  const std::vector<std::string>* find(const std::string& key) const {
    const auto it = facts.find(key);
    return it == facts.end() ? nullptr : &it->second;
  }
};

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Runs read_run.py on the index and the given frame files.
Seen paraview_reads(const std::string& index, const std::vector<std::string>& frames) {
  std::string command = std::string(BW_PVPYTHON) + " --force-offscreen-rendering " + BW_READ_RUN_PY + " " + index;
  for (const auto& f : frames) command += " " + f;
  const test::CommandResult r = test::run("QT_QPA_PLATFORM=offscreen " + command);
  EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.out << r.err;
  Seen seen;
  seen.text = r.out;
  std::istringstream in(r.out);
  std::map<std::string, int> time_index;
  for (std::string line; std::getline(in, line);) {
    const auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "reader" && w.size() == 3) seen.reader = w[2];
    if (w[0] == "times")
      for (std::size_t i = 1; i < w.size(); ++i) time_index[w[i]] = static_cast<int>(i - 1), seen.times.push_back(std::stod(w[i]));
    if (w[0] == "frame") seen.frames.push_back(w);
    if ((w[0] == "block" || w[0] == "points") && w.size() >= 3 && time_index.count(w[1]))
      seen.facts[fmt::format("{} {} {}", w[0], time_index[w[1]], w[2])] = {w.begin() + 3, w.end()};
    if ((w[0] == "array" || w[0] == "first") && w.size() >= 4 && time_index.count(w[1]))
      seen.facts[fmt::format("{} {} {} {}", w[0], time_index[w[1]], w[2], w[3])] = {w.begin() + 4, w.end()};
  }
  return seen;
}

bool close(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)}); }

// The block's point count and coordinate sums are those of x, y, z.
void expect_points(const Seen& seen, int t, const std::string& block, const std::vector<float>& x,
                   const std::vector<float>& y, const std::vector<float>& z) {
  const auto* b = seen.find(fmt::format("block {} {}", t, block));
  ASSERT_TRUE(b) << "no block " << block << " at time " << t << "\n" << seen.text;
  EXPECT_EQ(std::stoul((*b)[0]), x.size()) << block << " at time " << t;
  if (x.empty()) return;
  const auto* p = seen.find(fmt::format("points {} {}", t, block));
  ASSERT_TRUE(p && p->size() == 3) << block;
  const std::vector<float>* c[3] = {&x, &y, &z};
  for (int k = 0; k < 3; ++k) {
    double sum = 0;
    for (float v : *c[k]) sum += v;
    EXPECT_TRUE(close(std::stod((*p)[k]), sum)) << block << " at time " << t << " coordinate " << k << ": "
                                                << (*p)[k] << " vs " << sum;
  }
}

// A field of the block: its centring, tuples, components and component sums.
void expect_field(const Seen& seen, int t, const std::string& block, const std::string& name,
                  const std::vector<std::vector<double>>& components, const char* center = "Node") {
  const auto* a = seen.find(fmt::format("array {} {} {}", t, block, name));
  ASSERT_TRUE(a) << "no field " << name << " in " << block << " at time " << t << "\n" << seen.text;
  ASSERT_EQ(a->size(), 3 + components.size()) << name;
  EXPECT_EQ((*a)[0], center) << name;
  EXPECT_EQ(std::stoul((*a)[1]), components[0].size()) << name;
  EXPECT_EQ(std::stoul((*a)[2]), components.size()) << name;
  for (std::size_t k = 0; k < components.size(); ++k) {
    double sum = 0;
    for (double v : components[k]) sum += v;
    EXPECT_TRUE(close(std::stod((*a)[3 + k]), sum)) << name << " at time " << t << " component " << k << ": "
                                                    << (*a)[3 + k] << " vs " << sum;
  }
}

template <class T>
std::vector<double> doubles(const std::vector<T>& v) {
  return {v.begin(), v.end()};
}

std::vector<double> column(const std::vector<Vec3d>& v, int k) {
  std::vector<double> out;
  for (const Vec3d& p : v) out.push_back(p[k]);
  return out;
}

// Every time of the index against the frames: fluid with its fields, boundary
// particles with their solids and wall pressure, bodies' poses.
void expect_frames(const Seen& seen, const std::string& out) {
  ASSERT_EQ(seen.times.size(), static_cast<std::size_t>(kFrames)) << seen.text;
  for (int f = 0; f < kFrames; ++f) {
    SCOPED_TRACE(fmt::format("frame {}", f));
    const FrameData d = read_frame(frame_file_name(out + "/frames", f));
    EXPECT_NEAR(seen.times[f], d.time, 1e-15);
    expect_points(seen, f, "fluid", d.x, d.y, d.z);
    expect_field(seen, f, "fluid", "velocity", {doubles(d.vx), doubles(d.vy), doubles(d.vz)});
    expect_field(seen, f, "fluid", "density", {doubles(d.rho)});
    expect_field(seen, f, "fluid", "pressure", {doubles(d.p)});
    expect_field(seen, f, "fluid", "id", {doubles(d.id)});
    expect_points(seen, f, "boundary", d.bx, d.by, d.bz);
    expect_field(seen, f, "boundary", "wall_pressure", {doubles(d.bp)});
    expect_field(seen, f, "boundary", "solid", {doubles(d.bsolid)});
    ASSERT_EQ(d.bodies.size(), 1u);
    const auto* b = seen.find(fmt::format("block {} bodies", f));
    ASSERT_TRUE(b) << seen.text;
    EXPECT_EQ((*b)[0], "1");
    const auto* p = seen.find(fmt::format("points {} bodies", f));
    ASSERT_TRUE(p) << seen.text;
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(close(std::stod((*p)[k]), d.bodies.position[0][k])) << (*p)[k];
    expect_field(seen, f, "bodies", "body", {doubles(d.bodies.id)});
    const Eigen::Quaterniond& q = d.bodies.orientation[0];
    expect_field(seen, f, "bodies", "orientation", {{q.w()}, {q.x()}, {q.y()}, {q.z()}});
    expect_field(seen, f, "bodies", "linear_velocity",
                 {column(d.bodies.linear_velocity, 0), column(d.bodies.linear_velocity, 1), column(d.bodies.linear_velocity, 2)});
  }
}

class ParaView : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const test::TempDir& dir = *dir_;
    test::write_open_tank(dir.file("tank.h5"), {0.14, 0.1, 0.12}, 0.03, 0.01);
    test::write_box(dir.file("box.h5"), {0.06, 0.06, 0.04}, 0.01);
    std::ofstream(dir.file("scene.toml"))
        << "spacing = 0.01\n[time]\nend = 0.1\nframe_rate = 40\n[domain]\nmin = [-0.04, -0.04, -0.04]\n"
           "max = [0.18, 0.14, 0.16]\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [0.14, 0.1, 0.03]\n"
           "[[solid]]\nname = \"tank\"\nparticles = \"tank.h5\"\n"
           "[[solid]]\nname = \"crate\"\nparticles = \"box.h5\"\ndynamic = true\ndensity = 600\n"
           "translation = [0.04, 0.02, 0.05]\n"
           "[output]\nfields = [\"velocity\", \"density\", \"pressure\", \"id\", \"boundary\", \"wall_pressure\"]\n";
    sim_ = new test::CommandResult(test::run(test::tool("bw-sim") + " " + dir.file("scene.toml") + " -o " +
                                             dir.file("out") + " --quiet"));
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete dir_;
  }
  void SetUp() override {
    ASSERT_EQ(sim_->exit_code, 0) << sim_->err;
    ASSERT_TRUE(fs::exists(BW_PVPYTHON))
        << "pvpython not found (" << BW_PVPYTHON
        << "): ParaView's tests need Debian's python3-paraview; tools/install-deps.sh installs it, then run cmake again";
  }
  static std::string out() { return dir_->file("out"); }

  static test::TempDir* dir_;
  static test::CommandResult* sim_;
};

test::TempDir* ParaView::dir_ = nullptr;
test::CommandResult* ParaView::sim_ = nullptr;

TEST_F(ParaView, OpensTheIndexOfBwSimAsOneTimeSeries) {
  ASSERT_TRUE(test::exists(out() + "/run.xdmf2"));
  const Seen seen = paraview_reads(out() + "/run.xdmf2", {});
  EXPECT_EQ(seen.reader, "XdmfReader") << seen.text;
  expect_frames(seen, out());
  EXPECT_FALSE(seen.find("block 0 solids")) << "no meshes before bw-voronoi index";
}

TEST_F(ParaView, OpensTheIndexWithTheSolidsAndTheBodiesPlacedAsMeshes) {
  // A fragments file whose one fragment, a tetrahedron, belongs to the crate's body:
  // it stands for the crate's mesh, placed by the body's pose.
  const RunRecord run = read_run(out() + "/run.h5");
  ASSERT_EQ(run.bodies.size(), 1u);
  const Vec3d c = run.bodies[0].reference_center;
  FragmentSet set;
  set.source = out() + "/run.h5";
  Fragment piece;
  piece.mesh.vertices = {c, c + Vec3d(0.02, 0, 0), c + Vec3d(0, 0.02, 0), c + Vec3d(0, 0, 0.02)};
  piece.mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  piece.body = 0;
  piece.seed = 0;
  set.seeds = {c};
  set.fragments = {piece};
  write_fragments(set, dir_->file("fragments.h5"));
  const auto r = test::run(test::tool("bw-voronoi") + " index " + out() + "/run.h5 --fragments " +
                           dir_->file("fragments.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const Seen seen = paraview_reads(out() + "/run.xdmf2", {});
  expect_frames(seen, out());
  // The tank's mesh where the scene puts it (no transform), in every frame.
  const SampledSolid tank = read_particles(dir_->file("tank.h5"));
  std::vector<float> tx, ty, tz;
  for (const Vec3d& v : tank.mesh.vertices) tx.push_back(float(v.x())), ty.push_back(float(v.y())), tz.push_back(float(v.z()));
  for (int f = 0; f < kFrames; ++f) {
    SCOPED_TRACE(fmt::format("frame {}", f));
    expect_points(seen, f, "solids", tx, ty, tz);
    expect_field(seen, f, "solids", "solid", {std::vector<double>(tank.mesh.triangles.size(), 0.0)}, "Cell");
    // The tetrahedron placed: x_world = R (x_ref - c_ref) + position.
    const FrameData d = read_frame(frame_file_name(out() + "/frames", f));
    const Mat3d rot = d.bodies.orientation[0].normalized().toRotationMatrix();
    std::vector<float> x, y, z;
    for (const Vec3d& v : piece.mesh.vertices) {
      const Vec3d w = rot * (v - c) + d.bodies.position[0];
      x.push_back(float(w.x())), y.push_back(float(w.y())), z.push_back(float(w.z()));
    }
    expect_points(seen, f, "body_meshes", x, y, z);
    const auto* b = seen.find(fmt::format("block {} body_meshes", f));
    ASSERT_TRUE(b);
    EXPECT_EQ((*b)[1], "4") << "triangles";
    expect_field(seen, f, "body_meshes", "body", {{0, 0, 0, 0}}, "Cell");
  }
  // The crate fell: its mesh too.
  const auto* first = seen.find("points 0 body_meshes");
  const auto* last = seen.find(fmt::format("points {} body_meshes", kFrames - 1));
  ASSERT_TRUE(first && last);
  EXPECT_LT(std::stod((*last)[2]), std::stod((*first)[2]) - 0.04);
}

TEST_F(ParaView, OpensEveryFrameFileAloneWithItsTime) {
  std::vector<std::string> files;
  for (int f = 0; f < kFrames; ++f) files.push_back(frame_file_name(out() + "/frames", f));
  const Seen seen = paraview_reads(out() + "/run.xdmf2", files);
  ASSERT_EQ(seen.frames.size(), files.size()) << seen.text;
  for (int f = 0; f < kFrames; ++f) {
    const FrameData d = read_frame(files[f]);
    const auto& w = seen.frames[f];
    ASSERT_EQ(w.size(), 5u) << seen.text;
    EXPECT_NEAR(std::stod(w[2]), d.time, 1e-15) << files[f];
    EXPECT_EQ(std::stoul(w[3]), d.fluid_count()) << files[f];
    for (const char* field : {"id", "p", "rho", "vx", "vy", "vz"})
      EXPECT_NE(("," + w[4] + ",").find(std::string(",") + field + ","), std::string::npos) << field << " in " << w[4];
  }
}

}  // namespace
}  // namespace bw
