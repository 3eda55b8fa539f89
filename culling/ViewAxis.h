#pragma once
// The view axis of the collision-independent-set strategies (cis, ours): the world axis along
// which the objects' centres spread the most, so that their intervals along it overlap the least.
#include <cstddef>

#include <Eigen/Core>

namespace cdb {

// 0, 1 or 2 (x, y, z): the axis of largest variance of centreOf(0) .. centreOf(n - 1), the first
// of equal ones. n > 0.
template <typename CentreOf>
[[nodiscard]] int axisOfLargestSpread(std::size_t n, CentreOf&& centreOf) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sumSq = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d c = centreOf(i);
    sum += c;
    sumSq += c.cwiseProduct(c);
  }
  const double count = static_cast<double>(n);
  const Eigen::Vector3d variance = sumSq / count - (sum / count).cwiseProduct(sum / count);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (variance[k] > variance[axis]) axis = k;
  return axis;
}

}  // namespace cdb
