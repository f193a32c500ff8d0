// Throwaway entry point for the face-model worktree; main's facectl replaces it.
#include <CLI/CLI.hpp>

#include "face_cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"facectl (face commands only)"};
  app.require_subcommand(1);
  register_face_commands(app);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
