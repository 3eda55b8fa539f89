#include "culling/exact/OrientationPredicates.h"

#include <gmpxx.h>

namespace cdb::predicates {

namespace {

int signOf(const mpq_class& value) { return sgn(value); }

}  // namespace

int orient2dExact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  if (!a.allFinite() || !b.allFinite() || !c.allFinite()) return 0;
  // mpq_class(double) is exact: every finite double is a dyadic rational.
  const mpq_class cx(c.x()), cy(c.y());
  const mpq_class acx = mpq_class(a.x()) - cx, acy = mpq_class(a.y()) - cy;
  const mpq_class bcx = mpq_class(b.x()) - cx, bcy = mpq_class(b.y()) - cy;
  return signOf(acx * bcy - acy * bcx);
}

int orient3dExact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  if (!a.allFinite() || !b.allFinite() || !c.allFinite() || !d.allFinite()) return 0;
  mpq_class ad[3], bd[3], cd[3];
  for (int i = 0; i < 3; ++i) {
    const mpq_class di(d[i]);
    ad[i] = mpq_class(a[i]) - di;
    bd[i] = mpq_class(b[i]) - di;
    cd[i] = mpq_class(c[i]) - di;
  }
  const mpq_class det = ad[2] * (bd[0] * cd[1] - cd[0] * bd[1]) +
                        bd[2] * (cd[0] * ad[1] - ad[0] * cd[1]) +
                        cd[2] * (ad[0] * bd[1] - bd[0] * ad[1]);
  return signOf(det);
}

}  // namespace cdb::predicates
