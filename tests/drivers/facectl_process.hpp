#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace facectl::testing {

// Runs the built `facectl` with `args` (shell words); returns its exit code,
// and its stdout and stderr together in `out`.
inline int run_facectl(const std::string& args, std::string& out) {
  const std::string path = "/tmp/facectl-test-run-" + std::to_string(getpid()) + ".txt";
  const int status =
      std::system((std::string(FACECTL_BINARY) + " " + args + " >" + path + " 2>&1").c_str());
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  out = s.str();
  std::remove(path.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace facectl::testing
