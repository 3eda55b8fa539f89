// The pose recording file format, byte by byte in docs/pose-recording.md. Every number is
// little-endian whatever the machine, so recordings can be shared.
#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <unistd.h>

#include "core/Errors.h"
#include "scenes/DynamicsModel.h"
#include "scenes/PoseRecording.h"

namespace cdb {

namespace {

constexpr std::string_view kMagic = "CDBPOSE1";
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kDoublesPerPose = 7;  // translation x y z, rotation w x y z
constexpr std::size_t kBytesPerPose = kDoublesPerPose * 8;
// Far above any real name; a larger value means the header is garbage.
constexpr std::uint32_t kMaxEnvironmentLength = 4096;
// ODE renormalises every step, so a recorded rotation is a unit quaternion to a few ulps.
constexpr double kUnitTolerance = 1e-6;
// The simulation stops when a body's centre of mass leaves this distance; a pose places the mesh's
// origin, which lies within the mesh's size of it, hence the margin.
constexpr double kMaxDistance = 2 * dynamics_model::kMaxDistanceFromOrigin;

class ByteWriter {
 public:
  void bytes(std::string_view s) { out_.insert(out_.end(), s.begin(), s.end()); }
  void u32(std::uint32_t v) { little(v, 4); }
  void u64(std::uint64_t v) { little(v, 8); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  [[nodiscard]] const std::vector<char>& data() const { return out_; }

 private:
  void little(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(char(std::uint8_t(v >> (8 * i))));
  }
  std::vector<char> out_;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const char> in) : in_(in) {}
  [[nodiscard]] std::size_t remaining() const { return in_.size() - at_; }
  [[nodiscard]] bool has(std::size_t n) const { return remaining() >= n; }
  [[nodiscard]] std::string bytes(std::size_t n) {
    std::string s(in_.data() + at_, n);
    at_ += n;
    return s;
  }
  [[nodiscard]] std::uint32_t u32() { return std::uint32_t(little(4)); }
  [[nodiscard]] std::uint64_t u64() { return little(8); }
  [[nodiscard]] double f64() { return std::bit_cast<double>(u64()); }

 private:
  std::uint64_t little(int n) {
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint64_t(std::uint8_t(in_[at_ + std::size_t(i)])) << (8 * i);
    at_ += std::size_t(n);
    return v;
  }
  std::span<const char> in_;
  std::size_t at_ = 0;
};

std::vector<char> encode(const PoseRecording& r) {
  ByteWriter w;
  w.bytes(kMagic);
  w.u32(kVersion);
  w.u32(std::uint32_t(r.environment.size()));
  w.bytes(r.environment);
  w.u64(r.fingerprint);
  w.u64(r.seed);
  w.u32(r.objectCount);
  w.u32(r.frameCount());
  w.u64(r.hash());
  for (const Pose& pose : r.poses) {
    for (int k = 0; k < 3; ++k) w.f64(pose.translation[k]);
    w.f64(pose.rotation.w());
    w.f64(pose.rotation.x());
    w.f64(pose.rotation.y());
    w.f64(pose.rotation.z());
  }
  return w.data();
}

std::filesystem::path temporaryPathFor(const std::filesystem::path& file) {
  // Same directory, so the final rename stays on one file system and is atomic; pid and counter
  // keep concurrent writers apart.
  static std::atomic<unsigned> counter{0};
  std::filesystem::path tmp = file;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

[[noreturn]] void failWrite(const std::filesystem::path& file, const std::string& why) {
  throw RunError(file.string() + ": cannot write pose recording: " + why);
}

void writeAll(const std::filesystem::path& tmp, const std::vector<char>& data) {
  std::FILE* out = std::fopen(tmp.c_str(), "wb");
  if (!out) throw std::runtime_error(std::strerror(errno));
  const bool written = std::fwrite(data.data(), 1, data.size(), out) == data.size() &&
                       std::fflush(out) == 0 && ::fsync(::fileno(out)) == 0;
  const int error = errno;
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) throw std::runtime_error(std::strerror(written ? errno : error));
}

[[noreturn]] void failRead(const std::filesystem::path& file, const std::string& why) {
  throw InputError(file.string() + ": " + why);
}

}  // namespace

void writePoseRecording(const PoseRecording& recording, const std::filesystem::path& file) {
  if (recording.objectCount == 0 ? !recording.poses.empty()
                                 : recording.poses.size() % recording.objectCount != 0) {
    failWrite(file, std::to_string(recording.poses.size()) + " poses are not whole frames of " +
                        std::to_string(recording.objectCount) + " objects");
  }
  if (recording.environment.size() > kMaxEnvironmentLength) {
    failWrite(file, "environment name longer than " + std::to_string(kMaxEnvironmentLength) + " bytes");
  }
  const std::vector<char> data = encode(recording);
  const std::filesystem::path tmp = temporaryPathFor(file);
  try {
    writeAll(tmp, data);
    std::filesystem::rename(tmp, file);
  } catch (const std::filesystem::filesystem_error& error) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    failWrite(file, error.code().message());
  } catch (const std::runtime_error& error) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    failWrite(file, error.what());
  }
}

PoseRecording readPoseRecording(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) failRead(file, std::string("cannot open pose recording: ") + std::strerror(errno));
  const std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) failRead(file, "cannot read pose recording");
  return readPoseRecordingFromBytes(data, file.string());
}

PoseRecording readPoseRecordingFromBytes(std::span<const char> data, const std::string& name) {
  const std::filesystem::path file = name;
  ByteReader r(data);
  if (!r.has(kMagic.size()) || r.bytes(kMagic.size()) != kMagic) {
    failRead(file, "not a pose recording (it does not start with " + std::string(kMagic) + ")");
  }
  if (!r.has(4)) failRead(file, "truncated: the header ends before the version");
  const std::uint32_t version = r.u32();
  if (version != kVersion) {
    failRead(file, "unsupported pose recording version " + std::to_string(version) +
                       " (this build reads version " + std::to_string(kVersion) + ")");
  }
  if (!r.has(4)) failRead(file, "truncated: the header ends before the environment name");
  const std::uint32_t nameLength = r.u32();
  if (nameLength > kMaxEnvironmentLength) {
    failRead(file, "corrupt header: environment name of " + std::to_string(nameLength) + " bytes");
  }
  if (!r.has(std::size_t(nameLength) + 8 + 8 + 4 + 4 + 8)) failRead(file, "truncated: the header is incomplete");

  PoseRecording recording;
  recording.environment = r.bytes(nameLength);
  recording.fingerprint = r.u64();
  recording.seed = r.u64();
  recording.objectCount = r.u32();
  const std::uint32_t frameCount = r.u32();
  const std::uint64_t storedHash = r.u64();
  if (recording.objectCount == 0 && frameCount != 0) {
    failRead(file, "corrupt header: " + std::to_string(frameCount) + " frames of 0 objects");
  }

  // At most 2^64 / 56 poses fit in a 64-bit size; a u32 x u32 product can exceed that.
  const unsigned __int128 expected =
      static_cast<unsigned __int128>(frameCount) * recording.objectCount * kBytesPerPose;
  if (expected > r.remaining()) {
    failRead(file, "truncated: expected " + std::to_string(frameCount) + " frames of " +
                       std::to_string(recording.objectCount) + " objects, found " +
                       std::to_string(r.remaining()) + " of " +
                       std::to_string(std::uint64_t(expected)) + " bytes of pose data");
  }
  if (expected < r.remaining()) {
    failRead(file, std::to_string(r.remaining() - std::size_t(expected)) +
                       " unexpected bytes after the last frame");
  }

  recording.poses.resize(std::size_t(frameCount) * recording.objectCount);
  for (std::size_t i = 0; i < recording.poses.size(); ++i) {
    double v[kDoublesPerPose];
    for (double& x : v) x = r.f64();
    for (double x : v) {
      if (!std::isfinite(x)) {
        failRead(file, std::string(std::isnan(x) ? "NaN" : "infinity") + " in frame " +
                           std::to_string(i / recording.objectCount) + " object " +
                           std::to_string(i % recording.objectCount));
      }
    }
    Pose& pose = recording.poses[i];
    pose.translation = Eigen::Vector3d(v[0], v[1], v[2]);
    pose.rotation = Eigen::Quaterniond(v[3], v[4], v[5], v[6]);
    // The simulation never records these (it stops on an unstable body, and ODE keeps its
    // quaternions normalised); a file that holds them would feed nonsense geometry to the GL.
    const auto where = [&] {
      return "frame " + std::to_string(i / recording.objectCount) + " object " +
             std::to_string(i % recording.objectCount);
    };
    if (pose.translation.norm() > kMaxDistance) {
      failRead(file, where() + ": expected a position within " + std::to_string(kMaxDistance) +
                         " of the origin, got one " + std::to_string(pose.translation.norm()) +
                         " away");
    }
    if (std::abs(pose.rotation.norm() - 1.0) > kUnitTolerance) {
      failRead(file, where() + ": expected a unit quaternion, got one of norm " +
                         std::to_string(pose.rotation.norm()));
    }
  }
  if (recording.hash() != storedHash) {
    failRead(file, "pose data does not match the checksum in its header (corrupted file)");
  }
  return recording;
}

}  // namespace cdb
