#pragma once
// Detectors by name. The harness creates every detector through here and knows nothing else of
// them; a new culling strategy or CPU peer is one class plus one line in DetectorRegistry.cpp.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "culling/CollisionDetector.h"
#include "culling/CullingStrategy.h"
#include "culling/exact/ExactPhase.h"
#include "culling/visibility/VisibilityBackend.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct DetectorOptions {
  int resolution = 800;  // frame-buffer side in pixels
  // The config's culling section: the visibility mode, and each strategy's own options, which
  // the registry's factories pass to the strategy.
  CullingSpec culling;
};

class DetectorRegistry {
 public:
  using StrategyFactory = std::function<std::unique_ptr<CullingStrategy>(const DetectorOptions&)>;
  using PeerFactory = std::function<std::unique_ptr<CollisionDetector>(const DetectorOptions&)>;

  // The registry with every detector of the project.
  static const DetectorRegistry& builtin();

  // What an entry is: an image-based culling strategy (asks a visibility backend, leaves sets for
  // the exact phase), a reference that leaves sets without asking any backend (all_pairs), or a
  // CPU peer (a detector by itself: decides the colliding pairs, draws nothing).
  enum class Kind { ImageBased, Reference, CpuPeer };

  // A culling strategy (kind ImageBased or Reference); `orderIndependent`: its passes are
  // DepthUse::OrderIndependent, so it runs only on backends that offer them.
  void add(std::string name, std::string description, StrategyFactory factory,
           Kind kind = Kind::ImageBased, bool orderIndependent = false);
  void addPeer(std::string name, std::string description, PeerFactory factory);

  // The detector `name` stands for, not yet attached: a CPU peer alone, or the culling strategy
  // with `backend` and `exact` (both outlive the detector; `exact` built for the scene it will be
  // attached to). Throws InputError naming the unknown detector and listing the known ones.
  [[nodiscard]] std::unique_ptr<CollisionDetector> createDetector(std::string_view name,
                                                                  const DetectorOptions& options,
                                                                  VisibilityBackend& backend,
                                                                  ExactPhase& exact) const;
  // The culling strategy alone; throws InputError for an unknown name or a CPU peer.
  [[nodiscard]] std::unique_ptr<CullingStrategy> create(std::string_view name,
                                                        const DetectorOptions& options) const;
  // A CPU peer; throws InputError for an unknown name or a culling strategy.
  [[nodiscard]] std::unique_ptr<CollisionDetector> createPeer(std::string_view name,
                                                              const DetectorOptions& options) const;
  [[nodiscard]] bool contains(std::string_view name) const;
  [[nodiscard]] std::vector<std::string> names() const;
  // The entries of one kind, in registration order.
  [[nodiscard]] std::vector<std::string> names(Kind kind) const;
  [[nodiscard]] std::string description(std::string_view name) const;
  // Throws InputError for an unknown name.
  [[nodiscard]] Kind kind(std::string_view name) const;
  // Whether its answer or time depends on the visibility backend and the resolution.
  [[nodiscard]] bool usesBackend(std::string_view name) const { return kind(name) == Kind::ImageBased; }
  // Whether detector `name` runs on visibility backend `backend` (a registered name): every one but
  // a strategy of order-independent passes on a backend without them. Throws InputError for an
  // unknown name.
  [[nodiscard]] bool runsOn(std::string_view name, std::string_view backend) const;
  // Throws InputError for the first unknown name.
  void validate(const std::vector<std::string>& names) const;

 private:
  struct Entry {
    std::string name;
    std::string description;
    StrategyFactory strategy;  // set for ImageBased and Reference
    PeerFactory peer;          // set for CpuPeer
    Kind kind = Kind::ImageBased;
    bool orderIndependent = false;
  };
  const Entry* find(std::string_view name) const;
  const Entry& get(std::string_view name) const;  // throws InputError for an unknown name
  std::vector<Entry> entries_;
};

}  // namespace cdb
