// StagedDir: an output folder appears whole or not at all, and replacing an
// earlier output never loses it when the replacement fails.
#include "firmware-host/simulate/staged_dir.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "simulate_process.hpp"

namespace facectl {
namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// An earlier output folder "out" holding old.txt.
fs::path earlier_output(const testing::TempDir& tmp) {
  const fs::path out = tmp.path() / "out";
  fs::create_directories(out);
  write_file(out / "old.txt", "old");
  return out;
}

TEST(StagedDir, CommitReplacesAnEarlierOutputAndLeavesNothingAside) {
  testing::TempDir tmp;
  const fs::path out = earlier_output(tmp);
  {
    StagedDir staged(out);
    write_file(staged.path() / "new.txt", "new");
    EXPECT_TRUE(fs::exists(out / "old.txt"));  // untouched until commit
    staged.commit();
  }
  EXPECT_EQ(read_file(out / "new.txt"), "new");
  EXPECT_FALSE(fs::exists(out / "old.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 1)
      << "a staging or previous folder was left beside the output";
}

TEST(StagedDir, AFailedCommitKeepsTheEarlierOutput) {
  testing::TempDir tmp;
  const fs::path out = earlier_output(tmp);
  StagedDir staged(out);
  write_file(staged.path() / "new.txt", "new");
  fs::remove_all(staged.path());  // the rename into place now fails
  EXPECT_THROW(staged.commit(), fs::filesystem_error);
  EXPECT_EQ(read_file(out / "old.txt"), "old");
}

TEST(StagedDir, AnOutputLeftAsideByACrashIsTheEarlierOutput) {
  // A run that died between moving DIR aside and renaming the new one in
  // left only ".out.previous": it is put back, never deleted unreplaced.
  testing::TempDir tmp;
  const fs::path out = tmp.path() / "out";
  const fs::path aside = tmp.path() / ".out.previous";
  fs::create_directories(aside);
  write_file(aside / "old.txt", "old");
  {
    StagedDir staged(out);
    write_file(staged.path() / "new.txt", "new");
    fs::remove_all(staged.path());  // the rename into place fails
    EXPECT_THROW(staged.commit(), fs::filesystem_error);
  }
  EXPECT_EQ(read_file(out / "old.txt"), "old");
  {
    StagedDir staged(out);
    write_file(staged.path() / "new.txt", "new");
    staged.commit();
  }
  EXPECT_EQ(read_file(out / "new.txt"), "new");
  EXPECT_FALSE(fs::exists(aside));
}

TEST(StagedDir, WithoutCommitTheTargetIsAsItWas) {
  testing::TempDir tmp;
  const fs::path out = tmp.path() / "out";
  {
    StagedDir staged(out);
    write_file(staged.path() / "new.txt", "new");
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(std::distance(fs::directory_iterator(tmp.path()), fs::directory_iterator()), 0);
}

}  // namespace
}  // namespace facectl
