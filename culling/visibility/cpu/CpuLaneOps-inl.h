// Lane-by-lane forms of the scalar steps the cpu backend's SIMD code must match bit for bit (and
// the SIMD files must match each other in); for
// the files Highway compiles once per target (included after hwy/highway.h, inside nothing).
#if defined(CDB_CPU_LANE_OPS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CDB_CPU_LANE_OPS_INL_H_
#undef CDB_CPU_LANE_OPS_INL_H_
#else
#define CDB_CPU_LANE_OPS_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace cdb {
namespace HWY_NAMESPACE {

// std::min(a, b) and std::max(a, b) lane by lane: a unless b is below (above) it.
template <class V>
HWY_INLINE V lesserOf(V a, V b) {
  namespace hn = hwy::HWY_NAMESPACE;
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}
template <class V>
HWY_INLINE V greaterOf(V a, V b) {
  namespace hn = hwy::HWY_NAMESPACE;
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

// A conservative set-up's pixel box along one axis, before clipping to the frame (setupBounds):
// from ceil(lo - margin) - 1 to floor(hi + margin), `lo`, `hi` the piece's extent on that axis.
template <class V>
HWY_INLINE V firstPixelOf(V lo, V negativeMargin) {
  namespace hn = hwy::HWY_NAMESPACE;
  return hn::Sub(hn::Ceil(hn::Add(lo, negativeMargin)), hn::Set(hn::DFromV<V>(), 1.0));
}
template <class V>
HWY_INLINE V lastPixelOf(V hi, V margin) {
  namespace hn = hwy::HWY_NAMESPACE;
  return hn::Floor(hn::Add(hi, margin));
}

}  // namespace HWY_NAMESPACE
}  // namespace cdb
HWY_AFTER_NAMESPACE();

#endif  // CDB_CPU_LANE_OPS_INL_H_
