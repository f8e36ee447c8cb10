#!/usr/bin/python3
"""Plots the surge front and the residual column of a 2D dam break run against experiment.

Reads RUN_DIR/probes.csv written by `cascade run cases/dam_break_2d.yaml --out RUN_DIR` (columns
time, front_x, column_height) and writes RUN_DIR/surge_front.png with two panels:

  - surge front Z = x_front / a against T = t sqrt(2 g / a), with Martin & Moyce (1952) and
    Ritter's dry-bed front as an upper bound;
  - residual column height H = column_height / (2a) at the left wall against the same T, with
    Martin & Moyce (1952).

The tank's right wall (x = 4a in cases/dam_break_2d.yaml) stops the front at Z = 4, so the last
experimental points (Z > 4, from a longer plate) lie beyond what the case can reach.

usage: /usr/bin/python3 scripts/plot_dam_break.py RUN_DIR [--a 0.146] [--g 9.81] [--wall 0.584] [--out FILE]
"""

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

# Martin, J. C. & Moyce, W. J. (1952), "An experimental study of the collapse of liquid columns on
# a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244, 312-324: the column of width
# a = 2.25 in and height 2a (n^2 = 2).
#
# Table 2, surge front: Z = x/a against T = n t sqrt(g/a) = t sqrt(2g/a). The front was timed as it
# passed marks half an inch apart, hence Z in steps of 0.5/2.25 = 2/9.
MM_FRONT_T = [0.0, 0.41, 0.84, 1.19, 1.43, 1.63, 1.83, 1.98, 2.20, 2.32, 2.51, 2.65, 2.83, 2.98, 3.11, 3.33]
MM_FRONT_Z = [1.0, 1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.00, 3.22, 3.44, 3.67, 3.89, 4.11]
# Table 6, residual column height: H = eta/(2a) against tau = t sqrt(g/a) (no factor n here),
# heights in steps of 1/18. Plotted against T = sqrt(2) tau so both panels share one time axis.
MM_HEIGHT_TAU = [0.0, 0.56, 0.77, 0.93, 1.08, 1.28, 1.46, 1.66, 1.84, 2.00, 2.21, 2.45, 2.70, 3.06, 3.44, 4.20, 5.25]
MM_HEIGHT_H = [1.0, 0.94, 0.89, 0.83, 0.78, 0.72, 0.67, 0.61, 0.56, 0.50, 0.44, 0.39, 0.33, 0.28, 0.22, 0.17, 0.11]


def read_probes(path):
    """Returns {column name: numpy array} from a probes.csv (quoted names, nan and inf allowed)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path} is empty")
    header, data = rows[0], [r for r in rows[1:] if r]
    if not data:
        raise ValueError(f"{path} has a header but no rows")
    values = np.array([[float(v) for v in r] for r in data], dtype=float)
    return {name: values[:, k] for k, name in enumerate(header)}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", type=Path, help="output directory of the run (holds probes.csv)")
    parser.add_argument("--a", type=float, default=0.146, help="column width a in m (default 0.146)")
    parser.add_argument("--g", type=float, default=9.81, help="gravity in m/s^2 (default 9.81)")
    parser.add_argument("--wall", type=float, default=0.584,
                        help="x of the tank's right wall in m, from the left wall (default 0.584 = 4a)")
    parser.add_argument("--out", type=Path, help="PNG to write (default RUN_DIR/surge_front.png)")
    args = parser.parse_args(argv)
    a, g = args.a, args.g
    out = args.out or args.run_dir / "surge_front.png"

    probes = read_probes(args.run_dir / "probes.csv")
    for name in ("time", "front_x", "column_height"):
        if name not in probes:
            sys.exit(f"plot_dam_break: {args.run_dir / 'probes.csv'} has no column '{name}' "
                     f"(columns: {', '.join(probes)})")

    t_scale = math.sqrt(2 * g / a)  # T = t * t_scale
    T = probes["time"] * t_scale
    Z = probes["front_x"] / a
    H = probes["column_height"] / (2 * a)
    # Ritter (1892): over a dry bed the front of an ideal shallow-water dam break runs at
    # 2 sqrt(g H0), H0 = 2a, so x = a + 2 sqrt(2 g a) t, which is Z = 1 + 2T in these variables.
    T_ritter = np.array([0.0, max(T.max(), MM_FRONT_T[-1])])
    Z_ritter = 1 + 2 * T_ritter
    T_height = np.sqrt(2.0) * np.array(MM_HEIGHT_TAU)

    fig, (ax_front, ax_height) = plt.subplots(2, 1, figsize=(7.5, 8.5), sharex=True)
    fig.suptitle(f"2D dam break, column {a:g} m wide and {2 * a:g} m high")

    ax_front.plot(T, Z, "-", color="tab:blue", lw=1.8, label="Cascade (SPH)")
    ax_front.plot(MM_FRONT_T, MM_FRONT_Z, "o", mfc="none", color="black",
                  label="Martin & Moyce (1952), $n^2 = 2$")
    ax_front.plot(T_ritter, Z_ritter, "--", color="tab:red", label="Ritter, dry bed: $Z = 1 + 2T$")
    ax_front.axhline(args.wall / a, ls=":", color="gray", label=f"right wall of the tank, $Z = {args.wall / a:.3g}$")
    ax_front.set_ylabel("surge front $Z = x_{front}/a$ (–)")
    ax_front.set_ylim(0.8, max(4.5, np.nanmax(Z) * 1.05 if np.isfinite(Z).any() else 4.5))
    ax_front.grid(True, alpha=0.3)
    ax_front.legend(loc="upper left")
    seconds = ax_front.secondary_xaxis("top", functions=(lambda x: x / t_scale, lambda s: s * t_scale))
    seconds.set_xlabel("time $t$ (s)")

    ax_height.plot(T, H, "-", color="tab:blue", lw=1.8, label="Cascade (SPH)")
    ax_height.plot(T_height, MM_HEIGHT_H, "s", mfc="none", color="black",
                   label="Martin & Moyce (1952), $n^2 = 2$")
    ax_height.set_ylabel("column height at the wall $H = \\eta/(2a)$ (–)")
    ax_height.set_xlabel("dimensionless time $T = t\\,\\sqrt{2g/a}$ (–)")
    ax_height.set_ylim(0, 1.1)
    ax_height.set_xlim(0, max(T.max(), MM_FRONT_T[-1]) * 1.02)
    ax_height.grid(True, alpha=0.3)
    ax_height.legend(loc="upper right")

    fig.tight_layout()
    fig.savefig(out, dpi=150)
    plt.close(fig)

    # The comparison in numbers, at the experimental times the run reached.
    print(f"plot_dam_break: T = t*sqrt(2g/a) up to {T.max():.2f} (t = {probes['time'].max():g} s)")
    for Te, Ze in zip(MM_FRONT_T[1:], MM_FRONT_Z[1:]):
        if Te > T.max() or Ze >= args.wall / a:
            break
        Zs = float(np.interp(Te, T, Z))
        print(f"  T = {Te:4.2f}: Z = {Zs:5.2f} (Martin & Moyce {Ze:4.2f}, {100 * (Zs - Ze) / Ze:+5.1f}%;"
              f" Ritter {1 + 2 * Te:4.2f})")
    print(f"plot_dam_break: wrote {out}")


if __name__ == "__main__":
    main()
