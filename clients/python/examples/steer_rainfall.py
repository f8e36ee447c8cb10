"""Steers the rain on a running simulation and plots a probe's pore pressure.

    PYTHONPATH=build/release/python:clients/python /usr/bin/python3 \
        clients/python/examples/steer_rainfall.py --server 127.0.0.1:50051 \
        --case tests/cli/fixtures/rain_column.yaml --probe p_top --out rain.png

Runs the case to a third of its end time, raises the rainfall tenfold, runs to the end, and plots
the probe against time with the moment of the change (matplotlib if present, else a CSV).
"""

import argparse

from cascade_client import Client


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", default="127.0.0.1:50051")
    parser.add_argument("--token")
    parser.add_argument("--case", required=True)
    parser.add_argument("--probe", required=True)
    parser.add_argument("--factor", type=float, default=10.0)
    parser.add_argument("--out", default="rain.png")
    args = parser.parse_args()

    with Client(args.server, token=args.token) as client:
        sim = client.create(args.case)
        end = sim.get().end_time
        sim.run_until(end / 3)
        before = sim.get().forcing.rainfall.intensity
        change = sim.set_rainfall(before * args.factor)
        print(f"rainfall {before:g} -> {before * args.factor:g} m/s from step {change.effective_step} "
              f"(t = {change.effective_time:g} s)")
        sim.resume()  # run_until left it PAUSED
        for status in sim.watch(interval=0.5):
            print(f"t = {status.time:.1f} s, step {status.step}")
        names, times, _, values = sim.probes()
        column = values[:, names.index(args.probe)]
        sim.delete()

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        path = args.out.rsplit(".", 1)[0] + ".csv"
        with open(path, "w") as f:
            f.write(f"time,{args.probe}\n")
            f.writelines(f"{t!r},{v!r}\n" for t, v in zip(times, column))
        print(f"no matplotlib: wrote {path}")
        return
    plt.plot(times, column)
    plt.axvline(change.effective_time, linestyle="--", label="rainfall raised")
    plt.xlabel("time (s)")
    plt.ylabel(f"{args.probe} (Pa)")
    plt.legend()
    plt.savefig(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
