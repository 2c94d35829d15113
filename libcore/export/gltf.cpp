#include "export/gltf.h"

#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "common/error.h"
#include "common/text.h"
#include "io/particles_file.h"

namespace bw::exporter {
namespace {

// The renderer's colours (libcore/render/solids.h), so exports look like the frames.
constexpr double kStaticColor[3] = {0.6, 0.6, 0.6};
constexpr double kBodyColor[3] = {0.6, 0.4, 0.3};

// glTF's component and target codes.
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

std::string number(double v) { return fmt::format("{}", v); }

// The binary chunk and the accessors, buffer views that describe it.
class Buffer {
 public:
  std::vector<std::uint8_t> bytes;
  std::vector<std::string> views, accessors;

  // Appends floats as an accessor of `type` ("SCALAR", "VEC3", ...) with
  // `components` per element; `bounds` adds min and max (required for positions and
  // animation inputs).
  int add_floats(const std::vector<float>& values, const char* type, int components, bool bounds, int target = 0) {
    const std::size_t count = values.size() / static_cast<std::size_t>(components);
    std::string extra;
    if (bounds) {
      std::vector<float> lo(components, INFINITY), hi(components, -INFINITY);
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::size_t c = i % static_cast<std::size_t>(components);
        lo[c] = std::min(lo[c], values[i]);
        hi[c] = std::max(hi[c], values[i]);
      }
      extra = fmt::format(",\"min\":[{}],\"max\":[{}]", join(lo), join(hi));
    }
    const int view = add_view(values.data(), values.size() * sizeof(float), target);
    accessors.push_back(fmt::format("{{\"bufferView\":{},\"componentType\":{},\"count\":{},\"type\":\"{}\"{}}}", view,
                                    kFloat, count, type, extra));
    return static_cast<int>(accessors.size()) - 1;
  }

  int add_indices(const std::vector<std::uint32_t>& values) {
    const int view = add_view(values.data(), values.size() * sizeof(std::uint32_t), kElementArrayBuffer);
    accessors.push_back(fmt::format("{{\"bufferView\":{},\"componentType\":{},\"count\":{},\"type\":\"SCALAR\"}}",
                                    view, kUnsignedInt, values.size()));
    return static_cast<int>(accessors.size()) - 1;
  }

 private:
  static std::string join(const std::vector<float>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) s += ',';
      s += number(v[i]);
    }
    return s;
  }
  int add_view(const void* data, std::size_t size, int target) {
    const std::size_t offset = bytes.size();
    bytes.resize(offset + size);
    std::memcpy(bytes.data() + offset, data, size);
    while (bytes.size() % 4) bytes.push_back(0);  // every view 4-byte aligned
    views.push_back(fmt::format("{{\"buffer\":0,\"byteOffset\":{},\"byteLength\":{}{}}}", offset, size,
                                target ? fmt::format(",\"target\":{}", target) : std::string()));
    return static_cast<int>(views.size()) - 1;
  }
};

struct Pose {
  Vec3d position = Vec3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

void append_mesh(TriMesh& to, const TriMesh& from) {
  const auto base = static_cast<std::int32_t>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (const Triangle& t : from.triangles) to.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

}  // namespace

Vec3d to_gltf(const Vec3d& p) { return Vec3d(p.x(), p.z(), -p.y()); }

std::array<double, 4> to_gltf(const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond n = q.normalized();
  const Vec3d v = to_gltf(Vec3d(n.x(), n.y(), n.z()));
  return {v.x(), v.y(), v.z(), n.w()};
}

std::array<double, 4> gltf_camera_rotation(const render::Camera& camera) {
  const Vec3d forward = (camera.target - camera.position).normalized();
  const Vec3d right = forward.cross(camera.up).normalized();
  const Vec3d up = right.cross(forward);
  Mat3d axes;
  axes.col(0) = to_gltf(right);
  axes.col(1) = to_gltf(up);
  axes.col(2) = -to_gltf(forward);
  const Eigen::Quaterniond q(axes);
  return {q.x(), q.y(), q.z(), q.w()};
}

SolidSet SolidSet::load(const std::string& run_path, const std::string& fragments_path) {
  SolidSet set;
  set.run_path = run_path;
  set.run = read_run(run_path);
  std::vector<TriMesh> meshes = reference_meshes(set.run, run_path);
  for (std::size_t s = 0; s < set.run.solids.size(); ++s) {
    const SolidRecord& r = set.run.solids[s];
    if (r.body >= static_cast<std::int32_t>(set.run.bodies.size()))
      fail_input("{}: solid {} ('{}') names body {}, the run has {} bodies", run_path, s, r.name, r.body,
                 set.run.bodies.size());
    set.solid_meshes.push_back(std::move(meshes[s]));
  }
  if (!fragments_path.empty()) {
    set.fragments = read_fragments(fragments_path);
    for (std::size_t f = 0; f < set.fragments.fragments.size(); ++f) {
      const std::int32_t b = set.fragments.fragments[f].body;
      if (b < 0)
        fail_input("{}: fragment {} belongs to no body: a prefracture check, not a replay of {} (bw-voronoi replay)",
                   fragments_path, f, run_path);
      if (static_cast<std::size_t>(b) >= set.run.bodies.size())
        fail_input("{}: fragment {} belongs to body {}, but {} has {} bodies", fragments_path, f, b, run_path,
                   set.run.bodies.size());
    }
  }
  return set;
}

std::vector<std::uint8_t> build_glb(const SolidSet& solids, const std::vector<PoseFrame>& frames,
                                    const std::string& source, GltfStats* stats_out, const GltfCamera* camera) {
  GltfStats stats;
  Buffer buffer;
  std::vector<std::string> meshes, nodes, channels, samplers;
  const RunRecord& run = solids.run;
  const std::size_t bodies = run.bodies.size();

  // Each body's mesh in its reference configuration: its solid's, or the fragments'.
  std::vector<TriMesh> body_mesh(bodies);
  std::vector<bool> has_fragments(bodies, false);
  for (const Fragment& f : solids.fragments.fragments) {
    append_mesh(body_mesh[static_cast<std::size_t>(f.body)], f.mesh);
    has_fragments[static_cast<std::size_t>(f.body)] = true;
  }
  for (std::size_t s = 0; s < run.solids.size(); ++s) {
    const std::int32_t b = run.solids[s].body;
    if (b >= 0 && !has_fragments[static_cast<std::size_t>(b)]) append_mesh(body_mesh[static_cast<std::size_t>(b)], solids.solid_meshes[s]);
  }

  // Poses per body and frame; nullopt where the frame has no row for it.
  std::vector<std::vector<std::optional<Pose>>> poses(bodies, std::vector<std::optional<Pose>>(frames.size()));
  bool any_rows = false;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const BodyStates& b = frames[k].bodies;
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (b.id[i] < 0 || static_cast<std::size_t>(b.id[i]) >= bodies) continue;
      poses[static_cast<std::size_t>(b.id[i])][k] = Pose{b.position[i], b.orientation[i].normalized()};
      any_rows = true;
    }
  }

  auto add_mesh = [&](const TriMesh& mesh, const Vec3d& center, int material) {
    std::vector<float> positions;
    positions.reserve(3 * mesh.vertices.size());
    for (const Vec3d& v : mesh.vertices) {
      const Vec3d g = to_gltf(v - center);
      for (int c = 0; c < 3; ++c) positions.push_back(static_cast<float>(g[c]));
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(3 * mesh.triangles.size());
    for (const Triangle& t : mesh.triangles)
      for (int c = 0; c < 3; ++c) indices.push_back(static_cast<std::uint32_t>(t[c]));
    stats.triangles += mesh.triangles.size();
    const int pos = buffer.add_floats(positions, "VEC3", 3, true, kArrayBuffer);
    const int idx = buffer.add_indices(indices);
    meshes.push_back(fmt::format(
        "{{\"primitives\":[{{\"attributes\":{{\"POSITION\":{}}},\"indices\":{},\"material\":{},\"mode\":4}}]}}", pos,
        idx, material));
    return static_cast<int>(meshes.size()) - 1;
  };

  // Static solids: in place, no animation.
  for (std::size_t s = 0; s < run.solids.size(); ++s) {
    if (run.solids[s].body >= 0 || solids.solid_meshes[s].triangles.empty()) continue;
    const int mesh = add_mesh(solids.solid_meshes[s], Vec3d::Zero(), 0);
    nodes.push_back(fmt::format("{{\"name\":{},\"mesh\":{},\"extras\":{{\"solid\":{},\"kind\":\"static\"}}}}",
                                json_quote(run.solids[s].name), mesh, s));
    ++stats.static_nodes;
  }

  int times = -1;
  if (!frames.empty()) {
    std::vector<float> t;
    for (const PoseFrame& f : frames) t.push_back(static_cast<float>(f.time));
    times = buffer.add_floats(t, "SCALAR", 1, true);
  }
  // One animation channel of a node: values at the frames' times.
  auto add_channel = [&](int node, const std::vector<float>& values, const char* type, int components,
                         const char* path, const char* interpolation) {
    const int output = buffer.add_floats(values, type, components, false);
    samplers.push_back(
        fmt::format("{{\"input\":{},\"output\":{},\"interpolation\":\"{}\"}}", times, output, interpolation));
    channels.push_back(fmt::format("{{\"sampler\":{},\"target\":{{\"node\":{},\"path\":\"{}\"}}}}",
                                   samplers.size() - 1, node, path));
  };
  for (std::size_t b = 0; b < bodies; ++b) {
    const BodyRecord& body = run.bodies[b];
    const auto& p = poses[b];
    std::optional<std::size_t> first_seen;
    for (std::size_t k = 0; k < p.size() && !first_seen; ++k)
      if (p[k]) first_seen = k;
    // A solid's own body in frames without any body rows stands where it started.
    const bool at_rest = !any_rows && body.parent < 0;
    if (!first_seen && !at_rest) continue;
    if (body_mesh[b].triangles.empty()) {
      ++stats.bodies_without_mesh;
      continue;
    }
    const int mesh = add_mesh(body_mesh[b], body.reference_center, 1);
    const std::string extras =
        fmt::format("\"extras\":{{\"body\":{},\"parent\":{},\"created_time\":{},\"kind\":\"body\"}}", b, body.parent,
                    number(body.created_time));
    if (at_rest || times < 0) {
      const Vec3d c = to_gltf(body.reference_center);
      nodes.push_back(fmt::format("{{\"name\":{},\"mesh\":{},\"translation\":[{},{},{}],{}}}", json_quote(body.name),
                                  mesh, number(c.x()), number(c.y()), number(c.z()), extras));
      ++stats.body_nodes;
      continue;
    }
    // Absent frames hold the nearest pose: the last one seen, or the first to come.
    std::vector<float> translation, rotation, scale;
    Pose held = *p[*first_seen];
    Eigen::Quaterniond previous = held.orientation;
    bool visible_changes = false;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (p[k]) held = *p[k];
      Eigen::Quaterniond q = held.orientation;
      // Neighbouring keys in the same hemisphere, so that interpolation takes the
      // short way round.
      if (q.coeffs().dot(previous.coeffs()) < 0) q.coeffs() *= -1;
      previous = q;
      const Vec3d t = to_gltf(held.position);
      const auto r = to_gltf(q);
      for (int c = 0; c < 3; ++c) translation.push_back(static_cast<float>(t[c]));
      for (int c = 0; c < 4; ++c) rotation.push_back(static_cast<float>(r[static_cast<std::size_t>(c)]));
      const float s = p[k] ? 1.0f : 0.0f;
      for (int c = 0; c < 3; ++c) scale.push_back(s);
      if (!p[k]) visible_changes = true;
    }
    const auto node = static_cast<int>(nodes.size());
    add_channel(node, translation, "VEC3", 3, "translation", "LINEAR");
    add_channel(node, rotation, "VEC4", 4, "rotation", "LINEAR");
    if (visible_changes) add_channel(node, scale, "VEC3", 3, "scale", "STEP");
    stats.keyframes += frames.size();
    // The node's own transform is its first frame's, for viewers that show no animation.
    const Vec3d t0 = to_gltf(p[*first_seen]->position);
    const auto r0 = to_gltf(p[*first_seen]->orientation);
    const std::string s0 = p.front() ? "" : ",\"scale\":[0,0,0]";
    nodes.push_back(fmt::format("{{\"name\":{},\"mesh\":{},\"translation\":[{},{},{}],\"rotation\":[{},{},{},{}]{},{}}}",
                                json_quote(body.name), mesh, number(t0.x()), number(t0.y()), number(t0.z()),
                                number(r0[0]), number(r0[1]), number(r0[2]), number(r0[3]), s0, extras));
    ++stats.body_nodes;
  }

  std::string cameras;
  if (camera) {
    // At each frame's time, as bw-render draws it; one key when it does not move.
    std::vector<render::Camera> keys;
    if (frames.empty() || (!camera->path.animated() && camera->track.id < 0)) {
      keys.push_back(camera->path.at(frames.empty() ? 0 : frames.front().time));
    } else {
      for (const PoseFrame& f : frames)
        keys.push_back(render::frame_camera(camera->path, camera->track, f.time, f.bodies, fmt::format("frame {}", f.number)));
    }
    // Clip planes that hold the solids and the targets from every key.
    Aabb box;
    for (const TriMesh& m : solids.solid_meshes)
      for (const Vec3d& v : m.vertices) box.add(v);
    for (const render::Camera& c : keys) box.add(c.target);
    double farthest = 0;
    for (const render::Camera& c : keys)
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3d p((corner & 1 ? box.max : box.min).x(), (corner & 2 ? box.max : box.min).y(),
                      (corner & 4 ? box.max : box.min).z());
        farthest = std::max(farthest, (p - c.position).norm());
      }
    const double zfar = 2 * std::max(farthest, 1e-3), znear = zfar * 1e-4;
    stats.camera = true;
    stats.camera_first = keys.front();
    stats.fov_first = stats.fov_least = stats.fov_most = keys.front().fov_degrees;
    for (const render::Camera& c : keys) {
      stats.fov_least = std::min(stats.fov_least, c.fov_degrees);
      stats.fov_most = std::max(stats.fov_most, c.fov_degrees);
    }
    cameras = fmt::format(
        "\"cameras\":[{{\"name\":\"camera\",\"type\":\"perspective\",\"perspective\":{{\"yfov\":{},\"aspectRatio\":{},"
        "\"znear\":{},\"zfar\":{}}}}}],",
        number(keys.front().fov_degrees * M_PI / 180), number(camera->aspect), number(znear), number(zfar));
    const auto node = static_cast<int>(nodes.size());
    if (keys.size() > 1) {
      std::vector<float> translation, rotation;
      std::array<double, 4> previous = gltf_camera_rotation(keys.front());
      for (const render::Camera& c : keys) {
        const Vec3d t = to_gltf(c.position);
        std::array<double, 4> r = gltf_camera_rotation(c);
        // Neighbouring keys in the same hemisphere: interpolation takes the short way.
        if (r[0] * previous[0] + r[1] * previous[1] + r[2] * previous[2] + r[3] * previous[3] < 0)
          for (double& v : r) v = -v;
        previous = r;
        for (int k = 0; k < 3; ++k) translation.push_back(static_cast<float>(t[k]));
        for (double v : r) rotation.push_back(static_cast<float>(v));
      }
      add_channel(node, translation, "VEC3", 3, "translation", "LINEAR");
      add_channel(node, rotation, "VEC4", 4, "rotation", "LINEAR");
      stats.keyframes += keys.size();
    }
    const Vec3d t0 = to_gltf(keys.front().position);
    const auto r0 = gltf_camera_rotation(keys.front());
    nodes.push_back(fmt::format(
        "{{\"name\":\"camera\",\"camera\":0,\"translation\":[{},{},{}],\"rotation\":[{},{},{},{}],"
        "\"extras\":{{\"kind\":\"camera\",\"fov_degrees\":{}}}}}",
        number(t0.x()), number(t0.y()), number(t0.z()), number(r0[0]), number(r0[1]), number(r0[2]), number(r0[3]),
        number(keys.front().fov_degrees)));
  }

  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) s += ',';
      s += v[i];
    }
    return s;
  };
  std::string scene_nodes;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (n) scene_nodes += ',';
    scene_nodes += std::to_string(n);
  }
  auto material = [](const char* name, const double* c) {
    return fmt::format(
        "{{\"name\":\"{}\",\"pbrMetallicRoughness\":{{\"baseColorFactor\":[{},{},{},1],\"metallicFactor\":0,"
        "\"roughnessFactor\":0.8}}}}",
        name, c[0], c[1], c[2]);
  };
  const std::string range =
      frames.empty() ? std::string("null") : fmt::format("[{},{}]", frames.front().number, frames.back().number);
  std::string json = fmt::format(
      "{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"breakwater bw-export\",\"extras\":{{\"source\":{},"
      "\"up\":\"breakwater z is glTF y; breakwater (x, y, z) is glTF (x, z, -y)\",\"frames\":{}}}}},"
      "\"scene\":0,\"scenes\":[{{\"name\":\"breakwater\",\"nodes\":[{}]}}],\"nodes\":[{}],",
      json_quote(source), range, scene_nodes, join(nodes));
  json += cameras;
  if (!meshes.empty()) {
    json += fmt::format("\"meshes\":[{}],\"materials\":[{},{}],", join(meshes), material("static", kStaticColor),
                        material("body", kBodyColor));
  }
  if (!channels.empty())
    json += fmt::format("\"animations\":[{{\"name\":\"run\",\"channels\":[{}],\"samplers\":[{}]}}],", join(channels),
                        join(samplers));
  if (!buffer.bytes.empty()) {
    json += fmt::format("\"accessors\":[{}],\"bufferViews\":[{}],\"buffers\":[{{\"byteLength\":{}}}],",
                        join(buffer.accessors), join(buffer.views), buffer.bytes.size());
  }
  json.back() = '}';
  while (json.size() % 4) json += ' ';

  // GLB: a 12-byte header, the JSON chunk, the binary chunk (docs: glTF 2.0, 4.4).
  std::vector<std::uint8_t> glb;
  auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) glb.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  };
  const std::size_t total = 12 + 8 + json.size() + (buffer.bytes.empty() ? 0 : 8 + buffer.bytes.size());
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(static_cast<std::uint32_t>(total));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);  // "JSON"
  glb.insert(glb.end(), json.begin(), json.end());
  if (!buffer.bytes.empty()) {
    u32(static_cast<std::uint32_t>(buffer.bytes.size()));
    u32(0x004E4942);  // "BIN"
    glb.insert(glb.end(), buffer.bytes.begin(), buffer.bytes.end());
  }
  stats.bytes = glb.size();
  if (stats_out) *stats_out = stats;
  return glb;
}

}  // namespace bw::exporter
