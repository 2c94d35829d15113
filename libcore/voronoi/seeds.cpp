#include "voronoi/seeds.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/input_file.h"
#include "io/h5.h"

namespace bw::voronoi {
namespace {

std::vector<Vec3d> read_seeds_hdf5(const std::string& path) {
  const h5::File file = h5::File::open(path);
  const h5::Group& root = file.root();
  if (!root.has("seeds") || root.is_group("seeds")) {
    fail_input("{}: a {} file without a /seeds dataset (S x 3) to take seeds from", file.name(), file.kind());
  }
  std::size_t rows = 0;
  const std::vector<double> flat = root.read_rows<double>("seeds", 3, &rows);
  std::vector<Vec3d> seeds;
  seeds.reserve(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const Vec3d p(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    if (!p.allFinite()) fail_input("{}: seed {} has a non-finite coordinate", root.where("seeds"), i);
    seeds.push_back(p);
  }
  return seeds;
}

std::vector<Vec3d> read_seeds_text(const std::string& path) {
  std::ifstream in(seekable_path(path));  // a pipe's copy, which is_hdf5_file has read already
  if (!in) fail_input("{}: cannot open the seeds file", path);
  std::vector<Vec3d> seeds;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r') c = ' ';
    std::vector<double> values;
    const char* p = line.data();
    const char* end = line.data() + line.size();
    while (true) {
      while (p < end && *p == ' ') ++p;
      if (p == end) break;
      const char* word_end = std::find(p, end, ' ');
      double value = 0;
      // from_chars does not take a leading '+'; accept it as people write it.
      const char* start = (*p == '+' && p + 1 < word_end) ? p + 1 : p;
      const auto [stop, ec] = std::from_chars(start, word_end, value);
      if (ec != std::errc() || stop != word_end) {
        fail_input("{}:{}: '{}' is not a number (expected 'x y z')", path, number, std::string(p, word_end));
      }
      if (!std::isfinite(value)) fail_input("{}:{}: '{}' is not a finite number", path, number, std::string(p, word_end));
      values.push_back(value);
      p = word_end;
    }
    if (values.empty()) continue;
    if (values.size() != 3) {
      fail_input("{}:{}: {} numbers where a seed needs three (x y z)", path, number, values.size());
    }
    seeds.emplace_back(values[0], values[1], values[2]);
  }
  if (in.bad()) fail_input("{}: cannot read the seeds file", path);
  return seeds;
}

}  // namespace

std::vector<Vec3d> read_seeds(const std::string& path) {
  std::vector<Vec3d> seeds = h5::is_hdf5_file(path) ? read_seeds_hdf5(path) : read_seeds_text(path);
  if (seeds.empty()) fail_input("{}: no seeds in the file", path);
  return seeds;
}

void write_seeds_text(std::span<const Vec3d> seeds, const std::string& path) {
  std::string text = "# breakwater fracture seeds: x y z\n";
  for (const Vec3d& s : seeds) text += fmt::format("{} {} {}\n", s.x(), s.y(), s.z());
  write_file_atomically(path, text.data(), text.size());
}

std::vector<Vec3d> random_seeds(const Solid& solid, std::size_t count, std::uint64_t random_seed) {
  std::mt19937_64 rng(random_seed);
  const Aabb& box = solid.bounds();
  const Vec3d extent = box.extent();
  std::vector<Vec3d> seeds;
  seeds.reserve(count);
  const std::size_t max_draws = kMaxDrawsPerSeed * std::max<std::size_t>(count, 1);
  for (std::size_t draws = 0; seeds.size() < count; ++draws) {
    if (draws == max_draws) {
      fail_input("found only {} of {} random seeds inside the mesh in {} draws in its bounding box", seeds.size(),
                 count, max_draws);
    }
    // Coordinates drawn in x, y, z order: part of what makes the result reproducible.
    const double u = uniform01(rng), v = uniform01(rng), w = uniform01(rng);
    const Vec3d p = box.min + Vec3d(u * extent.x(), v * extent.y(), w * extent.z());
    if (solid.side(p) == Side::inside) seeds.push_back(p);
  }
  return seeds;
}

const char* to_string(SeedFate fate) {
  switch (fate) {
    case SeedFate::used: return "used";
    case SeedFate::outside: return "outside";
    case SeedFate::on_surface: return "on_surface";
    case SeedFate::duplicate: return "duplicate";
  }
  return "?";
}

SeedSorting sort_seeds(const Solid& solid, std::span<const Vec3d> seeds) {
  SeedSorting out;
  out.fate.assign(seeds.size(), SeedFate::used);
  out.same_as.assign(seeds.size(), -1);
  auto less = [](const Vec3d& a, const Vec3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::map<Vec3d, std::int32_t, decltype(less)> first(less);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const auto index = static_cast<std::int32_t>(i);
    const Side side = solid.side(seeds[i]);
    if (side == Side::outside) {
      out.fate[i] = SeedFate::outside;
    } else if (side == Side::boundary) {
      out.fate[i] = SeedFate::on_surface;
    } else if (const auto [it, inserted] = first.emplace(seeds[i], index); !inserted) {
      out.fate[i] = SeedFate::duplicate;
      out.same_as[i] = it->second;
    } else {
      out.active.push_back(index);
    }
  }
  return out;
}

}  // namespace bw::voronoi
