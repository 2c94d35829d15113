#include "io/describe.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "common/text.h"
#include "io/h5.h"

namespace bw {
namespace {

void add_attributes(const h5::Group& group, Report& out) {
  for (const std::string& name : group.attr_names()) {
    const h5::AttrInfo info = group.attr_info(name);
    switch (info.cls) {
      case h5::AttrInfo::Class::string: out.set(name, group.attr_string(name)); break;
      case h5::AttrInfo::Class::integer:
        if (info.count == 1) out.set(name, group.attr<std::int64_t>(name));
        else {
          const auto v = group.attr_array<std::int64_t>(name);
          out.set(name, Report::Numbers(v.begin(), v.end()));
        }
        break;
      case h5::AttrInfo::Class::floating:
        if (info.count == 1) out.set(name, group.attr<double>(name));
        else out.set(name, group.attr_array<double>(name));
        break;
      default: out.set(name, "(unsupported type)");
    }
  }
}

std::string shape_text(const h5::Shape& shape) {
  std::string text;
  for (std::size_t i = 0; i < shape.size(); ++i) text += (i ? " x " : "") + std::to_string(shape[i]);
  return text.empty() ? "scalar" : text;
}

void list_datasets(const h5::Group& group, const std::string& prefix, Report& out) {
  for (const std::string& name : group.children()) {
    const h5::ObjectInfo info = group.info(name);
    if (info.is_group) list_datasets(group.open_group(name), prefix + name + "/", out);
    else out.set(prefix + name, shape_text(info.shape) + " " + info.type);
  }
}

// min and max over the rows of an N x 3 array.
void add_bounds(const std::vector<double>& xyz, Report& out) {
  if (xyz.empty()) return;
  double lo[3], hi[3];
  std::fill(lo, lo + 3, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + 3, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], xyz[i + k]);
      hi[k] = std::max(hi[k], xyz[i + k]);
    }
  Report& b = out.child("bounds");
  b.set("min", Report::Numbers(lo, lo + 3));
  b.set("max", Report::Numbers(hi, hi + 3));
}

void describe_particles(const h5::Group& root, Report& out) {
  std::size_t surface = 0;
  const auto positions = root.open_group("surface").read_rows<double>("position", 3, &surface);
  out.set("surface_particles", static_cast<std::int64_t>(surface));
  if (root.is_group("voxels")) {
    out.set("voxels", static_cast<std::int64_t>(root.open_group("voxels").shape("cell")[0]));
    if (root.open_group("voxels").has_attr("volume")) out.set("voxel_volume", root.open_group("voxels").attr<double>("volume"));
  } else {
    out.set("voxels", "not sampled (bw-sample --volume)");
  }
  if (root.is_group("mesh")) {
    const h5::Group mesh = root.open_group("mesh");
    out.set("mesh_vertices", static_cast<std::int64_t>(mesh.shape("vertices")[0]));
    out.set("mesh_triangles", static_cast<std::int64_t>(mesh.shape("triangles")[0]));
  }
  add_bounds(positions, out);
}

// H5Part: groups Step#N with 1-D datasets x, y, z (and optional fields); a frame file
// has one, Step#0 (Step#F, F the frame, in files of earlier versions).
void describe_steps(const h5::Group& root, Report& out) {
  for (const std::string& name : root.children()) {
    if (name.rfind("Step#", 0) != 0 || !root.is_group(name)) continue;
    const h5::Group step = root.open_group(name);
    Report& s = out.append("steps");
    s.set("name", name);
    if (step.has_attr("time")) s.set("time", step.attr<double>("time"));
    if (step.has("x") && step.has("y") && step.has("z")) {
      const auto x = step.read<double>("x"), y = step.read<double>("y"), z = step.read<double>("z");
      s.set("particles", static_cast<std::int64_t>(x.size()));
      std::vector<double> xyz(3 * x.size());
      for (std::size_t i = 0; i < x.size() && i < y.size() && i < z.size(); ++i) {
        xyz[3 * i] = x[i];
        xyz[3 * i + 1] = y[i];
        xyz[3 * i + 2] = z[i];
      }
      add_bounds(xyz, s);
    }
    const auto datasets_of = [](const h5::Group& g) {
      std::string list;
      for (const std::string& child : g.children())
        if (!g.is_group(child)) list += (list.empty() ? "" : " ") + child;
      return list;
    };
    s.set("fields", datasets_of(step));
    // Groups of their own particles (boundary, bodies): how many and what they hold.
    for (const std::string& child : step.children()) {
      if (step.is_group(child)) {
        const h5::Group sub = step.open_group(child);
        const auto children = sub.children();
        if (!children.empty() && !sub.is_group(children.front())) {
          s.set(child + "_count", static_cast<std::int64_t>(sub.shape(children.front()).empty() ? 0 : sub.shape(children.front())[0]));
          s.set(child + "_fields", datasets_of(sub));
        }
      }
    }
  }
}

void describe_fragments(const h5::Group& root, Report& out) {
  const h5::Group g = root.open_group("fragment");
  const auto volume = g.read<double>("volume");
  const auto body = g.read<std::int32_t>("body");
  out.set("fragments", static_cast<std::int64_t>(volume.size()));
  out.set("seeds", static_cast<std::int64_t>(root.shape("seeds").empty() ? 0 : root.shape("seeds")[0]));
  out.set("triangles", static_cast<std::int64_t>(root.shape("triangles")[0]));
  double total = 0, smallest = volume.empty() ? 0 : volume[0], largest = smallest;
  for (double v : volume) {
    total += v;
    smallest = std::min(smallest, v);
    largest = std::max(largest, v);
  }
  out.set("total_volume", total);
  out.set("smallest_volume", smallest);
  out.set("largest_volume", largest);
  std::int64_t matched = 0;
  for (auto b : body) matched += b >= 0;
  out.set("fragments_with_body", matched);
  std::size_t rows = 0;
  add_bounds(root.read_rows<double>("vertices", 3, &rows), out);
}

// Placed meshes for the run index: counts, not the triangles.
void describe_meshes(const h5::Group& root, Report& out) {
  auto rows = [](const h5::Group& g, const char* name) -> std::int64_t {
    const h5::Shape shape = g.shape(name);
    return shape.empty() ? 0 : static_cast<std::int64_t>(shape[0]);
  };
  if (root.is_group("static")) out.set("static_triangles", rows(root.open_group("static"), "triangles"));
  std::int64_t frames = 0, most = 0;
  if (root.is_group("frames")) {
    const h5::Group g = root.open_group("frames");
    for (const std::string& name : g.children()) {
      ++frames;
      most = std::max(most, rows(g.open_group(name), "triangles"));
    }
  }
  out.set("frames", frames);
  out.set("body_triangles_max", most);
}

// A group of 1-D datasets of equal length is shown as a table, one row per element.
bool describe_table(const h5::Group& group, const std::string& key, Report& out) {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> data;
  std::size_t rows = 0;
  for (const std::string& name : group.children()) {
    if (group.is_group(name)) continue;
    const h5::Shape shape = group.shape(name);
    if (shape.size() != 1) continue;
    if (!columns.empty() && shape[0] != rows) return false;
    rows = shape[0];
    columns.push_back(name);
    data.push_back(group.read<double>(name));
  }
  if (columns.empty()) return false;
  Report::Table table;
  table.columns = columns;
  table.rows.resize(rows);
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < columns.size(); ++c) table.rows[r].push_back(data[c][r]);
  out.set(key, std::move(table));
  // Rows with names (bodies, sensors) keep them in an attribute, one a line: listed
  // in order, the first kListedNames.
  if (group.has_attr("names")) {
    constexpr std::size_t kListedNames = 64;
    const std::vector<std::string> names = split(group.attr_string("names"), '\n');
    std::string listed;
    for (std::size_t i = 0; i < names.size() && i < kListedNames; ++i) listed += (i ? ", " : "") + names[i];
    if (names.size() > kListedNames) listed += fmt::format(" and {} more", names.size() - kListedNames);
    out.set(key + "_names", listed);
  }
  return true;
}

}  // namespace

Report describe_file(const std::string& path, const DescribeOptions& options) {
  h5::File file = h5::File::open(path);
  const h5::Group& root = file.root();
  Report out;
  out.set("file", file.name());
  out.set("kind", file.kind());
  out.set("format_version", static_cast<std::int64_t>(file.format_version()));
  Report& summary = out.child("summary");
  if (file.kind() == "particles") {
    describe_particles(root, summary);
  } else if (file.kind() == "frame") {
    describe_steps(root, summary);
  } else if (file.kind() == "fragments") {
    describe_fragments(root, summary);
  } else if (file.kind() == "meshes") {
    describe_meshes(root, summary);
  } else {
    // run, fragments and later kinds: every group of equal-length columns is a table.
    for (const std::string& name : root.children()) {
      if (root.is_group(name)) describe_table(root.open_group(name), name, summary);
    }
  }
  Report& attributes = out.child("attributes");
  add_attributes(root, attributes);
  if (options.list_datasets) list_datasets(root, "/", out.child("datasets"));
  return out;
}

}  // namespace bw
