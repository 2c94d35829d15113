// The pressure on the solids as OpenVDB points: what bw-export writes is what OpenVDB
// reads back, every boundary particle with a finite position once, its position to a
// float's precision in the export's up axis, its pressure and solid exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "common/error.h"
#include "export/wall_points.h"
#include "io/frame_file.h"
#include "test_support.h"

namespace bw {
namespace {

// 600 boundary particles on three faces, several to a voxel, and one lost (NaN).
FrameData loaded_frame() {
  FrameData f;
  for (int k = 0; k < 600; ++k) {
    const float a = 0.013f * static_cast<float>(k % 30), b = 0.017f * static_cast<float>(k / 30);
    const int face = k % 3;
    f.bx.push_back(face == 0 ? 0.5f : a);
    f.by.push_back(face == 1 ? -0.25f : b);
    f.bz.push_back(face == 2 ? 1.0f : a + b);
    f.bp.push_back(face == 2 ? 0.0f : 100.0f * static_cast<float>(k) - 3000.0f);
    f.bsolid.push_back(face);
  }
  f.bx[7] = std::numeric_limits<float>::quiet_NaN();
  return f;
}

bool by_position(const exporter::WallPoint& a, const exporter::WallPoint& b) {
  return std::lexicographical_compare(a.position.data(), a.position.data() + 3, b.position.data(),
                                      b.position.data() + 3);
}

TEST(WallPoints, WhatIsWrittenReadsBackInEitherUpAxis) {
  test::TempDir dir;
  const FrameData f = loaded_frame();
  for (exporter::Up up : {exporter::Up::kZ, exporter::Up::kY}) {
    const std::string path = dir.file(up == exporter::Up::kZ ? "z.vdb" : "y.vdb");
    EXPECT_EQ(exporter::write_wall_points(f, up, 0.05, path, "frame"), 599u);
    std::vector<exporter::WallPoint> got = exporter::read_wall_points(path);
    ASSERT_EQ(got.size(), 599u);
    std::vector<exporter::WallPoint> want;
    for (std::size_t k = 0; k < f.bp.size(); ++k)
      if (k != 7)
        want.push_back({exporter::to_up(Vec3d(f.bx[k], f.by[k], f.bz[k]), up), f.bp[k], f.bsolid[k]});
    std::sort(got.begin(), got.end(), by_position);
    std::sort(want.begin(), want.end(), by_position);
    double worst = 0;
    for (std::size_t k = 0; k < want.size(); ++k) {
      worst = std::max(worst, (got[k].position - want[k].position).norm());
      EXPECT_EQ(got[k].pressure, want[k].pressure) << k;
      EXPECT_EQ(got[k].solid, want[k].solid) << k;
    }
    test::figure("largest position error (m)", worst);
    EXPECT_LT(worst, 1e-6);  // a float's precision within a 5 cm voxel, and the file's float positions
  }
}

TEST(WallPoints, AFrameWithoutTheFieldAndAFileOfAnotherKindAreNamed) {
  test::TempDir dir;
  FrameData bare = loaded_frame();
  bare.bp.clear();
  EXPECT_THROW(
      try { exporter::write_wall_points(bare, exporter::Up::kZ, 0.05, dir.file("x.vdb"), "frames/000004.h5"); } catch (
          const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("frames/000004.h5: holds no wall pressure"), std::string::npos)
            << e.what();
        throw;
      },
      InputError);
  EXPECT_FALSE(test::exists(dir.file("x.vdb")));
  std::ofstream(dir.file("not.vdb")) << "text";
  EXPECT_THROW(exporter::read_wall_points(dir.file("not.vdb")), InputError);
}

}  // namespace
}  // namespace bw
