#include "voronoi/check.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>

#include <fmt/format.h>

#include "common/error.h"
#include "common/terminal.h"
#include "io/h5.h"
#include "io/particles_file.h"
#include "mesh/import.h"
#include "mesh/properties.h"
#include "voronoi/parallel.h"

namespace bw::voronoi {
namespace {

std::string point_text(const Vec3d& p) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x(), p.y(), p.z()); }

CheckItem item(const char* name, const char* title) {
  CheckItem c;
  c.name = name;
  c.title = title;
  return c;
}

void set(CheckItem& c, bool ok, std::string detail) {
  c.status = ok ? CheckStatus::pass : CheckStatus::fail;
  c.detail = std::move(detail);
}

// Worst violation found by one of the geometric checks, kept across threads.
struct Worst {
  std::mutex mutex;
  std::size_t fragments = 0;   // fragments with at least one violation
  double distance = 0;
  std::size_t fragment = 0;
  Vec3d where = Vec3d::Zero();
  std::int32_t other = -1;     // within_cells: the seed nearer than its own
  void add(std::size_t f, double d, const Vec3d& p, std::int32_t o = -1) {
    const std::lock_guard<std::mutex> lock(mutex);
    ++fragments;
    if (d > distance) {
      distance = d;
      fragment = f;
      where = p;
      other = o;
    }
  }
};

}  // namespace

const char* to_string(CheckStatus status) {
  switch (status) {
    case CheckStatus::pass: return "pass";
    case CheckStatus::fail: return "fail";
    case CheckStatus::skipped: return "skipped";
  }
  return "?";
}

TriMesh load_solid_mesh(const std::string& path, std::string* kind) {
  if (path == "-" || h5::is_hdf5_file(path)) {
    SampledSolid solid = read_particles(path);
    if (solid.mesh.triangles.empty()) fail_input("{}: the particles file holds no mesh", path);
    if (kind) *kind = "particles";
    return std::move(solid.mesh);
  }
  if (kind) *kind = "mesh";
  return mesh::import_mesh(path);
}

InputSummary prepare_solid_mesh(TriMesh& mesh, const std::string& source) {
  InputSummary s;
  s.mesh = mesh::check_mesh(mesh);
  const mesh::MeshReport& r = s.mesh;
  if (r.triangles == 0) fail_input("{}: the mesh has no triangles", source);
  if (r.bad_indices) fail_input("{}: {} faces refer to vertices that do not exist", source, r.bad_indices);
  if (r.nonfinite_vertices) fail_input("{}: {} vertices have a non-finite coordinate", source, r.nonfinite_vertices);
  if (r.boundary_edges || r.nonmanifold_edges) {
    fail_input("{}: the mesh does not bound a volume: {} (fragments need a closed, manifold mesh)", source,
               r.summary());
  }
  if (r.misoriented_edges) {
    fail_input("{}: the mesh is not consistently oriented: {} edges are traversed the same way by both faces",
               source, r.misoriented_edges);
  }
  s.nonmanifold_vertices = count_nonmanifold_vertices(mesh);
  if (s.nonmanifold_vertices) {
    fail_input("{}: the mesh is not manifold: at {} vertices faces meet only at a point", source,
               s.nonmanifold_vertices);
  }
  s.volume = mesh::mass_properties(mesh).volume;
  if (s.volume < 0) {
    mesh::flip_faces(mesh);
    s.volume = -s.volume;
    s.flipped = true;
  }
  if (!(s.volume > 0)) fail_input("{}: the mesh bounds no volume", source);
  return s;
}

std::vector<CheckItem> check_fragments(const Solid& solid, std::span<const Vec3d> seeds,
                                       std::span<const std::int32_t> active, std::span<const Fragment> fragments,
                                       std::span<const CellFailure> failures, int threads,
                                       FragmentFigures* figures_out) {
  threads = detail::thread_count(threads);
  FragmentFigures fig;
  fig.fragments = fragments.size();
  std::vector<CheckItem> out;

  CheckItem cut = item("cells_cut", "every cell was cut");
  std::vector<bool> has_fragment(seeds.size(), false);
  for (const Fragment& f : fragments)
    if (f.seed >= 0 && static_cast<std::size_t>(f.seed) < seeds.size()) has_fragment[static_cast<std::size_t>(f.seed)] = true;
  std::vector<std::int32_t> missing;
  for (const std::int32_t i : active)
    if (!has_fragment[static_cast<std::size_t>(i)]) missing.push_back(i);
  if (failures.empty() && missing.empty()) {
    set(cut, true, fmt::format("{} cells", active.size()));
  } else if (!failures.empty()) {
    set(cut, false, fmt::format("{} of {} cells failed; seed {}: {}", failures.size(), active.size(),
                                failures.front().seed, failures.front().message));
  } else {
    set(cut, false, fmt::format("{} of {} cells gave no fragment, the first is seed {}", missing.size(),
                                active.size(), missing.front()));
  }
  out.push_back(cut);

  // Topology and volume of each fragment.
  CheckItem closed = item("fragments_closed", "every fragment is closed and bounds a positive volume");
  std::vector<double> volume(fragments.size(), 0);
  std::vector<std::string> problem(fragments.size());
  detail::parallel_for(fragments.size(), threads, [&](std::size_t i) {
    const TriMesh& m = fragments[i].mesh;
    const mesh::MeshReport r = mesh::check_mesh(m);
    if (!r.bounds_volume()) {
      problem[i] = r.triangles ? r.summary() : "no triangles";
      return;
    }
    if (const std::size_t nm = count_nonmanifold_vertices(m)) {
      problem[i] = fmt::format("{} non-manifold vertices", nm);
      return;
    }
    volume[i] = mesh::mass_properties(m).volume;
    if (!(volume[i] > 0)) problem[i] = fmt::format("volume {:.6g}", volume[i]);
  });
  std::size_t bad = 0, first_bad = 0;
  for (std::size_t i = fragments.size(); i-- > 0;)
    if (!problem[i].empty()) ++bad, first_bad = i;
  if (fragments.empty()) {
    set(closed, false, "no fragments");
  } else if (bad == 0) {
    set(closed, true, fmt::format("{} fragments", fragments.size()));
  } else {
    const Fragment& f = fragments[first_bad];
    set(closed, false, fmt::format("{} of {} fragments are not; fragment {} (seed {}, component {}): {}", bad,
                                   fragments.size(), first_bad, f.seed, f.component, problem[first_bad]));
  }
  out.push_back(closed);

  CheckItem sum = item("volumes_add_up", "fragment volumes add up to the mesh volume");
  std::vector<std::size_t> per_seed(seeds.size(), 0);
  fig.min_volume = fragments.empty() ? 0 : std::numeric_limits<double>::infinity();
  fig.max_volume = fragments.empty() ? 0 : -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    fig.volume_sum += volume[i];
    fig.min_volume = std::min(fig.min_volume, volume[i]);
    fig.max_volume = std::max(fig.max_volume, volume[i]);
    fig.triangles += fragments[i].mesh.triangles.size();
    const std::int32_t s = fragments[i].seed;
    if (s >= 0 && static_cast<std::size_t>(s) < seeds.size()) ++per_seed[static_cast<std::size_t>(s)];
  }
  for (const std::size_t n : per_seed) fig.split_cells += n > 1;
  fig.relative_error = std::fabs(fig.volume_sum - solid.volume()) / solid.volume();
  set(sum, fig.relative_error <= kVolumeTolerance,
      fmt::format("relative error {:.3g} (limit {:g}): fragments {:.17g}, mesh {:.17g}", fig.relative_error,
                  kVolumeTolerance, fig.volume_sum, solid.volume()));
  out.push_back(sum);

  // Vertices and face centroids of every fragment inside the solid, or within the
  // tolerance of its surface.
  const double tolerance = kDistanceTolerance * solid.length_scale();
  CheckItem inside = item("inside_mesh", "no fragment reaches outside the mesh");
  Worst outside;
  detail::parallel_for(fragments.size(), threads, [&](std::size_t i) {
    const TriMesh& m = fragments[i].mesh;
    double worst = 0;
    Vec3d where = Vec3d::Zero();
    auto test = [&](const Vec3d& p) {
      if (!p.allFinite()) {
        worst = std::numeric_limits<double>::infinity();
        where = p;
        return;
      }
      if (solid.side(p) != Side::outside) return;
      const double d = solid.distance(p);
      if (d > tolerance && d > worst) {
        worst = d;
        where = p;
      }
    };
    for (const Vec3d& v : m.vertices) test(v);
    for (const Triangle& t : m.triangles) {
      bool valid = true;
      for (const auto k : t) valid = valid && k >= 0 && static_cast<std::size_t>(k) < m.vertices.size();
      if (valid) test((m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) / 3.0);
    }
    if (worst > 0) outside.add(i, worst, where);
  });
  if (outside.fragments == 0) {
    set(inside, true, fmt::format("tolerance {:.3g}", tolerance));
  } else {
    const Fragment& f = fragments[outside.fragment];
    set(inside, false, fmt::format("{} fragments reach outside; fragment {} (seed {}) by {:.3g} at {}",
                                   outside.fragments, outside.fragment, f.seed, outside.distance,
                                   point_text(outside.where)));
  }
  out.push_back(inside);

  // Every vertex of a fragment on its own seed's side of every bisector plane.
  CheckItem cells = item("within_cells", "every fragment lies in its Voronoi cell");
  Worst stray;
  detail::parallel_for(fragments.size(), threads, [&](std::size_t i) {
    const Fragment& f = fragments[i];
    if (f.seed < 0 || static_cast<std::size_t>(f.seed) >= seeds.size()) {
      stray.add(i, std::numeric_limits<double>::infinity(), Vec3d::Zero());
      return;
    }
    const Vec3d& s = seeds[static_cast<std::size_t>(f.seed)];
    double worst = 0;
    Vec3d where = Vec3d::Zero();
    std::int32_t nearer = -1;
    for (const std::int32_t j : active) {
      if (j == f.seed) continue;
      const Vec3d& q = seeds[static_cast<std::size_t>(j)];
      const Vec3d normal = (q - s).normalized();
      const Vec3d middle = 0.5 * (s + q);
      for (const Vec3d& v : f.mesh.vertices) {
        const double d = (v - middle).dot(normal);  // > 0: nearer to q than to s
        if (d > tolerance && d > worst) {
          worst = d;
          where = v;
          nearer = j;
        }
      }
    }
    if (worst > 0) stray.add(i, worst, where, nearer);
  });
  if (stray.fragments == 0) {
    set(cells, true, fmt::format("tolerance {:.3g}", tolerance));
  } else {
    const Fragment& f = fragments[stray.fragment];
    set(cells, false, fmt::format("{} fragments leave their cells; fragment {} (seed {}) reaches {:.3g} into the "
                                  "cell of seed {} at {}",
                                  stray.fragments, stray.fragment, f.seed, stray.distance, stray.other,
                                  point_text(stray.where)));
  }
  out.push_back(cells);

  if (figures_out) *figures_out = fig;
  return out;
}

bool CheckResult::passed() const {
  for (const CheckItem& c : checks)
    if (c.status == CheckStatus::fail) return false;
  return true;
}

FragmentSet CheckResult::fragment_set() const {
  FragmentSet set;
  set.source = source;
  set.seeds = seeds;
  set.fragments = fragments;
  return set;
}

CheckResult prefracture_check(TriMesh mesh, const SeedChoice& choice, const CheckOptions& options) {
  const std::size_t seed_count = choice.random > 0 ? choice.random : choice.points.size();
  if (seed_count > kMaxSeeds)
    fail_input("{}: {} seeds; a check cuts at most {}", options.source, seed_count, kMaxSeeds);
  CheckResult r;
  r.source = options.source;
  r.input_kind = options.input_kind;
  auto warn = [&](std::string message) {
    if (options.warn) options.warn(message);
    r.warnings.push_back(std::move(message));
  };
  Stopwatch clock;

  // 1. The input.
  r.input = prepare_solid_mesh(mesh, options.source);
  if (r.input.flipped) warn("the mesh faced inwards: its faces were reversed");
  const Solid solid(std::move(mesh));
  r.concave_edges = solid.concave_edges();
  CheckItem closed = item("input_closed", "input is closed and consistently oriented");
  set(closed, true, fmt::format("{} vertices, {} triangles, volume {:.6g}", r.input.mesh.vertices,
                                r.input.mesh.triangles, r.input.volume));
  r.checks.push_back(closed);
  CheckItem manifold = item("input_manifold", "input is manifold (edges and vertices)");
  set(manifold, true, fmt::format("{} components", r.input.mesh.components));
  r.checks.push_back(manifold);
  CheckItem crossing = item("input_self_intersections", "input is free of self-intersections");
  const auto pairs = solid.self_intersections(1, &r.self_intersection_pairs);
  if (pairs.empty()) {
    set(crossing, true, "");
  } else if (pairs.front().first == pairs.front().second) {
    set(crossing, false, fmt::format("{} pairs of faces intersect; face {} is degenerate (zero area)",
                                     r.self_intersection_pairs, pairs.front().first));
  } else {
    set(crossing, false, fmt::format("{} pairs of faces intersect, e.g. faces {} and {}", r.self_intersection_pairs,
                                     pairs.front().first, pairs.front().second));
  }
  r.checks.push_back(crossing);
  r.seconds_input = clock.seconds();

  // 2. The seeds.
  if (choice.random > 0) {
    r.seeds = random_seeds(solid, choice.random, choice.random_seed);
  } else {
    r.seeds = choice.points;
  }
  if (r.seeds.empty()) fail_input("{}: no seeds given", options.source);
  r.sorting = sort_seeds(solid, r.seeds);
  for (std::size_t i = 0; i < r.seeds.size(); ++i) {
    switch (r.sorting.fate[i]) {
      case SeedFate::used: break;
      case SeedFate::outside:
        warn(fmt::format("seed {} at {} lies outside the mesh: ignored", i, point_text(r.seeds[i])));
        break;
      case SeedFate::on_surface:
        warn(fmt::format("seed {} at {} lies on the surface of the mesh: ignored", i, point_text(r.seeds[i])));
        break;
      case SeedFate::duplicate:
        warn(fmt::format("seed {} at {} repeats seed {}: ignored", i, point_text(r.seeds[i]), r.sorting.same_as[i]));
        break;
    }
  }
  if (r.sorting.active.empty()) {
    fail_input("{}: none of the {} seeds lies inside the mesh", options.source, r.seeds.size());
  }

  // 3. Cut and check, unless the input intersects itself (the cut needs a clean
  // surface to tell inside from outside).
  if (crossing.status == CheckStatus::pass) {
    CutOptions cut_options;
    cut_options.threads = options.threads;
    cut_options.progress = options.progress;
    CutResult cut_result = cut(solid, r.seeds, r.sorting.active, cut_options);
    r.seconds_cells = cut_result.cell_seconds;
    r.seconds_clip = cut_result.clip_seconds;
    if (cut_result.seed_nudge > 0) {
      warn(fmt::format("seeds moved by up to {:.3g} so that no cell boundary passes exactly through a reflex "
                       "vertex or concave edge of the mesh",
                       cut_result.seed_nudge));
    }
    r.seed_nudge = cut_result.seed_nudge;
    r.fragments = std::move(cut_result.fragments);
    r.failures = std::move(cut_result.failures);
    clock.restart();
    for (CheckItem& c :
         check_fragments(solid, r.seeds, r.sorting.active, r.fragments, r.failures, options.threads, &r.figures)) {
      r.checks.push_back(std::move(c));
    }
    r.seconds_checks = clock.seconds();
  } else {
    for (const auto& [name, title] :
         {std::pair{"cells_cut", "every cell was cut"},
          {"fragments_closed", "every fragment is closed and bounds a positive volume"},
          {"volumes_add_up", "fragment volumes add up to the mesh volume"},
          {"inside_mesh", "no fragment reaches outside the mesh"},
          {"within_cells", "every fragment lies in its Voronoi cell"}}) {
      CheckItem c = item(name, title);
      c.detail = "not run: the input intersects itself";
      r.checks.push_back(c);
    }
  }
  return r;
}

Report CheckResult::report() const {
  Report report;
  report.set("result", passed() ? "pass" : "fail");
  Report& in = report.child("input");
  in.set("source", source);
  in.set("kind", input_kind);
  in.set("vertices", static_cast<std::int64_t>(input.mesh.vertices));
  in.set("triangles", static_cast<std::int64_t>(input.mesh.triangles));
  in.set("components", static_cast<std::int64_t>(input.mesh.components));
  in.set("volume", input.volume);
  in.set("flipped", input.flipped);
  in.set("concave_edges", static_cast<std::int64_t>(concave_edges));
  in.set("self_intersections", static_cast<std::int64_t>(self_intersection_pairs));
  Report& s = report.child("seeds");
  s.set("given", static_cast<std::int64_t>(seeds.size()));
  s.set("used", static_cast<std::int64_t>(sorting.active.size()));
  s.set("ignored", static_cast<std::int64_t>(seeds.size() - sorting.active.size()));
  s.set("nudge", seed_nudge);
  for (std::size_t i = 0; i < sorting.fate.size(); ++i) {
    if (sorting.fate[i] == SeedFate::used) continue;
    Report& e = s.append("ignored_seeds");
    e.set("seed", static_cast<std::int64_t>(i));
    e.set("reason", to_string(sorting.fate[i]));
    e.set("position", Report::Numbers{seeds[i].x(), seeds[i].y(), seeds[i].z()});
    if (sorting.same_as[i] >= 0) e.set("same_as", static_cast<std::int64_t>(sorting.same_as[i]));
  }
  Report& f = report.child("fragments");
  f.set("count", static_cast<std::int64_t>(figures.fragments));
  f.set("split_cells", static_cast<std::int64_t>(figures.split_cells));
  f.set("triangles", static_cast<std::int64_t>(figures.triangles));
  f.set("volume_sum", figures.volume_sum);
  f.set("relative_error", figures.relative_error);
  f.set("min_volume", figures.min_volume);
  f.set("max_volume", figures.max_volume);
  Report& c = report.child("checks");
  for (const CheckItem& check : checks) {
    Report& e = c.child(check.name);
    e.set("status", to_string(check.status));
    e.set("title", check.title);
    e.set("detail", check.detail);
  }
  for (const CellFailure& failure : failures) {
    Report& e = report.append("failures");
    e.set("seed", static_cast<std::int64_t>(failure.seed));
    e.set("message", failure.message);
  }
  for (const std::string& w : warnings) report.append("warnings").set("message", w);
  Report& t = report.child("seconds");
  t.set("input", seconds_input);
  t.set("cells", seconds_cells);
  t.set("clip", seconds_clip);
  t.set("checks", seconds_checks);
  return report;
}

std::string CheckResult::text() const {
  std::string out = fmt::format("{} ({}): {} vertices, {} triangles, volume {:.6g}\n", source, input_kind,
                                input.mesh.vertices, input.mesh.triangles, input.volume);
  out += fmt::format("  seeds      {} given, {} used, {} ignored\n", seeds.size(), sorting.active.size(),
                     seeds.size() - sorting.active.size());
  out += fmt::format("  fragments  {} ({} cells split into several), {} triangles, volumes {:.3g} .. {:.3g}\n",
                     figures.fragments, figures.split_cells, figures.triangles, figures.min_volume,
                     figures.max_volume);
  out += fmt::format("  time       input {:.2f} s, cells {:.2f} s, clip {:.2f} s, checks {:.2f} s\n", seconds_input,
                     seconds_cells, seconds_clip, seconds_checks);
  for (const CheckItem& c : checks) {
    const char* mark = c.status == CheckStatus::pass ? "PASS" : c.status == CheckStatus::fail ? "FAIL" : "skip";
    out += fmt::format("  {}  {}{}{}\n", mark, c.title, c.detail.empty() ? "" : ": ", c.detail);
  }
  for (const CellFailure& f : failures) out += fmt::format("  cell of seed {} failed: {}\n", f.seed, f.message);
  out += fmt::format("  result     {}\n", passed() ? "pass" : "FAIL");
  return out;
}

}  // namespace bw::voronoi

namespace bw::voronoi {

std::vector<std::string> export_fragments(std::span<const Fragment> fragments, const std::string& folder,
                                          const std::string& extension) {
  if (extension != "obj" && extension != "ply") {
    fail_input("--export-format: '{}' is not one of obj, ply", extension);
  }
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec || !std::filesystem::is_directory(folder)) {
    fail_input("{}: cannot create the export folder: {}", folder, ec ? ec.message() : "not a folder");
  }
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < fragments.size(); ++i) {
    const Fragment& f = fragments[i];
    const std::string path =
        (std::filesystem::path(folder) / fmt::format("fragment_{:04}_seed_{:04}_{}.{}", i, f.seed, f.component,
                                                     extension))
            .string();
    mesh::export_mesh(f.mesh, path);
    paths.push_back(path);
  }
  return paths;
}

}  // namespace bw::voronoi
