#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

namespace facectl::testing {

// The `facectl` program run as a child process, its stdout and stderr in one file.
struct Child {
  pid_t pid = -1;
  std::string out_path;
};

struct ChildOptions {
  // RLIMIT_FSIZE for the child, a disk that fills up at that size (writes
  // past it fail with EFBIG, as ENOSPC on a full disk).
  rlim_t file_size_limit = RLIM_INFINITY;
  std::vector<std::string> env;  // NAME=VALUE added to the child's environment
};

inline Child spawn_facectl(const std::vector<std::string>& args, const ChildOptions& options = {}) {
  Child c;
  c.out_path = "/tmp/facectl-test-out-" + std::to_string(getpid()) + "-" +
               std::to_string(std::rand()) + ".txt";
  c.pid = fork();
  if (c.pid == 0) {
    FILE* f = std::freopen(c.out_path.c_str(), "w", stdout);
    (void)f;
    dup2(fileno(stdout), STDERR_FILENO);
    if (options.file_size_limit != RLIM_INFINITY) {
      signal(SIGXFSZ, SIG_IGN);  // the write fails instead
      const rlimit lim{options.file_size_limit, options.file_size_limit};
      setrlimit(RLIMIT_FSIZE, &lim);
    }
    std::vector<std::string> env = options.env;
    for (std::string& e : env) putenv(e.data());
    std::vector<char*> argv;
    std::string bin = FACECTL_BINARY;
    argv.push_back(bin.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(bin.c_str(), argv.data());
    _exit(127);
  }
  return c;
}

inline int wait_exit(const Child& c) {
  int status = 0;
  waitpid(c.pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// As wait_exit, but gives up after `seconds`: kills the child and returns -1.
inline int wait_exit_within(const Child& c, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (waitpid(c.pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > until) {
      kill(c.pid, SIGKILL);
      waitpid(c.pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace facectl::testing
