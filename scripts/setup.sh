#!/usr/bin/env bash
# Installs the Debian packages cueplan needs to build, test and benchmark.
# Idempotent: installs only what is missing, and runs apt-get update first when it
# has anything to install.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev
  libeigen3-dev libnlopt-cxx-dev libyaml-cpp-dev
  libompl-dev librapidcheck-dev libfmt-dev
  libcairo2-dev libpango1.0-dev fonts-dejavu-core
  librsvg2-dev libxml2-dev poppler-utils
  clang libclang-rt-14-dev
  libcpp-httplib-dev
  chromium chromium-driver python3-selenium
  pybind11-dev python3-dev python3-pybind11 python3-numpy
  python3-setuptools python3-wheel python3-pip python3-venv
  python3-dask python3-distributed python3-matplotlib python3-pandas
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
