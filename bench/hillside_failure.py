"""The shipped hillside's section under its storm, run to failure on a real server (issue 15: "the
shipped hillside case runs to failure under a storm"; docs/cases.md, the case table). The case
(cases/hillside_dem_2d.yaml, from the GeoTIFFs of cases/terrain/) runs its geostatic start and its
pore-water stage, whose motion trials decide when the slope can no longer stand; at the switch to
the dynamic stage the script pauses the simulation and reports the failure: its time into the
storm, the trial, the soil at yield and the stage's water balance, and the wall time it took.
Exits 1 when the storm (12 h) passes without a failure, or the run fails.

    /usr/bin/python3 bench/hillside_failure.py --build build/release     # about 10 minutes on 2 cores
"""

import argparse
import pathlib
import subprocess
import sys
import time

import python_client

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build/release")
parser.add_argument("--case", default="cases/hillside_dem_2d.yaml")
parser.add_argument("--storm", type=float, default=12 * 3600.0, help="the storm's length in the case (s)")
parser.add_argument("--threads", type=int, default=2)
args = parser.parse_args()
build = python_client.use_client(args.build)
import cascade_client  # noqa: E402


def stage_switches(sim):
    return [e for e in sim.events() if e.kind == "stage_changed"]


with python_client.server(build, args.threads) as (server, address):
    with cascade_client.Client(address) as client:
        start = time.perf_counter()
        # `cascade create` reads the rasters on the client and sends the spec (a case text
        # naming rasters is refused by the server, which reads no files a request names).
        subprocess.run([str(build / "bin" / "cascade"), "create", args.case, "--server", address, "--id", "hillside"],
                       check=True, capture_output=True)
        sim = client.simulation("hillside")
        sim.start()
        failure = None
        while failure is None:
            time.sleep(2.0)
            got = sim.get()
            # The pore-water stage's end: "rain -> slide: the slope moves: ..." (the geostatic
            # start's own end hands over to the rain stage).
            failure = next((e for e in stage_switches(sim) if e.message.startswith("rain -> ")), None)
            if failure is None and (got.status.time > args.storm or
                                    got.state in (cascade_client.State.COMPLETED, cascade_client.State.FAILED)):
                print(f"no failure: state {cascade_client.State.Name(got.state)}, t = {got.status.time:.0f} s, "
                      f"stage {got.status.stage_name}: {got.failure_reason}")
                sys.exit(1)
        sim.pause()
        wall = time.perf_counter() - start
        print(f"load average {pathlib.Path('/proc/loadavg').read_text().split()[0]}; {args.case}: "
              f"{got.particle_count} particles, {args.threads} threads")
        print(f"failure {failure.time:.0f} s ({failure.time / 3600:.2f} h) into the {args.storm / 3600:.0f} h storm, "
              f"step {failure.step}, after {wall / 60:.1f} min of wall time")
        print(f"  {failure.message}")
        if not failure.time < args.storm:
            sys.exit(1)
