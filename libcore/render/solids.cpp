#include "render/solids.h"

#include <map>
#include <set>

#include "common/error.h"
#include "io/fragments_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"

namespace bw::render {
namespace {

// Fragments of one body differ a little in shade so that cracks read as cracks.
constexpr double kShadeSpread = 0.22;

Vec3d shade_of(const Vec3d& base, std::int32_t key) {
  // A fixed integer hash: the same body has the same shade in every frame and run.
  std::uint32_t h = static_cast<std::uint32_t>(key) * 2654435761u;
  h ^= h >> 16;
  const double u = (h & 0xffff) / 65535.0;  // [0, 1]
  return (base * (1.0 - kShadeSpread / 2 + kShadeSpread * u)).cwiseMin(1.0);
}

void append(TriangleSoup& soup, const TriMesh& mesh, const Eigen::Affine3d& pose, const Vec3d& color,
            std::int32_t solid) {
  soup.vertices.reserve(soup.vertices.size() + 27 * mesh.triangles.size());
  soup.solid.reserve(soup.solid.size() + 3 * mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    const Vec3d a = pose * mesh.vertices[t[0]], b = pose * mesh.vertices[t[1]], c = pose * mesh.vertices[t[2]];
    Vec3d n = (b - a).cross(c - a);
    const double len = n.norm();
    if (!(len > 0)) continue;  // degenerate triangles have no normal and no area
    n /= len;
    for (const Vec3d* p : {&a, &b, &c}) {
      for (int k = 0; k < 3; ++k) soup.vertices.push_back(static_cast<float>((*p)[k]));
      for (int k = 0; k < 3; ++k) soup.vertices.push_back(static_cast<float>(n[k]));
      for (int k = 0; k < 3; ++k) soup.vertices.push_back(static_cast<float>(color[k]));
      soup.solid.push_back(solid);
    }
  }
}

}  // namespace

Aabb TriangleSoup::bounds() const {
  Aabb box;
  for (std::size_t v = 0; v + 9 <= vertices.size(); v += 9) box.add(Vec3d(vertices[v], vertices[v + 1], vertices[v + 2]));
  return box;
}

SolidScene SolidScene::load(const SolidSources& sources, const SolidColors& colors, RunRecord* run_out) {
  RunRecord run;
  std::vector<TriMesh> meshes;
  if (!sources.run_path.empty()) {
    run = read_run(sources.run_path);
    meshes = reference_meshes(run, sources.run_path);
  }
  FragmentSet fragments;
  if (!sources.fragments_path.empty()) fragments = read_fragments(sources.fragments_path);
  SolidScene scene = from(run, std::move(meshes), std::move(fragments), sources, colors);
  if (run_out) *run_out = std::move(run);
  return scene;
}

SolidScene SolidScene::from(const RunRecord& run, std::vector<TriMesh> solid_meshes, FragmentSet fragments,
                            const SolidSources& sources, const SolidColors& colors) {
  SolidScene scene;
  scene.colors_ = colors;
  for (std::size_t s = 0; s < run.solids.size(); ++s) {
    const SolidRecord& r = run.solids[s];
    Part part;
    part.mesh = std::move(solid_meshes.at(s));
    part.body = r.body;
    part.is_static = r.body < 0;
    if (r.body >= static_cast<std::int32_t>(run.bodies.size()))
      fail_input("{}: solid {} ('{}') names body {}, the run has {} bodies", sources.run_path, s, r.name, r.body,
                 run.bodies.size());
    scene.solids_.push_back(std::move(part));
  }
  for (const BodyRecord& b : run.bodies) {
    scene.body_centers_.push_back(b.reference_center);
    scene.body_solids_.push_back(b.solid);
  }
  for (std::size_t f = 0; f < fragments.fragments.size(); ++f) {
    Fragment& fragment = fragments.fragments[f];
    if (fragment.body >= 0 && static_cast<std::size_t>(fragment.body) >= scene.body_centers_.size())
      fail_input("{}: fragment {} belongs to body {}, but {} has {} bodies", sources.fragments_path, f, fragment.body,
                 sources.run_path.empty() ? "there is no run file, which" : sources.run_path,
                 scene.body_centers_.size());
    Part part;
    part.mesh = std::move(fragment.mesh);
    part.body = fragment.body;
    part.is_static = false;
    scene.fragments_.push_back(std::move(part));
  }
  return scene;
}

TriangleSoup SolidScene::place(const BodyStates& bodies, std::size_t* missing) const {
  TriangleSoup soup;
  const Eigen::Affine3d identity = Eigen::Affine3d::Identity();
  // Which bodies have fragments to draw.
  std::set<std::int32_t> fragmented;
  for (const Part& f : fragments_)
    if (f.body >= 0) fragmented.insert(f.body);

  for (std::size_t k = 0; k < solids_.size(); ++k)
    if (solids_[k].is_static)
      append(soup, solids_[k].mesh, identity, colors_.static_color, static_cast<std::int32_t>(k));
  for (const Part& f : fragments_)
    if (f.body < 0) append(soup, f.mesh, identity, shade_of(colors_.body_color, -1), -1);

  std::size_t without_mesh = 0;
  if (bodies.size() == 0) {
    // No poses in this frame: bodies stand where they started (time 0).
    for (const Part& s : solids_)
      if (!s.is_static) append(soup, s.mesh, identity, shade_of(colors_.body_color, s.body), body_solids_[s.body]);
  } else {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::int32_t b = bodies.id[i];
      if (b < 0 || static_cast<std::size_t>(b) >= body_centers_.size()) {
        ++without_mesh;
        continue;
      }
      const Eigen::Affine3d pose = Eigen::Translation3d(bodies.position[i]) *
                                   Eigen::Affine3d(bodies.orientation[i].normalized().toRotationMatrix()) *
                                   Eigen::Translation3d(-body_centers_[b]);
      const Vec3d color = shade_of(colors_.body_color, b);
      bool drawn = false;
      if (fragmented.count(b)) {
        for (const Part& f : fragments_)
          if (f.body == b) append(soup, f.mesh, pose, color, body_solids_[b]);
        drawn = true;
      } else {
        for (const Part& s : solids_)
          if (s.body == b) append(soup, s.mesh, pose, color, body_solids_[b]), drawn = true;
      }
      if (!drawn) ++without_mesh;
    }
  }
  if (missing) *missing = without_mesh;
  return soup;
}

Aabb SolidScene::reference_bounds() const {
  Aabb box;
  for (const Part& s : solids_)
    for (const Vec3d& v : s.mesh.vertices) box.add(v);
  for (const Part& f : fragments_)
    for (const Vec3d& v : f.mesh.vertices) box.add(v);
  return box;
}

}  // namespace bw::render
