#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz with clang (ASan + UBSan),
# assembles each one's seed corpus from the repository's own files, and runs
# each for FUZZ_SECONDS (docs/FUZZING.md). Exits nonzero on any finding (a
# crash, a sanitizer report, a timeout, an out-of-memory, a leak); the input
# that found it is left in BUILD/fuzz/TARGET/ as crash-*, timeout-*, oom-* or
# leak-*. Prints each target's executions.
#
# Usage: scripts/fuzz.sh [TARGET...]     (default: every target)
#   FUZZ_SECONDS  seconds per target (default 60; .ci/run passes 20 to keep
#                 the CI under its 45 minutes, see the comment there)
#   FUZZ_JOBS     targets run at once (default: the number of CPUs)
#   BUILD_FUZZ    build directory (default build-fuzz); the CI passes
#                 build-asan, which scripts/sanitize.sh asan has built with
#                 the fuzz targets and the tests in one tree
#   FUZZ_NICE     nice level of the fuzzing processes (default 0)
set -euo pipefail
cd "$(dirname "$0")/.."
src="$PWD"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}"
FUZZ_JOBS="${FUZZ_JOBS:-$(nproc)}"
BUILD_FUZZ="${BUILD_FUZZ:-build-fuzz}"
FUZZ_NICE="${FUZZ_NICE:-0}"

all_targets=(runtime_config head_config rig_config expressions show fap_file fap_udp recorded_input
             live_link_face_packet osc_datagram
             telemetry_csv modbus_reply custom_can cia402_can hid_report hid_descriptor
             dynamixel2_status feetech_status)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=("${all_targets[@]}"); fi

# ---- build (a tree configured before keeps its other settings, e.g. tests ON)
cmake_args=(-S . -B "$BUILD_FUZZ" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Sanitize -DFACECTL_FUZZ=ON
            -DFACECTL_LTO=OFF)
if [ ! -f "$BUILD_FUZZ/CMakeCache.txt" ]; then cmake_args+=(-DFACECTL_BUILD_TESTS=OFF); fi
cmake "${cmake_args[@]}" >/dev/null
# facectl too: its `simulate` writes the telemetry CSV that seeds telemetry_csv.
cmake --build "$BUILD_FUZZ" --target facectl "${targets[@]/%/_fuzz}"
out="$PWD/$BUILD_FUZZ/fuzz"

# ---- seeds: rebuilt from the repository on every run
seed() {  # target files...
  local dir="$out/$1/seeds"
  shift
  mkdir -p "$dir"
  for f in "$@"; do cp "$f" "$dir/$(echo "${f#"$src"/}" | tr / _)"; done
}
rm -rf "$out"/*/seeds
seed runtime_config "$src"/config/facectl.yaml
seed head_config "$src"/config/heads/*/head.yaml
seed rig_config "$src"/config/rigs/*.yaml "$src"/tests/firmware-host/verify/rigs/*.yaml
seed expressions "$src"/config/expressions/*.yaml
seed show "$src"/config/shows/*.yaml
# Other players' files too (files/real/PRODUCER/; files/*.fap has Greta's and
# VREng's layouts): what the parser's leniencies are for.
fap_files=("$src"/config/fap/*.fap "$src"/tests/firmware-host/fap/files/*.fap
           "$src"/tests/firmware-host/fap/files/real/*/*.fap)
seed fap_file "${fap_files[@]}"
seed recorded_input "$src"/tests/firmware-host/inputs/real/*/*.{csv,json,tsv,TextGrid}
seed live_link_face_packet "$src"/tests/firmware-host/inputs/real/live_link_face_udp/*.bin
# OSC as python-osc (an independent implementation) encodes it.
python3 "$src"/tests/firmware-host/inputs/peers/osc_peer.py write "$out/osc_datagram/seeds"
seed hid_report  # none: the repository holds no captured reports (libFuzzer starts empty)
# Real pads' descriptors, each as [length, 2 bytes LE][descriptor][a report].
mkdir -p "$out/hid_descriptor/seeds"
for f in "$src"/tests/drivers/hid_descriptors/*.hex; do
  python3 -c 'import sys; d = bytes.fromhex(open(sys.argv[1]).read())
sys.stdout.buffer.write(len(d).to_bytes(2, "little") + d + bytes([1]) + bytes(range(63)))' "$f" \
    >"$out/hid_descriptor/seeds/$(basename "$f" .hex)"
done
seed custom_can  # none: no recorded CAN traffic in the repository
seed cia402_can
seed dynamixel2_status  # none: the e-Manual's status packets are in the unit test
seed feetech_status  # none: the protocol examples are in the unit test
# Every input a finding was fixed for (tests/fuzz/regressions/TARGET) runs again.
for d in "$src"/tests/fuzz/regressions/*/; do
  t=$(basename "$d")
  if [ -d "$out/$t" ] || [ -n "$(ls -A "$d")" ]; then seed "$t" "$d"*; fi
done
# The FAP files again as datagrams (fap_udp splits its input at 0xFF bytes):
# the header, then one frame (mask and values lines) per datagram.
mkdir -p "$out/fap_udp/seeds"
python3 - "$out/fap_udp/seeds" "${fap_files[@]}" <<'PY'
import os, sys
out = sys.argv[1]
for path in sys.argv[2:]:
    lines = [l for l in open(path, encoding="latin-1").read().split("\n")
             if l.strip() and not l.startswith("#")]
    if not lines:
        continue
    grams = [lines[0]] + ["\n".join(lines[i:i + 2]) for i in range(1, len(lines), 2)]
    data = b"\xff".join(g.encode("latin-1") + b"\n" for g in grams[:40])
    name = "_".join(path.split("/")[-2:])  # two players may both have a fear.fap
    open(os.path.join(out, name + ".udp"), "wb").write(data)
PY
# Telemetry as `facectl simulate` records it for the demo show (2 s of it).
sim_out="$out/telemetry_csv/simulate"
"$BUILD_FUZZ/firmware-host/facectl" simulate --rig config/rigs/default.yaml \
  --show config/shows/demo.yaml --out "$sim_out" --duration 2 --quiet >/dev/null
mkdir -p "$out/telemetry_csv/seeds"
cp "$sim_out/telemetry.csv" "$out/telemetry_csv/seeds/demo_telemetry.csv"
head -n 20 "$sim_out/telemetry.csv" >"$out/telemetry_csv/seeds/demo_telemetry_head.csv"
# The same rows with fb. columns, as `facectl run --record` names the measured
# position (simulate writes the plant's as pos.): what `facectl plot` draws.
sed '1s/,pos\./,fb./g' "$out/telemetry_csv/seeds/demo_telemetry_head.csv" \
  >"$out/telemetry_csv/seeds/demo_telemetry_fb.csv"
# Modbus: a good reply to each request ModbusBus makes, from the register map
# of docs/PROTOCOLS.md (unit 1, 8 channels, transaction id 1). The fuzz
# target reads its settings from the input's last bytes (FuzzedDataProvider):
# request, unit - 1, channels - 1, raw type and actuator kind.
mkdir -p "$out/modbus_reply/seeds"
python3 - "$out/modbus_reply/seeds" <<'PY'
import os, struct, sys
out = sys.argv[1]
def mbap(pdu, unit=1, tid=1):
    return struct.pack(">HHHB", tid, 0, len(pdu) + 1, unit) + pdu
def settings(request, unit=1, channels=8):
    # consumed from the end: request, unit, channels, raw, kind
    return bytes([1, 1, channels - 1, unit - 1, request])
regs = [0x0001, 0, 7, 8] + [100 * i for i in range(8)]
replies = {
    "read_inputs": (0, mbap(struct.pack(">BB", 4, 2 * len(regs)) + struct.pack(">%dH" % len(regs), *regs))),
    "write_targets": (1, mbap(struct.pack(">BHH", 0x10, 0, 10))),
    "write_control": (2, mbap(struct.pack(">BHH", 0x10, 0, 1))),
    "write_watchdog": (3, mbap(struct.pack(">BHH", 0x06, 10, 100))),
    "exception": (0, mbap(struct.pack(">BB", 0x84, 2))),
}
for name, (request, reply) in replies.items():
    open(os.path.join(out, name), "wb").write(reply + settings(request))
PY

# ---- run
echo "fuzz: ${#targets[@]} targets, ${FUZZ_SECONDS} s each, ${FUZZ_JOBS} at a time"
run_one() {  # target
  local t="$1" dir="$out/$1"
  mkdir -p "$dir/corpus"
  local rc=0
  # -timeout: one input taking 25 s is a hang (a parse takes milliseconds; the
  # margin is for a shared, busy machine); -rss_limit_mb: 1 GB is an OOM.
  # On an OOM libFuzzer prints a profile of the live heap before it writes the
  # input, which took over 25 minutes at 2 GB: the limit is 1 GB, of which
  # ASan's quarantine of freed blocks takes 64 MB instead of 256. `timeout`
  # ends a target that still overruns; that is a finding, with no input saved.
  ASAN_OPTIONS="quarantine_size_mb=64${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
    timeout --foreground -s KILL "$((FUZZ_SECONDS + 300))" \
    nice -n "$FUZZ_NICE" "$BUILD_FUZZ/tests/fuzz/${t}_fuzz" "$dir/corpus" "$dir/seeds" \
    -max_total_time="$FUZZ_SECONDS" -timeout=25 -rss_limit_mb=1024 -print_final_stats=1 \
    -artifact_prefix="$dir/" >"$dir/log" 2>&1 || rc=$?
  local execs corpus
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log" | tail -1)
  corpus=$(ls "$dir/corpus" | wc -l)
  if [ "$rc" -eq 0 ]; then
    echo "fuzz: $t: ok, ${execs:-?} execs in ${FUZZ_SECONDS} s, corpus $corpus inputs"
  else
    echo "fuzz: $t: FINDING (exit $rc), ${execs:-?} execs; see $dir/log and $dir/:"
    ls "$dir" | grep -E '^(crash|timeout|oom|leak|slow-unit)-' | sed 's/^/fuzz:   /' || true
    grep -m1 -E 'ERROR: |runtime error:|==ERROR' "$dir/log" | sed 's/^/fuzz:   /' || true
  fi
  return "$rc"
}
running=0
for t in "${targets[@]}"; do
  rm -f "$out/$t/status"
  (rc=0; run_one "$t" || rc=$?; echo "$rc" >"$out/$t/status") &
  running=$((running + 1))
  if [ "$running" -ge "$FUZZ_JOBS" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait
failed=()
for t in "${targets[@]}"; do
  if [ "$(cat "$out/$t/status" 2>/dev/null)" != 0 ]; then failed+=("$t"); fi
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: findings in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: no findings"
