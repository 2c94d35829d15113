#include "study_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <fmt/format.h>

#include "analysis/measure.h"
#include "common/error.h"
#include "fracture/fracture.h"
#include "io/frame_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "mesh/closest_point.h"
#include "scene/scene.h"

namespace bw::study {
namespace {

double parameter(const RunRecord& run, const std::string& name, const std::string& where) {
  for (const auto& [key, value] : run.parameters)
    if (key == name) return value;
  fail_input("{}: the run file has no parameter '{}'", where, name);
}

// With what left the domain, beyond what the emitters put in (sim/run.cpp's energy).
double total_energy(const FrameStats& s) {
  return s.kinetic_energy + s.potential_energy + s.elastic_energy - s.emitted_energy + s.outflow_energy;
}

// The voxels of one body of a run: its root solid's sampling grid and placement, its
// cells, and where they lie in the reference configuration.
struct BodyVoxels {
  const scene::Solid* solid = nullptr;
  SampleGrid grid;
  fracture::Piece piece;
  Vec3d reference_center = Vec3d::Zero();
  double radius = 0;  // of its voxels' centres around reference_center (m)
  std::unordered_map<std::int64_t, std::int32_t> cells;

  static std::int64_t key(const CellIndex& c) {
    constexpr std::int64_t kOffset = 1 << 20;
    return ((std::int64_t(c[2]) + kOffset) << 42) | ((std::int64_t(c[1]) + kOffset) << 21) | (std::int64_t(c[0]) + kOffset);
  }
  void index() {
    cells.clear();
    for (std::size_t v = 0; v < piece.cells.size(); ++v) cells[key(piece.cells[v])] = static_cast<std::int32_t>(v);
    radius = 0;
    for (const Vec3d& c : piece.centers) radius = std::max(radius, (c - reference_center).norm());
  }
  bool has(const CellIndex& c) const { return cells.count(key(c)) > 0; }
  // How deep a reference-configuration point lies inside the union of the voxels'
  // cubes (m): 0 outside, the distance to the nearest cell around its own that is not
  // a voxel, at most one voxel edge.
  double depth(const Vec3d& reference) const {
    const double scale = solid->scale;
    const Vec3d file = solid->rotation().conjugate() * (reference - solid->translation) / scale;
    const Vec3d g = (file - grid.origin) / grid.spacing;
    const CellIndex c{static_cast<std::int32_t>(std::floor(g.x())), static_cast<std::int32_t>(std::floor(g.y())),
                      static_cast<std::int32_t>(std::floor(g.z()))};
    if (!has(c)) return 0;
    double best = 1;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (has({c[0] + dx, c[1] + dy, c[2] + dz})) continue;
          // distance (in cells) from g to the cell c + (dx, dy, dz)
          const Vec3d lo(c[0] + dx, c[1] + dy, c[2] + dz);
          const Vec3d d = (lo - g).cwiseMax(Vec3d::Zero()) + (g - lo - Vec3d::Ones()).cwiseMax(Vec3d::Zero());
          best = std::min(best, d.norm());
        }
    return best * grid.spacing * scale;
  }
};

// The voxels of every body of a run, in the run's body order: a dynamic or breakable
// solid's from its particles file, a fragment's by splitting its parent's as the
// simulator did (fracture::split, with the seeds the run file recorded). Throws when
// a body's voxel count does not match the run file's.
std::vector<BodyVoxels> body_voxels(const RunRecord& run, const scene::Scene& scene, const std::string& where) {
  std::vector<BodyVoxels> out(run.bodies.size());
  std::vector<bool> known(run.bodies.size(), false);
  for (std::size_t b = 0; b < run.bodies.size(); ++b) {
    const BodyRecord& rec = run.bodies[b];
    if (rec.parent >= 0) continue;
    if (rec.solid < 0 || static_cast<std::size_t>(rec.solid) >= scene.solids.size())
      fail_input("{}: body {} names solid {}, which the scene does not have", where, b, rec.solid);
    BodyVoxels& bv = out[b];
    bv.solid = &scene.solids[static_cast<std::size_t>(rec.solid)];
    const SampledSolid sampled = read_particles(bv.solid->particles);
    bv.grid = sampled.grid;
    bv.piece.cells = sampled.voxels;
    for (const Vec3d& c : sampled.voxel_positions()) bv.piece.centers.push_back(bv.solid->to_world(c));
    for (const Vec3d& q : sampled.surface_positions()) {
      bv.piece.particles.push_back(bv.solid->to_world(q));
      bv.piece.normals.push_back(Vec3d::Zero());
    }
    bv.piece.particle_cells = sampled.surface;
    known[b] = true;
  }
  for (const FractureEvent& e : run.fractures) {
    const auto parent = static_cast<std::size_t>(e.parent);
    if (e.parent < 0 || parent >= out.size() || !known[parent])
      fail_input("{}: a fracture at t = {} s breaks body {}, whose voxels are not known", where, e.time, e.parent);
    const BodyVoxels& pv = out[parent];
    const double voxel = pv.grid.spacing * pv.solid->scale;
    std::vector<fracture::Fragment> fragments = fracture::split(pv.piece, e.seeds, voxel, 1.0);
    for (std::size_t k = 0; k < e.child_body.size(); ++k) {
      const auto child = static_cast<std::size_t>(e.child_body[k]);
      auto it = std::find_if(fragments.begin(), fragments.end(), [&](const fracture::Fragment& f) {
        return f.seed == e.child_seed[k] && f.component == e.child_component[k];
      });
      if (child >= out.size() || it == fragments.end())
        fail_input("{}: the fracture at t = {} s has a child (body {}, seed {}, component {}) that splitting its "
                   "parent does not give",
                   where, e.time, e.child_body[k], e.child_seed[k], e.child_component[k]);
      out[child].solid = pv.solid;
      out[child].grid = pv.grid;
      out[child].piece = std::move(it->piece);
      known[child] = true;
    }
  }
  for (std::size_t b = 0; b < out.size(); ++b) {
    if (!known[b]) fail_input("{}: body {} ('{}') has no voxels from its solid or a fracture", where, b, run.bodies[b].name);
    // A solid moved as told records no voxels (its mass is nominal); its sampled ones
    // still say where it is solid.
    const bool told = out[b].solid->moving() && run.bodies[b].voxels == 0;
    if (!told && static_cast<std::int64_t>(out[b].piece.size()) != run.bodies[b].voxels)
      fail_input("{}: body {} ('{}') has {} voxels in the run file, {} rebuilt from its solid and the fractures", where,
                 b, run.bodies[b].name, run.bodies[b].voxels, out[b].piece.size());
    out[b].reference_center = run.bodies[b].reference_center;
    out[b].index();
  }
  return out;
}

}  // namespace

RunIndicators read_indicators(const std::string& run_dir) {
  const std::string path = run_dir + "/run.h5";
  const RunRecord run = read_run(path);
  RunIndicators r;
  r.status = run.status;
  if (run.frames.empty()) fail_input("{}: holds no frame", path);
  const FrameStats& first = run.frames.front();
  const FrameStats& last = run.frames.back();
  r.wall_time = last.wall_time;
  r.simulated_time = last.time;
  r.steps = static_cast<double>(last.steps);
  r.fluid = static_cast<double>(first.fluid);
  r.removed = static_cast<double>(last.removed);
  const double e0 = total_energy(first);
  double highest = e0;
  for (const FrameStats& s : run.frames) {
    r.density_error_worst = std::max(r.density_error_worst, s.density_error_max);
    r.speed_worst = std::max(r.speed_worst, s.speed_max);
    highest = std::max(highest, total_energy(s));
  }
  // The larger of the initial total and what the emitters put in (sim::RunSummary).
  const double scale = std::max(std::abs(e0), last.emitted_energy) > 0 ? std::max(std::abs(e0), last.emitted_energy) : 1.0;
  r.energy_drift = (total_energy(last) - e0) / scale;
  r.energy_growth = (highest - e0) / scale;
  r.spacing = parameter(run, "spacing", path);
  r.h = parameter(run, "smoothing_length", path);
  r.c0 = parameter(run, "c0", path);
  return r;
}

DamBreakError dambreak_error(const std::string& run_dir, const analysis::DamBreakSetup& setup,
                             const std::string& reference_csv) {
  std::vector<analysis::DamBreakSample> samples;
  for (const std::string& frame : analysis::list_frames(run_dir + "/frames"))
    samples.push_back(analysis::measure_dambreak(read_frame(frame), setup));
  const analysis::DamBreakReference reference = analysis::read_dambreak_reference(reference_csv);
  DamBreakError e;
  e.comparison = analysis::compare_dambreak(samples, setup, reference);
  // Shifts of the time origin over +-kShiftRange in steps of kShiftStep (in T): the
  // experiment's points stay within the run as long as the run goes on past the last
  // one by kShiftRange.
  constexpr double kShiftRange = 1.0, kShiftStep = 0.01;
  const double t_of_T = 1 / std::sqrt(2 * setup.gravity / setup.column_width);
  e.front_rms_shifted = e.comparison.front.rms;
  for (double dT = -kShiftRange; dT <= kShiftRange + 1e-9; dT += kShiftStep) {
    std::vector<analysis::DamBreakSample> shifted = samples;
    for (analysis::DamBreakSample& s : shifted) s.time += dT * t_of_T;
    // Delayed, the column stands as it starts until the release.
    if (dT > 0 && !samples.empty()) shifted.insert(shifted.begin(), samples.front());
    const analysis::SeriesError f = analysis::compare_dambreak(shifted, setup, reference).front;
    if (f.skipped == 0 && f.rms < e.front_rms_shifted) {
      e.front_rms_shifted = f.rms;
      e.front_shift = dT;
    }
  }
  return e;
}

double front_difference(const std::string& run_dir, const analysis::DamBreakSetup& setup, const std::string& other_dir,
                        const analysis::DamBreakSetup& other_setup, const std::string& reference_csv) {
  // The other run's front series stands in for the experiment's: compare_dambreak
  // interpolates this run's front at its times.
  analysis::DamBreakReference reference = analysis::read_dambreak_reference(reference_csv);
  std::vector<analysis::DamBreakSample> other;
  for (const std::string& frame : analysis::list_frames(other_dir + "/frames"))
    other.push_back(analysis::measure_dambreak(read_frame(frame), other_setup));
  const double T_of_t = std::sqrt(2 * other_setup.gravity / other_setup.column_width);
  auto other_front = [&](double T) {
    for (std::size_t i = 0; i + 1 < other.size(); ++i) {
      const double t0 = other[i].time * T_of_t, t1 = other[i + 1].time * T_of_t;
      if (T >= t0 && T <= t1)
        return (other[i].front + (other[i + 1].front - other[i].front) * (T - t0) / (t1 - t0)) / other_setup.column_width;
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  for (analysis::ReferencePoint& p : reference.front) {
    p.value = other_front(p.T);
    if (!std::isfinite(p.value)) fail_input("{}: its frames do not reach T = {} of the experiment", other_dir, p.T);
  }
  std::vector<analysis::DamBreakSample> samples;
  for (const std::string& frame : analysis::list_frames(run_dir + "/frames"))
    samples.push_back(analysis::measure_dambreak(read_frame(frame), setup));
  return analysis::compare_dambreak(samples, setup, reference).front.rms;
}

HydrostaticError hydrostatic_error(const std::string& run_dir, const Vec3d& point, double surface, double radius,
                                   double from) {
  const std::string path = run_dir + "/run.h5";
  const RunRecord run = read_run(path);
  const double rho0 = parameter(run, "rho0", path);
  const scene::Scene scene = scene::parse_scene(run.scene_text, run.scene_path);
  HydrostaticError e;
  e.expected = rho0 * scene.gravity.norm() * (surface - point.z());
  if (!(e.expected > 0)) fail_input("hydrostatic: the point {} m lies above the surface {} m", point.z(), surface);
  double sum = 0;
  for (const std::string& name : analysis::list_frames(run_dir + "/frames")) {
    const FrameData frame = read_frame(name);
    if (frame.time < from) continue;
    const double p = analysis::probe(frame, analysis::Field::pressure, point, radius);
    if (!std::isfinite(p)) fail_input("{}: no fluid within {} m of the probe at t = {} s", name, radius, frame.time);
    sum += p;
    ++e.frames;
  }
  if (e.frames == 0) fail_input("{}: no frame at or after t = {} s", run_dir, from);
  e.pressure = sum / e.frames;
  e.relative = e.pressure / e.expected - 1;
  const SensorRecord& sensors = run.sensors;
  for (std::size_t k = 0; k < sensors.names.size(); ++k) {
    if (sensors.names[k] != "floor") continue;
    int samples = 0;
    e.floor_pressure = sensors.mean_from(k, from, &samples);
    if (samples == 0) fail_input("{}: no sample of sensor 'floor' at or after t = {} s", path, from);
    e.floor_expected = rho0 * scene.gravity.norm() * (surface - sensors.at[k].z());
    e.floor_relative = e.floor_pressure / e.floor_expected - 1;
  }
  return e;
}

double distance_to_surface(const TriMesh& mesh, const Vec3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Triangle& t : mesh.triangles) {
    best = std::min(best, mesh::point_triangle_distance(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
  }
  return best;
}

double winding_number(const TriMesh& mesh, const Vec3d& p) {
  // Van Oosterom and Strackee's signed solid angle of each triangle seen from p.
  double omega = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3d a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    omega += 2 * std::atan2(numerator, denominator);
  }
  return omega / (4 * std::numbers::pi);
}

StabilityReport check_stability(const std::string& run_dir, const StabilityLimits& limits) {
  StabilityReport report;
  report.run = read_indicators(run_dir);
  const RunRecord run = read_run(run_dir + "/run.h5");
  const scene::Scene scene = scene::parse_scene(run.scene_text, run.scene_path);
  const double spacing = report.run.spacing;

  // The static solids' meshes in the world, with their bounding boxes for a quick
  // rejection; bodies (dynamic and breakable solids, and their fragments) by their
  // voxels, where each frame's body states put them.
  std::vector<TriMesh> solids;
  std::vector<Aabb> boxes;
  for (const scene::Solid& solid : scene.solids) {
    TriMesh m;
    if (!solid.body() && !solid.moving()) {  // bodies and solids moved as told: by their voxels, below
      m = read_particles(solid.particles).mesh;
      for (Vec3d& v : m.vertices) v = solid.to_world(v);
    }
    boxes.push_back(m.bounds());
    solids.push_back(std::move(m));
  }
  const std::vector<BodyVoxels> bodies = body_voxels(run, scene, run_dir + "/run.h5");

  for (const std::string& name : analysis::list_frames(run_dir + "/frames")) {
    const FrameData frame = read_frame(name);
    const BodyStates& states = frame.bodies;
    long bad = 0;
    for (std::size_t i = 0; i < frame.fluid_count(); ++i) {
      const Vec3d q(frame.x[i], frame.y[i], frame.z[i]);
      if (!q.allFinite()) {
        ++report.nonfinite;
        ++bad;
        continue;
      }
      if ((q.array() < scene.domain.min.array()).any() || (q.array() > scene.domain.max.array()).any()) {
        ++report.outside_domain;
        ++bad;
      }
      bool inside = false;
      for (std::size_t s = 0; s < solids.size() && !inside; ++s) {
        if (solids[s].triangles.empty()) continue;
        if ((q.array() < boxes[s].min.array()).any() || (q.array() > boxes[s].max.array()).any()) continue;
        if (std::abs(winding_number(solids[s], q)) > 0.5) {
          const double depth = distance_to_surface(solids[s], q) / spacing;
          report.deepest = std::max(report.deepest, depth);
          inside = depth >= limits.penetration;
        }
      }
      for (std::size_t k = 0; k < states.id.size() && !inside; ++k) {
        const auto b = static_cast<std::size_t>(states.id[k]);
        if (b >= bodies.size()) fail_input("{}: body {} is not in the run file", name, states.id[k]);
        const BodyVoxels& bv = bodies[b];
        if ((q - states.position[k]).norm() > bv.radius + 2 * spacing) continue;
        const Vec3d reference = states.orientation[k].conjugate() * (q - states.position[k]) + bv.reference_center;
        const double depth = bv.depth(reference) / spacing;
        if (depth <= 0) continue;
        report.deepest = std::max(report.deepest, depth);
        inside = depth >= limits.penetration;
      }
      if (inside) {
        ++report.inside_solids;
        ++bad;
      }
    }
    if (bad > 0 && report.first_bad_frame < 0) report.first_bad_frame = frame.frame;
    ++report.frames;
  }

  auto& f = report.failures;
  const RunIndicators& r = report.run;
  if (!r.complete()) f.push_back("did not finish: " + r.status);
  if (report.nonfinite > 0) f.push_back(fmt::format("{} non-finite positions", report.nonfinite));
  auto& l = report.leaks;
  if (r.removed > 0) l.push_back(fmt::format("{} particles left the domain", r.removed));
  if (report.outside_domain > 0) l.push_back(fmt::format("{} particle positions outside the domain", report.outside_domain));
  if (report.inside_solids > 0)
    l.push_back(fmt::format("{} particle positions inside solids, behind their boundary particles (first in frame {}, "
                            "deepest {:.3f} spacings)",
                            report.inside_solids, report.first_bad_frame, report.deepest));
  const double density_limit = limits.density_error_limit(r);
  if (!(r.density_error_worst <= density_limit))
    f.push_back(fmt::format("worst density error {:.4f} above {:.4f} (2 x the fastest fluid, {:.1f} m/s, over c0, "
                            "at least {})",
                            r.density_error_worst, density_limit, r.speed_worst, limits.density_error));
  if (!(r.energy_growth <= limits.energy_growth))
    f.push_back(fmt::format("energy rose {:.2e} of its initial total, above {}", r.energy_growth, limits.energy_growth));
  if (!(r.energy_drift <= limits.energy_final_growth))
    f.push_back(fmt::format("energy ended {:.2e} of its initial total above it, above {}", r.energy_drift,
                            limits.energy_final_growth));
  return report;
}

}  // namespace bw::study
