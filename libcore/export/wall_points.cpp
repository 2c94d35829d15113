#include "export/wall_points.h"

#include <cmath>

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>

#include "common/atomic_file.h"
#include "common/error.h"

namespace bw::exporter {
namespace {

constexpr const char* kGrid = "wall_pressure";

}  // namespace

std::size_t write_wall_points(const FrameData& frame, Up up, double voxel, const std::string& path,
                              const std::string& where) {
  require_wall_pressure(frame.fields(), where);
  if (!(voxel > 0) || !std::isfinite(voxel)) fail_input("{}: the points' voxel {} is not positive", where, voxel);
  openvdb::initialize();  // once per process; later calls return at once
  std::vector<openvdb::Vec3R> positions;
  std::vector<float> pressure;
  std::vector<std::int32_t> solid;
  for (std::size_t k = 0; k < frame.bp.size(); ++k) {
    const Vec3d p = to_up(Vec3d(frame.bx[k], frame.by[k], frame.bz[k]), up);
    if (!p.allFinite()) continue;
    positions.emplace_back(p.x(), p.y(), p.z());
    pressure.push_back(frame.bp[k]);
    solid.push_back(frame.bsolid[k]);
  }
  const openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(voxel);
  const openvdb::points::PointAttributeVector<openvdb::Vec3R> position_list(positions);
  const openvdb::tools::PointIndexGrid::Ptr index =
      openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(position_list, *transform);
  // Positions as floats within their voxel (NullCodec): exact to a float's precision.
  openvdb::points::PointDataGrid::Ptr grid =
      openvdb::points::createPointDataGrid<openvdb::points::NullCodec, openvdb::points::PointDataGrid>(
          *index, position_list, *transform);
  using openvdb::points::PointAttributeVector;
  openvdb::points::appendAttribute<float>(grid->tree(), "pressure");
  openvdb::points::populateAttribute(grid->tree(), index->tree(), "pressure", PointAttributeVector<float>(pressure));
  openvdb::points::appendAttribute<std::int32_t>(grid->tree(), "solid");
  openvdb::points::populateAttribute(grid->tree(), index->tree(), "solid",
                                     PointAttributeVector<std::int32_t>(solid));
  grid->setName(kGrid);
  AtomicFile out(path);
  try {
    openvdb::io::File file(out.temp_path());
    file.setCompression(openvdb::io::COMPRESS_BLOSC);
    file.write(openvdb::GridPtrVec{grid});
    file.close();
  } catch (const std::exception& e) {
    fail_run("{}: writing the VDB file failed: {}", path, e.what());
  }
  out.commit();
  return positions.size();
}

std::vector<WallPoint> read_wall_points(const std::string& path) {
  openvdb::initialize();
  openvdb::points::PointDataGrid::Ptr grid;
  try {
    openvdb::io::File file(path);
    file.open();
    grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid(kGrid));
    file.close();
  } catch (const std::exception& e) {
    fail_input("{}: not a VDB file with a point grid '{}': {}", path, kGrid, e.what());
  }
  if (!grid) fail_input("{}: its grid '{}' is not a point data grid", path, kGrid);
  std::vector<WallPoint> points;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    const openvdb::points::AttributeSet& set = leaf->attributeSet();
    if (set.find("pressure") == openvdb::points::AttributeSet::INVALID_POS ||
        set.find("solid") == openvdb::points::AttributeSet::INVALID_POS)
      fail_input("{}: the points of '{}' lack a 'pressure' or 'solid' attribute", path, kGrid);
    const openvdb::points::AttributeHandle<openvdb::Vec3f> position(leaf->constAttributeArray("P"));
    const openvdb::points::AttributeHandle<float> pressure(leaf->constAttributeArray("pressure"));
    const openvdb::points::AttributeHandle<std::int32_t> solid(leaf->constAttributeArray("solid"));
    for (auto voxel = leaf->cbeginValueOn(); voxel; ++voxel) {
      const openvdb::Vec3d centre = voxel.getCoord().asVec3d();
      for (auto i = leaf->beginIndexVoxel(voxel.getCoord()); i; ++i) {
        const openvdb::Vec3d world = grid->transform().indexToWorld(centre + position.get(*i));
        points.push_back({Vec3d(world.x(), world.y(), world.z()), pressure.get(*i), solid.get(*i)});
      }
    }
  }
  return points;
}

}  // namespace bw::exporter
