#pragma once
// Strategies by name. The harness creates every strategy through here and knows nothing else of
// them; a new strategy is one class plus one line in StrategyRegistry.cpp.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "culling/CullingStrategy.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct StrategyOptions {
  int resolution = 800;  // frame-buffer side in pixels
  CullingSpec culling;   // conservative/raw mode, BVH parameters
};

class StrategyRegistry {
 public:
  using Factory = std::function<std::unique_ptr<CullingStrategy>(const StrategyOptions&)>;

  // The registry with every strategy of the project.
  static const StrategyRegistry& builtin();

  // What an entry is: an image-based culling strategy (asks a visibility backend, leaves sets for
  // the exact phase), a reference that leaves sets without asking any backend (all_pairs), or a
  // CPU peer (decides the colliding pairs itself, draws nothing).
  enum class Kind { ImageBased, Reference, CpuPeer };

  void add(std::string name, std::string description, Factory factory,
           Kind kind = Kind::ImageBased);
  // Throws InputError naming the unknown strategy and listing the known ones.
  [[nodiscard]] std::unique_ptr<CullingStrategy> create(std::string_view name,
                                                        const StrategyOptions& options) const;
  [[nodiscard]] bool contains(std::string_view name) const;
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] std::string description(std::string_view name) const;
  // Throws InputError for an unknown name.
  [[nodiscard]] Kind kind(std::string_view name) const;
  [[nodiscard]] bool isCpuPeer(std::string_view name) const { return kind(name) == Kind::CpuPeer; }
  // Whether its answer or time depends on the visibility backend and the resolution.
  [[nodiscard]] bool usesBackend(std::string_view name) const { return kind(name) == Kind::ImageBased; }
  // Throws InputError for the first unknown name.
  void validate(const std::vector<std::string>& names) const;

 private:
  struct Entry {
    std::string name;
    std::string description;
    Factory factory;
    Kind kind = Kind::ImageBased;
  };
  const Entry* find(std::string_view name) const;
  std::vector<Entry> entries_;
};

}  // namespace cdb
