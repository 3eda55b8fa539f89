#pragma once
// What visibility backends may share in one process: the headless GL context, opened on first
// use with the platform the run asked for, so that a run on a backend that needs no GL (the CPU
// rasteriser) never touches EGL.
#include <functional>
#include <memory>

#include "render/HeadlessGlContext.h"

namespace cdb {

class BackendResources {
 public:
  // GL is opened on the first gl() with `platform`.
  explicit BackendResources(GlPlatform platform = GlPlatform::Auto) : platform_(platform) {}
  // GL is the context `borrow` returns on the first gl(), which must outlive this (tests share
  // one context).
  explicit BackendResources(std::function<HeadlessGlContext&()> borrow) : borrow_(std::move(borrow)) {}
  BackendResources(const BackendResources&) = delete;
  BackendResources& operator=(const BackendResources&) = delete;

  // The context, opened now if it is not yet; throws RunError when none opens.
  [[nodiscard]] HeadlessGlContext& gl();
  // The context if one is open, else null.
  [[nodiscard]] const HeadlessGlContext* openedGl() const {
    return borrowed_ ? borrowed_ : owned_.get();
  }

 private:
  GlPlatform platform_ = GlPlatform::Auto;
  std::function<HeadlessGlContext&()> borrow_;
  HeadlessGlContext* borrowed_ = nullptr;
  std::unique_ptr<HeadlessGlContext> owned_;
};

}  // namespace cdb
