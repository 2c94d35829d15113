#include "render/framing.h"

#include <algorithm>

#include <fmt/format.h>

#include "common/error.h"
#include "io/frame_file.h"
#include "io/run_file.h"
#include "render/particle_spacing.h"
#include "render/view_fit.h"

namespace bw::render {
namespace {

// The reference frame is the folder's first with at least kReferenceParticles
// particles (a scene with emitters starts nearly empty), among its first
// kReferenceScan frames; failing that, the folder's first.
constexpr std::size_t kReferenceParticles = 64;
constexpr std::size_t kReferenceScan = 32;
// Sphere radius (m) when the reference frame has too few particles to measure their
// spacing: a centimetre suits the metre-sized example scenes.
constexpr double kFallbackRadius = 0.01;

}  // namespace

std::vector<std::string> reference_frame_candidates(const std::map<int, std::string>& frames) {
  std::vector<std::string> out;
  for (const auto& [number, path] : frames) {
    if (out.size() == kReferenceScan) break;
    out.push_back(path);
  }
  return out;
}

TrackedBody tracked_body(const RenderSettings& settings, const std::string& run_path) {
  TrackedBody track;
  if (settings.camera_track.empty()) return track;
  track.name = settings.camera_track;
  if (run_path.empty())
    fail_input("camera.track '{}': no run file beside the frames to find the body in; give --run", track.name);
  const RunRecord run = read_run(run_path);
  std::string names;
  for (std::size_t b = 0; b < run.bodies.size(); ++b) {
    if (run.bodies[b].name == track.name) {
      track.id = static_cast<std::int32_t>(b);
      track.reference_center = run.bodies[b].reference_center;
      return track;
    }
    if (b < 8) names += (names.empty() ? "" : ", ") + run.bodies[b].name;
  }
  if (run.bodies.size() > 8) names += fmt::format(" and {} more", run.bodies.size() - 8);
  fail_input("camera.track '{}': {} has no body of that name ({})", track.name, run_path,
             names.empty() ? "it has no bodies" : "its bodies: " + names);
}

Camera frame_camera(const CameraPath& path, const TrackedBody& track, double time, const BodyStates& bodies,
                    const std::string& frame) {
  Camera c = path.at(time);
  if (track.id >= 0) {
    const auto row = std::find(bodies.id.begin(), bodies.id.end(), track.id);
    if (row == bodies.id.end())
      fail_input("{}: camera.track: the body '{}' is not in this frame (t = {:.6g} s): not made yet, or broken", frame,
                 track.name, time);
    c.target = bodies.position[static_cast<std::size_t>(row - bodies.id.begin())];
  }
  if (const std::string problem = camera_problem(c); !problem.empty())
    fail_input("{}: the camera at t = {:.6g} s: {}", frame, time, problem);
  return c;
}

Framing frame_sequence(const std::vector<std::string>& candidates, const RenderSettings& settings,
                       const SolidScene& solids, const TrackedBody& track) {
  Framing framing;
  FrameData reference = read_frame(candidates.front());
  framing.reference_frame = candidates.front();
  for (std::size_t k = 1; k < candidates.size() && reference.fluid_count() < kReferenceParticles; ++k) {
    FrameData next = read_frame(candidates[k]);
    if (next.fluid_count() >= kReferenceParticles) {
      reference = std::move(next);
      framing.reference_frame = candidates[k];
    }
  }
  framing.reference_time = reference.time;
  const double spacing =
      estimate_particle_spacing(reference.x.data(), reference.y.data(), reference.z.data(), reference.fluid_count());
  double radius = settings.particle_radius;
  if (!(radius > 0)) radius = spacing > 0 ? settings.particle_radius_factor * spacing : kFallbackRadius;
  framing.particle_radius = radius;
  framing.particle_spacing = spacing;

  Aabb solid_box = solids.reference_bounds();
  const TriangleSoup reference_solids = solids.place(reference.bodies);
  const Aabb placed = reference_solids.bounds();
  if (!placed.empty()) solid_box.add(placed.min), solid_box.add(placed.max);
  std::vector<Vec3d> water;
  water.reserve(reference.fluid_count());
  Aabb box = solid_box;
  for (std::size_t i = 0; i < reference.fluid_count(); ++i) {
    const Vec3d p(reference.x[i], reference.y[i], reference.z[i]);
    if (!p.allFinite()) continue;
    water.push_back(p);
    box.add(p - Vec3d::Constant(radius));
    box.add(p + Vec3d::Constant(radius));
  }
  framing.ground_height = settings.ground_height.value_or(box.empty() ? 0.0 : box.min.z());
  const double aspect = static_cast<double>(settings.width) / settings.height;
  // Solids hide water: the fitted view is chosen to see it, and either camera is
  // checked for how much of it it sees.
  const Occluders occluders(reference_solids);
  if (settings.camera) {
    framing.camera = settings.camera->at(reference.time);
    if (track.id >= 0) {  // where the body is, or was made when it comes later
      const auto row = std::find(reference.bodies.id.begin(), reference.bodies.id.end(), track.id);
      framing.camera.target = row == reference.bodies.id.end()
                                  ? track.reference_center
                                  : reference.bodies.position[static_cast<std::size_t>(row - reference.bodies.id.begin())];
    }
  } else {
    ViewFitInput fit;
    fit.solids = solid_box;
    fit.occluders = &occluders;
    fit.particle_radius = radius;
    if (settings.ground) fit.ground_height = framing.ground_height;
    fit.water = water;
    const FittedView view = fit_view(fit, Camera{}.fov_degrees, aspect);
    framing.camera = view.camera;
    framing.camera_fitted = true;
    framing.fit_azimuth = view.azimuth;
    framing.fit_elevation = view.elevation;
    framing.fit_surface_seen = view.surface_seen;
    framing.fit_floor_seen = view.floor_seen;
  }
  framing.reference_water = water.size();
  framing.water_seen = fraction_seen(framing.camera, aspect, water, &occluders);
  return framing;
}

}  // namespace bw::render
