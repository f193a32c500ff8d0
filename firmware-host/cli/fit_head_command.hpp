// `facectl face fit-head`: places the default head's landmarks, openings and muscle map
// on a new skin mesh and writes a head folder (sim/face head_fit.hpp, head_writer.hpp).
#pragma once

#include <CLI/CLI.hpp>

void add_fit_head_command(CLI::App* face);
