#pragma once
// Progress of a run on stderr: cells done, frames per second, ETA. Redrawn in place on a
// terminal, one line per finished cell otherwise (logs, CI).
#include <chrono>
#include <cstddef>
#include <string>

namespace cdb {

class ProgressBar {
 public:
  ProgressBar(std::size_t cellsTotal, std::size_t framesPerCell, bool enabled);
  void startCell(const std::string& label);
  void frameDone();
  void cellDone();
  // A cell of the total that another share measures (cdbench run --balance): one fewer to do.
  void cellTakenElsewhere();
  void finish();

 private:
  void draw(bool newline);
  using Clock = std::chrono::steady_clock;
  std::size_t cellsTotal_;
  std::size_t framesPerCell_;
  bool enabled_;
  bool terminal_;
  std::size_t cellsDone_ = 0;
  std::size_t framesDone_ = 0;
  std::string label_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point lastDraw_{};
};

}  // namespace cdb
