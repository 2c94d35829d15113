#include "voronoi/replay.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "common/error.h"
#include "io/particles_file.h"
#include "mesh/properties.h"
#include "voronoi/check.h"
#include "voronoi/solid.h"
#include "voronoi/voronoi.h"

namespace bw::voronoi {
namespace {

// A solid's mesh in the reference configuration, and its voxel edge there.
struct RootSolid {
  TriMesh mesh;
  double spacing = 0;
  std::string problem;  // why it could not be loaded
};

RootSolid load_root(const SolidRecord& record, std::size_t index) {
  RootSolid root;
  try {
    SampledSolid sampled = read_particles(record.particles);
    if (sampled.mesh.triangles.empty()) fail_input("{}: the particles file holds no mesh", record.particles);
    const Mat3d rotation = record.rotation.normalized().toRotationMatrix();
    for (Vec3d& v : sampled.mesh.vertices) v = rotation * (record.scale * v) + record.translation;
    root.mesh = std::move(sampled.mesh);
    root.spacing = sampled.grid.spacing * record.scale;
    // Turned right, checked: replay cuts only meshes that bound a volume.
    prepare_solid_mesh(root.mesh, record.particles);
  } catch (const Error& e) {
    root.problem = fmt::format("solid {} ({}): {}", index, record.name, e.what());
  }
  return root;
}

double surface_area(const TriMesh& mesh) { return mesh::mass_properties(mesh).area; }

}  // namespace

ReplayResult replay_run(const RunRecord& run, const ReplayOptions& options) {
  ReplayResult r;
  r.source = options.source;
  r.fragments.source = options.source;
  r.events = run.fractures.size();
  auto warn = [&](std::string message) {
    if (options.warn) options.warn(message);
    r.warnings.push_back(std::move(message));
  };

  const auto body_count = static_cast<std::int32_t>(run.bodies.size());
  // The exact mesh of each body, once known, and why not otherwise.
  std::map<std::int32_t, TriMesh> body_mesh;
  std::map<std::int32_t, std::string> body_problem;
  std::map<std::size_t, RootSolid> roots;
  auto root_of = [&](std::size_t solid) -> const RootSolid& {
    auto it = roots.find(solid);
    if (it == roots.end()) it = roots.emplace(solid, load_root(run.solids[solid], solid)).first;
    return it->second;
  };
  auto spacing_of = [&](std::int32_t body) {
    const std::int32_t solid = run.bodies[static_cast<std::size_t>(body)].solid;
    if (solid < 0 || static_cast<std::size_t>(solid) >= run.solids.size()) return 0.0;
    return root_of(static_cast<std::size_t>(solid)).spacing;
  };
  // The mesh a parent body is cut from: its own replayed mesh, or its solid's.
  auto mesh_of = [&](std::int32_t body, std::string* problem) -> const TriMesh* {
    if (auto it = body_mesh.find(body); it != body_mesh.end()) return &it->second;
    if (auto it = body_problem.find(body); it != body_problem.end()) {
      *problem = it->second;
      return nullptr;
    }
    if (body < 0 || body >= body_count) {
      *problem = fmt::format("body {} is not in the run's {} bodies", body, body_count);
      return nullptr;
    }
    for (std::size_t s = 0; s < run.solids.size(); ++s) {
      if (run.solids[s].body != body) continue;
      const RootSolid& root = root_of(s);
      if (!root.problem.empty()) {
        *problem = root.problem;
        return nullptr;
      }
      return &root.mesh;
    }
    *problem = fmt::format("body {} is neither a solid's body nor a fragment replayed before", body);
    return nullptr;
  };

  std::int32_t seed_base = 0;
  for (std::size_t e = 0; e < run.fractures.size(); ++e) {
    const FractureEvent& event = run.fractures[e];
    const auto base = seed_base;
    seed_base += static_cast<std::int32_t>(event.seeds.size());
    r.fragments.seeds.insert(r.fragments.seeds.end(), event.seeds.begin(), event.seeds.end());
    const std::size_t first_match = r.bodies.size();
    for (std::size_t c = 0; c < event.child_body.size(); ++c) {
      BodyMatch m;
      m.body = event.child_body[c];
      m.event = static_cast<std::int32_t>(e);
      m.seed = base + event.child_seed[c];
      if (m.body < 0 || m.body >= body_count) {
        m.problem = fmt::format("body {} is not in the run's {} bodies", m.body, body_count);
      } else if (event.child_seed[c] < 0 || static_cast<std::size_t>(event.child_seed[c]) >= event.seeds.size()) {
        m.problem = fmt::format("its seed {} is not among the event's {} seeds", event.child_seed[c], event.seeds.size());
      } else {
        m.spacing = spacing_of(m.body);
        m.voxel_volume = run.bodies[static_cast<std::size_t>(m.body)].voxels * m.spacing * m.spacing * m.spacing;
      }
      r.bodies.push_back(m);
    }
    auto fail_event = [&](const std::string& why) {
      for (std::size_t k = first_match; k < r.bodies.size(); ++k)
        if (r.bodies[k].problem.empty()) r.bodies[k].problem = why;
    };

    std::string problem;
    const TriMesh* parent = mesh_of(event.parent, &problem);
    if (!parent) {
      fail_event(fmt::format("event {} (t = {:g} s): parent body {} has no exact mesh: {}", e, event.time,
                             event.parent, problem));
    } else {
      try {
        const Solid solid(*parent);
        std::vector<std::int32_t> all(event.seeds.size());
        std::iota(all.begin(), all.end(), 0);
        CutOptions cut_options;
        cut_options.threads = options.threads;
        CutResult cut_result = cut(solid, event.seeds, all, cut_options);
        if (cut_result.seed_nudge > 0) {
          warn(fmt::format("event {}: seeds moved by up to {:.3g} so that no cell boundary passes exactly through a "
                           "reflex vertex or concave edge",
                           e, cut_result.seed_nudge));
        }
        std::map<std::int32_t, std::string> failed;
        for (const CellFailure& f : cut_result.failures) failed[f.seed] = f.message;

        // Per seed: the bodies of the simulator and the exact components; pairs
        // taken greedily by increasing distance between centroid and centre.
        std::map<std::int32_t, std::vector<std::size_t>> exact_of_seed;
        for (std::size_t f = 0; f < cut_result.fragments.size(); ++f)
          exact_of_seed[cut_result.fragments[f].seed].push_back(f);
        std::vector<Vec3d> centroid(cut_result.fragments.size());
        for (std::size_t f = 0; f < centroid.size(); ++f)
          centroid[f] = mesh::mass_properties(cut_result.fragments[f].mesh).centroid;
        std::vector<bool> taken(cut_result.fragments.size(), false);
        struct Pair {
          double distance;
          std::size_t match, fragment;
        };
        std::vector<Pair> pairs;
        for (std::size_t k = first_match; k < r.bodies.size(); ++k) {
          BodyMatch& m = r.bodies[k];
          if (!m.problem.empty()) continue;
          const std::int32_t local = m.seed - base;
          const Vec3d& center = run.bodies[static_cast<std::size_t>(m.body)].reference_center;
          for (const std::size_t f : exact_of_seed[local]) pairs.push_back({(centroid[f] - center).norm(), k, f});
        }
        std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
          return a.distance != b.distance ? a.distance < b.distance
                                          : (a.match != b.match ? a.match < b.match : a.fragment < b.fragment);
        });
        std::vector<bool> matched(r.bodies.size(), false);
        std::map<std::size_t, Fragment> given;  // by match, to keep the bodies' order
        for (const Pair& p : pairs) {
          if (matched[p.match] || taken[p.fragment]) continue;
          matched[p.match] = taken[p.fragment] = true;
          BodyMatch& m = r.bodies[p.match];
          Fragment fragment = cut_result.fragments[p.fragment];
          m.component = fragment.component;
          m.volume = fragment.volume;
          m.center_distance = p.distance;
          m.volume_tolerance = kResolutionFactor * surface_area(fragment.mesh) * m.spacing;
          if (std::fabs(m.volume - m.voxel_volume) > m.volume_tolerance) {
            m.problem = fmt::format("its exact volume {:.6g} differs from its voxels' {:.6g} by more than the voxel "
                                    "resolution allows ({:.3g})",
                                    m.volume, m.voxel_volume, m.volume_tolerance);
          }
          body_mesh[m.body] = fragment.mesh;
          fragment.seed = m.seed;
          fragment.body = m.body;
          given[p.match] = std::move(fragment);
        }
        for (auto& [k, fragment] : given) r.fragments.fragments.push_back(std::move(fragment));
        for (std::size_t k = first_match; k < r.bodies.size(); ++k) {
          BodyMatch& m = r.bodies[k];
          if (matched[k] || !m.problem.empty()) continue;
          const std::int32_t local = m.seed - base;
          if (const auto it = failed.find(local); it != failed.end()) {
            m.problem = fmt::format("the cell of its seed could not be cut: {}", it->second);
          } else {
            m.problem = fmt::format("the exact cut gives seed {} of event {} {} fragments, all taken by other bodies "
                                    "(the voxels make more pieces than the exact solid)",
                                    local, e, exact_of_seed[local].size());
          }
        }
        for (std::size_t f = 0; f < taken.size(); ++f) {
          if (taken[f]) continue;
          ++r.spare;
          r.spare_volume += cut_result.fragments[f].volume;
          warn(fmt::format("event {}: exact fragment of seed {} (component {}, volume {:.3g}) matches no body",
                           e, cut_result.fragments[f].seed, cut_result.fragments[f].component,
                           cut_result.fragments[f].volume));
        }
      } catch (const Error& error) {
        fail_event(fmt::format("event {} (t = {:g} s): {}", e, event.time, error.what()));
      }
    }
    for (std::size_t k = first_match; k < r.bodies.size(); ++k) {
      const BodyMatch& m = r.bodies[k];
      if (m.component < 0) {
        ++r.unmatched;
        if (m.body >= 0 && !body_problem.count(m.body)) body_problem[m.body] = m.problem;
      } else if (!m.problem.empty()) {
        ++r.poor;
      }
    }
    if (options.progress) options.progress(e + 1, run.fractures.size());
  }
  return r;
}

Report ReplayResult::report() const {
  Report report;
  report.set("result", passed() ? "pass" : "fail");
  report.set("source", source);
  report.set("events", static_cast<std::int64_t>(events));
  report.set("bodies", static_cast<std::int64_t>(bodies.size()));
  report.set("matched", static_cast<std::int64_t>(bodies.size() - unmatched));
  report.set("unmatched", static_cast<std::int64_t>(unmatched));
  report.set("poor_matches", static_cast<std::int64_t>(poor));
  report.set("spare_fragments", static_cast<std::int64_t>(spare));
  report.set("spare_volume", spare_volume);
  for (const BodyMatch& m : bodies) {
    Report& b = report.append("body_matches");
    b.set("body", static_cast<std::int64_t>(m.body));
    b.set("event", static_cast<std::int64_t>(m.event));
    b.set("seed", static_cast<std::int64_t>(m.seed));
    b.set("component", static_cast<std::int64_t>(m.component));
    b.set("volume", m.volume);
    b.set("voxel_volume", m.voxel_volume);
    b.set("volume_tolerance", m.volume_tolerance);
    b.set("center_distance", m.center_distance);
    b.set("problem", m.problem);
  }
  for (const std::string& w : warnings) report.append("warnings").set("message", w);
  return report;
}

std::string ReplayResult::text() const {
  std::string out = fmt::format("{}: {} fracture events, {} bodies created\n", source, events, bodies.size());
  out += fmt::format("  matched    {} of {} bodies ({} with volumes beyond the voxel resolution)\n",
                     bodies.size() - unmatched, bodies.size(), poor);
  if (spare) out += fmt::format("  spare      {} exact fragments no body took, volume {:.3g}\n", spare, spare_volume);
  for (const BodyMatch& m : bodies) {
    if (m.problem.empty()) continue;
    out += fmt::format("  body {:<5} event {}, seed {}: {}\n", m.body, m.event, m.seed, m.problem);
  }
  out += fmt::format("  result     {}\n", passed() ? "pass" : "FAIL");
  return out;
}

}  // namespace bw::voronoi
