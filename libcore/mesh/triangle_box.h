// Triangle / axis-aligned box overlap (Akenine-Moeller 2001, separating axis test
// on 13 axes). With `closed` a triangle that only touches a face, an edge or a
// corner of the box overlaps it; otherwise it must enter the box's open interior.
#pragma once

#include "common/geometry.h"

namespace bw::mesh {

bool triangle_box_overlap(const Vec3d& box_center, const Vec3d& box_half_size, const Vec3d& a,
                          const Vec3d& b, const Vec3d& c, bool closed = true);

}  // namespace bw::mesh
