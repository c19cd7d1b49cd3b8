#!/usr/bin/env bash
# Installs everything TOPKit needs from Debian 12 packages. Idempotent and
# non-interactive; run as root (or with sudo available).
set -euo pipefail

packages=(
  build-essential g++ cmake ninja-build pkg-config python3 zip
  clang libclang-rt-14-dev          # libFuzzer and the sanitizer runtimes
  clang-format clang-tidy           # the lint tests (format, bugprone/analyzer checks)
  libpcap-dev                       # pcap/pcapng I/O
  libasio-dev                       # standalone Asio: sockets, serial ports
  libgtest-dev libgmock-dev         # GoogleTest
  libbenchmark-dev                  # Google Benchmark
  libspdlog-dev nlohmann-json3-dev libcli11-dev
  tcpdump socat                     # capture floor for bench/, pty peers for tests
  time                              # /usr/bin/time -v: peak RSS in bench/run.sh
  tshark                            # the generated Wireshark dissector's tests (tests/wireshark)
  chromium                          # topdump report pages load in headless Chromium (tests/analyzer)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# tshark: answer "no" to letting non-root users capture (wireshark-common)
echo "wireshark-common wireshark-common/install-setuid boolean false" | $SUDO debconf-set-selections
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: installed ${missing[*]}"
