// `facectl face clone`: the expression library and visemes of one head carried over to
// another (facial motion cloning, sim/face motion_clone.hpp).
#pragma once

#include <CLI/CLI.hpp>

void add_clone_command(CLI::App* face);
