// The index of a run for ParaView and VisIt: OUTDIR/run.xdmf2, an XDMF 2 file that
// opens the whole run as one time series (docs/formats.md, "The run index"). The
// extension .xdmf2 makes ParaView pick its XDMF 2 reader: for .xdmf it picks the
// XDMF 3 reader, which (in 5.11) reads neither X_Y_Z geometry nor JOIN functions.
//
// It holds no data of its own: every grid points at the datasets of a frame file (the
// fluid with its fields, the boundary particles, the bodies' poses) or of the meshes
// file (OUTDIR/meshes.h5: the solids and the bodies' meshes placed in every frame),
// by paths relative to the index, so that a run folder moves or copies as a whole.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/frame_file.h"

namespace bw {

// What the index says of one frame.
struct IndexFrame {
  std::int32_t frame = 0;
  double time = 0;
  std::string file;             // the frame file, relative to the index's folder
  std::string step = "/Step#0"; // its step group
  std::uint64_t fluid = 0, boundary = 0, bodies = 0;
  FrameFields fields;
};

// What the index says of a meshes file (kind "meshes", written by write_run_meshes).
struct IndexMeshes {
  std::string file;  // relative to the index's folder
  std::uint64_t static_vertices = 0, static_triangles = 0;
  // Per frame number: the placed bodies' vertices and triangles.
  std::map<std::int32_t, std::pair<std::uint64_t, std::uint64_t>> frames;
};

struct RunIndex {
  std::vector<IndexFrame> frames;  // in frame order
  IndexMeshes meshes;              // file empty: no meshes
};

// The index entry of a frame just written (`file` relative to the index's folder).
IndexFrame index_frame(const FrameData& frame, const std::string& file);
IndexFrame index_frame(const FrameHeader& header, const std::string& file);

// Scans OUTDIR/frames for frame files (six digits .h5), in frame order. Throws
// InputError when the folder is missing or a frame file is not one.
RunIndex scan_run(const std::string& outdir);

// The XDMF text of an index.
std::string xdmf_text(const RunIndex& index);

// Writes the index atomically (a reader never sees half a file).
void write_run_index(const RunIndex& index, const std::string& path);

// "OUTDIR/run.xdmf2".
std::string run_index_path(const std::string& outdir);

struct MeshesReport {
  std::string path;               // the meshes file written
  std::size_t frames = 0;
  std::size_t static_triangles = 0;
  std::size_t body_triangles = 0;  // largest count of one frame
  std::size_t bodies_without_mesh = 0;  // largest count of one frame (fragments without a fragments file)
};

// Writes OUTDIR/meshes.h5 beside the run file OUTDIR/run.h5: the static solids' meshes (from the particle files the run
// file names, placed by the solids' transforms) and, for every frame, each body's
// mesh placed by its pose (a solid's own body: its solid's mesh; a fragment: its
// mesh in `fragments_path`, from bw-voronoi replay; empty: no fragments file). Then
// rewrites OUTDIR/run.xdmf2 with the meshes. Throws InputError naming the file at fault.
MeshesReport write_run_meshes(const std::string& run_path, const std::string& fragments_path);

// Throws InputError unless `fragments_path` is free of what write_run_meshes writes
// beside `run_path` (OUTDIR/meshes.h5, OUTDIR/run.xdmf2), which would replace it.
void check_fragments_beside_run(const std::string& run_path, const std::string& fragments_path);

}  // namespace bw
