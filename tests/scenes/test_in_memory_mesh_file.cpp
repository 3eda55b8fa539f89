// The file system the in-memory mesh loader gives assimp: one file, read-only, one reader at a
// time, so that nothing a mesh refers to (a material library, the mesh itself) can be opened.
#include <gtest/gtest.h>

#include <array>
#include <assimp/IOStream.hpp>
#include <cstddef>
#include <memory>
#include <string>

#include "scenes/InMemoryMeshFile.h"

namespace cdb {
namespace {

TEST(InMemoryMeshFile, HoldsItsOneFileReadOnlyForOneReaderAtATime) {
  const std::array<std::byte, 4> bytes{std::byte{'a'}, std::byte{'b'}, std::byte{'c'},
                                       std::byte{'d'}};
  InMemoryMeshFile files("mesh.obj", bytes);
  EXPECT_TRUE(files.Exists("mesh.obj"));
  for (const char* other : {"mesh.mtl", "mesh", "./mesh.obj", "MESH.OBJ", "", "/etc/passwd"}) {
    EXPECT_FALSE(files.Exists(other)) << other;
    EXPECT_EQ(files.Open(other), nullptr) << other;
  }
  EXPECT_FALSE(files.Exists(nullptr));
  for (const char* write : {"wb", "w", "ab", "r+b"})
    EXPECT_EQ(files.Open("mesh.obj", write), nullptr);

  Assimp::IOStream* first = files.Open("mesh.obj");
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->FileSize(), bytes.size());
  std::array<char, 4> read{};
  EXPECT_EQ(first->Read(read.data(), 1, read.size()), read.size());
  EXPECT_EQ(std::string(read.data(), read.size()), "abcd");
  EXPECT_EQ(files.Open("mesh.obj"), nullptr) << "a second reader while the first is open";
  files.Close(first);

  // Deleted without Close, as an importer's unique_ptr may do: the file can be opened again.
  std::unique_ptr<Assimp::IOStream> second(files.Open("mesh.obj"));
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(files.Open("mesh.obj"), nullptr);
  second.reset();
  Assimp::IOStream* third = files.Open("mesh.obj", "rt");
  EXPECT_NE(third, nullptr);
  files.Close(third);
}

}  // namespace
}  // namespace cdb
