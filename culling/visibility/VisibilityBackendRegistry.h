#pragma once
// Visibility backends by name, as DetectorRegistry holds strategies: every place that needs a
// backend (runner, check, floor comparison, benchmarks, tests) creates it through here, so a new
// backend is one class plus one entry in VisibilityBackendRegistry.cpp.
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "culling/visibility/BackendFloor.h"
#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackend.h"
#include "scenes/ScenarioConfig.h"

namespace cdb {

struct BackendTraits {
  bool needsGl = false;  // opens the headless GL context (EGL) of BackendResources
  // Begins DepthUse::OrderIndependent passes (VisibilityBackend::supportsOrderIndependent).
  bool orderIndependent = false;
};

class VisibilityBackendRegistry {
 public:
  using Factory = std::function<std::unique_ptr<VisibilityBackend>(BackendResources&,
                                                                   const VisibilityOptions&)>;
  using FloorFactory = std::function<std::unique_ptr<BackendFloor>(BackendResources&,
                                                                   const VisibilityOptions&)>;

  // The registry with every backend of the project.
  static const VisibilityBackendRegistry& builtin();
  // The backend a run uses when neither the command line nor the config names one: the CPU
  // rasteriser, the fastest correct backend where no GPU is at hand (8-21x gl-queries on llvmpipe,
  // README "Visibility backends"), needing no EGL, and with counters (pixels) that do not depend
  // on the machine.
  static constexpr std::string_view kDefault = "cpu";

  // Without a floor factory, the backend's floor replays the recorded calls on a new instance of
  // it (ReplayFloor).
  void add(std::string name, std::string description, BackendTraits traits, Factory factory,
           FloorFactory floor = {});
  // Throws InputError naming the unknown backend and listing the known ones; RunError when the
  // backend cannot start here (no GL).
  [[nodiscard]] std::unique_ptr<VisibilityBackend> create(std::string_view name,
                                                          BackendResources& resources,
                                                          const VisibilityOptions& options) const;
  // The floor a strategy's work on the backend is measured against (BackendFloor.h).
  [[nodiscard]] std::unique_ptr<BackendFloor> createFloor(std::string_view name,
                                                          BackendResources& resources,
                                                          const VisibilityOptions& options) const;
  // The backends that start here (the others need a GL that does not open); `why` gets a line
  // per backend that does not.
  [[nodiscard]] std::vector<std::string> available(BackendResources& resources,
                                                   std::vector<std::string>* why = nullptr) const;
  [[nodiscard]] bool contains(std::string_view name) const;
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] std::string description(std::string_view name) const;
  [[nodiscard]] BackendTraits traits(std::string_view name) const;
  // Throws InputError for an unknown name.
  void validate(std::string_view name) const;

 private:
  struct Entry {
    std::string name;
    std::string description;
    BackendTraits traits;
    Factory factory;
    FloorFactory floor;
  };
  const Entry* find(std::string_view name) const;
  std::vector<Entry> entries_;
};

// The backend a config's culling section names (the default when it names none).
[[nodiscard]] std::string backendNameOf(const CullingSpec& culling);
// The backend options a config's culling section sets.
[[nodiscard]] VisibilityOptions visibilityOptionsOf(const CullingSpec& culling);

}  // namespace cdb
