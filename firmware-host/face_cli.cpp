#include "face_cli.hpp"

void register_face_commands(CLI::App& app) { app.add_subcommand("face", "face model tools"); }
