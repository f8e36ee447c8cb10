"""What if the storm is heavier? Forks the storm demo mid-storm into forecast branches and compares
their times of failure and waves.

    PYTHONPATH=build/release/python:clients/python /usr/bin/python3 \
        clients/python/examples/forecast_ensemble.py --server 127.0.0.1:50051 \
        --case cases/cascade_storm_2d.yaml --fork-at 10800 --factors 1 1.5 2 --out ensemble.png

Creates the simulation, runs it to --fork-at (simulated seconds: 3 h into the storm), forks one
branch per rain factor (the case's storm times the factor from then on), runs them side by side on
the server, each to --after seconds past its own landslide onset, prints the table of each
branch's events and plots the probes (docs/api.md, "Clients"; 63 s of wall time for three
branches on 2 cores, docs/performance.md).
"""

import argparse

from cascade_client import Client
from cascade_client.ensemble import ensemble


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", default="127.0.0.1:50051")
    parser.add_argument("--token")
    parser.add_argument("--case", default="cases/cascade_storm_2d.yaml")
    parser.add_argument("--fork-at", type=float, default=10800.0, help="simulated seconds (default 3 h)")
    parser.add_argument("--factors", type=float, nargs="+", default=[1.0, 1.5, 2.0])
    parser.add_argument("--after", type=float, default=1.0, help="seconds past each branch's landslide onset")
    parser.add_argument("--out", default="ensemble.png")
    args = parser.parse_args()

    with Client(args.server, token=args.token) as client:
        sim = client.create(args.case)
        sim.run_until(args.fork_at)
        result = ensemble(sim, rain_factors=args.factors, stop_after=("landslide_onset", args.after))
        print(result.table())
        result.plot(args.out)
        print(f"probes of every branch: {args.out}")


if __name__ == "__main__":
    main()
