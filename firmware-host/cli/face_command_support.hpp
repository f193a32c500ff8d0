// What the `facectl face` subcommands share: the head and library options, the model at
// a requested skin resolution, and the rule that unusable input exits 2 with its
// file:line message.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "facectl/face/face_model.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/input_error.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl::face_cli {

// Pictures default to the head's finest variant: at the base mesh's 468 vertices
// sadness, disgust and fear barely differ from neutral (issue #20).
constexpr int kLargestVariant = -1;

struct FaceArgs {
  std::string head;     // default: the shipped default head
  std::string library;  // default: the shipped expression library
  int frames = 300;
  int resolution = 0;
};

// The shipped head and library, frames 300, the base mesh.
FaceArgs default_face_args();

// --head, --library, --frames and --resolution, bound to `a`.
void add_common(CLI::App* c, FaceArgs& a);
// For commands that run each input to a steady state: --frames is a cap, with this default.
void cap_frames_option(CLI::App* c, int default_cap);
// --passes N: N skin iterations and N muscle passes a frame in each run to steady state.
void passes_option(CLI::App* c, face::SolverPasses& passes);

// The model at the requested skin resolution (kLargestVariant: face.yaml's largest); a
// count the base mesh cannot be refined to is an error rather than a silent fallback.
face::FaceModel build_model(const face::HeadSpec& spec, int resolution);

// Writes `text` to `path`; InputError when it cannot.
void write_text_file(const std::string& path, const std::string& text);

// Runs `body`; unusable input (a head, library or mesh file that cannot be read or is
// malformed) becomes exit code 2 with its file:line message, prefixed by the subcommand.
template <class F>
void guarded(const char* command, F&& body) {
  auto fail = [command](const std::exception& e) {
    std::fprintf(stderr, "facectl face %s: %s\n", command, e.what());
    throw CLI::RuntimeError(2);
  };
  try {
    body();
  } catch (const face::InputError& e) {
    fail(e);
  } catch (const ConfigError& e) {
    fail(e);
  } catch (const std::invalid_argument& e) {
    fail(e);
  } catch (const std::filesystem::filesystem_error& e) {
    fail(e);
  }
}

}  // namespace facectl::face_cli
