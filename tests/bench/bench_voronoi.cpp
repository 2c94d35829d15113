// Voronoi fragments benchmark: the whole prefracture check (input checks, exact
// cells, corefinement of each cell with the solid, fragment checks) for 100 random
// seeds in meshes of about 20 k triangles: an icosphere (convex) and a torus (cells
// fall apart into several fragments). Prints figures, asserts nothing.
//   bench-voronoi [SEEDS [THREADS]]
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common/terminal.h"
#include "mesh/shapes.h"
#include "test_support.h"
#include "voronoi/check.h"

namespace {

void run(const std::string& name, bw::TriMesh mesh, std::size_t seeds, int threads) {
  const std::size_t triangles = mesh.triangles.size();
  bw::voronoi::CheckOptions options;
  options.source = name;
  options.threads = threads;
  bw::voronoi::SeedChoice choice;
  choice.random = seeds;
  choice.random_seed = 1;
  bw::Stopwatch clock;
  const bw::voronoi::CheckResult r = bw::voronoi::prefracture_check(std::move(mesh), choice, options);
  const double total = clock.seconds();
  std::printf("%s: %zu triangles, %zu seeds, %d threads: %s\n", name.c_str(), triangles, seeds, threads,
              r.passed() ? "every check passed" : "A CHECK FAILED");
  bw::test::figure(name + " fragments", static_cast<double>(r.figures.fragments));
  bw::test::figure(name + " cells split", static_cast<double>(r.figures.split_cells));
  bw::test::figure(name + " fragment triangles", static_cast<double>(r.figures.triangles));
  bw::test::figure(name + " volume relative error", r.figures.relative_error);
  bw::test::figure(name + " input checks", r.seconds_input, "s");
  bw::test::figure(name + " cells", r.seconds_cells, "s");
  bw::test::figure(name + " clip", r.seconds_clip, "s");
  bw::test::figure(name + " fragment checks", r.seconds_checks, "s");
  bw::test::figure(name + " total", total, "s");
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t seeds = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  run("icosphere", bw::mesh::icosphere(bw::Vec3d::Zero(), 1.0, 5), seeds, threads);
  run("torus", bw::mesh::torus(bw::Vec3d::Zero(), 1.0, 0.3, 160, 64), seeds, threads);
  return 0;
}
