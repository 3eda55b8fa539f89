#pragma once
// The GPU time of a pipeline's draws, for profiling a GL backend (VisibilityOptions::timeGpu):
// each draw call is bracketed by a GL_TIME_ELAPSED query, and the elapsed times are summed when
// the answers are read back (after a read-back every query issued before it is complete, so
// collecting them waits for nothing more). Off, a draw costs one branch.
#include <cstdint>
#include <vector>

#include "render/Gl.h"

namespace cdb {

class GlDrawTimer {
 public:
  GlDrawTimer() = default;
  ~GlDrawTimer();
  GlDrawTimer(const GlDrawTimer&) = delete;
  GlDrawTimer& operator=(const GlDrawTimer&) = delete;

  void enable(bool on) { enabled_ = on; }
  [[nodiscard]] bool enabled() const { return enabled_; }

  // Brackets one draw call (no nesting: GL allows one GL_TIME_ELAPSED query at a time).
  class Scope {
   public:
    explicit Scope(GlDrawTimer& timer) : timer_(timer.enabled_ ? &timer : nullptr) {
      if (timer_) timer_->begin();
    }
    ~Scope() {
      if (timer_) glEndQuery(GL_TIME_ELAPSED);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GlDrawTimer* timer_;
  };
  [[nodiscard]] Scope scope() { return Scope(*this); }

  // Nanoseconds the GPU spent on the draws bracketed since the last call; reuses their queries.
  std::uint64_t collectNs();

 private:
  void begin();

  bool enabled_ = false;
  std::vector<GLuint> names_;
  std::size_t used_ = 0;
};

}  // namespace cdb
