#include "export/job.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/terminal.h"
#include "export/blender_scene.h"
#include "export/wall_points.h"
#include "io/frame_file.h"
#include "io/run_file.h"
#include "mesh/import.h"
#include "render/framing.h"
#include "render/render_settings.h"

namespace bw::exporter {
namespace fs = std::filesystem;
namespace {

std::string beside_frames(const std::string& frames_dir, const char* name) {
  std::error_code ec;
  const fs::path guess = fs::path(frames_dir) / ".." / name;
  return fs::exists(guess, ec) ? guess.lexically_normal().string() : std::string();
}

// Frames per second: the run's, or else what the frames' numbers and times say.
double frame_rate_of(const RunRecord& run, const std::vector<FrameRef>& frames) {
  for (const auto& [name, value] : run.parameters)
    if (name == "frame_rate" && value > 0 && std::isfinite(value)) return value;
  for (auto f = frames.rbegin(); f != frames.rend(); ++f)
    if (f->number > 0 && f->time > 0) return f->number / f->time;
  return 30;  // one frame at time 0: any rate shows it
}

}  // namespace

std::string water_file_name(const std::string& dir, int frame, const std::string& extension) {
  return fmt::format("{}/water_{:06d}.{}", dir, frame, extension);
}

std::string wall_points_file_name(const std::string& dir, int frame) {
  return fmt::format("{}/wall_pressure_{:06d}.vdb", dir, frame);
}

ExportPlan plan_export(const ExportJob& job) {
  ExportPlan plan;
  if (!job.water && !job.solids && !job.wall_pressure)
    fail_input("nothing to export: both the water and the solids are left out");
  if (!job.mesh_format.empty() && job.mesh_format != "obj" && job.mesh_format != "ply")
    fail_input("--mesh '{}': expected obj or ply", job.mesh_format);
  if (!job.mesh_format.empty() && !job.water) fail_input("--mesh asks for the water, which --no-water leaves out");
  if (job.density && !job.water) fail_input("--density asks for the water, which --no-water leaves out");
  if (!(job.mesh_adaptivity >= 0 && job.mesh_adaptivity <= 1))
    fail_input("--adaptivity {}: expected a value in [0, 1]", job.mesh_adaptivity);
  plan.frames = resolve_frames(job.frames_dir, job.range);

  plan.run_path = job.run_path.empty() ? beside_frames(job.frames_dir, "run.h5") : job.run_path;
  plan.fragments_path = job.fragments_path.empty() ? beside_frames(job.frames_dir, "fragments.h5") : job.fragments_path;
  RunRecord run;
  if (!plan.run_path.empty()) run = read_run(plan.run_path);

  if (job.wall_pressure)  // every frame holds the field before anything is written
    for (const FrameRef& f : plan.frames) require_wall_pressure(read_frame_header(f.path).fields, f.path);

  if (job.water || job.wall_pressure) {
    plan.water_options = job.water_options;
    if (plan.water_options.spacing > 0) {
      plan.spacing_source = "--spacing";
    } else {
      plan.water_options.spacing = run.parameter("spacing").value_or(0);
      if (!(plan.water_options.spacing > 0)) {
        if (plan.run_path.empty())
          fail_input("{}: no run file beside the frames to take the particle spacing from; give --run or --spacing",
                     job.frames_dir);
        fail_input("{}: /parameters/spacing is missing; give --spacing", plan.run_path);
      }
      plan.spacing_source = plan.run_path + ":/parameters/spacing";
      if (!std::isfinite(plan.water_options.spacing))
        fail_input("{}: the particle spacing {} is not finite; give --spacing", plan.spacing_source,
                   plan.water_options.spacing);
    }
    plan.water_options.resolve("");
  }

  plan.solids = job.solids && !plan.run_path.empty() && !run.solids.empty();
  if (job.solids && job.run_path.empty() && plan.run_path.empty() && !job.water)
    fail_input("{}: no run file beside the frames, so no solids to export; give --run", job.frames_dir);
  if (!job.run_path.empty() && job.solids && run.solids.empty() && !job.water)
    fail_input("{}: the run has no solids to export", job.run_path);

  // blender_scene.py comes with solids.glb, and without solids with the water alone.
  plan.blender_script = job.solids;
  if (!job.scene_path.empty() && !job.solids)
    fail_input("--scene {}: its camera and look go into solids.glb and blender_scene.py, which --no-solids leaves out",
               job.scene_path);
  if (job.solids) {
    // The look bw-render draws with: [camera], [light] and [render] of the run's scene or of --scene.
    try {
      if (!job.scene_path.empty()) {
        plan.look = render::load_render_settings(job.scene_path);
        plan.camera_source = job.scene_path;
      } else if (!run.scene_text.empty()) {
        plan.look = render::parse_render_settings(run.scene_text, plan.run_path + ": scene");
        plan.camera_source = "the scene of " + plan.run_path;
      }
    } catch (const InputError& e) {
      fail_input("{} (the camera of solids.glb and the look of blender_scene.py come from it)", e.what());
    }
  }
  plan.frame_rate = frame_rate_of(run, plan.frames);
  if (plan.solids && job.camera) {
    const render::RenderSettings& look = plan.look;
    const double aspect = static_cast<double>(look.width) / look.height;
    if (look.camera) {
      plan.camera = GltfCamera{*look.camera, aspect, render::tracked_body(look, plan.run_path)};
      // A moving camera is drawable, and a tracked body there, in every frame: checked
      // before anything is written.
      const GltfCamera& c = *plan.camera;
      if (c.path.animated() || c.track.id >= 0)
        for (const FrameRef& f : plan.frames)
          render::frame_camera(c.path, c.track, f.time,
                               c.track.id >= 0 ? read_frame_header(f.path, true).bodies : BodyStates{}, f.path);
    } else {
      plan.fit_camera = true;  // by run_export, from the solids it reads
    }
  }

  if (job.output_dir.empty()) fail_input("no output folder given (-o)");
  std::error_code ec;
  if (!fs::is_directory(job.output_dir, ec)) {
    fs::create_directories(job.output_dir, ec);
    if (ec) fail_input("{}: cannot create the output folder: {}", job.output_dir, ec.message());
  }
  if (::access(job.output_dir.c_str(), W_OK) != 0) fail_input("{}: the output folder is not writable", job.output_dir);
  return plan;
}

ExportReport run_export(const ExportJob& job, const std::function<void(const ExportProgress&)>& on_frame) {
  Stopwatch clock;
  const ExportPlan plan = plan_export(job);
  ExportReport report;
  report.frames = plan.frames.size();
  report.first = plan.frames.front().number;
  report.last = plan.frames.back().number;
  report.water_options = plan.water_options;
  report.spacing_source = plan.spacing_source;

  // Inputs of the glTF are read before any file is written, so that a bad run or
  // fragments file leaves nothing behind.
  SolidSet solids;
  if (plan.solids) solids = SolidSet::load(plan.run_path, plan.fragments_path);
  std::optional<GltfCamera> camera = plan.camera;
  report.camera_source = plan.camera_source;
  if (plan.fit_camera) {
    // No [camera]: the one bw-render fits to the reference frame, from the same
    // frames, solids and look, so Blender sees what the images show.
    const render::SolidScene scene = render::SolidScene::from(solids.run, solids.solid_meshes, solids.fragments,
                                                              {plan.run_path, plan.fragments_path}, {});
    const render::Framing framing = render::frame_sequence(
        render::reference_frame_candidates(require_frame_files(job.frames_dir)), plan.look, scene);
    camera = GltfCamera{render::CameraPath::fixed(framing.camera),
                        static_cast<double>(plan.look.width) / plan.look.height};
    report.camera_source = fmt::format("the fit to {} (as bw-render's)", framing.reference_frame);
  }
  if (camera) {
    report.camera_keys = camera->path.keys().size();
    report.camera_track = camera->track.name;
  }

  std::vector<PoseFrame> poses;
  double water_seconds = 0;
  for (std::size_t k = 0; k < plan.frames.size(); ++k) {
    const FrameRef& ref = plan.frames[k];
    FrameData frame = read_frame(ref.path);
    if (job.wall_pressure) {
      // On a grid of the particles' spacing: a few points a voxel, as OpenVDB's points like.
      const std::size_t n = write_wall_points(frame, plan.water_options.up, plan.water_options.spacing,
                                              wall_points_file_name(job.output_dir, ref.number), ref.path);
      report.max_wall_points = std::max(report.max_wall_points, n);
    }
    if (plan.solids) poses.push_back({ref.number, frame.time, std::move(frame.bodies)});
    if (job.water) {
      Stopwatch water_clock;
      const WaterSurface surface = WaterSurface::build(frame.x.data(), frame.y.data(), frame.z.data(),
                                                       frame.fluid_count(), plan.water_options);
      surface.write_vdb(water_file_name(job.output_dir, ref.number, "vdb"), job.density);
      water_seconds += water_clock.seconds();
      report.max_particles = std::max(report.max_particles, surface.stats().particles);
      report.max_voxels = std::max(report.max_voxels, surface.stats().active_voxels);
      if (!job.mesh_format.empty()) {
        const TriMesh mesh = surface.mesh(job.mesh_adaptivity);
        report.max_triangles = std::max(report.max_triangles, mesh.triangles.size());
        mesh::export_mesh(mesh, water_file_name(job.output_dir, ref.number, job.mesh_format));
      }
    }
    if (on_frame) on_frame({k + 1, plan.frames.size(), ref.number, clock.seconds()});
  }
  if (job.water) report.water_ms_per_frame = 1000 * water_seconds / static_cast<double>(plan.frames.size());

  if (plan.solids) {
    report.gltf_path = job.output_dir + "/solids.glb";
    const std::vector<std::uint8_t> glb =
        build_glb(solids, poses, plan.run_path, &report.gltf, camera ? &*camera : nullptr);
    write_file_atomically(report.gltf_path, glb.data(), glb.size());
  }
  if (plan.blender_script) {
    report.blender_script_path = job.output_dir + "/blender_scene.py";
    const std::string script = blender_scene_script(
        {plan.run_path, plan.frame_rate, report.first, report.last, job.water_options.up, plan.look});
    write_file_atomically(report.blender_script_path, script.data(), script.size());
  }
  report.seconds = clock.seconds();
  return report;
}

}  // namespace bw::exporter
