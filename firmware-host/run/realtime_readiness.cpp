#include "firmware-host/run/realtime_readiness.hpp"

#include <fstream>
#include <optional>
#include <sstream>

namespace facectl {
namespace {

std::optional<std::string> read_trimmed(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// Whether `cpu` is in a kernel CPU list such as "1,3-5" (an empty list holds none).
bool in_cpu_list(const std::string& list, int cpu) {
  std::stringstream s(list);
  std::string part;
  while (std::getline(s, part, ',')) {
    const auto dash = part.find('-');
    try {
      const int lo = std::stoi(part.substr(0, dash));
      const int hi = dash == std::string::npos ? lo : std::stoi(part.substr(dash + 1));
      if (cpu >= lo && cpu <= hi) return true;
    } catch (const std::exception&) {
      return false;
    }
  }
  return false;
}

// Whether bit `cpu` is set in a hexadecimal CPU mask such as "3" or "ff,ffffffff".
bool in_cpu_mask(std::string mask, int cpu) {
  std::erase(mask, ',');
  int bit = 0;
  for (auto it = mask.rbegin(); it != mask.rend(); ++it, bit += 4) {
    const char c = *it;
    const int nibble = c >= '0' && c <= '9'   ? c - '0'
                       : c >= 'a' && c <= 'f' ? c - 'a' + 10
                       : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                              : 0;
    if (cpu >= bit && cpu < bit + 4) return ((nibble >> (cpu - bit)) & 1) != 0;
  }
  return false;
}

}  // namespace

std::vector<std::string> realtime_gaps(const RealtimeSettings& settings, const std::string& root) {
  std::vector<std::string> gaps;
  const std::string r = root.empty() || root.back() == '/' ? root : root + "/";
  if (settings.priority <= 0) {
    gaps.emplace_back("runtime.realtime.priority is 0: the loop runs at normal priority");
  }
  if (read_trimmed(r + "sys/kernel/realtime").value_or("0") != "1") {
    gaps.emplace_back(
        "the kernel is not PREEMPT_RT (/sys/kernel/realtime): a kernel code path can delay the "
        "loop's wake-up by milliseconds; install linux-image-rt-amd64 (or -arm64)");
  }
  if (settings.cpu < 0) {
    gaps.emplace_back(
        "runtime.realtime.cpu is -1: the loop shares every CPU with the rest of the machine");
  } else {
    const std::string cpu = std::to_string(settings.cpu);
    if (!in_cpu_list(read_trimmed(r + "sys/devices/system/cpu/isolated").value_or(""),
                     settings.cpu)) {
      gaps.push_back("CPU " + cpu +
                     " (the loop's) is not isolated: other processes run on it; boot with "
                     "isolcpus=" +
                     cpu + " nohz_full=" + cpu + " rcu_nocbs=" + cpu);
    }
    if (const auto mask = read_trimmed(r + "proc/irq/default_smp_affinity");
        mask && in_cpu_mask(*mask, settings.cpu)) {
      gaps.push_back("device interrupts may land on CPU " + cpu +
                     " (/proc/irq/default_smp_affinity is " + *mask +
                     "): set irqaffinity= on the kernel command line, or stop irqbalance and "
                     "write the other CPUs' mask to /proc/irq/*/smp_affinity");
    }
    const auto governor =
        read_trimmed(r + "sys/devices/system/cpu/cpu" + cpu + "/cpufreq/scaling_governor");
    if (governor && *governor != "performance") {
      gaps.push_back("CPU " + cpu + " scales its frequency (governor " + *governor +
                     "): set it to performance");
    }
  }
  return gaps;
}

}  // namespace facectl
