#!/bin/sh
# Creates the Python environment that `cloud_compare` drives Open3D in: a venv at
# target/open3d-venv (in the workspace root) with open3d-cpu 0.20.0 and its numpy, installed
# from the Python package index. Open3D's wheel links the system's libusb-1.0: on Debian or
# Ubuntu, `apt-get install libusb-1.0-0` first. Needs python3 (3.8 to 3.12) with its venv module.
#
#   compare/open3d/setup.sh           # then: cargo run --release -p orthtree-compare --bin cloud_compare
set -eu
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="$root/target/open3d-venv"
python="${PYTHON:-python3}"
mkdir -p "$root/target"
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "open3d-cpu==0.20.0"
"$venv/bin/python" -c 'import open3d; print("open3d", open3d.__version__, "in", "'"$venv"'")'
