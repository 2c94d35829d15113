#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "common/error.h"
#include "common/text.h"
#include "scene/overrides.h"

namespace bw::scene {
namespace fs = std::filesystem;

namespace {

// "no such file", and for a relative path where it was looked for: relative paths
// start at the scene's folder, not the working one.
std::string no_such_file(const std::string& given, const fs::path& looked_at) {
  if (fs::path(given).is_absolute()) return given + ": no such file";
  return fmt::format("{}: no such file ({}; a relative path starts at the scene's folder)", given,
                     looked_at.lexically_normal().string());
}

// Tables another tool owns (bw-render documents them in docs/rendering.md); the
// simulator accepts them as they are.
const std::set<std::string> kForeignTables = {"camera", "light", "render"};

// Limits that keep a scene within what the solver can index and store.
constexpr std::int64_t kMaxParticles = 1'000'000'000;   // ids are 32-bit on the device
constexpr double kMaxFrames = 1e6;
constexpr double kMaxSensorRate = 1e6;     // Hz
constexpr double kMaxSensorSamples = 1e7;  // per sensor over the run
constexpr double kMinSupportRatio = 1.0;  // h / spacing
constexpr double kMaxSupportRatio = 4.0;
// Most fragments a scene may hold (body indices are int32 in the run file).
constexpr std::int64_t kMaxChunks = 1'000'000;
// Density of a breakable solid that gives none (kg/m^3): concrete.
constexpr double kBreakableDensity = 2400;

// Edit distance, for "did you mean" hints on unknown keys.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return "an array";
    case toml::node_type::table: return "a table";
    default: return "a date or time";
  }
}

// Reads the keys of one table, remembers which were read, and reports the rest as
// unknown. Every message names the file and the key's full path.
class Reader {
 public:
  Reader(const toml::table& table, std::string path, const std::string& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  std::string key_path(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    fail_input("{}: {}: {}", file_, key_path(key), message);
  }
  [[noreturn]] void fail_here(const std::string& message) const { fail_input("{}: {}: {}", file_, path_, message); }

  bool has(std::string_view key) {
    used_.insert(std::string(key));
    return table_.contains(key);
  }

  const toml::node* node(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  double to_number(const toml::node& n, const std::string& where) const {
    if (auto v = n.value_exact<double>()) {
      if (!std::isfinite(*v)) fail_input("{}: {}: {} is not a finite number", file_, where, *v);
      return *v;
    }
    if (auto v = n.value_exact<std::int64_t>()) return static_cast<double>(*v);
    fail_input("{}: {}: expected a number, found {}", file_, where, type_name(n));
  }

  double number(std::string_view key, double fallback) {
    const toml::node* n = node(key);
    return n ? to_number(*n, key_path(key)) : fallback;
  }
  double required_number(std::string_view key) {
    if (!has(key)) fail(key, "missing (required)");
    return number(key, 0);
  }
  std::int64_t integer(std::string_view key, std::int64_t fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (auto v = n->value_exact<std::int64_t>()) return *v;
    if (auto v = n->value_exact<double>()) fail(key, fmt::format("{} is not a whole number", *v));
    fail(key, fmt::format("expected an integer, found {}", type_name(*n)));
  }
  bool boolean(std::string_view key, bool fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    const auto v = n->value_exact<bool>();
    if (!v) fail(key, fmt::format("expected true or false, found {}", type_name(*n)));
    return *v;
  }
  std::string string(std::string_view key, const std::string& fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (auto v = n->value_exact<std::string>()) return *v;
    fail(key, fmt::format("expected a string, found {}", type_name(*n)));
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vector(std::string_view key, const Eigen::Matrix<double, N, 1>& fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    const toml::array* a = n->as_array();
    if (!a || static_cast<int>(a->size()) != N)
      fail(key, fmt::format("expected an array of {} numbers, found {}", N,
                            a ? fmt::format("{} values", a->size()) : type_name(*n)));
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) out[i] = to_number(*a->get(static_cast<std::size_t>(i)), fmt::format("{}[{}]", key_path(key), i));
    return out;
  }
  Vec3d vec3(std::string_view key, const Vec3d& fallback) { return vector<3>(key, fallback); }
  Vec3d required_vec3(std::string_view key) {
    if (!has(key)) fail(key, "missing (required)");
    return vec3(key, Vec3d::Zero());
  }
  std::vector<std::string> strings(std::string_view key, const std::vector<std::string>& fallback) {
    const toml::node* n = node(key);
    if (!n) return fallback;
    const toml::array* a = n->as_array();
    if (!a) fail(key, fmt::format("expected an array of strings, found {}", type_name(*n)));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < a->size(); ++i) {
      auto v = a->get(i)->value_exact<std::string>();
      if (!v) fail_input("{}: {}[{}]: expected a string, found {}", file_, key_path(key), i, type_name(*a->get(i)));
      out.push_back(*v);
    }
    return out;
  }
  const toml::table* table(std::string_view key) {
    const toml::node* n = node(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail(key, fmt::format("expected a table ([{}]), found {}", key_path(key), type_name(*n)));
    return n->as_table();
  }
  // [[key]] arrays of tables; an empty list when absent.
  std::vector<const toml::table*> tables(std::string_view key) {
    const toml::node* n = node(key);
    std::vector<const toml::table*> out;
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables())
      fail(key, fmt::format("expected tables ([[{}]]), found {}", key_path(key), type_name(*n)));
    for (const toml::node& t : *a) out.push_back(t.as_table());
    return out;
  }

  // Every key not read is an error, with a hint when it is close to a known key.
  void finish(const std::vector<std::string>& known_extra = {}) const {
    for (const auto& [k, v] : table_) {
      const std::string key(k.str());
      if (used_.count(key)) continue;
      std::string hint;
      std::size_t best = 3;
      std::vector<std::string> known(used_.begin(), used_.end());
      known.insert(known.end(), known_extra.begin(), known_extra.end());
      for (const std::string& candidate : known) {
        const std::size_t d = edit_distance(key, candidate);
        if (d < best) {
          best = d;
          hint = fmt::format(" (did you mean '{}'?)", candidate);
        }
      }
      fail_input("{}: {}: unknown key{}", file_, key_path(key), hint);
    }
  }

  const std::string& path() const { return path_; }

 private:
  const toml::table& table_;
  std::string path_;
  const std::string& file_;
  std::set<std::string> used_;
};

void positive(Reader& r, std::string_view key, double v) {
  if (!(v > 0)) r.fail(key, fmt::format("{} must be positive", v));
}
void non_negative(Reader& r, std::string_view key, double v) {
  if (v < 0) r.fail(key, fmt::format("{} must not be negative", v));
}
void in_unit_interval(Reader& r, std::string_view key, double v) {
  if (!(v > 0 && v <= 1)) r.fail(key, fmt::format("{} is outside (0, 1]", v));
}

bool box_inside(const Aabb& inner, const Aabb& outer) {
  return (inner.min.array() >= outer.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

std::string vec_text(const Vec3d& v) { return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z()); }

void read_time(Reader& top, Scene& s) {
  const toml::table* t = top.table("time");
  if (!t) top.fail("time", "missing (required: at least time.end)");
  Reader r(*t, "time", s.path);
  TimeSettings& ts = s.time;
  ts.end = r.required_number("end");
  positive(r, "end", ts.end);
  ts.frame_rate = r.number("frame_rate", ts.frame_rate);
  positive(r, "frame_rate", ts.frame_rate);
  if (ts.end * ts.frame_rate > kMaxFrames)
    r.fail("frame_rate", fmt::format("{} frames per second over {} s is more than {} frames", ts.frame_rate, ts.end,
                                     kMaxFrames));
  ts.dt_min = r.number("dt_min", ts.dt_min);
  positive(r, "dt_min", ts.dt_min);
  ts.dt_max = r.number("dt_max", ts.dt_max);
  positive(r, "dt_max", ts.dt_max);
  if (ts.dt_max < ts.dt_min) r.fail("dt_max", fmt::format("{} is smaller than dt_min ({})", ts.dt_max, ts.dt_min));
  ts.cfl = r.number("cfl", ts.cfl);
  in_unit_interval(r, "cfl", ts.cfl);
  ts.force_factor = r.number("force_factor", ts.force_factor);
  in_unit_interval(r, "force_factor", ts.force_factor);
  ts.viscous_factor = r.number("viscous_factor", ts.viscous_factor);
  in_unit_interval(r, "viscous_factor", ts.viscous_factor);
  ts.diffusion_factor = r.number("diffusion_factor", ts.diffusion_factor);
  // Up to 2: the explicit update's eigenvalues lie within twice its diagonal, so 1 is
  // stable on any packing; above it a close pair's mode can grow (docs/scene.md, "[time]").
  if (!(ts.diffusion_factor > 0 && ts.diffusion_factor <= 2))
    r.fail("diffusion_factor", fmt::format("{} is outside (0, 2]", ts.diffusion_factor));
  ts.energy_limit = r.number("energy_limit", ts.energy_limit);
  if (!(ts.energy_limit >= 0 && std::isfinite(ts.energy_limit)))
    r.fail("energy_limit", fmt::format("{} must be a fraction, 0 or more (0.1: stop 10% above the start; 0: never)",
                                       ts.energy_limit));
  r.finish();
}

void read_domain(Reader& top, Scene& s) {
  const toml::table* t = top.table("domain");
  if (!t) top.fail("domain", "missing (required: the box particles live in, domain.min and domain.max)");
  Reader r(*t, "domain", s.path);
  s.domain.min = r.required_vec3("min");
  s.domain.max = r.required_vec3("max");
  for (int a = 0; a < 3; ++a) {
    if (!(s.domain.max[a] > s.domain.min[a]))
      r.fail("max", fmt::format("{} must exceed min {} along every axis", vec_text(s.domain.max), vec_text(s.domain.min)));
  }
  r.finish();
}

void read_block(Reader& r, Scene& s) {
  Block b;
  b.min = r.required_vec3("min");
  b.max = r.required_vec3("max");
  for (int a = 0; a < 3; ++a) {
    if (!(b.max[a] > b.min[a]))
      r.fail("max", fmt::format("{} must exceed min {} along every axis", vec_text(b.max), vec_text(b.min)));
    if (std::floor((b.max[a] - b.min[a]) / s.spacing + 1e-9) < 1)
      r.fail("max", fmt::format("the block is thinner than the spacing ({}) along {}: it holds no particle", s.spacing,
                                "xyz"[a]));
  }
  b.velocity = r.vec3("velocity", b.velocity);
  Aabb box;
  box.add(b.min);
  box.add(b.max);
  if (!box_inside(box, s.domain)) r.fail_here("the block reaches outside the domain");
  r.finish();
  s.blocks.push_back(b);
}

void read_emitter(Reader& r, Scene& s) {
  Emitter e;
  const std::string shape = r.string("shape", "");
  if (shape == "disc") {
    e.shape = Emitter::Shape::disc;
  } else if (shape == "rectangle") {
    e.shape = Emitter::Shape::rectangle;
  } else if (shape.empty()) {
    r.fail("shape", "missing (required: \"disc\" or \"rectangle\")");
  } else {
    r.fail("shape", fmt::format("'{}' is not \"disc\" or \"rectangle\"", shape));
  }
  e.center = r.required_vec3("center");
  const Vec3d normal = r.required_vec3("normal");
  if (normal.norm() < 1e-12) r.fail("normal", "must not be zero");
  e.normal = normal.normalized();
  if (e.shape == Emitter::Shape::disc) {
    e.radius = r.required_number("radius");
    positive(r, "radius", e.radius);
    if (e.radius < 0.5 * s.spacing)
      r.fail("radius", fmt::format("{} is less than half the spacing ({}): the disc holds no particle", e.radius, s.spacing));
  } else {
    if (!r.has("size")) r.fail("size", "missing (required for a rectangle: [width, height])");
    e.size = r.vector<2>("size", e.size);
    for (int a = 0; a < 2; ++a) {
      if (!(e.size[a] >= s.spacing))
        r.fail("size", fmt::format("{} is smaller than the spacing ({})", e.size[a], s.spacing));
    }
    e.up = r.vec3("up", Vec3d::Zero());
    if (r.has("up")) {
      if (e.up.norm() < 1e-12) r.fail("up", "must not be zero");
      if (e.up.normalized().cross(e.normal).norm() < 1e-6) r.fail("up", "must not be parallel to the normal");
    }
  }
  e.speed = r.required_number("speed");
  positive(r, "speed", e.speed);
  e.start = r.number("start", 0);
  non_negative(r, "start", e.start);
  e.stop = r.number("stop", std::numeric_limits<double>::infinity());
  if (!(e.stop > e.start)) r.fail("stop", fmt::format("{} must be later than start ({})", e.stop, e.start));
  Aabb point;
  point.add(e.center);
  if (!box_inside(point, s.domain)) r.fail("center", fmt::format("{} is outside the domain", vec_text(e.center)));
  r.finish();
  s.emitters.push_back(e);
}

void read_fluid(Reader& top, Scene& s) {
  const toml::table* t = top.table("fluid");
  if (!t) return;
  Reader r(*t, "fluid", s.path);
  FluidSettings& f = s.fluid;
  f.rho0 = r.number("rho0", f.rho0);
  positive(r, "rho0", f.rho0);
  const bool has_k = r.has("k"), has_c0 = r.has("c0");
  if (has_k && has_c0) r.fail("c0", "give either k or c0, not both");
  if (has_k) {
    f.k = r.number("k", 0);
    positive(r, "k", f.k);
  }
  if (has_c0) {
    f.c0 = r.number("c0", 0);
    positive(r, "c0", f.c0);
  }
  f.gamma = r.number("gamma", f.gamma);
  if (!(f.gamma >= 1)) r.fail("gamma", fmt::format("{} must be at least 1", f.gamma));
  f.mu = r.number("mu", f.mu);
  non_negative(r, "mu", f.mu);
  f.mu_b = r.number("mu_b", f.mu);
  non_negative(r, "mu_b", f.mu_b);
  if (r.has("gamma1")) {
    f.gamma1 = r.number("gamma1", f.gamma1);
    non_negative(r, "gamma1", f.gamma1);
  }
  if (r.has("gamma2")) {
    f.gamma2 = r.number("gamma2", f.gamma2);
    non_negative(r, "gamma2", f.gamma2);
  }
  if (r.has("density")) {
    const std::string scheme = r.string("density", "continuity");
    if (scheme == "continuity") f.density = DensityScheme::continuity;
    else if (scheme == "summation") f.density = DensityScheme::summation;
    else r.fail("density", fmt::format("\"{}\" is not a density scheme: \"continuity\" or \"summation\"", scheme));
  }
  if (r.has("diffusion")) {
    f.diffusion = r.number("diffusion", f.diffusion);
    if (!(f.diffusion >= 0 && f.diffusion <= 1))
      r.fail("diffusion", fmt::format("{} must be between 0 (none) and 1 (0.1 is the usual delta)", f.diffusion));
    if (f.density == DensityScheme::summation && f.diffusion > 0)
      r.fail("diffusion", "density diffusion needs fluid.density = \"continuity\"; set it to 0 with \"summation\"");
  }
  // The wall follows the density scheme unless the scene names one: the summation has only
  // the mirrored wall; the continuity equation mirrors the water in flat faces (docs/scene.md,
  // "Walls as mirror images": water slides along them without the particles' grip).
  f.wall_pressure = f.density == DensityScheme::continuity ? WallPressure::images : WallPressure::mirrored;
  if (r.has("wall_pressure")) {
    const std::string wall = r.string("wall_pressure", "images");
    if (wall == "hydrostatic") f.wall_pressure = WallPressure::hydrostatic;
    else if (wall == "mirrored") f.wall_pressure = WallPressure::mirrored;
    else if (wall == "images") f.wall_pressure = WallPressure::images;
    else
      r.fail("wall_pressure",
             fmt::format("\"{}\" is not a wall pressure: \"mirrored\", \"hydrostatic\" or \"images\"", wall));
    // Measured: with the summation the layer against a wall leaks through it.
    if (f.wall_pressure != WallPressure::mirrored && f.density == DensityScheme::summation)
      r.fail("wall_pressure", fmt::format("the {} wall pressure needs fluid.density = \"continuity\"", wall));
  }
  if (r.has("seed")) {
    f.seed = r.integer("seed", 0);
    if (f.seed < 0) r.fail("seed", fmt::format("{} must be 0 (the lattice as it is) or a draw's number, 1 or more", f.seed));
  }
  if (r.has("jitter")) {
    f.jitter = r.number("jitter", f.jitter);
    if (!(f.jitter > 0 && f.jitter <= 0.1))
      r.fail("jitter", fmt::format("{} is outside (0, 0.1] spacings", f.jitter));
    if (f.seed == 0) r.fail("jitter", "moves particles only in a draw: set fluid.seed to 1 or more");
  }
  if (r.has("max_particles")) {
    f.max_particles = r.integer("max_particles", 0);
    if (f.max_particles < 1) r.fail("max_particles", fmt::format("{} must be at least 1", f.max_particles));
    if (f.max_particles > kMaxParticles)
      r.fail("max_particles", fmt::format("{} is more than {}", f.max_particles, kMaxParticles));
  }
  const auto blocks = r.tables("block");
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Reader b(*blocks[i], fmt::format("fluid.block[{}]", i), s.path);
    read_block(b, s);
  }
  const auto emitters = r.tables("emitter");
  for (std::size_t i = 0; i < emitters.size(); ++i) {
    Reader e(*emitters[i], fmt::format("fluid.emitter[{}]", i), s.path);
    read_emitter(e, s);
  }
  r.finish();
}

// Keys of a moving solid: rows of `columns` numbers, the first a time, in the scene
// ([[t, ...], ...]) or in a text file named there (one key a line, numbers separated
// by commas or spaces, `#` comments, a first line of column names skipped). Times
// start at 0 or later and do not decrease.
std::vector<std::vector<double>> read_keys(Reader& r, const Scene& s, std::string_view key,
                                           const std::vector<std::string_view>& columns, std::string_view units) {
  const toml::node* n = r.node(key);
  std::vector<std::vector<double>> rows;
  if (!n) return rows;
  const std::string shape = fmt::format("[{}] ({})", fmt::join(columns, ", "), units);
  // Checks a key's time against the one before; `where` names the key.
  auto check_time = [&](const std::string& where, double t) {
    if (t < 0) r.fail(where, fmt::format("time {} s is before the start of the run", t));
    if (!rows.empty() && t < rows.back()[0])
      r.fail(where, fmt::format("time {} s is before the key above's {} s (times must not decrease)", t, rows.back()[0]));
  };
  if (const auto* given = n->as_string()) {
    fs::path p(given->get());
    if (p.is_relative()) p = fs::path(s.folder) / p;
    std::ifstream in(p);
    if (!in) r.fail(key, fs::exists(p) ? given->get() + ": cannot be read" : no_such_file(given->get(), p));
    std::string line;
    bool first = true;  // the first line that is not blank or a comment may name the columns
    for (int number = 1; std::getline(in, line); ++number) {
      if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream fields(line);
      std::vector<std::string> words;
      for (std::string w; fields >> w;) words.push_back(w);
      if (words.empty()) continue;
      const std::string where = fmt::format("{} ({} line {})", key, given->get(), number);
      std::vector<double> row;
      for (const std::string& w : words) {
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);
        if (end != w.c_str() + w.size() || !std::isfinite(v)) {
          if (first && row.empty()) break;  // column names
          r.fail(where, fmt::format("'{}' is not a number; expected {}", w, shape));
        }
        row.push_back(v);
      }
      first = false;
      if (row.empty()) continue;
      if (row.size() != columns.size())
        r.fail(where, fmt::format("expected {}, found {} values", shape, row.size()));
      check_time(where, row[0]);
      rows.push_back(std::move(row));
    }
    if (rows.empty()) r.fail(key, fmt::format("{} holds no keys; expected lines {}", given->get(), shape));
    return rows;
  }
  const toml::array* list = n->as_array();
  if (!list || list->empty())
    r.fail(key, fmt::format("expected rows {} or the name of a file of them, found {}", shape,
                            list ? std::string("an empty array") : type_name(*n)));
  for (std::size_t k = 0; k < list->size(); ++k) {
    const toml::array* row = list->get(k)->as_array();
    const std::string where = fmt::format("{}[{}]", key, k);
    if (!row || row->size() != columns.size())
      r.fail(where, fmt::format("expected {}, found {}", shape,
                                row ? fmt::format("{} values", row->size()) : type_name(*list->get(k))));
    std::vector<double> v;
    for (std::size_t i = 0; i < columns.size(); ++i)
      v.push_back(r.to_number(*row->get(i), r.key_path(where) + fmt::format("[{}]", i)));
    check_time(where, v[0]);
    rows.push_back(std::move(v));
  }
  return rows;
}

// A static solid moved as told: `motion` (its velocity) and `angular_motion` (its
// angular velocity about `axis` through `pivot`).
void read_motion(Reader& r, const Scene& s, Solid& solid) {
  for (const char* key : {"motion", "angular_motion"})
    if (r.has(key) && solid.body())
      r.fail(key, "only for a static solid (a dynamic or breakable one moves by its forces)");
  for (const std::vector<double>& row : read_keys(r, s, "motion", {"t", "vx", "vy", "vz"}, "s, m/s")) {
    solid.motion_times.push_back(row[0]);
    solid.motion_velocities.emplace_back(row[1], row[2], row[3]);
  }
  for (const std::vector<double>& row : read_keys(r, s, "angular_motion", {"t", "omega"}, "s, rad/s")) {
    solid.angular_times.push_back(row[0]);
    solid.angular_rates.push_back(row[1]);
  }
  if (solid.angular_times.empty()) {
    for (const char* key : {"axis", "pivot"})
      if (r.has(key)) r.fail(key, "only with angular_motion (the solid's turn about this axis)");
    return;
  }
  if (!r.has("axis")) r.fail("axis", "missing (required with angular_motion: the direction it turns about)");
  if (!r.has("pivot")) r.fail("pivot", "missing (required with angular_motion: a point of the axis, m)");
  const Vec3d axis = r.vec3("axis", solid.axis);
  if (!(axis.norm() > 0)) r.fail("axis", "[0, 0, 0] has no direction");
  solid.axis = axis.normalized();
  solid.pivot = r.vec3("pivot", solid.pivot);
}

void read_solid(Reader& r, Scene& s) {
  Solid solid;
  const std::string given = r.string("particles", "");
  if (given.empty()) r.fail("particles", "missing (required: a particle file written by bw-sample)");
  fs::path p(given);
  if (p.is_relative()) p = fs::path(s.folder) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (!fs::exists(p, ec)) r.fail("particles", no_such_file(given, p));
  if (fs::is_directory(p, ec)) r.fail("particles", fmt::format("{}: is a folder, not a particle file", given));
  solid.particles = p.string();
  solid.particles_given = given;
  // Loads, sensors and bw-measure find a solid by its name: names are unique. Solids
  // from one file without a name take its stem, then stem-2, stem-3, ...
  const auto owner = [&](const std::string& name) {
    return std::find_if(s.solids.begin(), s.solids.end(), [&](const Solid& o) { return o.name == name; });
  };
  if (r.has("name")) {
    solid.name = r.string("name", "");
    if (const auto it = owner(solid.name); it != s.solids.end())
      r.fail("name", fmt::format("'{}' names solid[{}] too", solid.name, it - s.solids.begin()));
  } else {
    const std::string stem = fs::path(given).stem().string();
    solid.name = stem;
    for (int n = 2; owner(solid.name) != s.solids.end(); ++n) solid.name = fmt::format("{}-{}", stem, n);
  }
  solid.translation = r.vec3("translation", solid.translation);
  solid.rotation_degrees = r.vec3("rotation", solid.rotation_degrees);
  solid.scale = r.number("scale", solid.scale);
  positive(r, "scale", solid.scale);
  solid.dynamic = r.boolean("dynamic", false);
  solid.breakable = r.boolean("breakable", false);
  if (solid.breakable) {
    solid.frc = r.number("frc", solid.frc);
    in_unit_interval(r, "frc", solid.frc);
    solid.anchored = r.boolean("anchored", solid.anchored);
    if (solid.anchored && solid.dynamic)
      r.fail("anchored", "an anchored breakable solid stays fixed until it breaks; it cannot also be dynamic (set "
                         "anchored = false for a breakable solid that moves)");
  } else {
    for (const char* key : {"frc", "anchored"})
      if (r.has(key)) r.fail(key, "only for a breakable solid (breakable = true)");
    solid.anchored = false;
  }
  if (solid.body()) {
    if (solid.dynamic && !r.has("density")) r.fail("density", "missing (required for a dynamic solid, kg/m^3)");
    solid.density = r.number("density", kBreakableDensity);
    positive(r, "density", solid.density);
    if (solid.anchored) {
      for (const char* key : {"velocity", "angular_velocity"})
        if (r.has(key)) r.fail(key, "an anchored solid starts at rest (set anchored = false to give it a velocity)");
    }
    solid.velocity = r.vec3("velocity", solid.velocity);
    solid.angular_velocity = r.vec3("angular_velocity", solid.angular_velocity);
  } else {
    for (const char* key : {"density", "velocity", "angular_velocity"})
      if (r.has(key)) r.fail(key, "only for a dynamic or breakable solid (dynamic = true or breakable = true)");
  }
  read_motion(r, s, solid);
  solid.friction = r.number("friction", solid.friction);
  non_negative(r, "friction", solid.friction);
  solid.restitution = r.number("restitution", solid.restitution);
  if (!(solid.restitution >= 0 && solid.restitution <= 1))
    r.fail("restitution", fmt::format("{} is outside [0, 1]", solid.restitution));
  r.finish();
  s.solids.push_back(solid);
}

void read_fracture(Reader& top, Scene& s) {
  const toml::table* t = top.table("fracture");
  if (!t) return;
  Reader r(*t, "fracture", s.path);
  FractureSettings& f = s.fracture;
  f.window = r.number("window", f.window);
  positive(r, "window", f.window);
  f.energy_scale = r.number("energy_scale", f.energy_scale);
  positive(r, "energy_scale", f.energy_scale);
  f.max_chunks = r.integer("max_chunks", f.max_chunks);
  if (f.max_chunks < 1) r.fail("max_chunks", fmt::format("{} must be at least 1", f.max_chunks));
  if (f.max_chunks > kMaxChunks) r.fail("max_chunks", fmt::format("{} is more than {}", f.max_chunks, kMaxChunks));
  r.finish();
}

void read_sensor(Reader& r, Scene& s) {
  Sensor sensor;
  if (!r.has("name")) r.fail("name", "missing (required: the sensor's name in the run file)");
  sensor.name = r.string("name", "");
  if (sensor.name.empty() || sensor.name.find_first_of(" ,\t\n") != std::string::npos)
    r.fail("name", fmt::format("'{}' must be a word without spaces or commas", sensor.name));
  for (const Sensor& other : s.sensors)
    if (other.name == sensor.name) r.fail("name", fmt::format("'{}' names another sensor too", sensor.name));
  sensor.at = r.required_vec3("at");
  sensor.normal = r.vec3("normal", sensor.normal);
  if (r.has("normal")) {
    if (!(sensor.normal.norm() > 0)) r.fail("normal", "must not be zero (leave it out to take the face's)");
    sensor.normal.normalize();
  }
  sensor.radius = r.number("radius", sensor.radius);
  non_negative(r, "radius", sensor.radius);
  if (r.has("solid")) {
    const std::string name = r.string("solid", "");
    const auto it = std::find_if(s.solids.begin(), s.solids.end(), [&](const Solid& solid) { return solid.name == name; });
    if (it == s.solids.end()) r.fail("solid", fmt::format("'{}' is not a solid of the scene", name));
    if (it->body())
      r.fail("solid", fmt::format("'{}' is {}; sensors sit on static solids", name,
                                  it->breakable ? "breakable" : "dynamic"));
    sensor.solid = static_cast<std::int32_t>(it - s.solids.begin());
  }
  r.finish();
  s.sensors.push_back(sensor);
}

void read_output(Reader& top, Scene& s) {
  std::vector<std::string> fields = {"velocity"};
  if (const toml::table* t = top.table("output")) {
    Reader r(*t, "output", s.path);
    fields = r.strings("fields", fields);
    s.loads = r.boolean("loads", false);
    const std::int64_t every = r.integer("checkpoint_every", 0);
    if (every < 0 || every > 1000000)
      r.fail("checkpoint_every", fmt::format("{} is not a number of frames from 0 to 1000000", every));
    s.checkpoint_every = static_cast<int>(every);
    s.sensor_rate = r.number("sensor_rate", s.sensor_rate);
    positive(r, "sensor_rate", s.sensor_rate);
    if (s.sensor_rate > kMaxSensorRate)
      r.fail("sensor_rate", fmt::format("{} Hz is more than {} Hz", s.sensor_rate, kMaxSensorRate));
    if (s.sensor_rate * s.time.end > kMaxSensorSamples)
      r.fail("sensor_rate", fmt::format("{} samples per second over {} s is more than {} samples", s.sensor_rate,
                                        s.time.end, kMaxSensorSamples));
    r.finish();
  }
  s.fields = FrameFields{};
  for (const std::string& f : fields) {
    if (f == "velocity") s.fields.velocity = true;
    else if (f == "density") s.fields.density = true;
    else if (f == "pressure") s.fields.pressure = true;
    else if (f == "id") s.fields.id = true;
    else if (f == "boundary") s.fields.boundary = true;
    else if (f == "wall_pressure") s.fields.wall_pressure = s.fields.boundary = true;  // on the boundary's particles
    else {
      std::string known;
      for (const auto& k : field_names()) known += (known.empty() ? "" : ", ") + k;
      fail_input("{}: output.fields: '{}' is not a field ({})", s.path, f, known);
    }
  }
  s.field_names = fields;
}

}  // namespace

const std::vector<std::string>& field_names() {
  static const std::vector<std::string> names = {"velocity", "density", "pressure", "id", "boundary", "wall_pressure"};
  return names;
}

Eigen::Quaterniond Solid::rotation() const {
  const Vec3d r = rotation_degrees * (std::numbers::pi / 180.0);
  const Eigen::Quaterniond q = Eigen::AngleAxisd(r.z(), Vec3d::UnitZ()) * Eigen::AngleAxisd(r.y(), Vec3d::UnitY()) *
                               Eigen::AngleAxisd(r.x(), Vec3d::UnitX());
  return q.normalized();
}

Vec3d Solid::to_world(const Vec3d& p) const { return rotation() * (scale * p) + translation; }

Scene parse_scene(std::string_view text, const std::string& path, const std::vector<std::string>& overrides) {
  Scene s;
  s.path = path;
  s.text = std::string(text);
  std::error_code ec;
  const fs::path abs = fs::absolute(fs::path(path), ec);
  s.folder = abs.parent_path().string();

  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    std::string what(e.description());
    std::replace(what.begin(), what.end(), '\n', ' ');
    fail_input("{}:{}:{}: {}", path, where.line, where.column, what);
  }
  if (!overrides.empty()) {
    apply_overrides(root, overrides, path);
    std::ostringstream effective;
    effective << "# " << path << " with";
    for (const std::string& o : overrides) effective << " --set " << o;
    effective << "\n" << root << "\n";
    s.text = effective.str();
  }

  Reader top(root, "", s.path);
  s.spacing = top.required_number("spacing");
  positive(top, "spacing", s.spacing);
  s.smoothing_length = top.number("smoothing_length", 2 * s.spacing);
  positive(top, "smoothing_length", s.smoothing_length);
  const double ratio = s.smoothing_length / s.spacing;
  if (ratio < kMinSupportRatio - 1e-9 || ratio > kMaxSupportRatio + 1e-9)
    top.fail("smoothing_length", fmt::format("{} is {:.3g} spacings; it must be between {} and {} (default 2)",
                                             s.smoothing_length, ratio, kMinSupportRatio, kMaxSupportRatio));
  s.gravity = top.vec3("gravity", s.gravity);
  read_time(top, s);
  read_domain(top, s);
  read_fluid(top, s);
  const auto solids = top.tables("solid");
  for (std::size_t i = 0; i < solids.size(); ++i) {
    Reader r(*solids[i], fmt::format("solid[{}]", i), s.path);
    read_solid(r, s);
  }
  read_fracture(top, s);
  const auto sensors = top.tables("sensor");
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    Reader r(*sensors[i], fmt::format("sensor[{}]", i), s.path);
    read_sensor(r, s);
  }
  read_output(top, s);
  for (const std::string& t : kForeignTables) {
    if (top.has(t) && !root.get(t)->is_table()) top.fail(t, "expected a table");
  }
  top.finish();
  const bool bodies = std::any_of(s.solids.begin(), s.solids.end(), [](const Solid& solid) { return solid.body(); });
  if (s.blocks.empty() && s.emitters.empty() && !bodies)
    fail_input("{}: fluid: the scene has no fluid and no dynamic or breakable solid (add a [[fluid.block]] or a [[fluid.emitter]])",
               s.path);
  return s;
}

int last_frame(double end, double frame_rate) {
  constexpr double kSlack = 1e-9;  // 0.3 s at 10 frames a second ends at frame 3
  return static_cast<int>(std::floor(end * frame_rate + kSlack));
}

bool may_have_body(const Scene& s, const std::string& name) {
  for (const Solid& solid : s.solids) {
    if (!solid.body() && !solid.moving()) continue;
    if (name == solid.name) return true;
    if (!solid.breakable || name.rfind(solid.name + ".", 0) != 0) continue;
    // The rest: numbers joined by dots, one per generation.
    const std::string rest = name.substr(solid.name.size() + 1);
    bool ok = true, digit_before = false;  // every dot follows a digit, and so does the end
    for (char c : rest) {
      if (c >= '0' && c <= '9') {
        digit_before = true;
      } else {
        ok = ok && c == '.' && digit_before;
        digit_before = false;
      }
    }
    if (ok && digit_before) return true;
  }
  return false;
}

std::string body_names(const Scene& s) {
  std::string names;
  for (const Solid& solid : s.solids)
    if (solid.body() || solid.moving()) names += (names.empty() ? "" : ", ") + solid.name;
  return names;
}

void check_end_time(const Scene& s, double end, const std::string& what) {
  if (!std::isfinite(end) || end <= 0) fail_input("{}: {} is not a positive time (s)", what, end);
  if (end * s.time.frame_rate > kMaxFrames)
    fail_input("{}: {} s at {} frames per second is more than {} frames", what, end, s.time.frame_rate, kMaxFrames);
  if (last_frame(end, s.time.frame_rate) < 1)
    fail_input("{}: {} s is shorter than one frame at {} frames per second", what, end, s.time.frame_rate);
  if (!s.sensors.empty() && end * s.sensor_rate > kMaxSensorSamples)
    fail_input("{}: {} s at {} sensor samples per second is more than {} samples", what, end, s.sensor_rate,
               kMaxSensorSamples);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_scene(read_text_file(path, "a scene file"), path, overrides);
}

}  // namespace bw::scene
