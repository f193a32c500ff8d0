// Throwaway entry point for the face-model worktree; main's facectl replaces it.
// Exit codes: 0 ok, 1 check failed, 2 unusable input or usage.
#include <CLI/CLI.hpp>

#include "face_cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"facectl (face commands only)"};
  app.require_subcommand(1);
  register_face_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {  // thrown by command callbacks with their code
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // help is 0; any usage error is 2
  }
  return 0;
}
