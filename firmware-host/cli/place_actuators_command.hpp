// `facectl face place-actuators`: a starting rig's control points, chosen to reproduce
// the expression library on the full face model (sim/face actuator_placement.hpp).
#pragma once

#include <CLI/CLI.hpp>

void add_place_actuators_command(CLI::App* face);
