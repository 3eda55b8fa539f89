#include "culling/visibility/cpu/CpuPassSpace.h"

#include <algorithm>
#include <cmath>

#include "culling/exact/SolidWinding.h"

namespace cdb {

RasterPass rasterPassOf(const DepthPassSetup& setup, const VisibilityOptions& options,
                        bool orderIndependent) {
  RasterPass r;
  r.resolution = setup.resolution;
  r.sign = setup.reversed() ? -1.f : 1.f;
  r.keyLo = static_cast<float>(r.sign * setup.depthNear);
  r.keyHi = static_cast<float>(r.sign * setup.depthFar);
  r.depthEpsilon = setup.depthEpsilon;
  // GL's margin holds the snapping (1/16 pixel) and the rounding of float vertex transforms,
  // about res 2^-20 (1 + magnitude / extent) pixels. Transforms here are in double (29 more
  // bits): the same bound times 2^-16 still leaves 2^13 times double's rounding of the dozen
  // operations of a transform, and snapping there is none.
  r.marginPx = std::max(0.0, setup.coverageMarginPx - 1.0 / 16.0) / 65536.0;
  // An NDC offset moves the window depth by half of it times the range.
  r.rawTestOffset = options.rawDepthOffset * 0.5 * std::abs(setup.depthFar - setup.depthNear);
  r.conservative = options.conservative;
  r.orderIndependent = orderIndependent;
  return r;
}

ScreenMatrix worldToKeyOf(const DepthPassSetup& setup) {
  const double sign = setup.reversed() ? -1.0 : 1.0;
  ScreenMatrix m;
  m.topRows<2>() = setup.worldToScreen.topRows<2>();
  m.row(2) = std::abs(setup.depthFar - setup.depthNear) * setup.worldToScreen.row(2);
  m(2, 3) += sign * setup.depthNear;
  return m;
}

std::int8_t meshWinding(const Mesh& mesh) {
  return static_cast<std::int8_t>(rememberedSolidWinding(mesh));
}

}  // namespace cdb
