#!/usr/bin/env bash
# Starts the dashboard (docs/dashboard.md) with the Python client and its stubs on PYTHONPATH:
#   bash scripts/dashboard.sh --server 127.0.0.1:50051 [--tls-ca F] [--token-file F] [--listen 127.0.0.1:8080]
# The stubs come from the build (cmake --build build/release --target cascade_python_stubs);
# CASCADE_BUILD names another build folder.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${CASCADE_BUILD:-$root/build/release}"
if [ ! -f "$build/python/cascade/v1/simulation_pb2.py" ]; then
  echo "dashboard: no Python stubs in $build/python; run: cmake --build $build --target cascade_python_stubs" >&2
  exit 2
fi
export PYTHONPATH="$build/python:$root/clients/python${PYTHONPATH:+:$PYTHONPATH}"
exec /usr/bin/python3 "$root/clients/dashboard/dashboard.py" "$@"
