#!/usr/bin/env bash
# The test suite under clang's sanitizers (docs/FUZZING.md, "Sanitizer builds"):
#
#   asan  ASan + UBSan (-fno-sanitize-recover: the first finding fails the
#         test) of the whole suite, run with ctest. The allocation tests are
#         not built there (tests/CMakeLists.txt says why). The tree is the
#         fuzz build (FACECTL_FUZZ), so scripts/fuzz.sh can reuse it.
#   tsan  TSan of the test binaries whose code runs threads, run directly, two at a time:
#         the lock-free mailbox and ring (facectl_control_tests), the
#         real-time loop and its threads through the facectl program
#         (facectl_process_tests, which runs the instrumented facectl), the
#         Modbus I/O thread and the gamepad reader (facectl_driver_tests), the
#         FAP UDP receiver thread (facectl_fap_tests), the show player
#         (facectl_host_tests), `facectl serve`'s threads: the face command
#         source, the monitor, the HTTP workers and the OSC receiver
#         (facectl_serve_tests), and the input layer's threads: the Live Link
#         Face receiver, the mixer and its sources (facectl_input_tests; not
#         its FACS geometry, which runs the face model on one thread), and
#         the face model's runs spread over threads for `face reduce` and
#         `check-reduced` (face_thread_tests).
#
# Usage: scripts/sanitize.sh [asan|tsan|all]   (default all)
# Build directories: build-asan and build-tsan (BUILD_ASAN, BUILD_TSAN).
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-all}"
BUILD_ASAN="${BUILD_ASAN:-build-asan}"
BUILD_TSAN="${BUILD_TSAN:-build-tsan}"
JOBS="${JOBS:-$(nproc)}"

configure() {  # dir cmake-options...
  local dir="$1"
  shift
  cmake -S . -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Sanitize \
    -DFACECTL_LTO=OFF -DFACECTL_WERROR=ON "$@" >/dev/null
}

# Every report is fatal and names its stack; a leak is a finding too.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# Leaks inside PocketSphinx, which we cannot fix, are suppressed (the file says which).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/tests/sanitizers/lsan.supp}"
tsan_supp="$PWD/tests/sanitizers/tsan.supp"

run_asan() {
  local t0=$SECONDS
  # FACECTL_FUZZ is ASan + UBSan (and the fuzzer's coverage) of the whole
  # tree: the same tree then holds the fuzz targets scripts/fuzz.sh runs, so
  # the CI compiles the instrumented sources once for both.
  configure "$BUILD_ASAN" -DFACECTL_FUZZ=ON -DFACECTL_BUILD_TESTS=ON
  cmake --build "$BUILD_ASAN" -j "$JOBS"
  # Not the QEMU guest test (label qemu): its CAN drives and boards keep
  # heartbeat and watchdog deadlines of 100 ms, which an ASan build on an
  # emulated CPU misses (heartbeat lost, watchdog tripped) whenever the host
  # is busy. Nor the install and package test (label deploy): it packages
  # the program, which an instrumented build tests no further. Nor the
  # console's browser test (label browser): it tests the page, in a Chromium
  # nothing instruments. The ordinary suite runs all three.
  # Nor long repeats of code that shorter tests run instrumented too
  # (the fit, the mechanism solver, the rendered simulate run and the render
  # sequence): they took 170 s of the 45-minute CI budget under ASan.
  local repeats='ReducedFaceModel.FitTracksTheFullModelOnHeldOutInputs'
  repeats+='|MandibleMechanism.UnreachableTargetsGoToTheNearestReachablePose'
  repeats+='|Simulate.TwoRenderedRunsGiveByteIdenticalFrames'
  repeats+='|RenderSequenceTest.WritesFramesWithIdenticalBytesOnASecondRun'
  # Nor the FACS action units on the full face model: 30 runs of the face
  # model code that face_tests run instrumented, about 80 s of test time.
  repeats+='|ActionUnitGeometry\.'
  # Nor the shipped model's channel proofs, 8 channels at a million boxes
  # (125 s): the bound's code runs instrumented in ChannelBound.* and, on the
  # shipped rig, in Verify.*. Nor the library run to steady state once more
  # (40 s; the expression tests do it), nor place-actuators at three budgets
  # (24 s; ChoosesLipCornersAndBrows runs the same code).
  repeats+='|ChannelBoundShippedModel\.(SoundAndTight|CoupledLimitsOnlyNarrow)'
  repeats+='|SteadyState\.EveryLibraryExpressionSettles'
  repeats+='|ActuatorPlacement\.ErrorFallsAsTheBudgetGrows'
  # The long randomised tests stay in, with a tenth of their samples
  # (tests/support/sample_count.hpp): each is the only instrumented run of
  # its code (the mechanism range proof, the actuator coupled limits through
  # faults, verify's adversarial search), and a tenth still takes every
  # path. In full they took 196 s of the suite's test time; a tenth takes
  # 27 s of CPU where the full count took 149 s (docs/FUZZING.md, "In CI").
  ctest --test-dir "$BUILD_ASAN" --output-on-failure -j "$JOBS" -LE 'qemu|deploy|browser' \
    -E "$repeats"
  echo "sanitize: asan+ubsan suite passed in $((SECONDS - t0)) s"
}

# Two lanes, one per core, each about half of the 200 s the binaries took
# one after another: they mostly wait on their loops, sockets and timeouts,
# and each took as long beside the other lane as alone. Not three: a third
# instrumented program on the two cores starved the 1 kHz loop of an input
# test's `facectl run` (the audio lead test) into an overrun FAULT at enable.
# The serve and the process tests, which run the loop in `facectl`, start in
# different lanes, as ctest -j2 runs them in the ASan suite.
tsan_lanes=("facectl_serve_tests facectl_driver_tests facectl_fap_tests facectl_host_tests"
            "facectl_process_tests facectl_input_tests facectl_control_tests face_thread_tests")
# The FACS geometry runs the full face model 30 times on one thread: minutes
# under TSan and nothing a race could hide in.
declare -A tsan_filter=([facectl_input_tests]='-ActionUnitGeometry.*')
tsan_lane() {  # log binaries...: runs them in turn, stops at the first that fails
  local log="$1" b
  shift
  for b in "$@"; do
    echo "sanitize: tsan $b"
    # ctest's working directory for these binaries.
    (cd "$BUILD_TSAN/tests" && "./$b" --gtest_brief=1 --gtest_filter="${tsan_filter[$b]:-*}") ||
      { echo "sanitize: tsan failed: $b"; return 1; }
  done >"$log" 2>&1
}
run_tsan() {
  local t0=$SECONDS
  configure "$BUILD_TSAN" -DFACECTL_SANITIZE=thread
  # shellcheck disable=SC2086,SC2048  # the lanes are word lists
  cmake --build "$BUILD_TSAN" -j "$JOBS" --target facectl ${tsan_lanes[*]}
  export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$tsan_supp}"
  local pids=() i status=0
  rm -f "$BUILD_TSAN"/tsan-lane-*.log
  for i in "${!tsan_lanes[@]}"; do
    # shellcheck disable=SC2086
    tsan_lane "$BUILD_TSAN/tsan-lane-$i.log" ${tsan_lanes[$i]} &
    pids+=($!)
  done
  for i in "${!pids[@]}"; do wait "${pids[$i]}" || status=1; done
  cat "$BUILD_TSAN"/tsan-lane-*.log
  if [ "$status" -ne 0 ]; then
    echo "sanitize: tsan failed (see above)" >&2
    return 1
  fi
  echo "sanitize: tsan passed in $((SECONDS - t0)) s"
}

case "$what" in
  asan) run_asan ;;
  tsan) run_tsan ;;
  all) run_asan; run_tsan ;;
  *) echo "usage: $0 [asan|tsan|all]" >&2; exit 2 ;;
esac
