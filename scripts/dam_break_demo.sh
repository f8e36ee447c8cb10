#!/usr/bin/env bash
# The 2D dam break of cases/dam_break_2d.yaml run headless,
# then a PNG of its surge front and residual column against Martin & Moyce (1952).
# Installs the Debian packages, builds the `cascade` executable of the `release` preset, runs the
# case into out/dam_break_2d/ and plots out/dam_break_2d/surge_front.png.
#
# usage: bash scripts/dam_break_demo.sh [cascade run options, e.g. --until 0.1 --set dp=0.0073 --threads 2]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

out=out/dam_break_2d
bash scripts/install-deps.sh
cmake --preset release
cmake --build --preset release -j"$(nproc)" --target cascade

# A fresh directory, so that no file of an earlier run is mistaken for this one's.
rm -rf "$out"
build/release/bin/cascade run cases/dam_break_2d.yaml --out "$out" "$@"
/usr/bin/python3 scripts/plot_dam_break.py "$out"

cat <<MSG

Outputs of the 2D dam break are in $out/:
  fields.h5, fields.xdmf   particle fields per output time (open fields.xdmf in ParaView)
  probes.csv               time, front_x, column_height, p_right_wall
  run.json                 run summary (status, steps, wall time, particle counts)
  surge_front.png          surge front and column height against Martin & Moyce (1952)
See README.md ("Results") and docs/output.md for how to read them.
MSG
