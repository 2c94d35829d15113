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
    handlers_[key] = [this, key, &out](const toml::node& n) {
      const toml::array* a = n.as_array();
      if (!a || a->size() != 3) fail(key, "expected an array of 3 numbers");
      for (std::size_t i = 0; i < 3; ++i) {
        const toml::node& e = *a->get(i);
        if (!e.is_number()) fail(key, "expected an array of 3 numbers");
        out[static_cast<int>(i)] = e.value<double>().value();
        if (!std::isfinite(out[static_cast<int>(i)])) fail(key, "expected finite numbers");
      }
    };
  }
  void text(const std::string& key, std::function<void(const std::string&)> parse) {
    handlers_[key] = [this, key, parse](const toml::node& n) {
      if (!n.is_string()) fail(key, "expected a string");
      parse(n.value<std::string>().value());
    };
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

// Largest image side: beyond this the framebuffers of one frame would need more
// than a gigabyte, which no one wants from a preview tool.
constexpr int kMaxImageSide = 16384;

void RenderSettings::validate(const std::string& where) const {
  check(width >= 1 && width <= kMaxImageSide, where, "render.width", fmt::format("{} is outside [1, {}]", width, kMaxImageSide));
  check(height >= 1 && height <= kMaxImageSide, where, "render.height",
        fmt::format("{} is outside [1, {}]", height, kMaxImageSide));
  if (camera) {
    const Camera& c = *camera;
    check(c.fov_degrees > 0 && c.fov_degrees < 180, where, "camera.fov",
          fmt::format("{} is outside (0, 180) degrees", c.fov_degrees));
    check((c.target - c.position).norm() > 0, where, "camera.target", "equals camera.position");
    check(c.up.norm() > 0, where, "camera.up", "is the zero vector");
    check(c.up.normalized().cross((c.target - c.position).normalized()).norm() > 1e-6, where, "camera.up",
          "is parallel to the viewing direction");
  }
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

  if (const toml::table* t = table("camera")) {
    Camera c;
    TableReader r(*t, name, "camera");
    bool has_position = false, has_target = false;
    r.vec3("position", c.position);
    r.vec3("target", c.target);
    r.vec3("up", c.up);
    r.number("fov", c.fov_degrees);
    r.read();
    has_position = t->contains("position");
    has_target = t->contains("target");
    if (!has_position || !has_target)
      fail_input("{}: camera.{}: required when a [camera] table is given", name, has_position ? "target" : "position");
    s.camera = c;
  }
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
    r.read();
  }
  s.validate(name);
  return s;
}

RenderSettings load_render_settings(const std::string& scene_path) {
  return parse_render_settings(read_text_file(scene_path, "a scene file"), scene_path);
}

}  // namespace bw::render
