#include "io/fragments_file.h"

#include "common/error.h"
#include "io/arrays.h"
#include "io/h5.h"

namespace bw {
namespace {

constexpr const char* kKind = "fragments";

}  // namespace

void write_fragments(const FragmentSet& set, const std::string& path) {
  std::vector<double> vertices;
  std::vector<std::int32_t> triangles;
  std::vector<std::int64_t> vertex_offset{0}, triangle_offset{0};
  std::vector<std::int32_t> seed, component, body;
  std::vector<double> volume;
  for (const Fragment& f : set.fragments) {
    for (const Vec3d& v : f.mesh.vertices) vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
    for (const Triangle& t : f.mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
    vertex_offset.push_back(vertex_offset.back() + static_cast<std::int64_t>(f.mesh.vertices.size()));
    triangle_offset.push_back(triangle_offset.back() + static_cast<std::int64_t>(f.mesh.triangles.size()));
    seed.push_back(f.seed);
    component.push_back(f.component);
    body.push_back(f.body);
    volume.push_back(f.volume);
  }

  h5::File file = h5::File::create(path, kKind);
  h5::Group& root = file.root();
  root.set_attr("source", set.source);
  if (!set.tool.empty()) root.set_attr("tool", set.tool);
  if (!set.options.empty()) root.set_attr("options", set.options);
  root.write<double>("vertices", vertices, {vertices.size() / 3, 3});
  root.write<std::int32_t>("triangles", triangles, {triangles.size() / 3, 3});
  root.write<double>("seeds", io::flatten(set.seeds), {set.seeds.size(), 3});
  h5::Group fragment = root.create_group("fragment");
  fragment.write("vertex_offset", vertex_offset);
  fragment.write("triangle_offset", triangle_offset);
  fragment.write("seed", seed);
  fragment.write("component", component);
  fragment.write("volume", volume);
  fragment.write("body", body);
  file.commit();
}

FragmentSet read_fragments(const std::string& path) {
  h5::File file = h5::File::open(path, kKind);
  const h5::Group& root = file.root();
  FragmentSet set;
  set.source = root.has_attr("source") ? root.attr_string("source") : "";
  set.tool = root.has_attr("tool") ? root.attr_string("tool") : "";
  set.options = root.has_attr("options") ? root.attr_string("options") : "";
  std::size_t nv = 0, nt = 0, ns = 0, n = 0, rows = 0;
  const auto vertices = root.read_rows<double>("vertices", 3, &nv);
  const auto triangles = root.read_rows<std::int32_t>("triangles", 3, &nt);
  const auto seeds = root.read_rows<double>("seeds", 3, &ns);
  set.seeds = io::unflatten_points(seeds);
  const h5::Group g = root.open_group("fragment");
  const auto vertex_offset = g.read_rows<std::int64_t>("vertex_offset", 0, &rows);
  const auto triangle_offset = g.read_rows<std::int64_t>("triangle_offset", 0, &rows);
  const auto seed = g.read_rows<std::int32_t>("seed", 0, &n);
  const auto component = g.read_rows<std::int32_t>("component", 0, &rows);
  const auto volume = g.read_rows<double>("volume", 0, &rows);
  const auto body = g.read_rows<std::int32_t>("body", 0, &rows);
  if (vertex_offset.size() != n + 1 || triangle_offset.size() != n + 1 || component.size() != n ||
      volume.size() != n || body.size() != n) {
    fail_input("{}: per-fragment arrays differ in length", g.where());
  }
  if (vertex_offset.front() != 0 || triangle_offset.front() != 0 ||
      static_cast<std::size_t>(vertex_offset.back()) != nv || static_cast<std::size_t>(triangle_offset.back()) != nt) {
    fail_input("{}: offsets do not cover the vertex and triangle arrays", g.where());
  }
  for (std::size_t f = 0; f < n; ++f) {
    Fragment frag;
    const auto v0 = vertex_offset[f], v1 = vertex_offset[f + 1], t0 = triangle_offset[f], t1 = triangle_offset[f + 1];
    if (v1 < v0 || t1 < t0) fail_input("{}: offsets of fragment {} decrease", g.where(), f);
    for (auto v = v0; v < v1; ++v) frag.mesh.vertices.emplace_back(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
    const auto count = static_cast<std::int32_t>(v1 - v0);
    for (auto t = t0; t < t1; ++t) {
      Triangle tri{triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
      for (auto i : tri)
        if (i < 0 || i >= count) fail_input("{}: fragment {} has a triangle index {} outside its {} vertices", root.where("triangles"), f, i, count);
      frag.mesh.triangles.push_back(tri);
    }
    frag.seed = seed[f];
    frag.component = component[f];
    frag.volume = volume[f];
    frag.body = body[f];
    set.fragments.push_back(std::move(frag));
  }
  return set;
}

}  // namespace bw
