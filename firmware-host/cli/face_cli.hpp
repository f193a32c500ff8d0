// `facectl face ...`: render, reduce and export-obj for the face model (sim/face).
#pragma once

#include <CLI/CLI.hpp>

void register_face_commands(CLI::App& app);
