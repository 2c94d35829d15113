#include "render/render_settings.h"

#include <cmath>
#include <functional>
#include <map>

#include <toml++/toml.h>

#include "common/error.h"
#include "common/text.h"

namespace bw::render {
namespace {

// Reads one table's keys, each with its own reader, and rejects the others.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string path)
      : table_(table), file_(std::move(file)), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    fail_input("{}: {}.{}: {}", file_, path_, key, problem);
  }

  void number(const std::string& key, double& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) {
      if (!n.is_number()) fail(key, "expected a number");
      out = n.value<double>().value();
      if (!std::isfinite(out)) fail(key, "expected a finite number");
    };
  }
  void optional_number(const std::string& key, std::optional<double>& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) {
      if (!n.is_number()) fail(key, "expected a number");
      const double v = n.value<double>().value();
      if (!std::isfinite(v)) fail(key, "expected a finite number");
      out = v;
    };
  }
  void integer(const std::string& key, int& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) {
      if (!n.is_integer()) fail(key, "expected an integer");
      const std::int64_t v = n.value<std::int64_t>().value();
      if (v < -1000000000 || v > 1000000000) fail(key, "out of range");
      out = static_cast<int>(v);
    };
  }
  void boolean(const std::string& key, bool& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) {
      if (!n.is_boolean()) fail(key, "expected true or false");
      out = n.value<bool>().value();
    };
  }
  void vec3(const std::string& key, Vec3d& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) { out = vec3_of(key, n); };
  }
  void optional_vec3(const std::string& key, std::optional<Vec3d>& out) {
    handlers_[key] = [this, key, &out](const toml::node& n) { out = vec3_of(key, n); };
  }
  // A key whose value is read by the caller (an array of tables).
  void node(const std::string& key, std::function<void(const toml::node&)> read) { handlers_[key] = std::move(read); }
  void text(const std::string& key, std::function<void(const std::string&)> parse) {
    handlers_[key] = [this, key, parse](const toml::node& n) {
      if (!n.is_string()) fail(key, "expected a string");
      parse(n.value<std::string>().value());
    };
  }

  Vec3d vec3_of(const std::string& key, const toml::node& n) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3) fail(key, "expected an array of 3 numbers");
    Vec3d out;
    for (std::size_t i = 0; i < 3; ++i) {
      const toml::node& e = *a->get(i);
      if (!e.is_number()) fail(key, "expected an array of 3 numbers");
      out[static_cast<int>(i)] = e.value<double>().value();
      if (!std::isfinite(out[static_cast<int>(i)])) fail(key, "expected finite numbers");
    }
    return out;
  }

  void read() const {
    for (auto&& [k, node] : table_) {
      const std::string key(k.str());
      auto it = handlers_.find(key);
      if (it == handlers_.end()) fail(key, "unknown key (see docs/rendering.md)");
      it->second(node);
    }
  }

 private:
  const toml::table& table_;
  std::string file_, path_;
  std::map<std::string, std::function<void(const toml::node&)>> handlers_;
};

void check(bool ok, const std::string& where, const char* key, const std::string& problem) {
  if (!ok) fail_input("{}: {}: {}", where, key, problem);
}

bool unit_color(const Vec3d& c) { return (c.array() >= 0).all() && (c.array() <= 1).all(); }

// What one [[camera.key]] gives; the rest comes from [camera] itself.
struct KeyValues {
  std::optional<double> time, frame, fov;
  std::optional<Vec3d> position, target, up;
};

// [camera]: one camera, or keys over time ([[camera.key]]) whose missing values are
// the table's own.
// `frame_rate`: the file's [time] frame_rate, for keys given by frame (0: not given).
CameraPath read_camera(const toml::table& t, const std::string& name, double frame_rate, std::string& track) {
  KeyValues base;
  std::vector<KeyValues> keys;
  std::string interpolation = "smooth";
  TableReader r(t, name, "camera");
  r.optional_vec3("position", base.position);
  r.optional_vec3("target", base.target);
  r.optional_vec3("up", base.up);
  r.optional_number("fov", base.fov);
  r.text("track", [&](const std::string& v) {
    if (v.empty()) r.fail("track", "expected the name of a body");
    track = v;
  });
  r.text("interpolation", [&](const std::string& v) {
    if (!parse_camera_interpolation(v)) r.fail("interpolation", fmt::format("'{}' is not one of smooth, linear", v));
    interpolation = v;
  });
  r.node("key", [&](const toml::node& n) {
    const toml::array* a = n.as_array();
    if (!a || !a->is_array_of_tables() || a->empty())
      r.fail("key", "expected an array of tables, each [[camera.key]] with a time");
    keys.resize(a->size());
    for (std::size_t k = 0; k < a->size(); ++k) {
      TableReader key(*a->get(k)->as_table(), name, fmt::format("camera.key[{}]", k));
      key.optional_number("time", keys[k].time);
      key.optional_number("frame", keys[k].frame);
      key.optional_vec3("position", keys[k].position);
      key.optional_vec3("target", keys[k].target);
      key.optional_vec3("up", keys[k].up);
      key.optional_number("fov", keys[k].fov);
      key.read();
    }
  });
  r.read();
  // A tracked body is the target: the camera's own would be a second answer.
  if (!track.empty()) {
    if (base.target) fail_input("{}: camera.target: not with camera.track, which aims the camera at the body", name);
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (keys[k].target)
        fail_input("{}: camera.key[{}].target: not with camera.track, which aims the camera at the body", name, k);
    base.target = Vec3d::Zero();  // replaced in each frame by the body's centre
  }
  if (keys.empty()) {
    if (!base.position || !base.target)
      fail_input("{}: camera.{}: required when a [camera] table is given", name, base.position ? "target" : "position");
    keys.push_back(base);
    keys.back().time = 0;
  }
  std::vector<CameraKey> path;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    KeyValues& v = keys[k];
    const std::string key = fmt::format("camera.key[{}]", k);
    if (v.frame) {
      // A frame of the run: frame F is written at F / [time] frame_rate (docs/formats.md).
      if (v.time) fail_input("{}: {}: give time or frame, not both", name, key);
      if (!(frame_rate > 0))
        fail_input("{}: {}.frame: needs [time] frame_rate in this file, the rate its frames count in", name, key);
      v.time = *v.frame / frame_rate;
    }
    if (!v.time) fail_input("{}: {}.time: required (the simulation time of the key, s; or its frame)", name, key);
    if (k > 0 && !(*v.time > *keys[k - 1].time)) {
      if (v.frame)
        fail_input("{}: {}.frame: {} (t = {} s) is not after camera.key[{}] (t = {} s)", name, key, *v.frame, *v.time,
                   k - 1, *keys[k - 1].time);
      fail_input("{}: {}.time: {} is not after camera.key[{}].time = {}", name, key, *v.time, k - 1, *keys[k - 1].time);
    }
    if (!v.position && !base.position)
      fail_input("{}: {}.position: required in every key when [camera] has no position", name, key);
    if (!v.target && !base.target)
      fail_input("{}: {}.target: required in every key when [camera] has no target", name, key);
    Camera c;
    c.position = v.position.value_or(base.position.value_or(Vec3d::Zero()));
    c.target = v.target.value_or(base.target.value_or(Vec3d::Zero()));
    c.up = v.up.value_or(base.up.value_or(c.up));
    c.fov_degrees = v.fov.value_or(base.fov.value_or(c.fov_degrees));
    if (const std::string problem = camera_problem(c, track.empty()); !problem.empty())
      fail_input("{}: {}.{}", name, t.contains("key") ? key : std::string("camera"), problem);
    path.push_back({*v.time, c});
  }
  return CameraPath(std::move(path), *parse_camera_interpolation(interpolation));
}

// Every key, and the cameras between them: the path must be drawable throughout (the
// frames' times are not known here; bw-render checks each frame's camera again).
void check_camera_path(const CameraPath& path, bool tracked, const std::string& where) {
  const auto& keys = path.keys();
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string problem = camera_problem(keys[k].camera, !tracked);
    if (!problem.empty())
      fail_input("{}: {}.{}", where, path.animated() ? fmt::format("camera.key[{}]", k) : "camera", problem);
  }
  constexpr int kSamples = 64;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k)
    for (int i = 1; i < kSamples; ++i) {
      const double t = keys[k].time + (keys[k + 1].time - keys[k].time) * i / kSamples;
      const std::string problem = camera_problem(path.at(t), !tracked);
      if (!problem.empty())
        fail_input("{}: camera.key[{}] to camera.key[{}]: at t = {:.6g} s, {}", where, k, k + 1, t, problem);
    }
}

}  // namespace

std::optional<Filter> parse_filter(const std::string& name) {
  if (name == "narrow-range") return Filter::kNarrowRange;
  if (name == "bilateral") return Filter::kBilateral;
  if (name == "none") return Filter::kNone;
  return std::nullopt;
}

const char* filter_name(Filter filter) {
  switch (filter) {
    case Filter::kNarrowRange: return "narrow-range";
    case Filter::kBilateral: return "bilateral";
    case Filter::kNone: return "none";
  }
  return "?";
}

std::optional<View> parse_view(const std::string& name) {
  if (name == "shaded") return View::kShaded;
  if (name == "depth") return View::kDepth;
  if (name == "thickness") return View::kThickness;
  if (name == "normals") return View::kNormals;
  return std::nullopt;
}

std::optional<SolidColoring> parse_solid_coloring(const std::string& name) {
  if (name == "shaded") return SolidColoring::kShaded;
  if (name == "wall_pressure") return SolidColoring::kWallPressure;
  return std::nullopt;
}

const char* solid_coloring_name(SolidColoring coloring) {
  return coloring == SolidColoring::kWallPressure ? "wall_pressure" : "shaded";
}

// Largest image side: beyond this the framebuffers of one frame would need more
// than a gigabyte, which no one wants from a preview tool.
constexpr int kMaxImageSide = 16384;

void RenderSettings::validate(const std::string& where) const {
  check(width >= 1 && width <= kMaxImageSide, where, "render.width", fmt::format("{} is outside [1, {}]", width, kMaxImageSide));
  check(height >= 1 && height <= kMaxImageSide, where, "render.height",
        fmt::format("{} is outside [1, {}]", height, kMaxImageSide));
  if (camera) check_camera_path(*camera, !camera_track.empty(), where);
  check(camera_track.empty() || camera, where, "camera.track", "needs a camera position");
  check(light.direction.norm() > 0, where, "light.direction", "is the zero vector");
  check(unit_color(light.color), where, "light.color", "components must lie in [0, 1]");
  check(light.intensity >= 0, where, "light.intensity", "must be >= 0");
  check(light.ambient >= 0, where, "light.ambient", "must be >= 0");
  check(particle_radius >= 0, where, "render.particle_radius", "must be >= 0 (0: estimated)");
  check(particle_radius_factor > 0, where, "render.particle_radius_factor", "must be > 0");
  check(unit_color(fluid_color), where, "render.fluid_color", "components must lie in [0, 1]");
  check((absorption.array() >= 0).all(), where, "render.absorption", "components must be >= 0");
  check(refraction >= 0, where, "render.refraction", "must be >= 0");
  check(specular >= 0, where, "render.specular", "must be >= 0");
  check(filter_radius > 0, where, "render.filter_radius", "must be > 0");
  check(filter_max_pixels >= 1 && filter_max_pixels <= 64, where, "render.filter_max_pixels",
        fmt::format("{} is outside [1, 64]", filter_max_pixels));
  check(spray_neighbours >= 0 && spray_neighbours <= 1000, where, "render.spray_neighbours",
        fmt::format("{} is outside [0, 1000]", spray_neighbours));
  check(foam_neighbours >= spray_neighbours && foam_neighbours <= 1000, where, "render.foam_neighbours",
        fmt::format("{} is outside [render.spray_neighbours = {}, 1000]", foam_neighbours, spray_neighbours));
  check(spray_size > 0, where, "render.spray_size", "must be > 0");
  check(spray_opacity >= 0 && spray_opacity <= 1, where, "render.spray_opacity", "must lie in [0, 1]");
  check(foam >= 0 && foam <= 1, where, "render.foam", "must lie in [0, 1]");
  check(unit_color(sky_color), where, "render.sky_color", "components must lie in [0, 1]");
  check(unit_color(horizon_color), where, "render.horizon_color", "components must lie in [0, 1]");
  check(ground_tile > 0, where, "render.ground_tile", "must be > 0");
  check(unit_color(ground_color), where, "render.ground_color", "components must lie in [0, 1]");
  check(unit_color(solid_color), where, "render.solid_color", "components must lie in [0, 1]");
  check(unit_color(body_color), where, "render.body_color", "components must lie in [0, 1]");
  if (pressure_range)
    check(pressure_range->max > pressure_range->min, where, "render.pressure_range",
          fmt::format("[{}, {}]: the second value must be above the first", pressure_range->min, pressure_range->max));
}

RenderSettings parse_render_settings(const std::string& toml_text, const std::string& name) {
  toml::table root;
  try {
    root = toml::parse(toml_text, name);
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    fail_input("{}:{}:{}: {}", name, at.line, at.column, std::string(e.description()));
  }
  RenderSettings s;
  auto table = [&](const char* key) -> const toml::table* {
    const toml::node* n = root.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) fail_input("{}: {}: expected a table", name, key);
    return n->as_table();
  };

  // Keys may count in frames of the file's own [time] frame_rate (bw-sim checks the rest of [time]).
  double frame_rate = 0;
  if (const toml::table* time = table("time"))
    if (const toml::node* rate = time->get("frame_rate"); rate && rate->is_number())
      frame_rate = rate->value<double>().value();
  if (const toml::table* t = table("camera")) s.camera = read_camera(*t, name, frame_rate, s.camera_track);
  if (const toml::table* t = table("light")) {
    TableReader r(*t, name, "light");
    r.vec3("direction", s.light.direction);
    r.vec3("color", s.light.color);
    r.number("intensity", s.light.intensity);
    r.number("ambient", s.light.ambient);
    r.boolean("shadows", s.light.shadows);
    r.read();
  }
  if (const toml::table* t = table("render")) {
    TableReader r(*t, name, "render");
    r.integer("width", s.width);
    r.integer("height", s.height);
    r.number("particle_radius", s.particle_radius);
    r.number("particle_radius_factor", s.particle_radius_factor);
    r.vec3("fluid_color", s.fluid_color);
    r.vec3("absorption", s.absorption);
    r.number("refraction", s.refraction);
    r.number("specular", s.specular);
    r.text("filter", [&](const std::string& v) {
      auto f = parse_filter(v);
      if (!f) r.fail("filter", fmt::format("'{}' is not one of narrow-range, bilateral, none", v));
      s.filter = *f;
    });
    r.number("filter_radius", s.filter_radius);
    r.integer("filter_max_pixels", s.filter_max_pixels);
    r.boolean("spray", s.spray);
    r.integer("spray_neighbours", s.spray_neighbours);
    r.integer("foam_neighbours", s.foam_neighbours);
    r.number("spray_size", s.spray_size);
    r.number("spray_opacity", s.spray_opacity);
    r.number("foam", s.foam);
    r.vec3("sky_color", s.sky_color);
    r.vec3("horizon_color", s.horizon_color);
    r.boolean("ground", s.ground);
    r.optional_number("ground_height", s.ground_height);
    r.number("ground_tile", s.ground_tile);
    r.vec3("ground_color", s.ground_color);
    r.vec3("solid_color", s.solid_color);
    r.vec3("body_color", s.body_color);
    r.text("solids", [&](const std::string& v) {
      auto c = parse_solid_coloring(v);
      if (!c) r.fail("solids", fmt::format("'{}' is not one of shaded, wall_pressure", v));
      s.solids = *c;
    });
    r.node("pressure_range", [&](const toml::node& n) {
      const toml::array* a = n.as_array();
      if (!a || a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number())
        r.fail("pressure_range", "expected an array of 2 numbers [min, max] (Pa)");
      const double lo = a->get(0)->value<double>().value(), hi = a->get(1)->value<double>().value();
      if (!std::isfinite(lo) || !std::isfinite(hi)) r.fail("pressure_range", "expected finite numbers");
      s.pressure_range = ValueRange{lo, hi};
    });
    r.boolean("legend", s.legend);
    r.boolean("water", s.water);
    r.read();
  }
  s.validate(name);
  return s;
}

RenderSettings load_render_settings(const std::string& scene_path) {
  return parse_render_settings(read_text_file(scene_path, "a scene file"), scene_path);
}

}  // namespace bw::render
