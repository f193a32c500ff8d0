// What `facectl run` warns about at start: the machine's real-time set-up,
// read from the kernel's files. Here from fake trees, so every case is covered
// whatever machine runs the test.
#include "firmware-host/run/realtime_readiness.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace facectl {
namespace {

namespace fs = std::filesystem;

class FakeKernel {
 public:
  FakeKernel() {
    root_ = fs::temp_directory_path() /
            ("facectl-readiness-" + std::to_string(::getpid()) + "-" + std::to_string(++count_));
    fs::remove_all(root_);
  }
  ~FakeKernel() { fs::remove_all(root_); }
  void write(const std::string& path, const std::string& text) {
    fs::create_directories((root_ / path).parent_path());
    std::ofstream(root_ / path) << text << "\n";
  }
  std::string root() const { return root_.string(); }

  // A machine set up as docs/REALTIME.md says, for the loop on CPU 1.
  void prepared() {
    write("sys/kernel/realtime", "1");
    write("sys/devices/system/cpu/isolated", "1");
    write("proc/irq/default_smp_affinity", "1");
    write("sys/devices/system/cpu/cpu1/cpufreq/scaling_governor", "performance");
  }

 private:
  fs::path root_;
  static inline int count_ = 0;
};

RealtimeSettings on_cpu(int cpu) {
  RealtimeSettings s;
  s.cpu = cpu;
  return s;
}

bool mentions(const std::vector<std::string>& gaps, const std::string& text) {
  for (const auto& g : gaps) {
    if (g.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(RealtimeReadiness, APreparedMachineHasNothingToWarnAbout) {
  FakeKernel k;
  k.prepared();
  EXPECT_TRUE(realtime_gaps(on_cpu(1), k.root()).empty());
}

// The gaps of a prepared machine (loop on CPU 1) with one kernel file changed.
std::vector<std::string> gaps_with(const std::string& path, const std::string& text) {
  FakeKernel k;
  k.prepared();
  k.write(path, text);
  return realtime_gaps(on_cpu(1), k.root());
}

TEST(RealtimeReadiness, EachMissingPieceIsNamedWithWhatToDo) {
  const struct {
    const char* path;
    const char* text;
    const char* says;
  } cases[] = {
      {"sys/kernel/realtime", "0", "install linux-image-rt"},
      {"sys/devices/system/cpu/isolated", "2-3", "isolcpus=1"},
      {"proc/irq/default_smp_affinity", "ff,ffffffff", "interrupts may land on CPU 1"},
      {"sys/devices/system/cpu/cpu1/cpufreq/scaling_governor", "powersave", "governor powersave"},
  };
  for (const auto& c : cases) {
    const auto gaps = gaps_with(c.path, c.text);
    ASSERT_EQ(gaps.size(), 1u) << c.path;
    EXPECT_TRUE(mentions(gaps, c.says)) << gaps[0];
  }
}

TEST(RealtimeReadiness, ReadsKernelCpuListsAndMasks) {
  FakeKernel k;
  k.prepared();
  k.write("sys/devices/system/cpu/isolated", "0,2-5");
  k.write("proc/irq/default_smp_affinity", "00000003");  // CPUs 0 and 1
  k.write("sys/devices/system/cpu/cpu4/cpufreq/scaling_governor", "performance");
  EXPECT_TRUE(realtime_gaps(on_cpu(4), k.root()).empty());
  const auto gaps = realtime_gaps(on_cpu(1), k.root());
  EXPECT_TRUE(mentions(gaps, "not isolated"));
  EXPECT_TRUE(mentions(gaps, "interrupts may land on CPU 1"));
}

TEST(RealtimeReadiness, NoPinnedCpuOrNoPriorityIsAGapItself) {
  FakeKernel k;
  k.prepared();
  EXPECT_TRUE(mentions(realtime_gaps(on_cpu(-1), k.root()), "cpu is -1"));
  RealtimeSettings s = on_cpu(1);
  s.priority = 0;
  EXPECT_TRUE(mentions(realtime_gaps(s, k.root()), "normal priority"));
}

}  // namespace
}  // namespace facectl
