#include "harness/run/ProgressBar.h"

#include <unistd.h>

#include <cstdio>

namespace cdb {

namespace {
std::string duration(double seconds) {
  if (seconds < 0 || seconds > 1e7) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  return buf;
}
}  // namespace

ProgressBar::ProgressBar(std::size_t cellsTotal, std::size_t framesPerCell, bool enabled)
    : cellsTotal_(cellsTotal), framesPerCell_(framesPerCell), enabled_(enabled),
      terminal_(::isatty(STDERR_FILENO) == 1) {}

void ProgressBar::startCell(const std::string& label) {
  label_ = label;
  if (terminal_) draw(false);
}

void ProgressBar::frameDone() {
  ++framesDone_;
  if (!terminal_) return;
  const auto now = Clock::now();
  if (now - lastDraw_ > std::chrono::milliseconds(200)) draw(false);
}

void ProgressBar::cellDone() {
  ++cellsDone_;
  draw(!terminal_);
}

void ProgressBar::cellTakenElsewhere() {
  if (cellsTotal_ > cellsDone_) --cellsTotal_;
}

void ProgressBar::finish() {
  if (enabled_ && terminal_) std::fputc('\n', stderr);
}

void ProgressBar::draw(bool newline) {
  if (!enabled_) return;
  lastDraw_ = Clock::now();
  const double elapsed = std::chrono::duration<double>(lastDraw_ - start_).count();
  const double fps = elapsed > 0 ? framesDone_ / elapsed : 0.0;
  const double framesLeft =
      static_cast<double>(cellsTotal_ * framesPerCell_) - static_cast<double>(framesDone_);
  const std::string eta = fps > 0 ? duration(framesLeft / fps) : "?";
  constexpr int kWidth = 24;
  const int filled = cellsTotal_ ? static_cast<int>(kWidth * cellsDone_ / cellsTotal_) : kWidth;
  std::string bar(static_cast<std::size_t>(filled), '=');
  bar.resize(kWidth, ' ');
  std::fprintf(stderr, "%s[%s] %zu/%zu cells  %.1f frames/s  ETA %s  %s%s",
               terminal_ ? "\r\033[K" : "", bar.c_str(), cellsDone_, cellsTotal_, fps, eta.c_str(),
               label_.c_str(), newline ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace cdb
