#include "harness/run/CullingSpecJson.h"

namespace cdb {
namespace {

nlohmann::json axisJson(const AxisChoice& axis) {
  if (!axis) return "auto";
  return std::string(1, "xyz"[*axis]);
}

nlohmann::json hierarchyJson(const HierarchySpec& h) {
  return {{"branching", h.branching}, {"leaf_triangles", h.leafTriangles}, {"offset", h.offset}};
}

}  // namespace

nlohmann::json toJson(const CullingSpec& culling) {
  const VisibilitySpec& v = culling.visibility;
  const StrategySpecs& s = culling.strategies;
  return {{"visibility",
           {{"backend", v.backend},
            {"conservative", v.conservative},
            {"raw_depth_offset", v.rawDepthOffset},
            {"threads", v.threads}}},
          {"strategies",
           {{"cis", {{"axis", axisJson(s.cis.axis)}}},
            {"cullide_bvh", {{"hierarchy", hierarchyJson(s.cullideBvh.hierarchy)}}},
            {"ours",
             {{"first_axis", axisJson(s.ours.firstAxis)},
              {"hierarchy", hierarchyJson(s.ours.hierarchy)}}}}}};
}

}  // namespace cdb
