// `facectl face reduce` (fit the reduced model to the full model) and `facectl face
// check-reduced` (the shipped reduced model's error on the named test sets).
#pragma once

#include <CLI/CLI.hpp>

void add_reduce_commands(CLI::App* face);
