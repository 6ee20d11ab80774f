#!/usr/bin/env bash
# Installs gearpath's build and test dependencies from Debian 12 packages.
# Idempotent: quiet and quick when everything is already there.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  dpkg-dev  # tests/install: cpack -G DEB runs dpkg-shlibdeps for the package's Depends
  help2man  # cmake/gearpath_install.cmake: the man pages, made from --help
  libeigen3-dev libfftw3-dev
  cyclonedds-dev cyclonedds-tools
  libspdlog-dev libfmt-dev nlohmann-json3-dev libcli11-dev libsystemd-dev
  libmicrohttpd-dev  # daemon/metrics_server.cc: the metrics endpoint (metrics.enabled)
  libxxhash-dev  # core/pipeline/learned_state.cc: the learned state's fingerprint
  libgtest-dev libgmock-dev libbenchmark-dev valgrind
  python3 python3-numpy
  openssl  # tools/make-security-fixtures.sh: the DDS Security tests make their PKI at test time
  fastddsgen default-jre-headless libfastrtps-dev  # tests/interop: Fast DDS interop (fastddsgen runs on Java)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
