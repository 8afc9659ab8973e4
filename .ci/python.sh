#!/usr/bin/env bash
# The Python package (python/): builds it into a fresh venv the way README.md says (pip install
# ./python), runs its pytest suite against the `nullpath` program built from the same tree, and
# executes the example notebook headless, which writes its plots to examples/plots/.
# CI machines start with only the Rust toolchain and CPython; everything else comes from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
venv="$target/ci-venv"
python3 -m venv "$venv"
# shellcheck disable=SC1091
. "$venv/bin/activate"
python -m pip install -q --upgrade pip
python -m pip install -q -r python/requirements-ci.txt
cargo build --release --bin nullpath
python -m pip install -q --no-build-isolation ./python
# A test that hangs prints every thread's stack after two minutes, so a CI log says where.
python -m pytest -q -ra -o faulthandler_timeout=120 --durations=5 python/tests
jupyter nbconvert --to notebook --execute examples/notebook.ipynb --output-dir "$target/notebook" \
  --ExecutePreprocessor.timeout=600
ls examples/plots/*.png
