#include "io/frame_file.h"

#include <fmt/format.h>

#include "common/error.h"
#include "io/arrays.h"
#include "io/h5.h"

namespace bw {
namespace {

constexpr const char* kKind = "frame";
constexpr const char* kStepName = "Step#0";

// The step group of a frame: Step#0, or Step#F (F the frame number) in files written
// before frames were numbered from 0 inside.
h5::Group open_step(const h5::File& file, std::int32_t frame) {
  const h5::Group& root = file.root();
  if (root.is_group(kStepName)) return root.open_group(kStepName);
  const std::string old_name = fmt::format("Step#{}", frame);
  if (!root.is_group(old_name)) fail_input("{}: missing group {} for frame {}", file.name(), kStepName, frame);
  return root.open_group(old_name);
}

template <class T>
void read_optional(const h5::Group& step, const char* name, std::size_t n, std::vector<T>& out) {
  if (!step.has(name)) return;
  std::size_t rows = 0;
  out = step.read_rows<T>(name, 0, &rows);
  if (rows != n) fail_input("{}: holds {} values, expected one per particle ({})", step.where(name), rows, n);
}

BodyStates read_bodies(const h5::Group& g) {
  BodyStates b;
  std::size_t m = 0, rows = 0;
  b.id = g.read_rows<std::int32_t>("id", 0, &m);
  auto read3 = [&](const char* name) {
    auto v = io::unflatten_points(g.read_rows<double>(name, 3, &rows));
    if (rows != m) fail_input("{}: {} rows, expected {}", g.where(name), rows, m);
    return v;
  };
  b.position = read3("position");
  b.linear_velocity = read3("linear_velocity");
  b.angular_velocity = read3("angular_velocity");
  const auto q = g.read_rows<double>("orientation", 4, &rows);
  if (rows != m) fail_input("{}: {} rows, expected {}", g.where("orientation"), rows, m);
  for (std::size_t i = 0; i < m; ++i) b.orientation.emplace_back(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
  return b;
}

void read_boundary_and_bodies(const h5::Group& step, FrameData& f) {
  if (step.is_group("boundary")) {
    const h5::Group b = step.open_group("boundary");
    std::size_t k = 0;
    f.bx = b.read_rows<float>("x", 0, &k);
    read_optional(b, "y", k, f.by);
    read_optional(b, "z", k, f.bz);
    read_optional(b, "p", k, f.bp);
    read_optional(b, "solid", k, f.bsolid);
  }
  if (step.is_group("bodies")) f.bodies = read_bodies(step.open_group("bodies"));
}

// The whole frame, or (with_fluid false) all but the fluid's arrays.
FrameData read_frame_parts(const std::string& path, bool with_fluid) {
  h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  FrameData f;
  f.frame = root.attr<std::int32_t>("frame");
  f.time = root.attr<double>("time");
  const h5::Group step = open_step(file, f.frame);
  if (with_fluid) {
    std::size_t n = 0;
    f.x = step.read_rows<float>("x", 0, &n);
    read_optional(step, "y", n, f.y);
    read_optional(step, "z", n, f.z);
    if (f.y.size() != n || f.z.size() != n) fail_input("{}: missing y or z", step.where());
    read_optional(step, "vx", n, f.vx);
    read_optional(step, "vy", n, f.vy);
    read_optional(step, "vz", n, f.vz);
    read_optional(step, "rho", n, f.rho);
    read_optional(step, "p", n, f.p);
    read_optional(step, "id", n, f.id);
  }
  read_boundary_and_bodies(step, f);
  return f;
}

}  // namespace

FrameFields FrameData::fields() const {
  FrameFields f;
  f.velocity = !vx.empty();
  f.density = !rho.empty();
  f.pressure = !p.empty();
  f.id = !id.empty();
  f.boundary = !bx.empty();
  f.wall_pressure = !bp.empty();
  f.boundary_solid = !bsolid.empty();
  return f;
}

void require_wall_pressure(const FrameFields& fields, const std::string& where) {
  if (!fields.wall_pressure)
    fail_input("{}: holds no wall pressure; add \"wall_pressure\" to the scene's [output] fields", where);
  if (!fields.boundary_solid)
    fail_input("{}: holds no boundary/solid, which tells each boundary particle's solid (bw-sim writes it from this "
               "version on): run the scene again",
               where);
}

std::string frame_file_name(const std::string& folder, int frame) {
  return fmt::format("{}/{:06d}.h5", folder, frame);
}

void write_frame(const FrameData& f, const std::string& path) {
  const std::size_t n = f.x.size();
  auto check = [&](const auto& v, const char* name) {
    if (!v.empty() && v.size() != n) fail_run("{}: field {} has {} values for {} particles", path, name, v.size(), n);
  };
  if (f.y.size() != n || f.z.size() != n) fail_run("{}: x, y, z differ in length", path);
  check(f.vx, "vx"), check(f.vy, "vy"), check(f.vz, "vz"), check(f.rho, "rho"), check(f.p, "p"), check(f.id, "id");
  if (f.by.size() != f.bx.size() || f.bz.size() != f.bx.size()) fail_run("{}: boundary x, y, z differ in length", path);
  if (!f.bp.empty() && f.bp.size() != f.bx.size())
    fail_run("{}: field boundary/p has {} values for {} boundary particles", path, f.bp.size(), f.bx.size());
  if (!f.bsolid.empty() && f.bsolid.size() != f.bx.size())
    fail_run("{}: boundary/solid has {} values for {} boundary particles", path, f.bsolid.size(), f.bx.size());

  h5::File file = h5::File::create(path, kKind);
  h5::Group& root = file.root();
  root.set_attr("frame", f.frame);
  root.set_attr("time", f.time);
  // H5Part readers (ParaView, VisIt) number a file's steps from 0, so the one step of a
  // frame file is Step#0 whatever the frame; TimeValue is the name they take times from.
  h5::Group step = root.create_group(kStepName);
  step.set_attr("time", f.time);
  step.set_attr("TimeValue", f.time);
  step.set_attr("frame", f.frame);
  step.write<float>("x", f.x);
  step.write<float>("y", f.y);
  step.write<float>("z", f.z);
  if (!f.vx.empty()) {
    step.write<float>("vx", f.vx);
    step.write<float>("vy", f.vy);
    step.write<float>("vz", f.vz);
  }
  if (!f.rho.empty()) step.write<float>("rho", f.rho);
  if (!f.p.empty()) step.write<float>("p", f.p);
  if (!f.id.empty()) step.write<std::int64_t>("id", f.id);
  if (!f.bx.empty()) {
    h5::Group boundary = step.create_group("boundary");
    boundary.write<float>("x", f.bx);
    boundary.write<float>("y", f.by);
    boundary.write<float>("z", f.bz);
    if (!f.bp.empty()) boundary.write<float>("p", f.bp);
    if (!f.bsolid.empty()) boundary.write<std::int32_t>("solid", f.bsolid);
  }
  if (f.bodies.size() > 0) {
    const BodyStates& b = f.bodies;
    const std::uint64_t m = b.size();
    h5::Group bodies = step.create_group("bodies");
    bodies.write<std::int32_t>("id", b.id);
    bodies.write<double>("position", io::flatten(b.position), {m, 3});
    std::vector<double> q(4 * m);
    for (std::size_t i = 0; i < m; ++i) {
      q[4 * i] = b.orientation[i].w();
      q[4 * i + 1] = b.orientation[i].x();
      q[4 * i + 2] = b.orientation[i].y();
      q[4 * i + 3] = b.orientation[i].z();
    }
    bodies.write<double>("orientation", q, {m, 4});
    bodies.write<double>("linear_velocity", io::flatten(b.linear_velocity), {m, 3});
    bodies.write<double>("angular_velocity", io::flatten(b.angular_velocity), {m, 3});
  }
  file.commit();
}

FrameData read_frame(const std::string& path) { return read_frame_parts(path, true); }

FrameData read_frame_boundary(const std::string& path) { return read_frame_parts(path, false); }

FrameHeader read_frame_header(const std::string& path, bool with_bodies) {
  h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  FrameHeader h;
  h.frame = root.attr<std::int32_t>("frame");
  h.time = root.attr<double>("time");
  const h5::Group step = open_step(file, h.frame);
  h.step = step.path();
  auto length = [](const h5::Group& g, const char* name) -> std::uint64_t {
    const h5::Shape shape = g.shape(name);
    return shape.empty() ? 0 : shape[0];
  };
  h.fluid = length(step, "x");
  h.fields.velocity = step.has("vx");
  h.fields.density = step.has("rho");
  h.fields.pressure = step.has("p");
  h.fields.id = step.has("id");
  h.fields.boundary = step.is_group("boundary");
  if (h.fields.boundary) {
    const h5::Group b = step.open_group("boundary");
    h.boundary = length(b, "x");
    h.fields.wall_pressure = b.has("p");
    h.fields.boundary_solid = b.has("solid");
  }
  if (step.is_group("bodies")) {
    const h5::Group g = step.open_group("bodies");
    h.body_count = length(g, "id");
    if (with_bodies) h.bodies = read_bodies(g);
  }
  return h;
}

}  // namespace bw
