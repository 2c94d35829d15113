// Rebuilding the exact meshes of the bodies that fracture created during a run
// (bw-voronoi replay), from the events the simulator recorded in its run file
// (docs/formats.md, kind "run", /fracture).
//
// The simulator breaks a body into the voxels nearest to each seed of an event, split
// into face-connected components; each component becomes a child body. The replay
// cuts the parent's exact mesh by the Voronoi cells of all the event's seeds (the
// same partition of space), splits each cell into its connected components, and
// gives each child body the component of its seed (child_seed) whose centroid lies
// nearest to the body's reference centre of mass: the simulator numbers components
// in its own order, so child_component is not relied on. Events are replayed in
// file order, so fragments of fragments are cut from the meshes replayed before.
//
// Meshes are in the reference configuration (docs/formats.md, "Body poses"): a
// solid's mesh is placed by its record as  translation + R(rotation) (scale x).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/report.h"
#include "io/fragments_file.h"
#include "io/run_file.h"

namespace bw::voronoi {

// An exact fragment matches its body when their volumes differ by at most
// kResolutionFactor * area * spacing: voxels of edge `spacing` represent a solid of
// surface `area` to within half a voxel layer over its surface (area * spacing / 2);
// twice that leaves room for the staircase along crack faces.
inline constexpr double kResolutionFactor = 1.0;

struct ReplayOptions {
  std::string source;   // the run file, for messages and the fragments file
  int threads = 0;      // 0: one per hardware thread
  std::function<void(const std::string&)> warn;
  std::function<void(std::size_t, std::size_t)> progress;  // (events done, events)
};

struct BodyMatch {
  std::int32_t body = -1;          // the child body
  std::int32_t event = -1;
  std::int32_t seed = -1;          // index into all events' seeds, in file order
  std::int32_t component = -1;     // the exact component given to it; -1: none
  double volume = 0;               // of the exact fragment
  double voxel_volume = 0;         // the body's voxels times the voxel volume
  double volume_tolerance = 0;     // kResolutionFactor * area * spacing
  double center_distance = 0;      // exact centroid to the body's reference centre
  double spacing = 0;              // voxel edge in the reference configuration
  std::string problem;             // why it has no mesh, or why the match is poor; empty when fine
};

struct ReplayResult {
  std::string source;
  FragmentSet fragments;           // one fragment per child body given a mesh, in the order of `bodies`
  std::vector<BodyMatch> bodies;   // one per child body, in event order
  std::vector<std::string> warnings;
  std::size_t events = 0;
  std::size_t unmatched = 0;       // child bodies without a mesh
  std::size_t poor = 0;            // matched, but the volumes differ beyond the tolerance
  std::size_t spare = 0;           // exact fragments that no body took
  double spare_volume = 0;

  bool passed() const { return unmatched == 0 && poor == 0; }
  Report report() const;
  std::string text() const;
};

// Replays every fracture event of `run`. Reads the particle files its solids name
// (their meshes). A failure that concerns one event or one body (an unreadable
// particle file, a cell CGAL cannot cut, a parent without a mesh) is reported on the
// bodies it leaves without a mesh, and the replay goes on.
ReplayResult replay_run(const RunRecord& run, const ReplayOptions& options);

}  // namespace bw::voronoi
