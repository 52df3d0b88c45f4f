#!/bin/sh
# Creates the Python environment that `joins_compare` drives scipy's cKDTree in:
# a venv at target/scipy-venv (in the workspace root) with scipy 1.17.1 and its numpy,
# installed from the Python package index. Needs python3 (3.11 or newer) with its venv module.
#
#   compare/scipy/setup.sh            # then: cargo run --release -p orthtree-compare --bin joins_compare
set -eu
root="$(cd "$(dirname "$0")/../.." && pwd)"
venv="$root/target/scipy-venv"
python="${PYTHON:-python3}"
"$python" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else "scipy 1.17 needs Python 3.11 or newer")'
mkdir -p "$root/target"
"$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "scipy==1.17.1"
"$venv/bin/python" -c 'import scipy; print("scipy", scipy.__version__, "in", "'"$venv"'")'
