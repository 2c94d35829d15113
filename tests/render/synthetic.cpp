#include "synthetic.h"

#include <cmath>
#include <random>

#include "io/fragments_file.h"
#include "io/particles_file.h"
#include "io/run_file.h"
#include "mesh/shapes.h"
#include "sample/sampler.h"

namespace bw::render::test {
namespace {

void add_lattice(FrameData& frame, const Vec3d& min, const Vec3d& max, double spacing, double jitter,
                 std::uint32_t seed, const Vec3d* center, double radius) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter * spacing, jitter * spacing);
  const Eigen::Vector3i n = ((max - min) / spacing).array().floor().cast<int>();
  for (int k = 0; k <= n.z(); ++k)
    for (int j = 0; j <= n.y(); ++j)
      for (int i = 0; i <= n.x(); ++i) {
        Vec3d p = min + spacing * Vec3d(i, j, k);
        if (center && (p - *center).norm() > radius) continue;
        p += Vec3d(u(rng), u(rng), u(rng));
        frame.x.push_back(static_cast<float>(p.x()));
        frame.y.push_back(static_cast<float>(p.y()));
        frame.z.push_back(static_cast<float>(p.z()));
      }
}

}  // namespace

void add_ball(FrameData& frame, const Vec3d& center, double radius, double spacing, double jitter,
              std::uint32_t seed) {
  add_lattice(frame, center.array() - radius, center.array() + radius, spacing, jitter, seed, &center, radius);
}

void add_block(FrameData& frame, const Vec3d& min, const Vec3d& max, double spacing, double jitter,
               std::uint32_t seed) {
  add_lattice(frame, min, max, spacing, jitter, seed, nullptr, 0);
}

FrameData splash_frame(std::size_t particles, int frame_number) {
  // Pool 2 x 1.2 x 0.25 m and a ball of radius 0.3 m: volume 0.6 + 0.113 m^3.
  const double volume = 2.0 * 1.2 * 0.25 + 4.0 / 3.0 * 3.14159265358979 * 0.027;
  const double spacing = std::cbrt(volume / static_cast<double>(particles));
  FrameData f;
  f.frame = frame_number;
  f.time = frame_number / 60.0;
  add_block(f, Vec3d(-1.0, -0.75, 0.0) + Vec3d::Constant(spacing / 2), Vec3d(1.0, 0.45, 0.25), spacing, 0.1, 7);
  add_ball(f, Vec3d(0.15, -0.2, 0.75), 0.3, spacing, 0.1, 11);
  return f;
}

Aabb write_wall_run(const std::string& dir, const Vec3d& translation, bool tank) {
  const Vec3d lo(-1.0, 0.5, 0.0), hi(1.0, 0.65, 1.0);
  RunRecord run;
  run.tool = "synthetic";
  run.status = "complete";
  auto add_solid = [&](const std::string& name, TriMesh mesh, const Vec3d& shift) {
    const SampledSolid sampled = sample::sample_mesh(std::move(mesh), {0.05, false, name, 1.0});
    write_particles(sampled, dir + "/" + name + ".h5", "synthetic");
    SolidRecord solid;
    solid.name = name;
    solid.particles = dir + "/" + name + ".h5";
    solid.kind = "static";
    solid.translation = shift;
    run.solids.push_back(solid);
  };
  run.parameters.emplace_back("spacing", 0.05);
  add_solid("wall", mesh::box(lo, hi), translation);
  if (tank) add_solid("tank", mesh::open_box(Vec3d(-1.0, -0.75, 0.0), Vec3d(1.0, 0.45, 0.4), 0.05), Vec3d::Zero());
  write_run(run, dir + "/run.h5");
  Aabb box;
  box.add(lo + translation);
  box.add(hi + translation);
  return box;
}

void add_wall_pressure(FrameData& frame, const std::string& dir, const std::function<double(const Vec3d&)>& pressure,
                       const Vec3d& translation) {
  for (const Vec3d& local : read_particles(dir + "/wall.h5").surface_positions()) {
    const Vec3d x = local + translation;
    frame.bx.push_back(static_cast<float>(x.x()));
    frame.by.push_back(static_cast<float>(x.y()));
    frame.bz.push_back(static_cast<float>(x.z()));
    frame.bp.push_back(static_cast<float>(pressure(x)));
    frame.bsolid.push_back(0);
  }
}

Aabb write_tank_run(const std::string& dir) {
  const Vec3d lo(0, 0, 0), hi(0.6, 0.15, 0.4);
  const SampledSolid sampled = sample::sample_mesh(mesh::open_box(lo, hi, 0.03), {0.01, false, "tank", 1.0});
  write_particles(sampled, dir + "/tank.h5", "synthetic");
  RunRecord run;
  run.tool = "synthetic";
  run.status = "complete";
  SolidRecord solid;
  solid.name = "tank";
  solid.particles = dir + "/tank.h5";
  solid.kind = "static";
  run.solids.push_back(solid);
  write_run(run, dir + "/run.h5");
  Aabb cavity;
  cavity.add(lo);
  cavity.add(hi);
  return cavity;
}

FrameData dambreak_frame(int frame_number) {
  FrameData f;
  f.frame = frame_number;
  f.time = frame_number / 60.0;
  const double s = 0.01;
  // Particle centres half a spacing inside the faces (the last row's upper bound
  // is a little past the centre, so that rounding keeps it).
  const Vec3d first = Vec3d::Constant(s / 2), last = Vec3d::Constant(0.45 * s);
  if (frame_number == 0)
    add_block(f, first, Vec3d(0.1, 0.15, 0.2) - last, s, 0.0, 1);
  else
    add_block(f, first, Vec3d(0.6, 0.15, 0.03) - last, s, 0.1, 1);
  return f;
}

void add_spray(FrameData& frame, std::uint32_t seed) {
  const double spacing = std::abs(frame.x.at(1) - frame.x.at(0));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3d center(0.15, -0.2, 0.25);
  auto add = [&](const Vec3d& p) {
    frame.x.push_back(static_cast<float>(p.x()));
    frame.y.push_back(static_cast<float>(p.y()));
    frame.z.push_back(static_cast<float>(p.z()));
  };
  // The sheet: radius 0.35 + 0.3 h at height h in [0, 0.3].
  for (double h = 0; h < 0.3; h += spacing) {
    const double r = 0.35 + 0.3 * h;
    const int around = static_cast<int>(2 * 3.14159265358979 * r / spacing);
    for (int k = 0; k < around; ++k) {
      const double a = 2 * 3.14159265358979 * k / around;
      add(center + Vec3d(r * std::cos(a), r * std::sin(a), h));
    }
  }
  // Drops: clusters of one to four particles above the rim.
  for (int d = 0; d < 600; ++d) {
    const double a = 2 * 3.14159265358979 * u(rng), r = 0.4 + 0.35 * u(rng), h = 0.3 + 0.35 * u(rng);
    const Vec3d p = center + Vec3d(r * std::cos(a), r * std::sin(a), h);
    const int n = 1 + static_cast<int>(4 * u(rng));
    for (int k = 0; k < n; ++k) add(p + spacing * Vec3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
  }
}

void break_wall(const std::string& dir, FrameData& frame) {
  RunRecord run = read_run(dir + "/run.h5");
  run.solids[0].kind = "breakable";
  run.solids[0].body = 0;
  BodyRecord root;
  root.solid = 0;
  root.reference_center = Vec3d(0, 0.575, 0.5);
  run.bodies = {root};
  FragmentSet set;
  const double cuts[4] = {-1.0, -0.3, 0.35, 1.0};
  for (int k = 0; k < 3; ++k) {
    Fragment f;
    f.mesh = mesh::box(Vec3d(cuts[k], 0.5, 0.0), Vec3d(cuts[k + 1], 0.65, 1.0));
    f.body = k + 1;
    f.seed = k;
    set.fragments.push_back(f);
    BodyRecord b;
    b.solid = 0;
    b.parent = 0;
    b.reference_center = Vec3d(0.5 * (cuts[k] + cuts[k + 1]), 0.575, 0.5);
    run.bodies.push_back(b);
    frame.bodies.id.push_back(k + 1);
    frame.bodies.position.push_back(b.reference_center + Vec3d(0.1 * (k - 1), -0.25 * k, 0.15 * k));
    frame.bodies.orientation.emplace_back(Eigen::AngleAxisd(0.25 * k, Vec3d(1, 0.3 * (k - 1), 0).normalized()));
    frame.bodies.linear_velocity.push_back(Vec3d::Zero());
    frame.bodies.angular_velocity.push_back(Vec3d::Zero());
  }
  write_run(run, dir + "/run.h5");
  write_fragments(set, dir + "/fragments.h5");
}

}  // namespace bw::render::test
