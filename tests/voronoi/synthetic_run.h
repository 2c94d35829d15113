// A run file made the way the simulator's fracture stage records one (method.md
// section 4): a breakable solid sampled into voxels, placed in the scene by a
// translation, rotation and scale; at each event the parent body's voxels go to their
// nearest seed, each seed's voxels split into face-connected components, and each
// component becomes a child body with its voxel count and reference centre of mass.
// For tests of bw-voronoi replay while the simulator's fracture stage is not there.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/particles_file.h"
#include "io/run_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"

namespace bw::test {

struct SyntheticRun {
  RunRecord run;
  SampledSolid sampled;                          // in the solid's own frame
  std::map<std::int32_t, std::vector<CellIndex>> voxels_of;  // per body
  double reference_spacing = 0;                  // voxel edge in the reference configuration

  Vec3d to_reference(const Vec3d& local) const {
    const SolidRecord& s = run.solids[0];
    return s.rotation * (s.scale * local) + s.translation;
  }

  // Breaks `parent` at `local_seeds` (given in the solid's own frame; recorded in the
  // reference configuration). Components are numbered in the order their first voxel
  // comes in (k, j, i) order, which is not the replay's order. Returns the children.
  std::vector<std::int32_t> fracture(std::int32_t parent, const std::vector<Vec3d>& local_seeds, double time) {
    FractureEvent event;
    event.time = time;
    event.parent = parent;
    for (const Vec3d& s : local_seeds) event.seeds.push_back(to_reference(s));
    const std::vector<CellIndex>& cells = voxels_of.at(parent);
    std::map<CellIndex, std::int32_t> nearest;
    for (const CellIndex& c : cells) {
      const Vec3d p = sampled.grid.cell_center(c);
      std::int32_t best = 0;
      for (std::size_t s = 1; s < local_seeds.size(); ++s)
        if ((p - local_seeds[s]).squaredNorm() < (p - local_seeds[static_cast<std::size_t>(best)]).squaredNorm())
          best = static_cast<std::int32_t>(s);
      nearest[c] = best;
    }
    std::set<CellIndex> seen;
    std::vector<std::int32_t> children;
    std::map<std::int32_t, std::int32_t> components_of_seed;
    std::vector<CellIndex> sorted = cells;
    std::sort(sorted.begin(), sorted.end(), [](const CellIndex& a, const CellIndex& b) {
      return std::array{a[2], a[1], a[0]} < std::array{b[2], b[1], b[0]};
    });
    for (const CellIndex& start : sorted) {
      if (seen.count(start)) continue;
      const std::int32_t seed = nearest[start];
      std::vector<CellIndex> component{start}, stack{start};
      seen.insert(start);
      while (!stack.empty()) {
        const CellIndex c = stack.back();
        stack.pop_back();
        for (int axis = 0; axis < 3; ++axis)
          for (int step : {-1, 1}) {
            CellIndex n = c;
            n[axis] += step;
            const auto it = nearest.find(n);
            if (it == nearest.end() || it->second != seed || seen.count(n)) continue;
            seen.insert(n);
            component.push_back(n);
            stack.push_back(n);
          }
      }
      BodyRecord body;
      body.name = "fragment";
      body.solid = 0;
      body.parent = parent;
      body.created_time = time;
      body.voxels = static_cast<std::int32_t>(component.size());
      Vec3d center = Vec3d::Zero();
      for (const CellIndex& c : component) center += to_reference(sampled.grid.cell_center(c));
      body.reference_center = center / static_cast<double>(component.size());
      const auto id = static_cast<std::int32_t>(run.bodies.size());
      run.bodies.push_back(body);
      voxels_of[id] = component;
      event.child_body.push_back(id);
      event.child_seed.push_back(seed);
      event.child_component.push_back(components_of_seed[seed]++);
      children.push_back(id);
    }
    run.fractures.push_back(event);
    return children;
  }
};

// A U-shaped prism (outer 3 x 3, notch 1 x 2, height 1) sampled at `spacing`, as
// solid 0 of a run, placed by a translation, a rotation and a scale; body 0 is its
// own. The particle file is written to `particles_path`.
inline SyntheticRun make_u_run(const std::string& particles_path, double spacing) {
  SyntheticRun s;
  const std::vector<Eigen::Vector2d> u = {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  sample::SampleOptions options;
  options.spacing = spacing;
  options.volume = true;
  options.source = "u.obj";
  s.sampled = sample::sample_mesh(mesh::extrude(u, 0, 1), options);
  write_particles(s.sampled, particles_path, "synthetic");
  SolidRecord solid;
  solid.name = "u";
  solid.particles = particles_path;
  solid.kind = "breakable";
  solid.translation = Vec3d(1, -2, 0.5);
  solid.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Vec3d(0, 0, 1)));
  solid.scale = 0.5;
  solid.body = 0;
  s.run.solids.push_back(solid);
  BodyRecord body;
  body.name = "u";
  body.solid = 0;
  body.voxels = static_cast<std::int32_t>(s.sampled.voxels.size());
  s.run.bodies.push_back(body);
  s.voxels_of[0] = s.sampled.voxels;
  s.reference_spacing = spacing * solid.scale;
  s.run.status = "complete";
  return s;
}

}  // namespace bw::test
