// A small run for the export tests, written with the file layer as bw-sim and
// bw-voronoi write it: the U-shaped breakable solid of tests/voronoi (body 0) breaks
// at t = 0.05 into children; frames 0, 1, 2 at 20 fps, each with a block of water,
// body 0 at rest in frame 0 and the children moving and turning in frames 1 and 2.
// The children's meshes (fragments.h5) are boxes around their voxels: the export
// does not care how exact they are.
#pragma once

#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "io/fragments_file.h"
#include "io/frame_file.h"
#include "mesh/shapes.h"
#include "synthetic.h"
#include "synthetic_run.h"

namespace bw::test {

inline constexpr double kExportSpacing = 0.05;
inline constexpr double kExportRate = 20;

// The pose of child body `b` in frame `f` (1 or 2).
inline void child_pose(int b, int f, Vec3d& position, Eigen::Quaterniond& orientation, const Vec3d& c_ref) {
  position = c_ref + Vec3d(0.1 * f * b, 0.02 * f, 0.05 * f);
  orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.2 * f + 0.1 * b, Vec3d(0.3, 1, 0.2).normalized()));
}

// Writes DIR/run.h5, DIR/u.h5, DIR/fragments.h5 and DIR/frames/00000{0,1,2}.h5.
// Returns the run.
inline RunRecord write_export_run(const std::string& dir, bool with_fragments = true) {
  SyntheticRun s = make_u_run(dir + "/u.h5", 0.25);
  Vec3d center = Vec3d::Zero();
  for (const CellIndex& c : s.sampled.voxels) center += s.to_reference(s.sampled.grid.cell_center(c));
  s.run.bodies[0].reference_center = center / static_cast<double>(s.sampled.voxels.size());
  const std::vector<std::int32_t> children =
      s.fracture(0, {Vec3d(0.5, 0.5, 0.5), Vec3d(2.5, 0.5, 0.5), Vec3d(1.5, 2.5, 0.5)}, 0.05);
  for (std::int32_t c : children) s.run.bodies[static_cast<std::size_t>(c)].name = fmt::format("u.{}", c - 1);
  s.run.parameters = {{"spacing", kExportSpacing}, {"frame_rate", kExportRate}};
  s.run.frames.resize(3);
  write_run(s.run, dir + "/run.h5");

  if (with_fragments) {
    FragmentSet set;
    set.source = dir + "/run.h5";
    set.options = "replay";
    for (std::int32_t c : children) {
      Aabb box;
      for (const CellIndex& cell : s.voxels_of.at(c)) {
        const Vec3d p = s.to_reference(s.sampled.grid.cell_center(cell));
        box.add(p - Vec3d::Constant(s.reference_spacing / 2));
        box.add(p + Vec3d::Constant(s.reference_spacing / 2));
      }
      Fragment f;
      f.mesh = mesh::box(box.min, box.max);
      f.body = c;
      set.fragments.push_back(std::move(f));
    }
    write_fragments(set, dir + "/fragments.h5");
  }

  std::filesystem::create_directories(dir + "/frames");
  for (int f = 0; f < 3; ++f) {
    FrameData frame;
    frame.frame = f;
    frame.time = f / kExportRate;
    render::test::add_block(frame, Vec3d(-1, -1, 0), Vec3d(-0.5, -0.6, 0.3 + 0.1 * f), kExportSpacing, 0.1,
                            static_cast<std::uint32_t>(f + 1));
    auto add_body = [&](std::int32_t id, const Vec3d& p, const Eigen::Quaterniond& q) {
      frame.bodies.id.push_back(id);
      frame.bodies.position.push_back(p);
      frame.bodies.orientation.push_back(q);
      frame.bodies.linear_velocity.push_back(Vec3d::Zero());
      frame.bodies.angular_velocity.push_back(Vec3d::Zero());
    };
    if (f == 0) {
      add_body(0, s.run.bodies[0].reference_center, Eigen::Quaterniond::Identity());
    } else {
      for (std::int32_t c : children) {
        Vec3d p;
        Eigen::Quaterniond q;
        child_pose(c, f, p, q, s.run.bodies[static_cast<std::size_t>(c)].reference_center);
        add_body(c, p, q);
      }
    }
    write_frame(frame, frame_file_name(dir + "/frames", f));
  }
  return s.run;
}

}  // namespace bw::test
