#include "culling/visibility/VisibilityBackendRegistry.h"

#include "core/Errors.h"
#include "culling/visibility/GlDrawFloor.h"
#include "culling/visibility/GlFlagBackend.h"
#include "culling/visibility/GlOcclusionQueryBackend.h"
#include "culling/visibility/compute/GlComputeBackend.h"
#include "culling/visibility/cpu/CpuRasterBackend.h"

namespace cdb {

const VisibilityBackendRegistry& VisibilityBackendRegistry::builtin() {
  static const VisibilityBackendRegistry registry = [] {
    VisibilityBackendRegistry r;
    r.add("gl-queries",
          "OpenGL occlusion queries, one query object per tested piece (the thesis' mechanism)",
          {.needsGl = true},
          [](BackendResources& resources, const VisibilityOptions& options) {
            return std::make_unique<GlOcclusionQueryBackend>(resources.gl(), options);
          },
          [](BackendResources& resources, const VisibilityOptions& options) {
            return std::make_unique<GlQueryFloor>(resources.gl(), options);
          });
    r.add("gl-flags",
          "OpenGL, a batch of tests in one draw whose failing fragments set their piece's flag in a "
          "storage buffer; one read-back per fetch; an order-independent pass in three draws",
          {.needsGl = true, .orderIndependent = true},
          [](BackendResources& resources, const VisibilityOptions& options) {
            return std::make_unique<GlFlagBackend>(resources.gl(), options);
          });
    r.add("gl-compute",
          "OpenGL 4.5 compute shaders: the cpu backend's exact conservative answers, set up, binned "
          "to tiles and evaluated in issue order on the GPU's multiprocessors; one upload and one "
          "read-back per fetch",
          {.needsGl = true, .orderIndependent = true},
          [](BackendResources& resources, const VisibilityOptions& options) {
            return std::make_unique<GlComputeBackend>(resources.gl(), options);
          });
    r.add("cpu",
          "exact conservative CPU depth rasteriser (SIMD, threads); needs no GL",
          {.needsGl = false, .orderIndependent = true},
          [](BackendResources&, const VisibilityOptions& options) {
            return std::make_unique<CpuRasterBackend>(options);
          });
    return r;
  }();
  return registry;
}

std::string backendNameOf(const CullingSpec& culling) {
  return culling.visibility.backend.empty() ? std::string(VisibilityBackendRegistry::kDefault)
                                            : culling.visibility.backend;
}

VisibilityOptions visibilityOptionsOf(const CullingSpec& culling) {
  VisibilityOptions o;
  o.conservative = culling.visibility.conservative;
  o.rawDepthOffset = culling.visibility.rawDepthOffset;
  o.threads = culling.visibility.threads;
  return o;
}

void VisibilityBackendRegistry::add(std::string name, std::string description,
                                    BackendTraits traits, Factory factory, FloorFactory floor) {
  entries_.push_back(
      {std::move(name), std::move(description), traits, std::move(factory), std::move(floor)});
}

std::unique_ptr<BackendFloor> VisibilityBackendRegistry::createFloor(
    std::string_view name, BackendResources& resources, const VisibilityOptions& options) const {
  validate(name);
  const Entry& e = *find(name);
  if (e.floor) return e.floor(resources, options);
  return std::make_unique<ReplayFloor>(e.factory(resources, options));
}

std::vector<std::string> VisibilityBackendRegistry::available(BackendResources& resources,
                                                              std::vector<std::string>* why) const {
  std::vector<std::string> out;
  for (const auto& e : entries_) {
    try {
      (void)e.factory(resources, {});
      out.push_back(e.name);
    } catch (const RunError& error) {
      if (why) why->push_back(e.name + ": " + error.what());
    }
  }
  return out;
}

const VisibilityBackendRegistry::Entry* VisibilityBackendRegistry::find(std::string_view name) const {
  for (const auto& e : entries_)
    if (e.name == name) return &e;
  return nullptr;
}

bool VisibilityBackendRegistry::contains(std::string_view name) const { return find(name) != nullptr; }

std::vector<std::string> VisibilityBackendRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.name);
  return out;
}

std::string VisibilityBackendRegistry::description(std::string_view name) const {
  const Entry* e = find(name);
  return e ? e->description : std::string();
}

BackendTraits VisibilityBackendRegistry::traits(std::string_view name) const {
  const Entry* e = find(name);
  return e ? e->traits : BackendTraits{};
}

void VisibilityBackendRegistry::validate(std::string_view name) const {
  if (contains(name)) return;
  std::string known;
  for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.name;
  throw InputError("unknown visibility backend '" + std::string(name) + "': expected one of " + known);
}

std::unique_ptr<VisibilityBackend> VisibilityBackendRegistry::create(
    std::string_view name, BackendResources& resources, const VisibilityOptions& options) const {
  validate(name);
  return find(name)->factory(resources, options);
}

}  // namespace cdb
