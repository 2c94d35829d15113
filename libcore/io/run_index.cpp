#include "io/run_index.h"

#include <algorithm>
#include <functional>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "io/fragments_file.h"
#include "io/frame_range.h"
#include "io/h5.h"
#include "io/particles_file.h"
#include "io/run_file.h"

namespace bw {
namespace fs = std::filesystem;

namespace {

constexpr const char* kMeshesKind = "meshes";
constexpr const char* kMeshesName = "meshes.h5";

// XML attribute text: file names may hold any character.
std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

struct Item {
  std::string dims;    // "N" or "N 3"
  std::string type;    // "Float" or "Int"
  int precision = 4;
  std::string where;   // "file:/path"
};

std::string item(const Item& d, const std::string& indent) {
  return fmt::format("{}<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}</DataItem>\n",
                     indent, d.dims, d.type, d.precision, escape(d.where));
}

std::string attribute(const std::string& name, const char* type, const char* center, const Item& d,
                      const std::string& indent) {
  return fmt::format("{}<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n{}{}</Attribute>\n", indent, name,
                     type, center, item(d, indent + "  "), indent);
}

// A vector field stored as three 1-D datasets, joined into one N x 3 array.
std::string joined_vector(const std::string& name, std::uint64_t n, const std::string& file,
                          const std::string& group, const char* const (&parts)[3], const std::string& indent) {
  std::string out = fmt::format("{}<Attribute Name=\"{}\" AttributeType=\"Vector\" Center=\"Node\">\n", indent, name);
  out += fmt::format("{}  <DataItem ItemType=\"Function\" Function=\"JOIN($0, $1, $2)\" Dimensions=\"{} 3\">\n",
                     indent, n);
  for (const char* part : parts) out += item({std::to_string(n), "Float", 4, file + ":" + group + "/" + part}, indent + "    ");
  out += indent + "  </DataItem>\n" + indent + "</Attribute>\n";
  return out;
}

// Particles as points: 1-D x, y, z datasets of one group.
std::string points_geometry(std::uint64_t n, const std::string& file, const std::string& group,
                            const std::string& indent) {
  std::string out = fmt::format("{}<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n",
                                indent, n);
  out += indent + "<Geometry GeometryType=\"X_Y_Z\">\n";
  for (const char* c : {"x", "y", "z"}) out += item({std::to_string(n), "Float", 4, file + ":" + group + "/" + c}, indent + "  ");
  out += indent + "</Geometry>\n";
  return out;
}

// A triangle mesh of a meshes-file group: vertices, triangles, one cell field.
std::string mesh_grid(std::uint64_t vertices, std::uint64_t triangles, const std::string& file,
                      const std::string& group, const std::string& cell_field, const std::string& in) {
  std::string out = fmt::format("{}<Topology TopologyType=\"Triangle\" NumberOfElements=\"{}\">\n", in, triangles);
  out += item({fmt::format("{} 3", triangles), "Int", 4, file + ":" + group + "/triangles"}, in + "  ");
  out += in + "</Topology>\n";
  out += in + "<Geometry GeometryType=\"XYZ\">\n";
  out += item({fmt::format("{} 3", vertices), "Float", 4, file + ":" + group + "/vertices"}, in + "  ");
  out += in + "</Geometry>\n";
  out += attribute(cell_field, "Scalar", "Cell", {std::to_string(triangles), "Int", 4, file + ":" + group + "/" + cell_field}, in);
  return out;
}

std::string frame_group(std::int32_t frame) { return fmt::format("/frames/{:06d}", frame); }

std::vector<float> to_float(const std::vector<Vec3d>& v) {
  std::vector<float> out;
  out.reserve(3 * v.size());
  for (const Vec3d& p : v)
    for (int k = 0; k < 3; ++k) out.push_back(static_cast<float>(p[k]));
  return out;
}

// Appends a mesh placed by `pose`, its triangles tagged with `tag`.
void append_mesh(const TriMesh& mesh, const Eigen::Affine3d& pose, std::int32_t tag, std::vector<Vec3d>& vertices,
                 std::vector<std::int32_t>& triangles, std::vector<std::int32_t>& tags) {
  const auto base = static_cast<std::int32_t>(vertices.size());
  for (const Vec3d& v : mesh.vertices) vertices.push_back(pose * v);
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) triangles.push_back(base + static_cast<std::int32_t>(t[k]));
    tags.push_back(tag);
  }
}

void write_mesh_group(h5::Group group, const std::vector<Vec3d>& vertices, const std::vector<std::int32_t>& triangles,
                      const std::vector<std::int32_t>& tags, const char* tag_name) {
  group.write<float>("vertices", to_float(vertices), {vertices.size(), 3});
  group.write<std::int32_t>("triangles", triangles, {tags.size(), 3});
  group.write<std::int32_t>(tag_name, tags);
}

}  // namespace

IndexFrame index_frame(const FrameData& frame, const std::string& file) {
  IndexFrame e;
  e.frame = frame.frame;
  e.time = frame.time;
  e.file = file;
  e.fluid = frame.fluid_count();
  e.boundary = frame.bx.size();
  e.bodies = frame.bodies.size();
  e.fields = frame.fields();
  return e;
}

IndexFrame index_frame(const FrameHeader& h, const std::string& file) {
  IndexFrame e;
  e.frame = h.frame;
  e.time = h.time;
  e.file = file;
  e.step = h.step;
  e.fluid = h.fluid;
  e.boundary = h.boundary;
  e.bodies = h.body_count;
  e.fields = h.fields;
  return e;
}

std::string run_index_path(const std::string& outdir) { return (fs::path(outdir) / "run.xdmf2").string(); }

RunIndex scan_run(const std::string& outdir) {
  const fs::path folder = fs::path(outdir) / "frames";
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) fail_input("{}: no frames folder (is {} a bw-sim output folder?)", folder.string(), outdir);
  RunIndex index;
  for (const auto& [number, path] : frame_files(folder.string()))
    index.frames.push_back(index_frame(read_frame_header(path), "frames/" + fs::path(path).filename().string()));
  if (index.frames.empty()) fail_input("{}: holds no frame files (NNNNNN.h5)", folder.string());
  return index;
}

std::string xdmf_text(const RunIndex& index) {
  // One temporal collection per part of the scene, so that each is one block of its
  // own name in ParaView, the same block in every time step.
  // A part without points in a frame (no fluid yet, no bodies) is an empty collection
  // there: XDMF readers refuse empty arrays, and a missing time would show another.
  struct Part {
    std::string grids;
    bool any = false;
  };
  Part fluid, boundary, bodies, solids, meshes;
  const std::string in = "        ";
  const IndexMeshes& m = index.meshes;
  for (const IndexFrame& f : index.frames) {
    const std::string& file = f.file;
    const std::string time = fmt::format("{}<Time Value=\"{:.17g}\"/>\n", in, f.time);
    const std::string head = fmt::format("      <Grid Name=\"frame {:06d}\" GridType=\"Uniform\">\n", f.frame) + time;
    const std::string empty =
        fmt::format("      <Grid Name=\"frame {:06d}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n",
                    f.frame) + time + "      </Grid>\n";
    auto add = [&](Part& part, bool has, const std::function<std::string()>& grid) {
      if (has) part.grids += head + grid() + "      </Grid>\n", part.any = true;
      else part.grids += empty;
    };
    add(fluid, f.fluid > 0, [&] {
      std::string g = points_geometry(f.fluid, file, f.step, in);
      if (f.fields.velocity) {
        static const char* const v[3] = {"vx", "vy", "vz"};
        g += joined_vector("velocity", f.fluid, file, f.step, v, in);
      }
      if (f.fields.density)
        g += attribute("density", "Scalar", "Node", {std::to_string(f.fluid), "Float", 4, file + ":" + f.step + "/rho"}, in);
      if (f.fields.pressure)
        g += attribute("pressure", "Scalar", "Node", {std::to_string(f.fluid), "Float", 4, file + ":" + f.step + "/p"}, in);
      if (f.fields.id)
        g += attribute("id", "Scalar", "Node", {std::to_string(f.fluid), "Int", 8, file + ":" + f.step + "/id"}, in);
      return g;
    });
    // The static solids' and the bodies' particles, with the pressure on their patches.
    add(boundary, f.boundary > 0, [&] {
      std::string g = points_geometry(f.boundary, file, f.step + "/boundary", in);
      if (f.fields.boundary_solid)
        g += attribute("solid", "Scalar", "Node",
                       {std::to_string(f.boundary), "Int", 4, file + ":" + f.step + "/boundary/solid"}, in);
      if (f.fields.wall_pressure)
        g += attribute("wall_pressure", "Scalar", "Node",
                       {std::to_string(f.boundary), "Float", 4, file + ":" + f.step + "/boundary/p"}, in);
      return g;
    });
    // The bodies' poses: one point per body at its centre of mass.
    add(bodies, f.bodies > 0, [&] {
      const std::string g = f.step + "/bodies";
      const std::string b = std::to_string(f.bodies);
      std::string out = fmt::format("{}<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n", in, b);
      out += in + "<Geometry GeometryType=\"XYZ\">\n";
      out += item({b + " 3", "Float", 8, file + ":" + g + "/position"}, in + "  ");
      out += in + "</Geometry>\n";
      out += attribute("body", "Scalar", "Node", {b, "Int", 4, file + ":" + g + "/id"}, in);
      out += attribute("orientation", "Matrix", "Node", {b + " 4", "Float", 8, file + ":" + g + "/orientation"}, in);
      out += attribute("linear_velocity", "Vector", "Node", {b + " 3", "Float", 8, file + ":" + g + "/linear_velocity"}, in);
      out += attribute("angular_velocity", "Vector", "Node", {b + " 3", "Float", 8, file + ":" + g + "/angular_velocity"}, in);
      return out;
    });
    // Meshes: the static solids, the same in every frame, and the bodies placed.
    if (!m.file.empty()) {
      add(solids, m.static_triangles > 0,
          [&] { return mesh_grid(m.static_vertices, m.static_triangles, m.file, "/static", "solid", in); });
      const auto it = m.frames.find(f.frame);
      const bool placed = it != m.frames.end() && it->second.second > 0;
      add(meshes, placed, [&] {
        return mesh_grid(it->second.first, it->second.second, m.file, frame_group(f.frame), "body", in);
      });
    }
  }
  std::string out =
      "<?xml version=\"1.0\" ?>\n"
      "<!-- breakwater run index (docs/formats.md, \"The run index\"): open in ParaView or VisIt -->\n"
      "<Xdmf Version=\"2.0\">\n"
      "  <Domain>\n";
  // The fluid always (an emitter's run starts without it); the other parts when some frame has them.
  fluid.any = true;
  for (const auto& [name, part] : {std::pair<const char*, const Part*>{"fluid", &fluid}, {"boundary", &boundary},
                                   {"bodies", &bodies}, {"solids", &solids}, {"body_meshes", &meshes}}) {
    if (!part->any) continue;
    out += fmt::format("    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name);
    out += part->grids;
    out += "    </Grid>\n";
  }
  out += "  </Domain>\n</Xdmf>\n";
  return out;
}

void write_run_index(const RunIndex& index, const std::string& path) {
  const std::string text = xdmf_text(index);
  write_file_atomically(path, text.data(), text.size());
}

namespace {

std::string outdir_of(const std::string& run_path) {
  return fs::path(run_path).parent_path().empty() ? "." : fs::path(run_path).parent_path().string();
}

}  // namespace

void check_fragments_beside_run(const std::string& run_path, const std::string& fragments_path) {
  if (fragments_path.empty() || fragments_path == "-") return;
  const std::string outdir = outdir_of(run_path);
  std::error_code ec;
  const fs::path fragments = fs::weakly_canonical(fragments_path, ec);
  for (const fs::path& written : {fs::path(outdir) / kMeshesName, fs::path(run_index_path(outdir))}) {
    if (!ec && fs::weakly_canonical(written, ec) == fragments)
      fail_input("{}: is where the index writes {}; give the fragments file another name", fragments_path,
                 written.filename().string());
  }
}

MeshesReport write_run_meshes(const std::string& run_path, const std::string& fragments_path) {
  if (run_path == "-") fail_input("-: the run file must be a file beside its frames folder, not standard input");
  check_fragments_beside_run(run_path, fragments_path);
  const std::string outdir = outdir_of(run_path);
  RunIndex index = scan_run(outdir);
  const RunRecord run = read_run(run_path);

  // Every solid's mesh in its reference configuration (x_ref = t + R (s x_mesh)).
  const std::vector<TriMesh> solid_mesh = reference_meshes(run, run_path);
  // Body -> its meshes: its fragment(s) when there are, else its own solid's mesh.
  std::map<std::int32_t, std::vector<const TriMesh*>> body_meshes;
  FragmentSet fragments;
  if (!fragments_path.empty()) {
    fragments = read_fragments(fragments_path);
    for (std::size_t f = 0; f < fragments.fragments.size(); ++f) {
      const std::int32_t b = fragments.fragments[f].body;
      if (b < 0) continue;  // a prefracture check's fragment belongs to no body of a run
      if (static_cast<std::size_t>(b) >= run.bodies.size())
        fail_input("{}: fragment {} belongs to body {}, but {} has {} bodies", fragments_path, f, b, run_path,
                   run.bodies.size());
      body_meshes[b].push_back(&fragments.fragments[f].mesh);
    }
  }
  for (std::size_t s = 0; s < run.solids.size(); ++s) {
    const std::int32_t b = run.solids[s].body;
    if (b < 0) continue;
    if (static_cast<std::size_t>(b) >= run.bodies.size())
      fail_input("{}: solid {} ('{}') names body {}, the run has {} bodies", run_path, s, run.solids[s].name, b,
                 run.bodies.size());
    if (!body_meshes.count(b)) body_meshes[b].push_back(&solid_mesh[s]);
  }

  MeshesReport report;
  report.path = (fs::path(outdir) / kMeshesName).string();
  h5::File file = h5::File::create(report.path, kMeshesKind);
  h5::Group& root = file.root();
  root.set_attr("source", run_path);
  root.set_attr("fragments", fragments_path);
  index.meshes.file = kMeshesName;
  {
    std::vector<Vec3d> v;
    std::vector<std::int32_t> t, tag;
    for (std::size_t s = 0; s < run.solids.size(); ++s)
      if (run.solids[s].body < 0)
        append_mesh(solid_mesh[s], Eigen::Affine3d::Identity(), static_cast<std::int32_t>(s), v, t, tag);
    write_mesh_group(root.create_group("static"), v, t, tag, "solid");
    index.meshes.static_vertices = v.size();
    index.meshes.static_triangles = tag.size();
    report.static_triangles = tag.size();
  }
  h5::Group frames = root.create_group("frames");
  for (const IndexFrame& f : index.frames) {
    const FrameHeader h = read_frame_header((fs::path(outdir) / f.file).string(), true);
    std::vector<Vec3d> v;
    std::vector<std::int32_t> t, tag;
    std::size_t without_mesh = 0;
    for (std::size_t i = 0; i < h.bodies.size(); ++i) {
      const std::int32_t b = h.bodies.id[i];
      const auto it = body_meshes.find(b);
      if (b < 0 || static_cast<std::size_t>(b) >= run.bodies.size() || it == body_meshes.end()) {
        ++without_mesh;
        continue;
      }
      // x_world = R(orientation) (x_ref - c_ref) + position (docs/formats.md, "Body poses").
      const Eigen::Affine3d pose = Eigen::Translation3d(h.bodies.position[i]) *
                                   Eigen::Affine3d(h.bodies.orientation[i].normalized().toRotationMatrix()) *
                                   Eigen::Translation3d(-run.bodies[b].reference_center);
      for (const TriMesh* mesh : it->second) append_mesh(*mesh, pose, b, v, t, tag);
    }
    h5::Group g = frames.create_group(fmt::format("{:06d}", f.frame));
    g.set_attr("frame", f.frame);
    g.set_attr("time", f.time);
    write_mesh_group(g, v, t, tag, "body");
    index.meshes.frames[f.frame] = {v.size(), tag.size()};
    report.body_triangles = std::max(report.body_triangles, tag.size());
    report.bodies_without_mesh = std::max(report.bodies_without_mesh, without_mesh);
  }
  report.frames = index.frames.size();
  file.commit();
  write_run_index(index, run_index_path(outdir));
  return report;
}

}  // namespace bw
