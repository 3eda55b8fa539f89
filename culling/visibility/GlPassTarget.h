#pragma once
// The buffers of an order-independent pass (FlagShaders.h): per pixel the nearest written depth d1
// and the object that wrote it id1 (one framebuffer, its colour attachment an R32UI texture), the
// nearest depth d2 written by any other object (a second framebuffer), and for the tests a third
// framebuffer whose depth attachment is d1 (read by the depth test, not written), while they fetch
// id1 and d2 as textures. Textures, not renderbuffers, so that the later draws can read them.
#include <cstdint>

#include "culling/visibility/FlagShaders.h"
#include "render/GlHandle.h"

namespace cdb {

class GlPassTarget {
 public:
  // id1 of a pixel no object wrote.
  static constexpr std::uint32_t kNoObject = 0xffffffffu;

  // Makes the buffers resolution x resolution (re-created when it changes); needs the context
  // current. RunError when a framebuffer is incomplete.
  void ensure(int resolution);
  // d1 = d2 = `depth`, id1 = kNoObject.
  void clear(float depth);
  // Binds the draw framebuffer `stage` draws into and the textures it reads.
  void bindFor(PassStage stage) const;
  // The framebuffer of the nearest depth (what a pass binds before its first draw).
  [[nodiscard]] GLuint nearestFramebuffer() const { return nearest_.get(); }

 private:
  GlTexture nearestDepth_, nearestObject_, othersDepth_;
  GlFramebuffer nearest_, others_, tests_;
  int resolution_ = 0;
};

}  // namespace cdb
