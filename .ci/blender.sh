#!/usr/bin/env bash
# CI: the Blender add-on (blender/, docs/blender.md) in a headless Blender. Installs Debian's
# Blender (and numpy, which its glTF exporter needs and Debian's package does not pull in) if
# missing, builds the add-on's zip, and runs tests/blender/test_addon.py against the nullpath
# program at $NULLPATH_BIN, else target/release/nullpath (built if missing).
set -euo pipefail
cd "$(dirname "$0")/.."

# Debian's Blender runs on Debian's Python, whatever python3 is first on PATH.
if ! command -v blender >/dev/null || ! dpkg -s python3-numpy >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends blender python3-numpy >/dev/null
fi

binary="${NULLPATH_BIN:-${CARGO_TARGET_DIR:-target}/release/nullpath}"
if [[ -z "${NULLPATH_BIN:-}" ]]; then
    cargo build --release --bin nullpath
fi
binary="$(realpath "$binary")"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 blender/make_zip.py "$work/nullpath_addon.zip"
# The add-on installs into a user folder of this run's own, not the machine's.
export BLENDER_USER_CONFIG="$work/config" BLENDER_USER_SCRIPTS="$work/scripts"
blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \
    --zip "$work/nullpath_addon.zip" --nullpath "$binary" --workdir "$work/test" 2>&1 \
    >"$work/log" || true
grep -E '^(ok|PASSED)' "$work/log" || true
if ! grep -q '^PASSED: tests/blender/test_addon.py' "$work/log"; then
    cat "$work/log"
    exit 1
fi
