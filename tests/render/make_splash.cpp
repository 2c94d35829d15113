// Writes the synthetic splash of synthetic.h as a simulation output folder:
//   make-splash OUTDIR [PARTICLES [broken]]
//     ->  OUTDIR/run.h5, OUTDIR/wall.h5, OUTDIR/tank.h5, OUTDIR/frames/000000.h5
// With "broken", the wall is a breakable solid cut into three fragments (bodies 1 to
// 3, in OUTDIR/fragments.h5) that the frame shows flung apart and turned. With
// "spray", a crown of thin sheets and loose drops rises around the ball instead.
// Used for the documentation picture (docs/rendering.md) and by hand.
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "io/frame_file.h"
#include "synthetic.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make-splash OUTDIR [PARTICLES]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const std::size_t particles = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 120000;
  std::filesystem::create_directories(dir + "/frames");
  const std::string abs = std::filesystem::absolute(dir).string();
  bw::render::test::write_wall_run(abs, bw::Vec3d::Zero(), true);
  bw::FrameData f = bw::render::test::splash_frame(particles);
  if (argc > 3 && std::string(argv[3]) == "broken") bw::render::test::break_wall(abs, f);
  if (argc > 3 && std::string(argv[3]) == "spray") bw::render::test::add_spray(f, 7);
  bw::write_frame(f, bw::frame_file_name(dir + "/frames", 0));
  std::fprintf(stderr, "%s: %zu particles\n", dir.c_str(), f.fluid_count());
  return 0;
}
