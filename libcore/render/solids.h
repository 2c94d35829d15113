// The solids a frame shows, as meshes placed in the world.
//
// Static solids come from the particle files that the run file's /solids records
// name, placed by the record's scale, rotation and translation:
//   x_ref = translation + R(rotation) * (scale * x_mesh)
// which is also the reference configuration of a dynamic or breakable solid's body.
// Bodies are placed by their pose in the frame (docs/formats.md, "Body poses"):
//   x_world = R(orientation) * (x_ref - c_ref) + position
// with c_ref from the run file's /bodies/reference_center. A body drawn is either the
// fragments of a fragments file whose `body` is that body, or, for a solid's own
// body, the solid's mesh. Fragments whose body is -1 (a prefracture check) are drawn
// in the reference configuration.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "io/run_file.h"

namespace bw::render {

// Flat-shaded triangles in world space, ready for a vertex buffer: three vertices
// per triangle, each with position, the triangle's normal and a colour (3 floats
// each, in that order, 9 floats per vertex).
struct TriangleSoup {
  std::vector<float> vertices;
  // Per vertex, the run file's row of the solid it belongs to (a fragment: its body's
  // root solid), -1 for none: which boundary particles colour it (wall_paint.h).
  std::vector<std::int32_t> solid;
  std::size_t triangle_count() const { return vertices.size() / 27; }
  Aabb bounds() const;
};

struct SolidSources {
  std::string run_path;        // run.h5; empty when there is none
  std::string fragments_path;  // fragments .h5; empty when there is none
};

struct SolidColors {
  Vec3d static_color = Vec3d(0.6, 0.6, 0.6);
  Vec3d body_color = Vec3d(0.6, 0.4, 0.3);
};

class SolidScene {
 public:
  // Reads the run file, the particle files it names (each once) and the fragments
  // file; `run` (optional) receives the run file's record, for what else a caller
  // needs of it. Throws InputError naming the file at fault.
  static SolidScene load(const SolidSources& sources, const SolidColors& colors, RunRecord* run = nullptr);
  // The same from what a caller has read already: the run, its solids' meshes in the
  // reference configuration (reference_meshes, run_file.h) and the fragments (none:
  // an empty set). `sources` names the files in messages.
  static SolidScene from(const RunRecord& run, std::vector<TriMesh> solid_meshes, FragmentSet fragments,
                         const SolidSources& sources, const SolidColors& colors);

  // The triangles of every solid at the given body states. `missing` (optional)
  // receives the number of bodies of the frame that have no mesh to draw (fragments
  // of a run rendered without its fragments file).
  TriangleSoup place(const BodyStates& bodies, std::size_t* missing = nullptr) const;

  // Bounds of every mesh in its reference configuration.
  Aabb reference_bounds() const;
  std::size_t solid_count() const { return solids_.size(); }
  std::size_t fragment_count() const { return fragments_.size(); }
  std::size_t body_count() const { return body_centers_.size(); }

  // One mesh in its reference configuration, with the body that moves it (-1: none).
  struct Part {
    TriMesh mesh;
    std::int32_t body = -1;
    bool is_static = true;
  };

 private:
  std::vector<Part> solids_;      // one per /solids record
  std::vector<Part> fragments_;   // one per fragment
  std::vector<Vec3d> body_centers_;  // c_ref per body of the run
  std::vector<std::int32_t> body_solids_;  // root solid per body of the run
  SolidColors colors_;
};

}  // namespace bw::render
