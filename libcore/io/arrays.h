// Conversions between the host's point and index arrays and the flat row-major
// arrays that HDF5 datasets hold (N x 3 and so on). Internal to the file layer.
#pragma once

#include <array>
#include <vector>

#include "common/geometry.h"

namespace bw::io {

inline std::vector<double> flatten(const std::vector<Vec3d>& points) {
  std::vector<double> flat(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) flat[3 * i + k] = points[i][k];
  return flat;
}

template <class T, std::size_t N>
std::vector<T> flatten(const std::vector<std::array<T, N>>& rows) {
  std::vector<T> flat(N * rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t k = 0; k < N; ++k) flat[N * i + k] = rows[i][k];
  return flat;
}

inline std::vector<Vec3d> unflatten_points(const std::vector<double>& flat) {
  std::vector<Vec3d> points(flat.size() / 3);
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = Vec3d(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return points;
}

}  // namespace bw::io
