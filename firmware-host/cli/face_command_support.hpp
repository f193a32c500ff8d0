// What the `facectl face` subcommands share: the head and library options, the model at
// a requested skin resolution, and the rule that unusable input exits 2 with its
// file:line message.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "facectl/face/face_model.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/input_error.hpp"

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

// The model at the requested skin resolution (kLargestVariant: face.yaml's largest); a
// count the base mesh cannot be refined to is an error rather than a silent fallback.
face::FaceModel build_model(const face::HeadSpec& spec, int resolution);

// Writes `text` to `path`; InputError when it cannot.
void write_text_file(const std::string& path, const std::string& text);

// Runs `body`; unusable input becomes exit code 2 with the InputError's file:line message.
template <class F>
void guarded(F&& body) {
  try {
    body();
  } catch (const face::InputError& e) {
    std::fprintf(stderr, "facectl face: %s\n", e.what());
    throw CLI::RuntimeError(2);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "facectl face: %s\n", e.what());
    throw CLI::RuntimeError(2);
  }
}

}  // namespace facectl::face_cli
