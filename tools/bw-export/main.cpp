// bw-export: a simulation's frames into the formats artists import: the water as
// OpenVDB level sets (and meshes), the solids as one animated glTF.
#include <cstdio>

#include "cli/tool.h"
#include "common/terminal.h"
#include "common/text.h"
#include "export/job.h"

namespace {

struct Options {
  std::string frames_dir;
  std::string output_dir;
  std::string frames;
  std::string run;
  std::string fragments;
  std::string mesh;
  double adaptivity = 0;
  double spacing = 0, radius = 0, voxel = 0;
  int smooth = 1;
  double erode = 0;
  std::string up = "z";
  bool density = false;
  bool wall_pressure = false;
  bool no_water = false;
  bool no_solids = false;
  std::string scene;
  bool no_camera = false;
  bool quiet = false;
  bool verbose = false;

  bw::exporter::ExportJob job() const {
    bw::exporter::ExportJob j;
    j.frames_dir = frames_dir;
    j.output_dir = output_dir;
    if (!frames.empty()) j.range = bw::exporter::parse_frame_range(frames);
    j.run_path = run;
    j.fragments_path = fragments;
    j.water = !no_water;
    j.density = density;
    j.wall_pressure = wall_pressure;
    j.mesh_format = mesh;
    j.mesh_adaptivity = adaptivity;
    j.solids = !no_solids;
    j.scene_path = scene;
    j.camera = !no_camera;
    j.water_options.spacing = spacing;
    j.water_options.radius = radius;
    j.water_options.voxel = voxel;
    j.water_options.smooth = smooth;
    j.water_options.erode = erode;
    j.water_options.up = up == "y" ? bw::exporter::Up::kY : bw::exporter::Up::kZ;
    return j;
  }
};

void print_summary(const Options& o, const bw::exporter::ExportReport& r) {
  std::fprintf(stderr, "bw-export: %zu frame%s (%06d..%06d) -> %s in %s\n", r.frames, r.frames == 1 ? "" : "s",
               r.first, r.last, o.output_dir.c_str(), bw::human_duration(r.seconds).c_str());
  if (!o.no_water) {
    const auto& w = r.water_options;
    std::fprintf(stderr, "  water        water_NNNNNN.vdb%s%s, %.0f ms per frame, up to %zu particles, %zu voxels\n",
                 o.mesh.empty() ? "" : " and .", o.mesh.c_str(), r.water_ms_per_frame, r.max_particles,
                 r.max_voxels);
    if (o.verbose)
      std::fprintf(stderr, "  level set    spacing %.4g m (%s), radius %.4g m, voxel %.4g m, %d smoothing pass%s, "
                   "erode %.4g m\n",
                   w.spacing, r.spacing_source.c_str(), w.radius, w.voxel, w.smooth, w.smooth == 1 ? "" : "es",
                   w.erode);
  }
  if (o.wall_pressure)
    std::fprintf(stderr, "  wall         wall_pressure_NNNNNN.vdb, points \"wall_pressure\" (P, pressure, solid), up to "
                 "%zu a frame\n",
                 r.max_wall_points);
  if (!r.gltf_path.empty()) {
    std::fprintf(stderr, "  solids       %s: %zu static, %zu bodies, %zu triangles, %s\n", r.gltf_path.c_str(),
                 r.gltf.static_nodes, r.gltf.body_nodes, r.gltf.triangles, bw::human_bytes(r.gltf.bytes).c_str());
    if (r.gltf.camera) {
      std::fprintf(stderr, "  camera       from %s, %s%s\n", r.camera_source.c_str(),
                   r.camera_keys > 1 ? fmt::format("moving ({} keys)", r.camera_keys).c_str() : "fixed",
                   r.camera_track.empty() ? "" : fmt::format(", looking at body '{}'", r.camera_track).c_str());
      const auto& c = r.gltf.camera_first;
      if (o.verbose)
        std::fprintf(stderr, "  at frame %-5d%g,%g,%g:%g,%g,%g:%g (as bw-render --camera takes it)\n", r.first,
                     c.position.x(), c.position.y(), c.position.z(), c.target.x(), c.target.y(), c.target.z(),
                     c.fov_degrees);
      if (r.gltf.fov_least != r.gltf.fov_most)
        std::fprintf(stderr,
                     "  note         the camera's field of view changes over the frames (%g to %g degrees); glTF "
                     "animates none, so solids.glb holds the first frame's, %g\n",
                     r.gltf.fov_least, r.gltf.fov_most, r.gltf.fov_first);
    }
    if (r.gltf.bodies_without_mesh)
      std::fprintf(stderr, "  note         %zu bodies had no mesh to export (give --fragments from bw-voronoi replay)\n",
                   r.gltf.bodies_without_mesh);
  } else if (!o.no_solids) {
    std::fprintf(stderr, "  solids       none: no run file with solids\n");
  }
  if (!r.blender_script_path.empty())
    std::fprintf(stderr, "  blender      blender --python %s (the scene set up; -- --save FILE.blend)\n",
                 r.blender_script_path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Export a simulation's frames for Blender, Houdini and other programs: the water as\n"
               "OpenVDB level sets (OUT_DIR/water_NNNNNN.vdb, a grid named \"surface\"), optionally as\n"
               "meshes too, every solid and body as one animated glTF (OUT_DIR/solids.glb), a script\n"
               "that sets up a Blender scene from them (OUT_DIR/blender_scene.py), and with --wall-pressure\n"
               "the pressure on the solids as OpenVDB points (OUT_DIR/wall_pressure_NNNNNN.vdb).",
               "bw-export"};
  bw::cli::setup(app,
                 "  bw-export out/scenes/plate/0.025/frames -o out/scenes/plate/0.025/export\n"
                 "  bw-export run/frames -o export --frames 0:44 --no-solids        # one part of a split job\n"
                 "  bw-export run/frames -o export --no-water                       # only solids.glb\n"
                 "  bw-export run/frames -o export --mesh obj --density --radius 0.03 --smooth 2\n"
                 "  bw-export run/frames -o export --wall-pressure --up y                # for Houdini\n");
  Options o;
  app.add_option("frames_dir", o.frames_dir, "Folder of frame files (OUTDIR/frames of a simulation)")->required();
  app.add_option("-o,--output", o.output_dir, "Folder for the files (created when missing)")->required();
  app.add_option("--frames", o.frames, "Frames A:B[:S], both ends included (default: all)");
  app.add_option("--run", o.run, "Run file (default: FRAMES_DIR/../run.h5 when present)");
  app.add_option("--fragments", o.fragments,
                 "Fragment meshes of the run, bw-voronoi replay (default: FRAMES_DIR/../fragments.h5 when present)");
  app.add_option("--mesh", o.mesh, "Also write the water's surface as a mesh per frame")
      ->check(CLI::IsMember({"obj", "ply"}));
  app.add_option("--adaptivity", o.adaptivity, "Mesh simplification in [0, 1] (default 0: none)")
      ->check(bw::cli::in_range(0, 1));
  app.add_flag("--density", o.density, "Also write a fog volume grid \"density\" (for volume shaders)");
  app.add_flag("--wall-pressure", o.wall_pressure,
               "Also write the solids' boundary particles with their wall pressure as OpenVDB points "
               "(OUT_DIR/wall_pressure_NNNNNN.vdb; frames with the wall_pressure field)");
  app.add_option("--spacing", o.spacing, "Particle spacing in m (default: the run's /parameters/spacing)")
      ->check(bw::cli::kPositive);
  app.add_option("--radius", o.radius, "Sphere radius per particle in m (default: the spacing)")
      ->check(bw::cli::kPositive);
  app.add_option("--voxel", o.voxel, "Voxel edge in m (default: half the radius)")->check(bw::cli::kPositive);
  app.add_option("--smooth", o.smooth, "Mean-curvature smoothing passes (default 1; 0: none)")
      ->check(CLI::Range(0, 100));
  app.add_option("--erode", o.erode,
                 "Move the surface inwards by this many m after smoothing (default 0; 0.4 x the spacing gives\n"
                 "the particles' volume back with the default radius, at about twice the time)")
      ->check(bw::cli::kNonNegative);
  app.add_option("--up", o.up, "Up axis of the water files: z as breakwater and Blender, y for Houdini")
      ->check(CLI::IsMember({"z", "y"}));
  app.add_flag("--no-water", o.no_water, "Leave out the water (only solids.glb)");
  app.add_flag("--no-solids", o.no_solids, "Leave out solids.glb and blender_scene.py (only the water)");
  auto* scene = app.add_option("--scene", o.scene,
                               "Scene file whose [camera] solids.glb gets, and whose look blender_scene.py (default: the run's scene)");
  app.add_flag("--no-camera", o.no_camera, "Leave the scene's camera out of solids.glb")->excludes(scene);
  app.add_flag("-q,--quiet", o.quiet, "No progress line and no summary");
  app.add_flag("-v,--verbose", o.verbose, "Print the level set's settings and where they came from");

  return bw::cli::run(app, argc, argv, [&] {
    const bw::exporter::ExportJob job = o.job();
    bw::ProgressLine progress(!o.quiet);
    const auto report = bw::exporter::run_export(job, [&](const bw::exporter::ExportProgress& p) {
      progress.update(bw::frame_progress_text("bw-export", p.frame, p.done, p.total, p.seconds), p.done == p.total);
    });
    progress.clear();
    if (!o.quiet) print_summary(o, report);
    return bw::kExitOk;
  });
}
