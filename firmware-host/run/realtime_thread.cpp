#include "firmware-host/run/realtime_thread.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstring>
#include <future>

namespace facectl {
namespace {

// Touches stack pages now so the tick never page-faults on them later.
void prefault_stack() {
  constexpr std::size_t kBytes = std::size_t{256} * 1024;
  unsigned char buffer[kBytes];
  volatile unsigned char* touch = buffer;
  for (std::size_t i = 0; i < kBytes; i += 4096) touch[i] = 0;
}

// The PM QoS request lasts as long as the file stays open: for the process.
bool hold_cpu_dma_latency(int microseconds, std::string& error) {
  static int fd = -1;
  if (fd >= 0) return true;
  fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
  if (fd < 0) {
    error = std::strerror(errno);
    return false;
  }
  const auto value = static_cast<std::int32_t>(microseconds);
  if (write(fd, &value, sizeof value) != static_cast<ssize_t>(sizeof value)) {
    error = std::strerror(errno);
    close(fd);
    fd = -1;
    return false;
  }
  return true;
}

}  // namespace

void keep_off_realtime_cpu(const RealtimeSettings& settings, RealtimeReport& report) {
  if (settings.cpu < 0) return;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return;
  CPU_CLR(static_cast<unsigned>(settings.cpu), &set);
  if (CPU_COUNT(&set) == 0) {
    report.warnings.push_back("only CPU " + std::to_string(settings.cpu) +
                              " is available: other threads share it with the loop");
    return;
  }
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);
}

std::thread start_realtime_thread(const RealtimeSettings& settings, std::function<void()> body,
                                  RealtimeReport& report) {
  if (settings.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      report.memory_locked = true;
    } else {
      report.warnings.push_back(std::string("mlockall refused (") + std::strerror(errno) +
                                "): memory may page; run as root or raise RLIMIT_MEMLOCK");
    }
  }
  if (settings.cpu_dma_latency_us >= 0) {
    std::string error;
    report.idle_latency_held = hold_cpu_dma_latency(settings.cpu_dma_latency_us, error);
    if (!report.idle_latency_held) {
      report.warnings.push_back("/dev/cpu_dma_latency refused (" + error +
                                "): idle CPUs may sleep deeply and wake late");
    }
  }
  std::promise<void> ready;
  std::future<void> applied = ready.get_future();
  // The promise moves into the thread, so it outlives set_value() there.
  std::thread thread(
      [&settings, &report, ready = std::move(ready), body = std::move(body)]() mutable {
        // Signals are for the other threads: the loop is never interrupted by them.
        sigset_t block;
        sigemptyset(&block);
        sigaddset(&block, SIGINT);
        sigaddset(&block, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &block, nullptr);
        if (settings.priority > 0) {
          sched_param param{};
          param.sched_priority = settings.priority;
          const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
          if (rc == 0) {
            report.fifo = true;
          } else {
            report.warnings.push_back(std::string("SCHED_FIFO priority ") +
                                      std::to_string(settings.priority) + " refused (" +
                                      std::strerror(rc) + "): running with normal scheduling");
          }
        }
        if (settings.cpu >= 0) {
          cpu_set_t set;
          CPU_ZERO(&set);
          CPU_SET(static_cast<unsigned>(settings.cpu), &set);
          const int rc = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
          if (rc == 0) {
            report.pinned = true;
          } else {
            report.warnings.push_back("CPU affinity to CPU " + std::to_string(settings.cpu) +
                                      " refused (" + std::strerror(rc) + "): not pinned");
          }
        }
        prefault_stack();
        ready.set_value();
        body();
      });
  applied.wait();
  return thread;
}

}  // namespace facectl
