#!/usr/bin/env bash
# CI: the Blender add-on (blender/, docs/blender.md) in three Blenders: Debian's (3.4) and the bpy
# module (Blender as a Python module, from PyPI) of the newest 4.x LTS and of 5.x. Installs Debian's
# Blender (and numpy, which its glTF exporter needs and Debian's package does not pull in) if
# missing; makes a venv for each bpy under ${CARGO_TARGET_DIR:-target}/blender-bpy/ once and keeps
# it; builds the add-on's zip; and runs tests/blender/test_addon.py in each Blender against the
# nullpath program at $NULLPATH_BIN, else target/release/nullpath (built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."

# The bpy modules the add-on is tested in besides Debian's Blender: 4.5 is the newest 4.x LTS.
BPY_VERSIONS=(4.5.15 5.0.1)
# Each bpy wheel is built for one CPython; these for 3.11 (Debian 12's python3).
BPY_PYTHON="${BPY_PYTHON:-python3.11}"

# Debian's Blender runs on Debian's Python, whatever python3 is first on PATH.
if ! command -v blender >/dev/null || ! dpkg -s python3-numpy >/dev/null 2>&1 \
    || ! "$BPY_PYTHON" -c 'import ensurepip' >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
        blender python3-numpy python3-venv >/dev/null
fi

target="${CARGO_TARGET_DIR:-target}"
binary="${NULLPATH_BIN:-$target/release/nullpath}"
if [[ -z "${NULLPATH_BIN:-}" ]]; then
    cargo build --release --bin nullpath
fi
binary="$(realpath "$binary")"

# bpy_python VERSION: the Python of a venv holding bpy==VERSION, made once (under a temporary
# name, renamed when complete, so that an interrupted install is not taken for one).
bpy_python() {
    local venv
    venv="$(realpath -m "$target/blender-bpy/$1")"
    if [[ ! -d "$venv" ]]; then
        rm -rf "$venv.partial"
        mkdir -p "$(dirname "$venv")"
        "$BPY_PYTHON" -m venv "$venv.partial"
        "$venv.partial/bin/python" -m pip install -q --disable-pip-version-check "bpy==$1" >&2
        mv "$venv.partial" "$venv"
    fi
    echo "$venv/bin/python"
}

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 blender/make_zip.py "$work/nullpath_addon.zip"

failed=()
# run_test NAME COMMAND...: runs `COMMAND tests/blender/test_addon.py -- ...` with user folders of
# its own (the add-on installs there, not into the machine's); says which Blender ran it and how
# it went, and prints its log if it failed.
run_test() {
    local name="$1" dir="$work/$1"
    shift
    mkdir -p "$dir"
    BLENDER_USER_CONFIG="$dir/config" BLENDER_USER_SCRIPTS="$dir/scripts" BLENDER_USER_EXTENSIONS="$dir/extensions" \
        "$@" tests/blender/test_addon.py -- \
        --zip "$work/nullpath_addon.zip" --nullpath "$binary" --workdir "$dir/test" >"$dir/log" 2>&1 || true
    local version checks
    version="$(sed -n 's/^Blender version: //p' "$dir/log")"
    checks="$(grep -c '^ok:' "$dir/log" || true)"
    if grep -q '^PASSED: tests/blender/test_addon.py' "$dir/log"; then
        echo "$name: Blender ${version:-?}: PASSED ($checks checks)"
    else
        cat "$dir/log"
        echo "$name: Blender ${version:-?}: FAILED after $checks checks"
        failed+=("$name")
    fi
}

run_test debian blender -b --factory-startup --python-exit-code 1 --python
for version in "${BPY_VERSIONS[@]}"; do
    run_test "bpy-$version" "$(bpy_python "$version")"
done

if ((${#failed[@]})); then
    echo "the Blender add-on's test failed in: ${failed[*]}"
    exit 1
fi
