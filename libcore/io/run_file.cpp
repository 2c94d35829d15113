#include "io/run_file.h"

#include <map>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "io/arrays.h"
#include "io/h5.h"
#include "io/particles_file.h"

namespace bw {
namespace {

constexpr const char* kKind = "run";

template <class T, class Row, class Get>
std::vector<T> column(const std::vector<Row>& rows, Get get) {
  std::vector<T> out;
  out.reserve(rows.size());
  for (const Row& r : rows) out.push_back(static_cast<T>(get(r)));
  return out;
}

}  // namespace

void write_run(const RunRecord& run, const std::string& path) {
  h5::File file = h5::File::create(path, kKind);
  h5::Group& root = file.root();
  root.set_attr("scene", run.scene_text);
  root.set_attr("scene_path", run.scene_path);
  root.set_attr("device", run.device);
  root.set_attr("tool", run.tool);
  root.set_attr("status", run.status);

  h5::Group frames = root.create_group("frames");
  const auto& f = run.frames;
  frames.write("frame", column<double>(f, [](const FrameStats& s) { return s.frame; }));
  frames.write("time", column<double>(f, [](const FrameStats& s) { return s.time; }));
  frames.write("steps", column<double>(f, [](const FrameStats& s) { return s.steps; }));
  frames.write("dt_min", column<double>(f, [](const FrameStats& s) { return s.dt_min; }));
  frames.write("dt_max", column<double>(f, [](const FrameStats& s) { return s.dt_max; }));
  frames.write("fluid", column<double>(f, [](const FrameStats& s) { return s.fluid; }));
  frames.write("boundary", column<double>(f, [](const FrameStats& s) { return s.boundary; }));
  frames.write("removed", column<double>(f, [](const FrameStats& s) { return s.removed; }));
  frames.write("density_error_max", column<double>(f, [](const FrameStats& s) { return s.density_error_max; }));
  frames.write("density_error_mean", column<double>(f, [](const FrameStats& s) { return s.density_error_mean; }));
  frames.write("kinetic_energy", column<double>(f, [](const FrameStats& s) { return s.kinetic_energy; }));
  frames.write("potential_energy", column<double>(f, [](const FrameStats& s) { return s.potential_energy; }));
  frames.write("wall_time", column<double>(f, [](const FrameStats& s) { return s.wall_time; }));
  frames.write("elastic_energy", column<double>(f, [](const FrameStats& s) { return s.elastic_energy; }));
  frames.write("speed_max", column<double>(f, [](const FrameStats& s) { return s.speed_max; }));
  frames.write("emitted_energy", column<double>(f, [](const FrameStats& s) { return s.emitted_energy; }));
  frames.write("outflow_energy", column<double>(f, [](const FrameStats& s) { return s.outflow_energy; }));

  // One float64 value per parameter: a one-row table for bw-info.
  h5::Group parameters = root.create_group("parameters");
  for (const auto& [name, value] : run.parameters) parameters.write<double>(name, std::vector<double>{value});
  h5::Group summary = root.create_group("summary");
  for (const auto& [name, value] : run.summary) summary.write<double>(name, std::vector<double>{value});

  h5::Group solids = root.create_group("solids");
  for (std::size_t i = 0; i < run.solids.size(); ++i) {
    const SolidRecord& s = run.solids[i];
    h5::Group g = solids.create_group(fmt::format("{:03d}", i));
    g.set_attr("name", s.name);
    g.set_attr("particles", s.particles);
    g.set_attr("kind", s.kind);
    const double t[3] = {s.translation.x(), s.translation.y(), s.translation.z()};
    g.set_attr("translation", std::span<const double>(t));
    const double q[4] = {s.rotation.w(), s.rotation.x(), s.rotation.y(), s.rotation.z()};
    g.set_attr("rotation", std::span<const double>(q));
    g.set_attr("scale", s.scale);
    g.set_attr("body", s.body);
  }

  h5::Group bodies = root.create_group("bodies");
  const auto& b = run.bodies;
  const std::uint64_t nb = b.size();
  std::string names;
  for (std::size_t i = 0; i < nb; ++i) names += (i ? "\n" : "") + b[i].name;
  bodies.set_attr("names", names);
  bodies.write("solid", column<std::int32_t>(b, [](const BodyRecord& r) { return r.solid; }));
  bodies.write("parent", column<std::int32_t>(b, [](const BodyRecord& r) { return r.parent; }));
  bodies.write("mass", column<double>(b, [](const BodyRecord& r) { return r.mass; }));
  bodies.write("created_time", column<double>(b, [](const BodyRecord& r) { return r.created_time; }));
  bodies.write("voxels", column<std::int32_t>(b, [](const BodyRecord& r) { return r.voxels; }));
  std::vector<double> inertia(9 * nb);
  std::vector<Vec3d> centers;
  for (std::size_t i = 0; i < nb; ++i) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) inertia[9 * i + 3 * r + c] = b[i].inertia(r, c);
    centers.push_back(b[i].reference_center);
  }
  bodies.write<double>("inertia", inertia, {nb, 9});
  bodies.write<double>("reference_center", io::flatten(centers), {nb, 3});

  h5::Group fracture = root.create_group("fracture");
  std::vector<double> time;
  std::vector<std::int32_t> parent, child_body, child_seed, child_component;
  std::vector<std::int64_t> seed_offset, seed_count, child_offset, child_count;
  std::vector<Vec3d> seeds;
  for (const FractureEvent& e : run.fractures) {
    time.push_back(e.time);
    parent.push_back(e.parent);
    seed_offset.push_back(static_cast<std::int64_t>(seeds.size()));
    seed_count.push_back(static_cast<std::int64_t>(e.seeds.size()));
    child_offset.push_back(static_cast<std::int64_t>(child_body.size()));
    child_count.push_back(static_cast<std::int64_t>(e.child_body.size()));
    seeds.insert(seeds.end(), e.seeds.begin(), e.seeds.end());
    if (e.child_seed.size() != e.child_body.size() || e.child_component.size() != e.child_body.size()) {
      fail_run("{}: fracture event at t={} has child arrays of different lengths", path, e.time);
    }
    child_body.insert(child_body.end(), e.child_body.begin(), e.child_body.end());
    child_seed.insert(child_seed.end(), e.child_seed.begin(), e.child_seed.end());
    child_component.insert(child_component.end(), e.child_component.begin(), e.child_component.end());
  }
  fracture.write("time", time);
  fracture.write("parent", parent);
  fracture.write("seed_offset", seed_offset);
  fracture.write("seed_count", seed_count);
  fracture.write("child_offset", child_offset);
  fracture.write("child_count", child_count);
  fracture.write<double>("seeds", io::flatten(seeds), {seeds.size(), 3});
  fracture.write("child_body", child_body);
  fracture.write("child_seed", child_seed);
  fracture.write("child_component", child_component);
  if (!run.loads.empty()) {
    h5::Group loads = root.create_group("loads");
    const std::size_t nsolids = run.loads.front().size();
    std::vector<Vec3d> impulse;
    for (const auto& row : run.loads) {
      if (row.size() != nsolids) fail_run("{}: load rows of {} and {} solids", path, nsolids, row.size());
      impulse.insert(impulse.end(), row.begin(), row.end());
    }
    loads.write<double>("impulse", io::flatten(impulse), {run.loads.size(), nsolids, 3});
  }
  if (!run.sensors.names.empty()) {
    const SensorRecord& r = run.sensors;
    const std::size_t ns = r.names.size();
    if (r.at.size() != ns || r.normal.size() != ns || r.radius.size() != ns || r.particles.size() != ns ||
        r.pressure.size() % ns != 0)
      fail_run("{}: sensor arrays of different lengths ({} names)", path, ns);
    h5::Group sensors = root.create_group("sensors");
    std::string name_lines;
    for (std::size_t i = 0; i < ns; ++i) name_lines += (i ? "\n" : "") + r.names[i];
    sensors.set_attr("names", name_lines);
    sensors.set_attr<double>("interval", r.interval);
    sensors.write<double>("at", io::flatten(r.at), {ns, 3});
    sensors.write<double>("normal", io::flatten(r.normal), {ns, 3});
    sensors.write("radius", r.radius);
    sensors.write("particles", r.particles);
    std::vector<double> middle(r.samples());
    for (std::size_t k = 0; k < middle.size(); ++k) middle[k] = (static_cast<double>(k) + 0.5) * r.interval;
    sensors.write("time", middle);
    sensors.write<double>("pressure", r.pressure, {r.samples(), ns});
  }
  file.commit();
}

std::optional<double> RunRecord::parameter(const std::string& name) const {
  for (const auto& [key, value] : parameters)
    if (key == name) return value;
  return std::nullopt;
}

RunRecord read_run(const std::string& path) {
  h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  RunRecord run;
  run.scene_text = root.attr_string("scene");
  run.scene_path = root.attr_string("scene_path");
  run.device = root.attr_string("device");
  run.tool = root.attr_string("tool");
  run.status = root.attr_string("status");

  const h5::Group frames = root.open_group("frames");
  std::size_t nf = 0;
  const auto frame = frames.read_rows<double>("frame", 0, &nf);
  auto col = [&](const char* name) {
    std::size_t n = 0;
    auto v = frames.read_rows<double>(name, 0, &n);
    if (n != nf) fail_input("{}: {} rows, expected {}", frames.where(name), n, nf);
    return v;
  };
  const auto time = col("time"), steps = col("steps"), dt_min = col("dt_min"), dt_max = col("dt_max");
  const auto fluid = col("fluid"), boundary = col("boundary"), removed = col("removed");
  const auto emax = col("density_error_max"), emean = col("density_error_mean");
  const auto ke = col("kinetic_energy"), pe = col("potential_energy"), wall = col("wall_time");
  // Columns added after the first files were written: zero when absent.
  auto optional_col = [&](const char* name) { return frames.has(name) ? col(name) : std::vector<double>(nf, 0.0); };
  const auto elastic = optional_col("elastic_energy"), speed = optional_col("speed_max");
  const auto emitted = optional_col("emitted_energy"), outflow = optional_col("outflow_energy");
  for (std::size_t i = 0; i < nf; ++i) {
    FrameStats s;
    s.frame = static_cast<std::int32_t>(frame[i]);
    s.time = time[i];
    s.steps = static_cast<std::int64_t>(steps[i]);
    s.dt_min = dt_min[i];
    s.dt_max = dt_max[i];
    s.fluid = static_cast<std::int64_t>(fluid[i]);
    s.boundary = static_cast<std::int64_t>(boundary[i]);
    s.removed = static_cast<std::int64_t>(removed[i]);
    s.density_error_max = emax[i];
    s.density_error_mean = emean[i];
    s.kinetic_energy = ke[i];
    s.potential_energy = pe[i];
    s.wall_time = wall[i];
    s.elastic_energy = elastic[i];
    s.speed_max = speed[i];
    s.emitted_energy = emitted[i];
    s.outflow_energy = outflow[i];
    run.frames.push_back(s);
  }

  if (root.is_group("parameters")) {
    const h5::Group parameters = root.open_group("parameters");
    for (const std::string& name : parameters.children()) {
      const auto v = parameters.read<double>(name);
      if (v.size() != 1) fail_input("{}: expected one value, found {}", parameters.where(name), v.size());
      run.parameters.emplace_back(name, v[0]);
    }
  }
  if (root.is_group("summary")) {  // older files have none
    const h5::Group summary = root.open_group("summary");
    for (const std::string& name : summary.children()) {
      const auto v = summary.read<double>(name);
      if (v.size() != 1) fail_input("{}: expected one value, found {}", summary.where(name), v.size());
      run.summary.emplace_back(name, v[0]);
    }
  }

  const h5::Group solids = root.open_group("solids");
  for (const std::string& name : solids.children()) {
    const h5::Group g = solids.open_group(name);
    SolidRecord s;
    s.name = g.attr_string("name");
    s.particles = g.attr_string("particles");
    s.kind = g.attr_string("kind");
    const auto t = g.attr_array<double>("translation");
    const auto q = g.attr_array<double>("rotation");
    if (t.size() != 3 || q.size() != 4) fail_input("{}: translation needs 3 values and rotation 4", g.where());
    s.translation = Vec3d(t[0], t[1], t[2]);
    s.rotation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    s.scale = g.attr<double>("scale");
    s.body = g.attr<std::int32_t>("body");
    run.solids.push_back(s);
  }

  const h5::Group bodies = root.open_group("bodies");
  std::size_t nb = 0, rows = 0;
  const auto solid = bodies.read_rows<std::int32_t>("solid", 0, &nb);
  const auto parent = bodies.read_rows<std::int32_t>("parent", 0, &rows);
  const auto mass = bodies.read_rows<double>("mass", 0, &rows);
  const auto created = bodies.read_rows<double>("created_time", 0, &rows);
  const auto voxels = bodies.read_rows<std::int32_t>("voxels", 0, &rows);
  const auto inertia = bodies.read_rows<double>("inertia", 9, &rows);
  const auto centers = bodies.read_rows<double>("reference_center", 3, &rows);
  const std::vector<std::string> names = nb ? split(bodies.attr_string("names"), '\n') : std::vector<std::string>{};
  if (parent.size() != nb || mass.size() != nb || created.size() != nb || voxels.size() != nb ||
      inertia.size() != 9 * nb || centers.size() != 3 * nb || names.size() != nb) {
    fail_input("{}: body arrays differ in length", bodies.where());
  }
  for (std::size_t i = 0; i < nb; ++i) {
    BodyRecord r;
    r.name = names[i];
    r.solid = solid[i];
    r.parent = parent[i];
    r.mass = mass[i];
    r.created_time = created[i];
    r.voxels = voxels[i];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) r.inertia(a, c) = inertia[9 * i + 3 * a + c];
    r.reference_center = Vec3d(centers[3 * i], centers[3 * i + 1], centers[3 * i + 2]);
    run.bodies.push_back(r);
  }

  const h5::Group fracture = root.open_group("fracture");
  std::size_t ne = 0;
  const auto time_e = fracture.read_rows<double>("time", 0, &ne);
  const auto parent_e = fracture.read_rows<std::int32_t>("parent", 0, &rows);
  const auto seed_offset = fracture.read_rows<std::int64_t>("seed_offset", 0, &rows);
  const auto seed_count = fracture.read_rows<std::int64_t>("seed_count", 0, &rows);
  const auto child_offset = fracture.read_rows<std::int64_t>("child_offset", 0, &rows);
  const auto child_count = fracture.read_rows<std::int64_t>("child_count", 0, &rows);
  std::size_t ns = 0, nc = 0;
  const auto seeds = fracture.read_rows<double>("seeds", 3, &ns);
  const auto child_body = fracture.read_rows<std::int32_t>("child_body", 0, &nc);
  const auto child_seed = fracture.read_rows<std::int32_t>("child_seed", 0, &rows);
  const auto child_component = fracture.read_rows<std::int32_t>("child_component", 0, &rows);
  if (child_seed.size() != nc || child_component.size() != nc) fail_input("{}: child arrays differ in length", fracture.where());
  for (std::size_t e = 0; e < ne; ++e) {
    FractureEvent ev;
    ev.time = time_e[e];
    ev.parent = parent_e[e];
    const auto s0 = seed_offset[e], sn = seed_count[e], c0 = child_offset[e], cn = child_count[e];
    if (s0 < 0 || sn < 0 || static_cast<std::size_t>(s0 + sn) > ns || c0 < 0 || cn < 0 ||
        static_cast<std::size_t>(c0 + cn) > nc) {
      fail_input("{}: event {} points outside the seed or child arrays", fracture.where(), e);
    }
    for (auto s = s0; s < s0 + sn; ++s) ev.seeds.emplace_back(seeds[3 * s], seeds[3 * s + 1], seeds[3 * s + 2]);
    for (auto c = c0; c < c0 + cn; ++c) {
      ev.child_body.push_back(child_body[c]);
      ev.child_seed.push_back(child_seed[c]);
      ev.child_component.push_back(child_component[c]);
    }
    run.fractures.push_back(std::move(ev));
  }
  if (root.is_group("sensors")) {
    const h5::Group sensors = root.open_group("sensors");
    SensorRecord& r = run.sensors;
    r.names = split(sensors.attr_string("names"), '\n');
    const std::size_t count = r.names.size();
    r.interval = sensors.attr<double>("interval");
    // want 0: any number of rows
    auto table = [&](const char* name, std::size_t want, std::size_t columns) {
      h5::Shape shape;
      auto v = sensors.read<double>(name, &shape);
      if (shape.size() != 2 || shape[1] != columns || (want > 0 && shape[0] != want))
        fail_input("{}: expected {} x {} values", sensors.where(name), want > 0 ? fmt::format("{}", want) : "N",
                   columns);
      return v;
    };
    r.at = io::unflatten_points(table("at", count, 3));
    r.normal = io::unflatten_points(table("normal", count, 3));
    r.radius = sensors.read<double>("radius");
    r.particles = sensors.read<std::int64_t>("particles");
    r.pressure = table("pressure", 0, count);
    if (r.radius.size() != count || r.particles.size() != count)
      fail_input("{}: {} sensors but {} radii and {} particle counts", sensors.where(), count, r.radius.size(),
                 r.particles.size());
  }
  if (root.is_group("loads")) {
    const h5::Group loads = root.open_group("loads");
    h5::Shape shape;
    const auto impulse = loads.read<double>("impulse", &shape);
    if (shape.size() != 3 || shape[0] != run.frames.size() || shape[1] != run.solids.size() || shape[2] != 3)
      fail_input("{}: expected frames x solids x 3 = {} x {} x 3", loads.where("impulse"), run.frames.size(),
                 run.solids.size());
    for (std::size_t f = 0; f < shape[0]; ++f) {
      std::vector<Vec3d> row;
      for (std::size_t k = 0; k < shape[1]; ++k) {
        const std::size_t at = 3 * (f * shape[1] + k);
        row.emplace_back(impulse[at], impulse[at + 1], impulse[at + 2]);
      }
      run.loads.push_back(std::move(row));
    }
  }
  return run;
}

std::vector<TriMesh> reference_meshes(const RunRecord& run, const std::string& run_path) {
  std::map<std::string, SampledSolid> files;
  std::vector<TriMesh> out;
  for (std::size_t s = 0; s < run.solids.size(); ++s) {
    const SolidRecord& r = run.solids[s];
    auto it = files.find(r.particles);
    if (it == files.end()) {
      try {
        it = files.emplace(r.particles, read_particles(r.particles)).first;
      } catch (const Error& e) {
        fail_input("{}: solid {} ('{}'): {}", run_path, s, r.name, e.what());
      }
    }
    TriMesh mesh;
    mesh.triangles = it->second.mesh.triangles;
    mesh.vertices.reserve(it->second.mesh.vertices.size());
    const Mat3d rot = r.rotation.normalized().toRotationMatrix();
    for (const Vec3d& v : it->second.mesh.vertices) mesh.vertices.push_back(r.translation + rot * (r.scale * v));
    out.push_back(std::move(mesh));
  }
  return out;
}

}  // namespace bw
