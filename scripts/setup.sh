#!/usr/bin/env bash
# Installs every build and test dependency of facectl from Debian 12 packages.
# Idempotent and non-interactive: packages already present are skipped.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libyaml-cpp-dev libmodbus-dev libgpiod-dev libhidapi-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libfmt-dev nlohmann-json3-dev libpng-dev libglpk-dev
  # PCA9685 PWM boards over i2c-dev: libi2c's SMBus calls (<i2c/smbus.h>).
  libi2c-dev
  # `facectl serve`'s HTTP server and its HTTPS (OpenSSL), the test that
  # checks it against docs/openapi.yaml (tests/firmware-host/serve/
  # openapi_conformance_test.py), and openssl, which makes the HTTPS test's
  # certificate.
  libcpp-httplib-dev libssl-dev openssl python3-yaml python3-jsonschema
  clang-format clang-tidy
  # `facectl serve` tells systemd it is ready and alive (sd_notify); the
  # deployment test checks the unit and sysusers file (systemd-analyze,
  # systemd-sysusers) and builds the .deb (dpkg-shlibdeps, dpkg-deb).
  libsystemd-dev systemd dpkg-dev
  # `--input speech.wav`: the speech-driven jaw reads WAV (and FLAC, Ogg)
  # through libsndfile (docs/INPUTS.md).
  libsndfile1-dev
  # `--format audio_phonemes`: PocketSphinx's allphone recogniser with its US
  # English acoustic and phone language models, and libsamplerate to bring
  # speech to the models' 16 kHz (docs/INPUTS.md, "Phonemes from audio").
  libpocketsphinx-dev libsphinxbase-dev pocketsphinx-en-us libsamplerate0-dev
  # `facectl serve`'s OSC control decodes messages with liblo (docs/INPUTS.md).
  liblo-dev
  # `facectl run --midi` is an ALSA sequencer client (libasound); its QEMU
  # test sends a MIDI file to it with alsa-utils' aplaymidi.
  libasound2-dev alsa-utils
  # The SocketCAN tests run in a QEMU guest (tests/drivers/qemu): the emulator,
  # Debian's kernel with the CAN modules, a static busybox for the initramfs,
  # and can-utils and iproute2 for the guest's candump, cansend and vcan set-up.
  qemu-system-x86 linux-image-amd64 busybox-static can-utils iproute2
  # The GPIO test in that guest builds the kernel's gpio-sim module out of
  # tree (tests/drivers/qemu/build_gpio_sim.sh): Debian's kernel source and
  # the headers of linux-image-amd64's kernel.
  linux-source-6.1 linux-headers-amd64
  # The `facectl simulate` HTML report test takes a headless screenshot (tests/simulate).
  chromium
  # The sanitizer builds and the libFuzzer targets (scripts/sanitize.sh,
  # scripts/fuzz.sh): clang 14 with its sanitizer and libFuzzer runtimes, and
  # python3 for the seeds fuzz.sh writes.
  clang clang-14 libclang-rt-14-dev python3
  # lld links the builds without LTO (the CI's) faster (CMakeLists.txt).
  lld
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
