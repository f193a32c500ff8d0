// Which shipped folders a program reads (firmware-host/config/config_location.hpp):
// the source tree's when it runs from inside its build tree, the installed ones
// otherwise, so that an installed copy never reads a source tree.
#include "firmware-host/config/config_location.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace facectl {
namespace {

namespace fs = std::filesystem;

class ConfigLocation : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string templ = "/tmp/facectl-test-location-XXXXXX";
    ASSERT_NE(mkdtemp(templ.data()), nullptr);
    root_ = templ;
    fs::create_directories(root_ / "src/config");
    fs::create_directories(root_ / "src/build/firmware-host");
    choice_ = {(root_ / "src/build").string(),
               {(root_ / "src/config").string(), (root_ / "src/console").string()},
               {"/etc/facectl", "/usr/share/facectl/console"}};
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string config_for(const fs::path& exe) const {
    return choose_shipped_dirs(exe.string(), choice_).config;
  }

  fs::path root_;
  ShippedDirChoice choice_;
};

TEST_F(ConfigLocation, BuildTreeBinaryReadsTheSourceTree) {
  EXPECT_EQ(config_for(root_ / "src/build/firmware-host/facectl"), choice_.source.config);
  EXPECT_EQ(choose_shipped_dirs((root_ / "src/build/tests/t").string(), choice_).console,
            choice_.source.console);
  // The way /proc/self/exe names a binary replaced while it runs.
  EXPECT_EQ(config_for(root_ / "src/build/firmware-host/facectl (deleted)"), choice_.source.config);
}

TEST_F(ConfigLocation, InstalledBinaryReadsTheInstalledFolders) {
  EXPECT_EQ(config_for("/usr/bin/facectl"), "/etc/facectl");
  EXPECT_EQ(choose_shipped_dirs("/usr/bin/facectl", choice_).console, "/usr/share/facectl/console");
  // A DESTDIR or a copy next to the build tree is not in it: not a prefix of the name.
  fs::create_directories(root_ / "src/build-staged/usr/bin");
  EXPECT_EQ(config_for(root_ / "src/build-staged/usr/bin/facectl"), "/etc/facectl");
  EXPECT_EQ(config_for(root_ / "src/build/../stage/facectl"), "/etc/facectl");
  EXPECT_EQ(config_for(""), "/etc/facectl");  // /proc/self/exe unreadable
}

TEST_F(ConfigLocation, BuildTreeWithoutItsSourceReadsTheInstalledFolders) {
  fs::remove_all(root_ / "src/config");
  EXPECT_EQ(config_for(root_ / "src/build/firmware-host/facectl"), "/etc/facectl");
}

TEST_F(ConfigLocation, SymlinkedBuildTreeIsStillTheBuildTree) {
  fs::create_directory_symlink(root_ / "src/build", root_ / "link");
  choice_.build_dir = (root_ / "link").string();
  EXPECT_EQ(config_for(root_ / "src/build/firmware-host/facectl"), choice_.source.config);
}

// This test binary runs from the build tree: it and `make run` read the
// source tree's config, as before, unless $FACECTL_CONFIG names another file.
TEST(ConfigLocationOfThisBinary, IsTheSourceTree) {
  EXPECT_EQ(fs::path(shipped_dirs().config), fs::path(FACECTL_SOURCE_DIR) / "config");
  const char* env = std::getenv("FACECTL_CONFIG");
  if (env == nullptr) {
    EXPECT_EQ(fs::path(default_config_path()),
              fs::path(FACECTL_SOURCE_DIR) / "config" / "facectl.yaml");
  }
}

}  // namespace
}  // namespace facectl
