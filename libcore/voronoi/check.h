// The prefracture check (bw-voronoi check): is this solid ready to break? Its mesh
// must bound a volume cleanly, and the Voronoi cells of the seeds must cut it into
// closed fragments that fill it exactly. Each check is reported on its own; the
// fragments are kept for the renderer and other tools.
//
// Checks, in order:
//   input_closed              every edge has two faces, consistently oriented
//   input_manifold            no edge with more than two faces, no vertex where
//                             faces meet only at a point
//   input_self_intersections  no two faces cross (exact predicates); no zero-area face
//   cells_cut                 every cell of a seed inside the solid was cut
//   fragments_closed          every fragment is closed, oriented, manifold and bounds
//                             a positive volume
//   volumes_add_up            the fragments' volumes add up to the solid's volume
//                             within kVolumeTolerance (relative)
//   inside_mesh               no fragment reaches outside the solid
//   within_cells              every fragment lies in its seed's Voronoi cell
// An input that is not closed, manifold and oriented cannot be cut: that is bad
// input (InputError, exit 2), not a failed check. An input that intersects itself is
// a failed check (exit 3) and the fragment checks are skipped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/report.h"
#include "io/fragments_file.h"
#include "mesh/check.h"
#include "voronoi/seeds.h"
#include "voronoi/solid.h"
#include "voronoi/voronoi.h"

namespace bw::voronoi {

// Fragment volumes must add up to the solid's volume within this relative error.
// The cut computes every intersection point exactly and rounds it once to double, so
// the sum agrees to ~1e-15; 1e-6 is the contract with the simulator and renderer
// (issue 6) and leaves room for meshes with many tiny fragments.
inline constexpr double kVolumeTolerance = 1e-6;

// Distances (inside_mesh, within_cells) are allowed this fraction of the solid's
// size (the larger of its bounding-box diagonal and its largest coordinate): rounding
// an exact point to double moves it by about 1e-16 of that; 1e-9 is a million times
// more and still far below any real excursion.
inline constexpr double kDistanceTolerance = 1e-9;

// Vertices where the faces around them form more than one fan (faces that touch at a
// single point). Precondition: every index is valid.
std::size_t count_nonmanifold_vertices(const TriMesh& mesh);

// The mesh of INPUT: a particles file written by bw-sample (detected by its HDF5
// signature; '-' reads one from standard input) or any mesh assimp reads.
// `kind` receives "particles" or "mesh".
TriMesh load_solid_mesh(const std::string& path, std::string* kind = nullptr);

struct InputSummary {
  mesh::MeshReport mesh;
  std::size_t nonmanifold_vertices = 0;
  bool flipped = false;          // the mesh faced inwards and was turned right
  double volume = 0;
};

// Throws InputError naming `source` unless the mesh bounds a volume: valid indices,
// finite coordinates, closed, edge- and vertex-manifold, consistently oriented,
// non-zero volume. A mesh that faces inwards is flipped.
InputSummary prepare_solid_mesh(TriMesh& mesh, const std::string& source);

enum class CheckStatus { pass, fail, skipped };
const char* to_string(CheckStatus status);

struct CheckItem {
  std::string name;     // "volumes_add_up"
  std::string title;    // "fragment volumes add up to the mesh volume"
  CheckStatus status = CheckStatus::skipped;
  std::string detail;   // figures, or what is wrong and where
};

struct FragmentFigures {
  std::size_t fragments = 0;
  std::size_t split_cells = 0;       // cells that gave more than one fragment
  double volume_sum = 0;
  double relative_error = 0;         // |volume_sum - solid volume| / solid volume
  double min_volume = 0, max_volume = 0;
  std::size_t triangles = 0;         // over all fragments
};

// The fragment checks (cells_cut .. within_cells) on `fragments` cut from `solid` by
// the active seeds. `failures` are the cells that could not be cut. Volumes are
// recomputed from the meshes, not taken from Fragment::volume.
std::vector<CheckItem> check_fragments(const Solid& solid, std::span<const Vec3d> seeds,
                                       std::span<const std::int32_t> active, std::span<const Fragment> fragments,
                                       std::span<const CellFailure> failures, int threads,
                                       FragmentFigures* figures = nullptr);

// The most seeds a check cuts: as many bodies as a scene lets its breakable solids
// become (fracture.max_chunks' limit). Each cell takes milliseconds.
constexpr std::size_t kMaxSeeds = 1'000'000;

struct SeedChoice {
  std::vector<Vec3d> points;         // given seeds; used when random == 0
  std::size_t random = 0;            // > 0: draw this many inside the solid
  std::uint64_t random_seed = 1;
};

struct CheckOptions {
  std::string source;                // INPUT as given, for messages and the fragments file
  std::string input_kind = "mesh";   // "mesh" or "particles"
  int threads = 0;                   // 0: one per hardware thread
  // Called once per warning (an ignored seed, a flipped mesh) as soon as it is known.
  std::function<void(const std::string&)> warn;
  // Called after each cell with (done, total).
  std::function<void(std::size_t, std::size_t)> progress;
};

struct CheckResult {
  std::string source, input_kind;
  InputSummary input;
  std::vector<Vec3d> seeds;          // every seed given or drawn; fragments index into them
  SeedSorting sorting;
  std::vector<CheckItem> checks;
  std::vector<std::string> warnings;
  std::vector<CellFailure> failures;
  std::vector<Fragment> fragments;
  FragmentFigures figures;
  std::size_t self_intersection_pairs = 0;
  std::size_t concave_edges = 0;
  double seed_nudge = 0;             // CutResult::seed_nudge
  double seconds_input = 0, seconds_cells = 0, seconds_clip = 0, seconds_checks = 0;

  bool passed() const;
  // The fragments file's content (source, seeds, fragments).
  FragmentSet fragment_set() const;
  // Everything above as a tree, for --json.
  Report report() const;
  // A summary for people: one line per check.
  std::string text() const;
};

// The whole check: validates the mesh (InputError when it cannot be cut), looks for
// self-intersections, takes or draws the seeds and ignores those that cannot take
// part (with a warning each; InputError when none is left), cuts, checks the
// fragments.
CheckResult prefracture_check(TriMesh mesh, const SeedChoice& seeds, const CheckOptions& options);

}  // namespace bw::voronoi

namespace bw::voronoi {

// Writes every fragment as its own mesh file in `folder` (created when missing):
// fragment_NNNN_seed_SSSS_C.EXT with NNNN its row in the fragments file, SSSS its
// seed and C its component. `extension` is "obj" (written natively, full precision)
// or "ply" (binary, through assimp). Returns the paths written.
std::vector<std::string> export_fragments(std::span<const Fragment> fragments, const std::string& folder,
                                          const std::string& extension);

}  // namespace bw::voronoi
