#!/usr/bin/env bash
# The preview's browser test (tests/preview_browser.rs) drives Debian's chromium. Installs it when
# it is absent (CI machines start with only the Rust toolchain); fails if it cannot.
set -euo pipefail
if command -v chromium >/dev/null 2>&1; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  sudo="sudo"
fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends chromium
command -v chromium >/dev/null
