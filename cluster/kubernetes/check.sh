#!/usr/bin/env bash
# CI step: checks the Kubernetes manifest (cluster/kubernetes/check.py) without a cluster.
# Needs Python 3 with PyYAML; as root on Debian it installs python3-yaml when missing. Without
# them it prints a SKIPPED line with the reason and succeeds; a bad manifest fails.
set -euo pipefail
cd "$(dirname "$0")"

has_yaml() { command -v "$1" >/dev/null && "$1" -c 'import yaml' 2>/dev/null; }

python=""
for candidate in python3 /usr/bin/python3; do
    if has_yaml "$candidate"; then
        python=$candidate
        break
    fi
done
if [[ -z $python && $(id -u) == 0 ]] && command -v apt-get >/dev/null; then
    echo "check.sh: installing python3-yaml (apt-get)" >&2
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
        python3-yaml >/dev/null) || true
    has_yaml /usr/bin/python3 && python=/usr/bin/python3
fi
if [[ -z $python ]]; then
    echo "SKIPPED: Kubernetes manifest check: no Python 3 with PyYAML (install python3-yaml)"
    exit 0
fi
"$python" check.py
