// PLY bodies that cannot hold what their header declares are refused before assimp sizes its
// arrays from the counts (a few hundred bytes asking for gigabytes).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "core/Errors.h"
#include "scenes/PlyBounds.h"

namespace cdb {
namespace {

constexpr std::string_view kBinaryHeader =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

std::string littleEndian(std::uint32_t v, int bytes) {
  std::string out;
  for (int k = 0; k < bytes; ++k) out += static_cast<char>((v >> (8 * k)) & 0xff);
  return out;
}

std::string triangleBody() {
  std::string body(36, '\0');  // three vertices at the origin
  body += static_cast<char>(3);
  for (std::uint32_t i = 0; i < 3; ++i) body += littleEndian(i, 4);
  return body;
}

std::string errorOf(const std::string& text, std::size_t bodyStart) {
  try {
    checkPlyBodyBounds(text, bodyStart, "m.ply");
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(PlyBodyBounds, AWholeFilePasses) {
  const std::string ply = std::string(kBinaryHeader) + triangleBody();
  EXPECT_EQ(errorOf(ply, kBinaryHeader.size()), "<no error>");
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0\n1\n2\n3 0 1 2\n";
  EXPECT_EQ(errorOf(ascii, ascii.find("0\n1")), "<no error>");
}

TEST(PlyBodyBounds, ListLongerThanTheFileIsRefused) {
  std::string body(36, '\0');
  body += static_cast<char>(200);  // 200 indices announced, 12 bytes follow
  for (std::uint32_t i = 0; i < 3; ++i) body += littleEndian(i, 4);
  const std::string message = errorOf(std::string(kBinaryHeader) + body, kBinaryHeader.size());
  EXPECT_EQ(message.rfind("m.ply: PLY element 'face' 0 of 1: a list of 200 items does not fit", 0),
            0u)
      << message;
}

TEST(PlyBodyBounds, HugeUintListCountIsRefused) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement face 1\n"
      "property list uint uint vertex_indices\nend_header\n";
  const std::string message = errorOf(header + littleEndian(0x7fffffff, 4) + "abcd", header.size());
  EXPECT_NE(message.find("a list of 2147483647 items does not fit"), std::string::npos) << message;
}

TEST(PlyBodyBounds, MoreElementsThanBytesIsRefused) {
  const std::string header =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4000000000\nproperty double x\n"
      "end_header\n";
  const std::string message = errorOf(header + std::string(16, '\0'), header.size());
  EXPECT_NE(message.find("PLY element 'vertex'"), std::string::npos) << message;
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n1\n";
  EXPECT_NE(errorOf(ascii, ascii.find("0\n1")).find("the data ends before it"), std::string::npos);
}

TEST(PlyBodyBounds, NegativeListLengthIsRefused) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  EXPECT_NE(errorOf(header + "-3 0 1 2\n", header.size()).find("expected a list length >= 0"),
            std::string::npos);
}

TEST(PlyBodyBounds, HeadersItDoesNotFollowAreLeftToAssimp) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty quaternion q\nend_header\n";
  EXPECT_EQ(errorOf(header, header.size()), "<no error>");
}

}  // namespace
}  // namespace cdb
