// A PLY is read as the format defines it and written out in the form assimp reads the same way;
// what does not fit is refused before assimp sizes its arrays from the counts (a few hundred bytes
// asking for gigabytes).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "core/Errors.h"
#include "scenes/PlyCanonical.h"

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

std::string plyErrorOf(const std::string& text, std::size_t bodyStart) {
  try {
    (void)canonicalPly(text, bodyStart, "m.ply");
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(PlyCanonical, AWholeFilePasses) {
  const std::string ply = std::string(kBinaryHeader) + triangleBody();
  EXPECT_EQ(plyErrorOf(ply, kBinaryHeader.size()), "<no error>");
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0\n1\n2\n3 0 1 2\n";
  EXPECT_EQ(plyErrorOf(ascii, ascii.find("0\n1")), "<no error>");
}

TEST(PlyCanonical, ListLongerThanTheFileIsRefused) {
  std::string body(36, '\0');
  body += static_cast<char>(200);  // 200 indices announced, 12 bytes follow
  for (std::uint32_t i = 0; i < 3; ++i) body += littleEndian(i, 4);
  const std::string message = plyErrorOf(std::string(kBinaryHeader) + body, kBinaryHeader.size());
  EXPECT_EQ(message.rfind("m.ply: PLY element 'face' 0 of 1: a list of 200 items does not fit", 0),
            0u)
      << message;
}

TEST(PlyCanonical, HugeUintListCountIsRefused) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement face 1\n"
      "property list uint uint vertex_indices\nend_header\n";
  const std::string message =
      plyErrorOf(header + littleEndian(0x7fffffff, 4) + "abcd", header.size());
  EXPECT_NE(message.find("a list of 2147483647 items does not fit"), std::string::npos) << message;
}

TEST(PlyCanonical, MoreElementsThanBytesIsRefused) {
  const std::string header =
      "ply\nformat binary_big_endian 1.0\nelement vertex 4000000000\nproperty double x\n"
      "end_header\n";
  const std::string message = plyErrorOf(header + std::string(16, '\0'), header.size());
  EXPECT_NE(message.find("PLY element 'vertex'"), std::string::npos) << message;
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n0\n1\n";
  EXPECT_NE(plyErrorOf(ascii, ascii.find("0\n1")).find("the data ends before it"),
            std::string::npos);
}

TEST(PlyCanonical, NegativeListLengthIsRefused) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  EXPECT_NE(plyErrorOf(header + "-3 0 1 2\n", header.size()).find("expected a list length >= 0"),
            std::string::npos);
}

// Where the body starts, in a text whose header ends "end_header\n".
std::size_t bodyOf(std::string_view text) { return text.find("end_header\n") + 11; }

std::string plyErrorOf(const std::string& text) { return plyErrorOf(text, bodyOf(text)); }

constexpr std::string_view kTriangleAscii =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST(PlyCanonical, AsciiIsWrittenOneItemPerLineWithoutComments) {
  const std::string in =
      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info 4000000000\r\n"
      "element vertex 3\r\nproperty float32 x\r\nproperty float y\r\nproperty float z\r\n"
      "element face 1\r\nproperty list uint8 int32 vertex_indices\r\nend_header\r\n"
      "0 0 +0\r\n1 0\n0 0 1e0 0\t3 +0 1 2\n";
  EXPECT_EQ(canonicalPly(in, in.find("0 0 +0"), "m.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 +0\n1 0 0\n0 1e0 0\n3 0 1 2\n");
}

TEST(PlyCanonical, BinaryBodyIsKeptAsItIs) {
  const std::string in = std::string(kBinaryHeader) + triangleBody();
  EXPECT_EQ(canonicalPly(in, kBinaryHeader.size(), "m.ply"), in);
}

// assimp takes an unknown element's count from its name: "7vertex" asks for seven items, any
// other unknown name for none, so the data after it is read from the wrong place.
TEST(PlyCanonical, UnknownElementWithItemsBeforeAKnownOneIsRefused) {
  const std::string digits =
      "ply\nformat binary_big_endian 1.0\nelement 777777777777vertex 3\nproperty double x\n"
      "element face 0\nproperty list uchar int vertex_indices\nend_header\n" +
      std::string(24, '\0');
  EXPECT_NE(plyErrorOf(digits).find("line 3: element '777777777777vertex' (3 items) comes before "
                                    "element 'face'"),
            std::string::npos)
      << plyErrorOf(digits);
  const std::string grid = "ply\nformat ascii 1.0\nelement range_grid 2\nproperty uchar n\n" +
                           std::string(kTriangleAscii);
  EXPECT_NE(plyErrorOf(grid).find("element 'range_grid' (2 items) comes before element 'vertex'"),
            std::string::npos);
}

TEST(PlyCanonical, UnknownElementsAfterTheMeshOrWithoutItemsAreDropped) {
  const std::string in = "ply\nformat ascii 1.0\nelement range_grid 0\nproperty uchar n\n" +
                         std::string(kTriangleAscii.substr(0, kTriangleAscii.find("end_header"))) +
                         "element TextureFile 2\nproperty uchar t\nend_header\n"
                         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n9\n9\n";
  const std::string out = canonicalPly(in, bodyOf(in), "m.ply");
  EXPECT_EQ(out.find("range_grid"), std::string::npos) << out;
  EXPECT_EQ(out.find("TextureFile"), std::string::npos) << out;
  EXPECT_EQ(out.substr(out.find("end_header")), "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
}

// assimp allocates the items of an element without reading anything when it has no properties.
TEST(PlyCanonical, KnownElementWithItemsButNoPropertiesIsRefused) {
  const std::string in =
      "ply\nformat ascii 1.0\nelement edge 4000000000\n" + std::string(kTriangleAscii);
  EXPECT_NE(plyErrorOf(in).find("line 3: element 'edge' has 4000000000 items but no properties"),
            std::string::npos)
      << plyErrorOf(in);
}

TEST(PlyCanonical, HeaderLinesOutsideTheFormatAreRefusedNamingTheLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty quaternion q\nend_header\n",
       "line 4: expected a PLY type"},
      {"ply\nformat ascii 1.0\nelement face 1\nproperty list float int i\nend_header\n",
       "line 4: expected an integer type for a list's length, got 'float'"},
      {"ply\nformat ascii 1.0\nelement vertex -3\nend_header\n",
       "line 3: expected a count of element 'vertex' from 0 to 4294967295, got '-3'"},
      {"ply\nformat ascii 1.0\nelement vertex 42949672963\nend_header\n", "got '42949672963'"},
      {"ply\nformat ascii 1.0\nelement vertex 0x10\nend_header\n", "got '0x10'"},
      {"ply\nformat ascii 1.0\nelement vertex 3 9\nend_header\n",
       "line 3: expected 'element NAME COUNT'"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement vertex 1\n"
       "end_header\n",
       "line 5: element 'vertex' is declared twice"},
      {"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
       "line 3: expected an element line before a property"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n",
       "line 4: expected 'property TYPE NAME'"},
      {"ply\nformat foo 1.0\nend_header\n", "line 2: expected format ascii"},
      {"ply\nelement vertex 1\nproperty float x\nend_header\n",
       "PLY header: expected a line 'format ascii 1.0'"},
      {"ply\nformat ascii 1.0\nelement vertex\v 1\nend_header\n",
       "line 3: expected printable text, got 'element vertex\\x0B 1'"},
      {"ply\nformat ascii 1.0\nelements vertex 1\nend_header\n",
       "line 3: expected format, element, property, comment or obj_info, got 'elements'"},
      {"plyx\nformat ascii 1.0\nend_header\n", "line 1: expected the line 'ply'"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string message = plyErrorOf(text);
    EXPECT_EQ(message.rfind("m.ply: PLY header", 0), 0u) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << text << "\n" << message;
  }
}

TEST(PlyCanonical, AsciiValuesThatAreNotNumbersOfTheirTypeAreRefused) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty uchar red\n"
      "end_header\n";
  EXPECT_EQ(plyErrorOf(header + "1.5 255\n"), "<no error>");
  EXPECT_NE(plyErrorOf(header + "1.5x 255\n").find("expected a number (float) for property 'x'"),
            std::string::npos);
  EXPECT_NE(plyErrorOf(header + "nan(1) 255\n").find("for property 'x'"), std::string::npos);
  EXPECT_NE(plyErrorOf(header + "1.5 2.5\n")
                .find("expected an integer >= 0 (uchar) for property "
                      "'red', got '2.5'"),
            std::string::npos);
  EXPECT_NE(plyErrorOf(header + "1.5 -1\n").find("expected an integer >= 0"), std::string::npos);
  EXPECT_NE(plyErrorOf(header + "+-1.5 1\n").find("for property 'x'"), std::string::npos);
  const std::string list =
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  EXPECT_NE(plyErrorOf(list + "3x 0 1 2\n").find("expected a list length from 0 to 4294967295"),
            std::string::npos);
  EXPECT_NE(plyErrorOf(list + "3 0 1\n").find("the data ends inside its list"), std::string::npos);
}

}  // namespace
}  // namespace cdb
