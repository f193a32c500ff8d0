#pragma once

#include <string>

namespace facectl {

// Where facectl finds the files it ships (README, "Install and run as a
// service"). A program that runs from inside the build tree it was built in
// (tests, `make run`, build/firmware-host/facectl) reads the source tree's
// folders, as it always has; any other copy of it (an installed one) reads the
// installed folders. Which one a program is decides itself from
// /proc/self/exe, so the same binary, copied by `cmake --install` or a
// package, needs no other build.
struct ShippedDirs {
  std::string config;   // the runtime file, heads, rigs, expressions, shows, fap/
  std::string console;  // the operator web console's static files
};

// The build tree's and the installed folders, and the choice between them.
// `exe` is the running program's canonical path and `build_dir` the build
// tree's: the build tree's folders when `exe` lies under `build_dir` and the
// source tree's config folder exists, else the installed ones.
struct ShippedDirChoice {
  std::string build_dir;
  ShippedDirs source;
  ShippedDirs installed;
};
ShippedDirs choose_shipped_dirs(const std::string& exe, const ShippedDirChoice& choice);

// The choice above for this program, with the folders compiled in.
ShippedDirs shipped_dirs();

// $FACECTL_CONFIG when set, else shipped_dirs().config + "/facectl.yaml":
// /etc/facectl/facectl.yaml installed with prefix /usr, the source tree's
// config/facectl.yaml from the build tree.
std::string default_config_path();

}  // namespace facectl
