#pragma once
// Occlusion queries reused frame after frame: names are created only when a frame issues more
// queries than any before it, and all answers are read at one synchronisation point.
#include <cstdint>
#include <vector>

#include "render/Gl.h"

namespace cdb {

class GlQueryPool {
 public:
  GlQueryPool() = default;
  ~GlQueryPool();
  GlQueryPool(const GlQueryPool&) = delete;
  GlQueryPool& operator=(const GlQueryPool&) = delete;

  // Starts the next query (GL_ANY_SAMPLES_PASSED: only "any sample" matters) and returns its
  // number.
  std::uint32_t begin() {
    if (used_ == names_.size()) grow();
    glBeginQuery(GL_ANY_SAMPLES_PASSED, names_[used_]);
    return static_cast<std::uint32_t>(used_++);
  }
  void end() { glEndQuery(GL_ANY_SAMPLES_PASSED); }

  [[nodiscard]] std::size_t pending() const { return used_; }
  // Answers of the pending queries in issue order (1 = no sample passed = fully visible); waits
  // once, for the last of them, then the earlier ones are complete. The pool is then empty.
  void fetch(std::vector<std::uint8_t>& fullyVisible);

 private:
  void grow();

  std::vector<GLuint> names_;
  std::size_t used_ = 0;
};

}  // namespace cdb
