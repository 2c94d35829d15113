// Writes the meshes of the example scenes into a folder. Scenes are z-up, in metres.
#include <cstdio>
#include <numbers>
#include <string>

#include "common/error.h"
#include "mesh/import.h"
#include "mesh/shapes.h"

namespace {

using bw::Vec3d;
namespace mesh = bw::mesh;

// A house: a gable-roofed prism (polygon in the xz plane, extruded along y).
bw::TriMesh house(double width, double depth, double wall_height, double roof_height) {
  const std::vector<Eigen::Vector2d> gable = {
      {0, 0}, {width, 0}, {width, wall_height}, {width / 2, wall_height + roof_height}, {0, wall_height}};
  bw::TriMesh m = mesh::extrude(gable, 0, depth);
  // Polygon (u, v) = (x, z); extrusion axis becomes -y... rotate so v is up (z) and
  // the extrusion runs along +y.
  bw::Mat3d r;
  r << 1, 0, 0,  //
      0, 0, 1,   //
      0, 1, 0;   // (u, v, w) -> (u, w, v): a reflection, so flip faces after.
  mesh::transform(m, r, Vec3d::Zero());
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bw-example-meshes OUTPUT_FOLDER\n");
    return bw::kExitBadInput;
  }
  const std::string dir = argv[1];
  try {
    // Scene 1: a strong concrete wall, 0.2 m thick, 1.6 m wide, 1 m high.
    mesh::export_mesh(mesh::box({0, -0.8, 0}, {0.2, 0.8, 1.0}), dir + "/wall.obj");
    // Scene 2: a fragile plate, 0.06 m thick.
    mesh::export_mesh(mesh::box({0, -0.5, 0}, {0.06, 0.5, 0.8}), dir + "/plate.obj");
    // Scene 4: a house, 1 m x 1.2 m, walls 0.8 m, roof ridge 1.2 m.
    mesh::export_mesh(house(1.0, 1.2, 0.8, 0.4), dir + "/house.obj");
    // A floor slab, 6 m x 4 m, its top at z = 0.
    mesh::export_mesh(mesh::box({-1, -2, -0.1}, {5, 2, 0}), dir + "/ground.obj");
    // A tank for dam breaks and floating bodies: cavity 0.6 x 0.15 x 0.4 m, walls 3 cm.
    mesh::export_mesh(mesh::open_box({0, 0, 0}, {0.6, 0.15, 0.4}, 0.03), dir + "/tank.obj");
    // Validation (docs/validation.md): a channel for Martin & Moyce's dam break,
    // cavity 1 x 0.1 x 0.6 m (high enough that the surge running up its end wall stays
    // in), and a column for hydrostatics, cavity 0.1 x 0.1 x 0.3 m,
    // walls 4 cm: every face lies on a cell plane of bw-sample's grid at spacings
    // 0.02, 0.01, 0.005 and 0.0025, so the fluid fills the cavity at each of them.
    mesh::export_mesh(mesh::open_box({0, 0, 0}, {1.0, 0.1, 0.6}, 0.04), dir + "/channel.obj");
    mesh::export_mesh(mesh::open_box({0, 0, 0}, {0.1, 0.1, 0.3}, 0.04), dir + "/column.obj");
    // Stability cases: a sealed tank, cavity 0.6 x 0.1 x 1 m, for jets and drops whose
    // splashes must stay in; a baffle across it, 4 cm thick and 0.2 m high; a sheet of
    // the same size only 1 cm thick (one cell of bw-sample's grid at a spacing of
    // 0.01 m: both faces in the same boundary particles).
    mesh::export_mesh(mesh::sealed_box({0, 0, 0}, {0.6, 0.1, 1.0}, 0.04), dir + "/sealed.obj");
    mesh::export_mesh(mesh::box({0, 0, 0}, {0.04, 0.1, 0.2}), dir + "/baffle.obj");
    mesh::export_mesh(mesh::box({0, 0, 0}, {0.01, 0.1, 0.2}), dir + "/sheet.obj");
    // Scene 4: a flume for the flood among four houses: cavity 8 x 8.4 x 1.6 m, open
    // at the top, walls 0.4 m thick, so that its inner faces lie on cell planes of
    // bw-sample's grid at the scene's spacings (0.1, 0.08, 0.05, 0.04, 0.025, 0.02,
    // 0.0125 m) and the flood's blocks and the houses sit on its floor; and the
    // dividers, 8 m long, 0.4 m thick, as high as the flume, five of them every 2 m
    // from its side walls in: four lanes of 1.6 m, one house in each, each between two
    // dividers, so that every house meets the same flood (with the flume's own wall on
    // one side the outer lanes' floods differed from the inner ones': walls sampled
    // apart weigh differently where they meet the floor). 0.4 and 2 m are whole
    // numbers of cells at every spacing above, so the lanes are copies of each other.
    mesh::export_mesh(mesh::open_box({0, 0, 0}, {8.0, 8.4, 1.6}, 0.4), dir + "/flume.obj");
    mesh::export_mesh(mesh::box({0, 0, 0}, {8.0, 0.4, 1.6}), dir + "/divider.obj");
    // SPHERIC Test 2 (examples/spheric2.toml): the closed MARIN tank, cavity 3.22 x 1 x 1 m,
    // walls 4 cm, and the box on its floor, 0.16 x 0.40 x 0.16 m with the face toward the
    // water at x = 0.8245 (the experiment's box is 0.161 x 0.403 x 0.161 m: these sizes put
    // every face on a cell plane of bw-sample's grid at 0.02 and 0.01 m, so the fluid meets
    // the face where the sensors are).
    mesh::export_mesh(mesh::sealed_box({0, 0, 0}, {3.22, 1.0, 1.0}, 0.04), dir + "/spheric_tank.obj");
    mesh::export_mesh(mesh::box({0.6645, 0.297, 0}, {0.8245, 0.697, 0.16}), dir + "/spheric_box.obj");
    // The same tank cut to a slice 4 cm wide, 0.7 m high, without the box
    // (examples/spheric2-slice.toml): the dam break's front at spacings down to 0.005 m.
    mesh::export_mesh(mesh::sealed_box({0, 0, 0}, {3.22, 0.04, 0.7}, 0.04), dir + "/spheric_slice.obj");
    // The box cut to the same slice, across its whole width (examples/spheric2-slice-box.toml):
    // the first impact on the sensors' face, which comes before the flow around the box's
    // sides reaches them, at spacings down to 0.004 m. Its faces lie on cell planes at
    // 0.02, 0.01, 0.008, 0.005 and 0.004 m, as the slice's walls do.
    mesh::export_mesh(mesh::box({0.6645, 0, 0}, {0.8245, 0.04, 0.16}), dir + "/spheric_slice_box.obj");
    // A gate across the slice, its face on the water's end (x = 1.992 m), 0.6 m high and
    // 0.04 m thick, on cell planes at the same spacings (examples/spheric2-slice-gate.toml:
    // the column released by lifting it).
    mesh::export_mesh(mesh::box({1.952, 0, 0}, {1.992, 0.04, 0.6}), dir + "/spheric_slice_gate.obj");
    // A wave flume (examples/wavemaker-piston.toml, wavemaker-flap.toml): cavity 8 m long,
    // 0.08 m wide (4 particles at 0.02 m, 8 at 0.01 m), 0.8 m high, open at the top, walls
    // 8 cm thick, so that their outer faces' particles lie more than h outside a domain
    // drawn tight around the cavity and are dropped; and its wave maker's paddle, a plate
    // 0.04 m thick across the whole width and as high as the flume, its back face 0.06 m
    // from the end wall (room for the piston's back stroke) and its wet face at x = 0.1 m.
    // Every face lies on a cell plane of bw-sample's grid at 0.04, 0.02, 0.01 and 0.005 m,
    // so the water fills the flume from the paddle's face to the far wall and the paddle
    // touches the floor and the side walls without overlapping them.
    mesh::export_mesh(mesh::open_box({0, 0, 0}, {8.0, 0.08, 0.8}, 0.08), dir + "/wave_flume.obj");
    mesh::export_mesh(mesh::box({0.06, 0, 0}, {0.1, 0.08, 0.8}), dir + "/wave_paddle.obj");
    // A crate, 0.1 m cube, for the floating-body scene.
    mesh::export_mesh(mesh::box({0, 0, 0}, {0.1, 0.1, 0.1}), dir + "/crate.obj");
    // Scene 3: a valley 8 m long falling 0.12 m per metre along x, with parabolic
    // sides rising 0.8 m over 1.5 m; its floor is 1.2 m high at x = 0. Across it, at
    // x = 4.7 .. 5.4 m, a flat bench cut down to z = 0.5 m (the terrain falls to it
    // over 0.1 m on either side) is the foundation of the dam, which stands on its
    // middle (x = 4.8 .. 5.3), 0.1 m from where the terrain starts to rise: quads of
    // 0.1 m along x put the bench's edges on vertices, and the bench's height above
    // the block's bottom (0.7 m) is a multiple of the scene's spacings (0.1, 0.05,
    // 0.025, 0.0125 m), so the bench lies on a cell plane of bw-sample's grid and the
    // dam stands on the terrain, touching it without overlapping it.
    mesh::export_mesh(mesh::heightfield({0, -1.5}, {8, 1.5}, 80, 24, -0.2,
                                        [](double x, double y) {
                                          if (x > 4.7 - 1e-9 && x < 5.4 + 1e-9) return 0.5;
                                          return 1.2 - 0.12 * x + 0.8 * (y / 1.5) * (y / 1.5);
                                        }),
                      dir + "/valley.obj");
    // Scene 3: a gravity dam on that bench, across the whole valley: trapezoidal
    // section, 0.5 m at the base, 0.15 m at the crest, from z = 0.5 to 1.7 m; its
    // upstream face is vertical.
    {
      bw::TriMesh dam = mesh::extrude({{0, 0}, {0.5, 0}, {0.15, 1.2}, {0, 1.2}}, -1.5, 1.5);
      bw::Mat3d r;
      r << 1, 0, 0,  //
          0, 0, 1,   //
          0, 1, 0;   // (u, v, w) -> (u, w, v): section in xz, extruded along y
      mesh::transform(dam, r, Vec3d(4.8, 0, 0.5));
      for (auto& t : dam.triangles) std::swap(t[1], t[2]);  // the swap of axes mirrors
      mesh::export_mesh(dam, dir + "/dam.obj");
    }
  } catch (const bw::Error& e) {
    std::fprintf(stderr, "bw-example-meshes: %s\n", e.what());
    return e.exit_code();
  }
  return 0;
}
