#include "render/sequence.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/text.h"
#include "common/terminal.h"
#include "io/frame_file.h"
#include "io/frame_range.h"
#include "io/h5.h"
#include "io/run_file.h"
#include "render/camera.h"
#include "render/framing.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/legend.h"
#include "render/particle_spacing.h"
#include "render/renderer.h"
#include "render/solids.h"
#include "render/view_fit.h"
#include "render/video.h"

namespace bw::render {
namespace fs = std::filesystem;
namespace {

// Video frame rate when the frames' times do not give one.
constexpr double kDefaultFps = 30;

std::vector<double> parse_numbers(std::string_view s, const std::string& whole) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t comma = s.find(',', start);
    const std::string part(s.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    char* end = nullptr;
    const double v = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(v))
      fail_input("--camera '{}': '{}' is not a number", whole, part);
    out.push_back(v);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

Camera parse_camera(const std::string& text) {
  Camera c;
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() < 2 || parts.size() > 3) fail_input("--camera '{}': expected PX,PY,PZ:TX,TY,TZ[:FOV]", text);
  const auto p = parse_numbers(parts[0], text), t = parse_numbers(parts[1], text);
  if (p.size() != 3 || t.size() != 3) fail_input("--camera '{}': position and target need 3 numbers each", text);
  c.position = Vec3d(p[0], p[1], p[2]);
  c.target = Vec3d(t[0], t[1], t[2]);
  if (parts.size() == 3) {
    const auto f = parse_numbers(parts[2], text);
    if (f.size() != 1) fail_input("--camera '{}': the field of view is one number", text);
    c.fov_degrees = f[0];
  }
  RenderSettings check;
  check.camera = CameraPath::fixed(c);
  check.validate("--camera");
  return c;
}

std::string default_run_path(const std::string& frames_dir) {
  const fs::path guess = fs::path(frames_dir) / ".." / "run.h5";
  std::error_code ec;
  return fs::exists(guess, ec) ? guess.lexically_normal().string() : std::string();
}

RenderSettings run_render_settings(const std::string& run_path) {
  const h5::File file = h5::File::open(run_path, "run");
  return parse_render_settings(file.root().attr_string("scene"), run_path + ": scene");
}

SequencePlan plan_sequence(const SequenceJob& job) {
  SequencePlan plan;
  const std::map<int, std::string> frames = require_frame_files(job.frames_dir);
  plan.reference_frames = reference_frame_candidates(frames);
  for (const auto& [number, path] : frames) plan.folder_frames.push_back(path);

  const int first = job.range.first.value_or(frames.begin()->first);
  const int last = job.range.last.value_or(frames.rbegin()->first);
  if (first > last) fail_input("{}: the range {}:{} is empty", job.frames_dir, first, last);
  const int step = std::max(job.range.step, 1);
  for (long n = first; n <= last; n += step) {
    auto it = frames.find(static_cast<int>(n));
    if (it == frames.end())
      fail_input("frame {} is missing: {}", n, frame_file_name(job.frames_dir, static_cast<int>(n)));
    plan.frames.push_back({static_cast<int>(n), it->second, 0});
  }
  if (plan.frames.empty()) fail_input("{}: the range {}:{}:{} is empty", job.frames_dir, first, last, step);
  // Every frame must be a frame file before anything is drawn.
  for (FramePlan& f : plan.frames) {
    h5::File file = h5::File::open(f.path, "frame");
    f.time = file.root().attr<double>("time");
  }
  if (plan.frames.size() >= 2) {
    const double span = plan.frames.back().time - plan.frames.front().time;
    plan.fps = span > 0 ? (plan.frames.size() - 1) / span : kDefaultFps;
  }
  if (job.fps > 0) plan.fps = job.fps;

  std::error_code ec;
  plan.run_path = job.run_path.empty() ? default_run_path(job.frames_dir) : job.run_path;
  if (job.settings.solids == SolidColoring::kWallPressure) {
    if (plan.run_path.empty())
      fail_input("{}: colouring the solids by the wall pressure needs the run file (its solids and spacing); none "
                 "beside the frames: give --run",
                 job.frames_dir);
    for (const FramePlan& f : plan.frames) require_wall_pressure(read_frame_header(f.path).fields, f.path);
  }

  if (job.output_dir.empty()) fail_input("no output folder given (-o)");
  // Every check before the output folder is made: bad input leaves nothing behind.
  if (!job.video_path.empty()) VideoWriter::check_available(job.video_path);
  if (!fs::is_directory(job.output_dir, ec)) {
    fs::create_directories(job.output_dir, ec);
    if (ec) fail_input("{}: cannot create the output folder: {}", job.output_dir, ec.message());
  }
  if (::access(job.output_dir.c_str(), W_OK) != 0) fail_input("{}: the output folder is not writable", job.output_dir);
  return plan;
}

SequenceReport render_sequence(const SequenceJob& job, const std::function<void(const SequenceProgress&)>& on_frame) {
  Stopwatch clock;
  const SequencePlan plan = plan_sequence(job);
  RenderSettings settings = job.settings;
  settings.validate();

  SequenceReport report;
  report.fps = plan.fps;
  RunRecord run;  // empty without a run file
  const SolidScene solids =
      SolidScene::load({plan.run_path, job.fragments_path}, {settings.solid_color, settings.body_color}, &run);
  report.solids = solids.solid_count();
  report.fragments = solids.fragment_count();

  // What must not change within a sequence, whichever part of it this process
  // renders: particle size, ground height, the fitted camera (framing.h).
  const TrackedBody track = tracked_body(settings, plan.run_path);
  report.framing = frame_sequence(plan.reference_frames, settings, solids, track);
  if (settings.camera) report.camera_keys = settings.camera->keys().size();
  const Framing& framing = report.framing;
  const double radius = framing.particle_radius, spacing = framing.particle_spacing;

  // The solids coloured by the wall pressure: one scale for the whole folder, so
  // that every part of a sequence rendered in pieces has the same.
  const bool paint = settings.solids == SolidColoring::kWallPressure;
  double boundary_spacing = 0;
  if (paint) {
    boundary_spacing = run.parameter("spacing").value_or(0);
    if (!(boundary_spacing > 0)) fail_input("{}: /parameters/spacing is missing or not positive", plan.run_path);
    if (settings.pressure_range) {
      report.paint = PaintRange{};
      report.paint->scale = {settings.pressure_range->min, settings.pressure_range->max};
      report.paint_source = "render.pressure_range";
    } else {
      report.paint = wall_pressure_range(plan.folder_frames);
      report.paint_source = fmt::format("up to the 99th percentile of the loaded patches of the folder's {} frames",
                                        report.paint->frames);
    }
  }

  // A moving or tracking camera is placed and checked at every frame before anything
  // is drawn (a tracked body's centre from the frame's body states).
  std::vector<Camera> frame_cameras(plan.frames.size(), framing.camera);
  if (settings.camera && (settings.camera->animated() || track.id >= 0))
    for (std::size_t i = 0; i < plan.frames.size(); ++i) {
      const FramePlan& f = plan.frames[i];
      const BodyStates bodies = track.id >= 0 ? read_frame_header(f.path, true).bodies : BodyStates{};
      frame_cameras[i] = frame_camera(*settings.camera, track, f.time, bodies, f.path);
    }

  std::unique_ptr<GlContext> context = GlContext::create(job.device);
  report.renderer = context->renderer();
  report.display = context->display();
  Renderer renderer(*context, settings);
  std::unique_ptr<VideoWriter> video;
  if (!job.video_path.empty()) video = std::make_unique<VideoWriter>(job.video_path, plan.fps);

  // What the images were made with, stored in each PNG (a frame can be remade).
  const auto settings_text = [&](const Camera& c) {
    return fmt::format(
        "camera {:.6g},{:.6g},{:.6g}:{:.6g},{:.6g},{:.6g}:{:.6g} up {:.6g},{:.6g},{:.6g}; particle radius {:.6g} m "
        "(spacing {:.6g} m); ground {:.6g} m; filter {}; light {:.6g},{:.6g},{:.6g}; {} x {}",
        c.position.x(), c.position.y(), c.position.z(), c.target.x(), c.target.y(), c.target.z(), c.fov_degrees,
        c.up.x(), c.up.y(), c.up.z(), radius, spacing, framing.ground_height, filter_name(settings.filter),
        settings.light.direction.x(), settings.light.direction.y(), settings.light.direction.z(), settings.width,
        settings.height);
  };
  double render_seconds = 0;
  for (std::size_t i = 0; i < plan.frames.size(); ++i) {
    const FramePlan& f = plan.frames[i];
    Stopwatch frame_clock;
    const FrameData frame = read_frame(f.path);
    std::size_t missing = 0;
    const TriangleSoup soup = solids.place(frame.bodies, &missing);
    report.bodies_without_mesh = std::max(report.bodies_without_mesh, missing);
    report.max_particles = std::max(report.max_particles, frame.fluid_count());
    RenderInput input;
    input.x = frame.x.data(), input.y = frame.y.data(), input.z = frame.z.data();
    input.count = settings.water ? frame.fluid_count() : 0;
    input.solids = &soup;
    PaintTable table;
    if (paint) {
      table = paint_table(frame, boundary_spacing, f.path);
      input.paint = &table;
      input.paint_scale = report.paint->scale;
    }
    input.camera = frame_cameras[i];
    input.particle_radius = radius;
    input.particle_spacing = spacing;
    input.ground_height = framing.ground_height;
    Image image = renderer.render(input);
    if (paint && settings.legend)
      draw_legend(image, input.paint_scale, pressure_unit(input.paint_scale.min, input.paint_scale.max));
    const std::vector<std::uint8_t> png = encode_png(image, {{"Software", "bw-render " BW_VERSION},
                                                             {"Title", fmt::format("frame {}, t = {:.6g} s", f.number, f.time)},
                                                             {"Comment", settings_text(input.camera)}});
    write_file_atomically(fmt::format("{}/{:06d}.png", job.output_dir, f.number), png.data(), png.size());
    if (video) video->add_png(png);
    render_seconds += frame_clock.seconds();
    if (on_frame) on_frame({i + 1, plan.frames.size(), f.number, clock.seconds(), render_seconds});
  }
  if (video) {
    video->finish();
    report.video_path = job.video_path;
  }
  report.frames = plan.frames.size();
  report.first = plan.frames.front().number;
  report.last = plan.frames.back().number;
  report.seconds = clock.seconds();
  report.render_ms_per_frame = 1000 * render_seconds / static_cast<double>(plan.frames.size());
  return report;
}

}  // namespace bw::render
