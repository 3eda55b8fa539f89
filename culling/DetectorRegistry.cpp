#include "culling/DetectorRegistry.h"

#include <stdexcept>

#include "core/Errors.h"
#include "culling/ImageBasedDetector.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "culling/peers/BulletPeer.h"
#include "culling/peers/FclPeer.h"
#include "culling/peers/OdePeer.h"
#include "culling/strategies/AllPairs.h"
#include "culling/strategies/CollisionIndependentSets.h"
#include "culling/strategies/Cullide.h"
#include "culling/strategies/CullideWithHierarchy.h"
#include "culling/strategies/DepthSortedCulling.h"
#include "culling/strategies/HierarchicalCollisionIndependentSets.h"
#include "culling/strategies/OrderIndependentCullide.h"
#include "culling/strategies/QuickCullide.h"

namespace cdb {

const DetectorRegistry& DetectorRegistry::builtin() {
  static const DetectorRegistry registry = [] {
    DetectorRegistry r;
    r.add("cullide", "CULLIDE without a hierarchy: object then triangle level, two passes, x y z",
          [](const DetectorOptions& o) { return std::make_unique<Cullide>(o); });
    r.add("cullide_bvh", "CULLIDE's pruning coarse to fine over each object's 8-ary OBB tree",
          [](const DetectorOptions& o) {
            return std::make_unique<CullideWithHierarchy>(o, o.culling.strategies.cullideBvh);
          });
    r.add("sorted", "CULLIDE's two passes in depth order, one depth clear (thesis 3.2)",
          [](const DetectorOptions& o) { return std::make_unique<DepthSortedCulling>(o); });
    r.add("cis", "collision-independent sets along one view axis (thesis 3.3, Algorithm 3.2)",
          [](const DetectorOptions& o) {
            return std::make_unique<CollisionIndependentSets>(o, o.culling.strategies.cis);
          });
    r.add("ours", "thesis 3.4: OBB trees, sorting, collision-independent sets, an axis per level",
          [](const DetectorOptions& o) {
            return std::make_unique<HierarchicalCollisionIndependentSets>(
                o, o.culling.strategies.ours);
          });
    r.add("quick_cullide",
          "Quick-CULLIDE: CULLIDE's passes with each pass' answers kept, pairs freed by either pass",
          [](const DetectorOptions& o) { return std::make_unique<QuickCullide>(o); });
    r.add("cullide_oi",
          "CULLIDE's answer order-independently: per axis every piece written, then every piece "
          "tested against the others' nearest depth (not in any paper)",
          [](const DetectorOptions& o) { return std::make_unique<OrderIndependentCullide>(o); },
          Kind::ImageBased, true);
    r.add("all_pairs", "reference: every object in one set, no culling; the exact phase alone",
          [](const DetectorOptions& o) { return std::make_unique<AllPairs>(o); }, Kind::Reference);
    r.addPeer("fcl", "CPU peer: FCL, dynamic AABB tree broad phase, OBBRSS mesh hierarchies",
              [](const DetectorOptions& o) { return std::make_unique<FclPeer>(o); });
    r.addPeer("bullet", "CPU peer: Bullet (double), btDbvtBroadphase, GImpact meshes, margin 0",
              [](const DetectorOptions& o) { return std::make_unique<BulletPeer>(o); });
    r.addPeer("ode", "CPU peer: ODE, hash space, OPCODE trimesh-trimesh collider",
              [](const DetectorOptions& o) { return std::make_unique<OdePeer>(o); });
    return r;
  }();
  return registry;
}

void DetectorRegistry::add(std::string name, std::string description, StrategyFactory factory,
                           Kind kind, bool orderIndependent) {
  if (kind == Kind::CpuPeer) throw std::logic_error("a CPU peer is added with addPeer");
  entries_.push_back(
      {std::move(name), std::move(description), std::move(factory), {}, kind, orderIndependent});
}

bool DetectorRegistry::runsOn(std::string_view name, std::string_view backend) const {
  return !get(name).orderIndependent ||
         VisibilityBackendRegistry::builtin().traits(backend).orderIndependent;
}

void DetectorRegistry::addPeer(std::string name, std::string description, PeerFactory factory) {
  entries_.push_back(
      {std::move(name), std::move(description), {}, std::move(factory), Kind::CpuPeer});
}

DetectorRegistry::Kind DetectorRegistry::kind(std::string_view name) const {
  return get(name).kind;
}

const DetectorRegistry::Entry& DetectorRegistry::get(std::string_view name) const {
  validate({std::string(name)});
  return *find(name);
}

const DetectorRegistry::Entry* DetectorRegistry::find(std::string_view name) const {
  for (const auto& e : entries_)
    if (e.name == name) return &e;
  return nullptr;
}

bool DetectorRegistry::contains(std::string_view name) const { return find(name) != nullptr; }

std::vector<std::string> DetectorRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.name);
  return out;
}

std::vector<std::string> DetectorRegistry::names(Kind kind) const {
  std::vector<std::string> out;
  for (const auto& e : entries_)
    if (e.kind == kind) out.push_back(e.name);
  return out;
}

std::string DetectorRegistry::description(std::string_view name) const {
  const Entry* e = find(name);
  return e ? e->description : std::string();
}

void DetectorRegistry::validate(const std::vector<std::string>& names) const {
  for (const auto& n : names) {
    if (!contains(n)) {
      std::string known;
      for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.name;
      throw InputError("unknown strategy '" + n + "': expected one of " + known);
    }
  }
}

std::unique_ptr<CullingStrategy> DetectorRegistry::create(std::string_view name,
                                                          const DetectorOptions& options) const {
  const Entry& e = get(name);
  if (e.kind == Kind::CpuPeer)
    throw InputError("'" + e.name + "' is a CPU peer, a detector by itself: no culling strategy");
  return e.strategy(options);
}

std::unique_ptr<CollisionDetector> DetectorRegistry::createPeer(
    std::string_view name, const DetectorOptions& options) const {
  const Entry& e = get(name);
  if (e.kind != Kind::CpuPeer)
    throw InputError("'" + e.name + "' is a culling strategy, not a CPU peer");
  return e.peer(options);
}

std::unique_ptr<CollisionDetector> DetectorRegistry::createDetector(std::string_view name,
                                                                    const DetectorOptions& options,
                                                                    VisibilityBackend& backend,
                                                                    ExactPhase& exact) const {
  const Entry& e = get(name);
  if (e.kind == Kind::CpuPeer) return e.peer(options);
  return std::make_unique<ImageBasedDetector>(e.strategy(options), backend, exact);
}

}  // namespace cdb
