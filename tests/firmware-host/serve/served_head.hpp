#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/serve/serve_session.hpp"
#include "tests/support/temp_dir.hpp"

namespace facectl::testing {

// The default head served on simulated hardware, as `facectl serve` runs it
// but in this process: its shows are the
// shipped demo plus whatever a test writes into shows().
class ServedHead {
 public:
  explicit ServedHead(const std::string& config = std::string(FACECTL_SOURCE_DIR) +
                                                  "/config/facectl.yaml") {
    std::filesystem::copy_file(std::string(FACECTL_SOURCE_DIR) + "/config/shows/demo.yaml",
                               shows_.file("demo.yaml"));
    s_.head.cfg = std::make_unique<LoadedConfig>(load_config(config));
    RuntimeConfig& rt = s_.head.cfg->runtime;
    // SCHED_FIFO where permitted (root, as in CI), as `facectl serve` runs:
    // at normal priority a busy machine (a sanitizer build) faults the loop
    // on missed deadlines. Not pinned, nor memory-locked: this is the test's
    // own process.
    rt.realtime.cpu = -1;
    rt.realtime.lock_memory = false;
    rt.realtime.cpu_dma_latency_us = -1;
    rt.serve.shows_dir = shows_.path();
    open_serve_session(s_, logs_.file("events.jsonl"));
    start_serve_session(s_);
  }
  ~ServedHead() { stop_serve_session(s_); }
  ServedHead(const ServedHead&) = delete;
  ServedHead& operator=(const ServedHead&) = delete;

  HeadService& service() { return *s_.service; }
  ServeSession& session() { return s_; }
  const TempDir& shows() const { return shows_; }
  std::string log_path() const { return logs_.file("events.jsonl"); }

  // Waits up to `seconds` for the state; true if it was reached.
  bool wait_for(SafetyState state, double seconds = 5.0) {
    return testing::wait_until([&] { return service().state() == state; }, seconds);
  }

 private:
  TempDir shows_;
  TempDir logs_;
  ServeSession s_;
};

// A runtime file in `dir` for a copy of the default head (with or without its reduced
// face model, reduced_face.txt) on the shipped rig `rig` ("hobby.yaml"), or on the rig
// file at the absolute path `rig` (kTermsOnlyRig reads no control points, so the head
// needs no reduced model).
inline const std::string kTermsOnlyRig =
    std::string(FACECTL_SOURCE_DIR) + "/tests/data/rigs/hobby_terms.yaml";

inline std::string copied_head_config(const TempDir& dir, const std::string& rig,
                                      bool with_reduced_model) {
  namespace fs = std::filesystem;
  const std::string src = std::string(FACECTL_SOURCE_DIR) + "/config/";
  fs::create_directory(dir.file("head"));
  for (const auto& f : fs::directory_iterator(src + "heads/default")) {
    if (!with_reduced_model && f.path().filename() == "reduced_face.txt") continue;
    fs::copy_file(f.path(), fs::path(dir.file("head")) / f.path().filename());
  }
  const std::string rig_path = rig.starts_with('/') ? rig : src + "rigs/" + rig;
  dir.write("facectl.yaml", "head: " + dir.file("head/head.yaml") + "\nrig: " + rig_path +
                                "\nexpressions: " + src + "expressions/library.yaml\nshow: " + src +
                                "shows/demo.yaml\n");
  return dir.file("facectl.yaml");
}

}  // namespace facectl::testing
