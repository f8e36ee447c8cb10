#!/usr/bin/env bash
# The README's main job: the rainfall → landslide → wave cascade of cases/cascade_demo_2d.yaml, run
# by cascade-server and steered live by a Python client (scripts/cascade_demo.py): rain on the
# slope, the rainfall raised part-way, the landslide, the wave at the far bank. Outputs in
# out/cascade_demo_2d/: PNG snapshots at the key moments, PNG plots of pore pressure, soil speed and
# wave elevation against time, the probes, summary.json; the summary (events and their times) is
# printed at the end. Installs the Debian packages and builds what it needs; no GPU, no display.
#
# usage: [CASCADE_THREADS=N] bash scripts/demo.sh [cascade_demo.py options, e.g. --raise-at 5 --raise-factor 3
#                             --set dp=0.08]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

out=out/cascade_demo_2d
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j"$(nproc)" --target cascade-server cascade_python_stubs

# A fresh directory, so that no file of an earlier run is mistaken for this one's.
rm -rf "$out"
mkdir -p "$out"
# Port 0: the server picks a free port and says which on its first line.
build/release/bin/cascade-server --listen 127.0.0.1:0 --data-dir "$out/server" --threads "${CASCADE_THREADS:-$(nproc)}" \
  2> "$out/server.log" &
server=$!
trap 'kill -TERM "$server" 2>/dev/null || true' EXIT
address=""
for _ in $(seq 1 300); do
  address=$(sed -n 's/^cascade-server: listening on \([^,]*\),.*/\1/p' "$out/server.log")
  [ -n "$address" ] && break
  kill -0 "$server" 2>/dev/null || { cat "$out/server.log"; exit 1; }
  sleep 0.1
done
[ -n "$address" ] || { echo "cascade-server did not start:"; cat "$out/server.log"; exit 1; }
echo "cascade-server (pid $server) listening on $address; its log: $out/server.log"

status=0
PYTHONPATH=build/release/python:clients/python /usr/bin/python3 scripts/cascade_demo.py \
  --server "$address" --case cases/cascade_demo_2d.yaml --out "$out" "$@" || status=$?

# SIGTERM: the server checkpoints what still runs and exits 0 (docs/api.md).
kill -TERM "$server"
wait "$server" || { echo "cascade-server exited $?"; status=1; }
trap - EXIT
echo "cascade-server stopped"
exit "$status"
