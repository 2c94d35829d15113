// gpu-tool: the measurements tools/gpu-check.sh makes that no product tool does:
// which EGL devices there are and which one the renderer takes, how far the frames
// of one scene on two devices lie apart (particles matched by id), how far two
// images differ, and steps per second from a run file. Every figure is printed as
// NAME=VALUE, one a line, for the script to collect.
//
//   gpu-tool egl
//   gpu-tool frames REF/frames RUN/frames --spacing 0.01 --id-until 0.1 --max-rms 0.05 --max-moved 0.05
//   gpu-tool images cpu.png gpu.png --diff diff.png --max-mean 3 --max-share 0.02
//   gpu-tool rate RUN/run.h5 --last 5
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "cli/tool.h"
#include "common/error.h"
#include "io/frame_file.h"
#include "io/run_file.h"
#include "render/gl_context.h"
#include "render/image.h"

namespace {

void print(const char* name, double value) { std::printf("%s=%.6g\n", name, value); }

// ---- egl: the EGL devices the driver offers, then the context the renderer makes.
int list_egl() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::printf("egl_client_extensions=%s\n", client ? client : "(none)");
  auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  EGLint count = 0;
  constexpr EGLint kMaxDevices = 32;
  EGLDeviceEXT devices[kMaxDevices];
  if (!query_devices || !query_devices(kMaxDevices, devices, &count)) count = 0;
  std::printf("egl_devices=%d\n", count);
  for (EGLint i = 0; i < count; ++i) {
    const char* ext = query_string ? query_string(devices[i], EGL_EXTENSIONS) : nullptr;
#ifdef EGL_DRM_DEVICE_FILE_EXT
    const char* drm = query_string ? query_string(devices[i], EGL_DRM_DEVICE_FILE_EXT) : nullptr;
#else
    const char* drm = nullptr;
#endif
    std::printf("egl_device_%d=%s%s%s\n", i, ext ? ext : "(no extensions)", drm ? " drm " : "", drm ? drm : "");
  }
  // What bw-render would use: fails like bw-render does when there is nothing.
  auto context = bw::render::GlContext::create();
  std::printf("gl_display=%s\ngl_renderer=%s\ngl_version=%s\n", context->display().c_str(),
              context->renderer().c_str(), context->version().c_str());
  return bw::kExitOk;
}

// ---- frames: particle positions of two runs of one scene, matched by id.
struct FrameDistance {
  int frame = 0;
  double time = 0;
  std::size_t matched = 0, unmatched = 0;
  double rms = 0, p99 = 0, max = 0;  // in spacings
  double moved = 0;                  // share of the particles in other cells (below)
};

// Share of the particles one run has in other cells than the other: half the sum
// over cells of |count a - count b|, over the particles. Unlike distances by id it
// does not grow with the chaos of single particles' paths, only with the flow's.
double occupancy_difference(const bw::FrameData& a, const bw::FrameData& b, double cell) {
  std::unordered_map<std::int64_t, std::int64_t> counts;
  auto key = [cell](float x, float y, float z) {
    const auto q = [cell](float v) { return static_cast<std::int64_t>(std::floor(double(v) / cell)) + (1 << 20); };
    return (q(x) << 42) | (q(y) << 21) | q(z);
  };
  for (std::size_t i = 0; i < a.x.size(); ++i) ++counts[key(a.x[i], a.y[i], a.z[i])];
  for (std::size_t i = 0; i < b.x.size(); ++i) --counts[key(b.x[i], b.y[i], b.z[i])];
  double sum = 0;
  for (const auto& [k, c] : counts) sum += static_cast<double>(std::llabs(c));
  const double n = 0.5 * static_cast<double>(a.x.size() + b.x.size());
  return n > 0 ? 0.5 * sum / n : 0;
}

FrameDistance compare_frame(const bw::FrameData& ref, const bw::FrameData& run, const std::string& ref_path,
                            const std::string& run_path, double spacing, double cell) {
  if (ref.id.empty()) bw::fail_input("{}: no particle ids (add \"id\" to the scene's output.fields)", ref_path);
  if (run.id.empty()) bw::fail_input("{}: no particle ids (add \"id\" to the scene's output.fields)", run_path);
  std::unordered_map<std::int64_t, std::size_t> where;
  where.reserve(ref.id.size());
  for (std::size_t i = 0; i < ref.id.size(); ++i) where.emplace(ref.id[i], i);
  FrameDistance d;
  d.frame = run.frame;
  d.time = run.time;
  std::vector<double> dist;
  dist.reserve(run.id.size());
  for (std::size_t i = 0; i < run.id.size(); ++i) {
    const auto it = where.find(run.id[i]);
    if (it == where.end()) continue;
    const std::size_t j = it->second;
    const double dx = double(run.x[i]) - ref.x[j], dy = double(run.y[i]) - ref.y[j], dz = double(run.z[i]) - ref.z[j];
    dist.push_back(std::sqrt(dx * dx + dy * dy + dz * dz) / spacing);
  }
  d.matched = dist.size();
  d.moved = occupancy_difference(ref, run, cell * spacing);
  d.unmatched = ref.id.size() + run.id.size() - 2 * dist.size();
  if (dist.empty()) return d;
  double sum = 0;
  for (double v : dist) sum += v * v;
  d.rms = std::sqrt(sum / static_cast<double>(dist.size()));
  std::sort(dist.begin(), dist.end());
  d.max = dist.back();
  d.p99 = dist[std::min(dist.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(dist.size())))];
  return d;
}

struct Tolerance {
  double id_until = 0.1;  // s: distances by id up to this time
  double max_rms = 0.05, max_p99 = 0.25;  // spacings
  double cell = 4;        // spacings: the cells of the occupancy
  double max_moved = 0.05;
};

int compare_frames(const std::string& ref_dir, const std::string& run_dir, double spacing, const Tolerance& tol) {
  // A run's folder or its frames folder.
  auto frames_folder = [](const std::string& dir) {
    return std::filesystem::exists(dir + "/000000.h5") ? dir : dir + "/frames";
  };
  const std::string a = frames_folder(ref_dir), b = frames_folder(run_dir);
  std::vector<FrameDistance> rows;
  for (int n = 0;; ++n) {
    const std::string pa = fmt::format("{}/{:06d}.h5", a, n), pb = fmt::format("{}/{:06d}.h5", b, n);
    if (!std::filesystem::exists(pa) || !std::filesystem::exists(pb)) break;
    rows.push_back(compare_frame(bw::read_frame(pa), bw::read_frame(pb), pa, pb, spacing, tol.cell));
  }
  if (rows.empty()) bw::fail_input("{} and {}: no frame both hold (000000.h5 in each)", ref_dir, run_dir);
  std::printf("# frame time matched unmatched rms p99 max (distances by id in spacings of %g m) moved (share of the "
              "particles in other cells of %g spacings)\n",
              spacing, tol.cell);
  for (const FrameDistance& r : rows)
    std::printf("# %d %.4f %zu %zu %.4f %.4f %.4f %.4f\n", r.frame, r.time, r.matched, r.unmatched, r.rms, r.p99,
                r.max, r.moved);
  // Distances by id at the last frame up to id_until; the occupancy at the last.
  const FrameDistance* early = &rows.front();
  for (const FrameDistance& r : rows)
    if (r.time <= tol.id_until + 1e-9) early = &r;
  const FrameDistance& last = rows.back();
  std::size_t unmatched = 0;
  for (const FrameDistance& r : rows) unmatched = std::max(unmatched, r.unmatched);
  print("frames", static_cast<double>(rows.size()));
  print("unmatched", static_cast<double>(unmatched));
  print("id_time", early->time);
  print("rms", early->rms);
  print("p99", early->p99);
  print("max", early->max);
  print("time", last.time);
  print("moved", last.moved);
  print("rms_last", last.rms);
  const bool ok = unmatched == 0 && early->rms <= tol.max_rms && early->p99 <= tol.max_p99 && last.moved <= tol.max_moved;
  std::printf("agree=%s\n", ok ? "yes" : "no");
  return ok ? bw::kExitOk : bw::kExitCheckFailed;
}

// ---- images: mean absolute difference (0-255 per channel) and the share of pixels
// whose largest channel difference exceeds `threshold`.
int compare_images(const std::string& a_path, const std::string& b_path, const std::string& diff_path,
                   double max_mean, double max_share, int threshold) {
  const bw::render::Image a = bw::render::read_png(a_path), b = bw::render::read_png(b_path);
  if (a.width != b.width || a.height != b.height)
    bw::fail_input("{} is {} x {}, {} is {} x {}: not comparable", a_path, a.width, a.height, b_path, b.width,
                   b.height);
  bw::render::Image diff{a.width, a.height, std::vector<std::uint8_t>(a.rgb.size())};
  double sum = 0;
  std::size_t over = 0;
  for (std::size_t p = 0; p < a.rgb.size(); p += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(a.rgb[p + c]) - int(b.rgb[p + c]));
      sum += d;
      worst = std::max(worst, d);
      diff.rgb[p + c] = static_cast<std::uint8_t>(std::min(255, 4 * d));  // 4x: small differences show
    }
    if (worst > threshold) ++over;
  }
  const double pixels = static_cast<double>(a.rgb.size() / 3);
  const double mean = sum / static_cast<double>(a.rgb.size());
  const double share = static_cast<double>(over) / pixels;
  if (!diff_path.empty()) bw::render::write_png(diff, diff_path);
  print("mean", mean);
  print("share", share);
  const bool ok = mean <= max_mean && share <= max_share;
  std::printf("agree=%s\n", ok ? "yes" : "no");
  return ok ? bw::kExitOk : bw::kExitCheckFailed;
}

// ---- rate: steps and particle-steps per second of a run, over all of it and over
// its last frames (where an emitter scene holds the most particles).
int run_rate(const std::string& path, int last) {
  const bw::RunRecord run = bw::read_run(path);
  if (run.frames.size() < 2) bw::fail_input("{}: {} frames, at least 2 needed for a rate", path, run.frames.size());
  const auto& f = run.frames;
  auto rate = [&](std::size_t from, std::size_t to, double* particle_rate) {
    const double wall = f[to].wall_time - f[from].wall_time;
    const double steps = static_cast<double>(f[to].steps - f[from].steps);
    // The fluid count changes between frames: take the mean of the two ends.
    *particle_rate = wall > 0 ? steps * 0.5 * static_cast<double>(f[to].fluid + f[from].fluid) / wall : 0;
    return wall > 0 ? steps / wall : 0;
  };
  const std::size_t end = f.size() - 1;
  const std::size_t from = end > static_cast<std::size_t>(last) ? end - static_cast<std::size_t>(last) : 0;
  double prate_all = 0, prate_last = 0;
  const double all = rate(0, end, &prate_all), tail = rate(from, end, &prate_last);
  print("frames", static_cast<double>(f.size()));
  print("simulated", f[end].time);
  print("steps", static_cast<double>(f[end].steps));
  print("wall", f[end].wall_time);
  print("fluid", static_cast<double>(f[end].fluid));
  print("steps_per_s", all);
  print("steps_per_s_last", tail);
  print("particle_steps_per_s_last", prate_last);
  print("last_from_time", f[from].time);
  std::printf("status=%s\n", run.status.c_str());
  std::printf("device=%s\n", run.device.c_str());
  return bw::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Measurements of tools/gpu-check.sh: EGL devices, frames and images of two devices compared, "
               "steps per second of a run. Figures print as NAME=VALUE lines; a comparison out of its "
               "tolerance exits with 3.",
               "gpu-tool"};
  bw::cli::setup(app,
                 "  gpu-tool egl\n"
                 "  gpu-tool frames ref/frames run/frames --spacing 0.01 --id-until 0.1 --max-rms 0.05 --max-moved 0.05\n"
                 "  gpu-tool images cpu.png gpu.png --diff diff.png --max-mean 3 --max-share 0.02\n"
                 "  gpu-tool rate out/wall/run.h5 --last 5\n");
  app.require_subcommand(1);
  auto* egl = app.add_subcommand("egl", "List the EGL devices and the OpenGL context bw-render would make");

  std::string ref, run, diff;
  Tolerance tol;
  double spacing = 0, max_mean = 3, max_share = 0.02;
  int threshold = 32, last = 5;
  auto* frames = app.add_subcommand("frames", "Distances between the particles of two runs' frames, matched by id");
  frames->add_option("reference", ref, "Frames folder of the reference run")->required();
  frames->add_option("run", run, "Frames folder of the run to compare")->required();
  frames->add_option("--spacing", spacing, "Particle spacing (m): distances are given in spacings")
      ->required()
      ->check(bw::cli::kPositive);
  frames->add_option("--id-until", tol.id_until, "Distances by id at the last frame up to this time (s)")
      ->capture_default_str();
  frames->add_option("--max-rms", tol.max_rms, "Tolerance: RMS distance by id (spacings)")->capture_default_str();
  frames->add_option("--max-p99", tol.max_p99, "Tolerance: 99th percentile of the distance by id (spacings)")
      ->capture_default_str();
  frames->add_option("--cell", tol.cell, "Cell edge of the occupancy (spacings)")
      ->capture_default_str()
      ->check(bw::cli::kPositive);
  frames->add_option("--max-moved", tol.max_moved,
                     "Tolerance: share of the particles in other cells at the last frame (0-1)")
      ->capture_default_str();

  auto* images = app.add_subcommand("images", "Differences between two images of the same size");
  images->add_option("reference", ref, "Reference PNG")->required();
  images->add_option("image", run, "PNG to compare")->required();
  images->add_option("--diff", diff, "Write |a - b| x 4 as a PNG here");
  images->add_option("--max-mean", max_mean, "Tolerance: mean absolute difference (0-255 per channel)")
      ->capture_default_str();
  images->add_option("--max-share", max_share, "Tolerance: share of pixels differing by more than --threshold")
      ->capture_default_str();
  images->add_option("--threshold", threshold, "A pixel differs when a channel differs by more (0-255)")
      ->capture_default_str()
      ->check(CLI::Range(0, 255));

  auto* rate = app.add_subcommand("rate", "Steps per second of a run (run.h5), overall and over its last frames");
  rate->add_option("run", ref, "Run file (OUTDIR/run.h5 of bw-sim)")->required();
  rate->add_option("--last", last, "Frames at the end to measure over")->capture_default_str()->check(CLI::Range(1, 100000));

  return bw::cli::run(app, argc, argv, [&]() -> int {
    if (egl->parsed()) return list_egl();
    if (frames->parsed()) return compare_frames(ref, run, spacing, tol);
    if (images->parsed()) return compare_images(ref, run, diff, max_mean, max_share, threshold);
    return run_rate(ref, last);
  });
}
