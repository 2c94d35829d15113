#include "export/water.h"

#include <cmath>
#include <mutex>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetMeasure.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/terminal.h"

namespace bw::exporter {
namespace {

void initialize_once() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

// The interface ParticlesToLevelSet reads particles through.
struct ParticleList {
  using PosType = openvdb::Vec3R;
  std::vector<openvdb::Vec3R> positions;
  openvdb::Real radius = 0;
  std::size_t size() const { return positions.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& xyz) const { xyz = positions[n]; }
  void getPosRad(std::size_t n, openvdb::Vec3R& xyz, openvdb::Real& r) const {
    xyz = positions[n];
    r = radius;
  }
};

}  // namespace

Vec3d to_up(const Vec3d& p, Up up) { return up == Up::kZ ? p : Vec3d(p.x(), p.z(), -p.y()); }

void WaterOptions::resolve(const std::string& where) {
  const std::string at = where.empty() ? std::string() : where + ": ";
  if (!(spacing > 0) || !std::isfinite(spacing)) fail_input("{}the particle spacing {} is not positive", at, spacing);
  if (radius == 0) radius = kRadiusFactor * spacing;
  if (!(radius > 0) || !std::isfinite(radius)) fail_input("{}--radius {} is not positive", at, radius);
  if (voxel == 0) voxel = radius / kVoxelsPerRadius;
  if (!(voxel > 0) || !std::isfinite(voxel)) fail_input("{}--voxel {} is not positive", at, voxel);
  if (voxel < kMinVoxel)
    fail_input("{}the voxel edge {} m (--voxel) is under {} m, the smallest OpenVDB takes", at, voxel, kMinVoxel);
  if (radius < 1.5 * voxel)
    fail_input("{}--radius {} m is under 1.5 voxels of {} m; OpenVDB would drop every particle", at, radius, voxel);
  if (radius > kMaxVoxelsPerRadius * voxel)
    fail_input("{}--radius {} m spans {:.0f} voxels of {} m, more than {}: each sphere would cost about {:.2g} voxels "
               "to draw; give a larger --voxel",
               at, radius, radius / voxel, voxel, kMaxVoxelsPerRadius, std::pow(2 * radius / voxel, 3));
  if (smooth < 0) fail_input("{}--smooth {} is negative", at, smooth);
  if (!(erode >= 0) || !std::isfinite(erode)) fail_input("{}--erode {} is negative", at, erode);
  if (!(half_width >= 2)) fail_input("{}the narrow band of {} voxels is under 2", at, half_width);
}

struct WaterSurface::Grid {
  openvdb::FloatGrid::Ptr grid;
};

WaterSurface::WaterSurface() : grid_(std::make_unique<Grid>()) {}
WaterSurface::~WaterSurface() = default;
WaterSurface::WaterSurface(WaterSurface&&) noexcept = default;
WaterSurface& WaterSurface::operator=(WaterSurface&&) noexcept = default;

WaterSurface WaterSurface::build(const float* x, const float* y, const float* z, std::size_t count,
                                 const WaterOptions& options) {
  initialize_once();
  Stopwatch clock;
  WaterSurface s;
  ParticleList particles;
  particles.radius = options.radius;
  particles.positions.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3d p = to_up(Vec3d(x[i], y[i], z[i]), options.up);
    if (p.allFinite()) particles.positions.emplace_back(p.x(), p.y(), p.z());
  }
  s.stats_.particles = particles.size();
  s.grid_->grid = openvdb::createLevelSet<openvdb::FloatGrid>(options.voxel, options.half_width);
  if (!particles.positions.empty()) {
    openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*s.grid_->grid);
    raster.setRmin(1.5);
    raster.rasterizeSpheres(particles);
    raster.finalize(/*prune=*/true);
    // Each filter pass also renormalizes the band (LevelSetTracker), which the
    // union of spheres is not inside overlapping spheres.
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*s.grid_->grid);
    for (int k = 0; k < options.smooth; ++k) filter.meanCurvature();
    if (options.erode > 0) filter.offset(static_cast<float>(options.erode));
  }
  s.grid_->grid->setName("surface");
  s.grid_->grid->setGridClass(openvdb::GRID_LEVEL_SET);
  s.grid_->grid->insertMeta("particle_radius", openvdb::DoubleMetadata(options.radius));
  s.grid_->grid->insertMeta("particle_spacing", openvdb::DoubleMetadata(options.spacing));
  s.grid_->grid->insertMeta("up", openvdb::StringMetadata(options.up == Up::kZ ? "z" : "y"));
  s.stats_.active_voxels = s.grid_->grid->activeVoxelCount();
  s.stats_.seconds = clock.seconds();
  return s;
}

bool WaterSurface::empty() const { return grid_->grid->activeVoxelCount() == 0; }

void WaterSurface::write_vdb(const std::string& path, bool density) const {
  openvdb::GridPtrVec grids{grid_->grid};
  if (density) {
    openvdb::FloatGrid::Ptr fog = grid_->grid->deepCopy();
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setName("density");
    grids.push_back(fog);
  }
  AtomicFile out(path);
  try {
    openvdb::io::File file(out.temp_path());
    file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
    file.write(grids);
    file.close();
  } catch (const std::exception& e) {
    fail_run("{}: writing the VDB file failed: {}", path, e.what());
  }
  out.commit();
}

TriMesh WaterSurface::mesh(double adaptivity) const {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid_->grid, points, triangles, quads, 0.0, adaptivity);
  TriMesh m;
  m.vertices.reserve(points.size());
  for (const auto& p : points) m.vertices.emplace_back(p.x(), p.y(), p.z());
  auto index = [](openvdb::Index i) { return static_cast<std::int32_t>(i); };
  // volumeToMesh winds its polygons clockwise seen from outside (the convention of
  // Houdini): reversed here.
  m.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const auto& t : triangles) m.triangles.push_back({index(t[0]), index(t[2]), index(t[1])});
  for (const auto& q : quads) {
    m.triangles.push_back({index(q[0]), index(q[2]), index(q[1])});
    m.triangles.push_back({index(q[0]), index(q[3]), index(q[2])});
  }
  return m;
}

double WaterSurface::volume() const {
  if (empty()) return 0;
  return openvdb::tools::levelSetVolume(*grid_->grid);
}

}  // namespace bw::exporter
