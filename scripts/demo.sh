#!/usr/bin/env bash
# The README's main job: the storm → landslide → wave cascade of cases/cascade_storm_2d.yaml (a sand
# slope at its real K_sat under a 12 h design storm in mm/h), run by cascade-server and steered live
# by a Python client (scripts/cascade_demo.py): the geostatic start, hours of rain in the implicit
# stage, the operator raising the forecast rain mid-storm, the failure, the slide and the wave at
# the far bank. Outputs in out/cascade_storm_2d/: PNG snapshots at the key moments, storm.png (rain
# in mm/h and pore pressures against hours), soil_speed.png and wave_elevation.png (against seconds
# after the failure), the probes, summary.json; the summary (time of failure in hours, events) is
# printed at the end. Installs the Debian packages and builds what it needs; no GPU, no display.
#
# usage: [CASCADE_THREADS=N] bash scripts/demo.sh [cascade_demo.py options, e.g. --raise-at "3 h"
#                             --raise-to "120 mm/h" --set dp=0.08]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

out=out/cascade_storm_2d
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
  --server "$address" --case cases/cascade_storm_2d.yaml --out "$out" "$@" || status=$?

# SIGTERM: the server checkpoints what still runs and exits 0 (docs/api.md).
kill -TERM "$server"
wait "$server" || { echo "cascade-server exited $?"; status=1; }
trap - EXIT
echo "cascade-server stopped"
exit "$status"
