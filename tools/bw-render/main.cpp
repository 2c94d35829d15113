// bw-render: screen-space fluid rendering of a simulation's frames into PNG images.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "cli/tool.h"
#include "common/error.h"
#include "common/terminal.h"
#include "common/text.h"
#include "render/sequence.h"

namespace {

// "MIN:MAX", two numbers.
bw::render::ValueRange parse_range(const std::string& text) {
  const std::vector<std::string> parts = bw::split(text, ':');
  double v[2] = {0, 0};
  bool ok = parts.size() == 2;
  for (std::size_t k = 0; ok && k < 2; ++k) {
    char* end = nullptr;
    v[k] = std::strtod(parts[k].c_str(), &end);
    ok = !parts[k].empty() && *end == '\0' && std::isfinite(v[k]);
  }
  if (!ok) bw::fail_input("--pressure-range '{}': expected MIN:MAX, two numbers in Pa", text);
  if (!(v[1] > v[0])) bw::fail_input("--pressure-range '{}': MAX must be above MIN", text);
  return {v[0], v[1]};
}

struct Options {
  std::string frames_dir;
  std::string output_dir;
  std::string frames;          // A:B[:S]
  std::string scene;
  bool no_scene = false;       // defaults, not the run's scene tables
  std::string fragments;
  std::string run;
  std::optional<int> width, height;
  std::string camera;          // PX,PY,PZ:TX,TY,TZ[:FOV]
  std::string filter;
  std::string spray;  // "on", "off" or empty: the scene's render.spray
  std::string view = "shaded";
  std::string solids;          // "shaded", "wall_pressure" or empty: the scene's render.solids
  std::string pressure_range;  // MIN:MAX in Pa
  bool no_water = false;
  std::string video;
  double fps = 0;
  double radius = 0;
  std::string device = "auto";
  bool quiet = false;
  bool verbose = false;

  // Builds the job: the scene's tables (--scene, else the run's scene), then the
  // command line over them. `look` gets where the tables came from.
  bw::render::SequenceJob job(std::string* look) const {
    bw::render::SequenceJob j;
    j.frames_dir = frames_dir;
    j.output_dir = output_dir;
    if (!frames.empty()) j.range = bw::render::parse_frame_range(frames);
    j.run_path = run;
    j.fragments_path = fragments;
    j.video_path = video;
    j.fps = fps;
    j.device = device == "auto" ? -1 : std::stoi(device);
    *look = "defaults";
    if (!scene.empty()) {
      j.settings = bw::render::load_render_settings(scene);
      *look = "scene " + scene;
    } else if (!no_scene) {
      const std::string run_path = run.empty() ? bw::render::default_run_path(frames_dir) : run;
      if (!run_path.empty()) {
        j.settings = bw::render::run_render_settings(run_path);
        *look = "the scene of " + run_path;
      }
    }
    if (width) j.settings.width = *width;
    if (height) j.settings.height = *height;
    if (!camera.empty()) {  // the whole camera: its target too
      j.settings.camera = bw::render::CameraPath::fixed(bw::render::parse_camera(camera));
      j.settings.camera_track.clear();
    }
    if (!filter.empty()) j.settings.filter = *bw::render::parse_filter(filter);
    j.settings.view = *bw::render::parse_view(view);
    if (radius > 0) j.settings.particle_radius = radius;
    if (!spray.empty()) j.settings.spray = spray == "on";
    if (!solids.empty()) j.settings.solids = *bw::render::parse_solid_coloring(solids);
    if (!pressure_range.empty()) {
      if (j.settings.solids != bw::render::SolidColoring::kWallPressure)
        bw::fail_input("--pressure-range: only with --solids wall_pressure (or the scene's render.solids)");
      j.settings.pressure_range = parse_range(pressure_range);
    }
    if (no_water) j.settings.water = false;
    j.settings.validate("command line");
    return j;
  }
};

void print_summary(const Options& o, const bw::render::SequenceJob& job, const std::string& look,
                   const bw::render::SequenceReport& r) {
  const bw::render::Framing& f = r.framing;
  std::fprintf(stderr, "bw-render: %zu frame%s (%06d..%06d) -> %s in %s, %.0f ms per frame\n", r.frames,
               r.frames == 1 ? "" : "s", r.first, r.last, o.output_dir.c_str(), bw::human_duration(r.seconds).c_str(),
               r.render_ms_per_frame);
  if (!r.video_path.empty()) std::fprintf(stderr, "  video        %s at %.3g fps\n", r.video_path.c_str(), r.fps);
  if (r.bodies_without_mesh)
    std::fprintf(stderr, "  note         up to %zu bodies per frame had no mesh to draw (give --fragments)\n",
                 r.bodies_without_mesh);
  if (f.reference_water > 0 && f.water_seen == 0)
    std::fprintf(stderr,
                 "  note         the camera%s sees none of the water of the reference frame: solids hide it or it is "
                 "out of view\n",
                 r.camera_keys > 1 ? " at the reference frame's time" : "");
  if (r.paint) {
    const auto& p = *r.paint;
    std::fprintf(stderr, "  solids       coloured by the wall pressure, %.4g to %.4g Pa (%s)\n", p.scale.min,
                 p.scale.max, r.paint_source.c_str());
    if (p.samples)
      std::fprintf(stderr, "               the highest patch %.4g Pa, %zu loaded patches pooled\n", p.peak, p.samples);
  }
  if (!o.verbose) return;
  const auto& s = job.settings;
  const auto& c = f.camera;
  std::fprintf(stderr, "  renderer     %s (%s)\n", r.renderer.c_str(), r.display.c_str());
  std::fprintf(stderr, "  look         %s\n", look.c_str());
  std::fprintf(stderr, "  image        %d x %d, filter %s\n", s.width, s.height, bw::render::filter_name(s.filter));
  std::fprintf(stderr, "  camera       %g,%g,%g:%g,%g,%g:%g%s\n", c.position.x(), c.position.y(), c.position.z(),
               c.target.x(), c.target.y(), c.target.z(), c.fov_degrees,
               f.camera_fitted ? " (fitted)" : r.camera_keys > 1 ? " (at the reference frame)" : "");
  if (!s.camera_track.empty())
    std::fprintf(stderr, "  tracking     the centre of body '%s' in each frame\n", s.camera_track.c_str());
  if (s.camera && s.camera->animated()) {
    const auto& keys = s.camera->keys();
    std::fprintf(stderr, "  moving       %zu keys from t = %g to %g s, %s\n", keys.size(), keys.front().time,
                 keys.back().time, bw::render::camera_interpolation_name(s.camera->interpolation()));
  }
  if (f.camera_fitted) {
    std::string seen;
    if (f.fit_surface_seen >= 0) seen += fmt::format(", sees {:.0f}% of the water's surface", 100 * f.fit_surface_seen);
    if (f.fit_floor_seen >= 0) seen += fmt::format(" and {:.0f}% of the floor around it", 100 * f.fit_floor_seen);
    std::fprintf(stderr, "  view         azimuth %g, elevation %g degrees%s\n", f.fit_azimuth, f.fit_elevation,
                 seen.c_str());
  }
  if (f.reference_water > 0)
    std::fprintf(stderr, "  water        %.0f%% of the reference frame's particles in view, not hidden by solids\n",
                 100 * f.water_seen);
  std::fprintf(stderr, "  particles    up to %zu, radius %.4g m (spacing %.4g m)\n", r.max_particles,
               f.particle_radius, f.particle_spacing);
  std::fprintf(stderr, "  solids       %zu, fragments %zu, ground at z = %.4g\n", r.solids, r.fragments,
               f.ground_height);
  std::fprintf(stderr, "  reference    %s (particle size, ground, fitted camera)\n", f.reference_frame.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Render a simulation's frames with screen-space fluid rendering: one PNG per frame,\n"
               "named by the frame's number, and optionally a video.",
               "bw-render"};
  bw::cli::setup(app,
                 "  bw-render out/wall/frames -o out/wall/images\n"
                 "  bw-render out/wall/frames -o images --scene examples/wall.toml --frames 0:239:2\n"
                 "  bw-render frames -o images --fragments fragments.h5 --video wall.mp4\n"
                 "  bw-render frames -o images --frames 0:99 --width 640 --height 360 --camera 2,-3,1.5:0,0,0.4:40\n"
                 "  bw-render frames -o loads --solids wall_pressure --pressure-range 0:20000 --no-water\n");
  Options o;
  app.add_option("frames_dir", o.frames_dir, "Folder of frame files (OUTDIR/frames of a simulation)")->required();
  app.add_option("-o,--output", o.output_dir, "Folder for the images (created when missing)")->required();
  app.add_option("--frames", o.frames, "Frames A:B[:S], both ends included (default: all)");
  auto* scene = app.add_option("--scene", o.scene,
                                "Scene file: its [camera], [light] and [render] tables (default: the run's scene)");
  app.add_flag("--no-scene", o.no_scene, "Default look and a fitted camera, not the run's scene tables")
      ->excludes(scene);
  app.add_option("--fragments", o.fragments, "Fragment meshes of the run (bw-voronoi replay)");
  app.add_option("--run", o.run, "Run file (default: FRAMES_DIR/../run.h5 when present)");
  app.add_option("--width", o.width, "Image width in pixels (default 1280)")->check(CLI::Range(1, 16384));
  app.add_option("--height", o.height, "Image height in pixels (default 720)")->check(CLI::Range(1, 16384));
  app.add_option("--camera", o.camera, "Camera PX,PY,PZ:TX,TY,TZ[:FOV] (position, target, vertical fov)");
  app.add_option("--filter", o.filter, "Depth smoothing")->check(CLI::IsMember({"narrow-range", "bilateral", "none"}));
  app.add_option("--view", o.view, "What to draw: the picture or a layer of the fluid")
      ->check(CLI::IsMember({"shaded", "depth", "thickness", "normals"}));
  app.add_option("--solids", o.solids,
                 "Colour of the solids: their own, or the pressure on their faces (frames with the wall_pressure "
                 "field), with a colour bar")
      ->check(CLI::IsMember({"shaded", "wall_pressure"}));
  app.add_option("--pressure-range", o.pressure_range,
                 "Pressures at the colour scale's ends, MIN:MAX in Pa (default: 0 to the 99th percentile of the "
                 "loaded patches over the folder's frames)");
  app.add_flag("--no-water", o.no_water, "Leave the water out: nothing hides the solids");
  app.add_option("--radius", o.radius, "Particle sphere radius in m (default: estimated)")->check(bw::cli::kPositive);
  app.add_option("--spray", o.spray, "Draw isolated particles as spray and tint thin water as foam (default on)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--video", o.video, "Also encode a video (.mp4, .mov, .mkv) with ffmpeg");
  app.add_option("--fps", o.fps, "Video frame rate (default: from the frames' times)")->check(bw::cli::kPositive);
  app.add_option("--device", o.device, "EGL device: auto, or an index (0, 1, ...) to pick one GPU of several")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            if (v == "auto" || (!v.empty() && v.size() < 4 && v.find_first_not_of("0123456789") == std::string::npos))
              return {};
            return "'" + v + "' is neither auto nor a device index";
          },
          "auto|N"));
  app.add_flag("-q,--quiet", o.quiet, "No progress line and no summary");
  app.add_flag("-v,--verbose", o.verbose, "Print the renderer, camera, particle size and solids used");

  return bw::cli::run(app, argc, argv, [&] {
    std::string look;
    const bw::render::SequenceJob job = o.job(&look);
    bw::ProgressLine progress(!o.quiet);
    const auto report = bw::render::render_sequence(job, [&](const bw::render::SequenceProgress& p) {
      progress.update(bw::frame_progress_text("bw-render", p.frame, p.done, p.total, p.render_seconds), p.done == p.total);
    });
    progress.clear();
    if (!o.quiet) print_summary(o, job, look, report);
    return bw::kExitOk;
  });
}
