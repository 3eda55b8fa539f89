// A cell claim (cdbench run --balance) is held by one holder at a time, across processes, and
// claims nothing once its process has ended, however it ended.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "harness/run/CellClaim.h"
#include "tests/common/FreshTempDir.h"

namespace fs = std::filesystem;

namespace {

fs::path claimFile(const fs::path& dir, const std::string& key) {
  return dir / "claims" / (key + ".lock");
}

TEST(CellClaim, OneHolderAtATimeAndFinishRemovesTheFile) {
  const auto dir = cdb::test::freshTempDir("claim_one");
  auto first = cdb::CellClaim::take(dir, "o-_r0_cullide_64");
  ASSERT_TRUE(first.has_value());
  EXPECT_FALSE(cdb::CellClaim::take(dir, "o-_r0_cullide_64").has_value());
  EXPECT_TRUE(cdb::CellClaim::take(dir, "o-_r0_cullide_96").has_value());  // another cell
  // Let go without finishing: the file stays and claims nothing.
  first.reset();
  EXPECT_TRUE(fs::exists(claimFile(dir, "o-_r0_cullide_64")));
  auto second = cdb::CellClaim::take(dir, "o-_r0_cullide_64");
  ASSERT_TRUE(second.has_value());
  second->finish();
  EXPECT_FALSE(fs::exists(claimFile(dir, "o-_r0_cullide_64")));
  EXPECT_TRUE(cdb::CellClaim::take(dir, "o-_r0_cullide_64").has_value());
  fs::remove_all(dir);
}

TEST(CellClaim, AnotherProcesssClaimHoldsUntilItEnds) {
  const auto dir = cdb::test::freshTempDir("claim_process");
  int ready[2], done[2];
  ASSERT_EQ(::pipe(ready), 0);
  ASSERT_EQ(::pipe(done), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // Holds the claim until told, then ends without letting it go (as a killed share would).
    auto claim = cdb::CellClaim::take(dir, "o-_r1_ours_800");
    const char ok = claim ? '1' : '0';
    (void)!::write(ready[1], &ok, 1);
    char go;
    (void)!::read(done[0], &go, 1);
    std::_Exit(0);
  }
  char ok = 0;
  ASSERT_EQ(::read(ready[0], &ok, 1), 1);
  ASSERT_EQ(ok, '1');
  EXPECT_FALSE(cdb::CellClaim::take(dir, "o-_r1_ours_800").has_value());
  (void)!::write(done[1], "x", 1);
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(fs::exists(claimFile(dir, "o-_r1_ours_800")));  // left behind, claiming nothing
  EXPECT_TRUE(cdb::CellClaim::take(dir, "o-_r1_ours_800").has_value());
  fs::remove_all(dir);
}

}  // namespace
