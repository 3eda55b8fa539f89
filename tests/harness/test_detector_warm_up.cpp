#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/Pose.h"
#include "harness/measure/DetectorWarmUp.h"

namespace cdb {
namespace {

// A detector that writes what happens to it into a shared log.
class LoggingDetector final : public CollisionDetector {
 public:
  LoggingDetector(std::vector<std::string>& log, int id) : log_(log), id_(id) {
    log_.push_back("made " + std::to_string(id_));
  }
  ~LoggingDetector() override { log_.push_back("dropped " + std::to_string(id_)); }
  [[nodiscard]] std::string_view name() const override { return "logging"; }
  void attach(const SceneGeometry&) override {}
  [[nodiscard]] DetectedFrame detect(const FrameInput& frame) override {
    log_.push_back("detected frame " + std::to_string(frame.frame) + " on " + std::to_string(id_) +
                   " (" + std::to_string(frame.poses.size()) + " poses)");
    return {};
  }

 private:
  std::vector<std::string>& log_;
  int id_;
};

TEST(DetectorWarmUp, TheFirstFrameIsDetectedOnADetectorThatIsDroppedBeforeTheTimedOneIsMade) {
  std::vector<std::string> log;
  int made = 0;
  const std::vector<Pose> poses(3);
  auto timed = detectorAfterUntimedFrame(
      [&] { return std::make_unique<LoggingDetector>(log, ++made); }, {poses, 12});
  const std::vector<std::string> expected = {"made 1", "detected frame 12 on 1 (3 poses)",
                                             "dropped 1", "made 2"};
  EXPECT_EQ(log, expected);
  // What the caller times is the second detector, which has detected nothing yet.
  (void)timed->detect({poses, 12});
  EXPECT_EQ(log.back(), "detected frame 12 on 2 (3 poses)");
  timed.reset();
  EXPECT_EQ(log.back(), "dropped 2");
}

}  // namespace
}  // namespace cdb
