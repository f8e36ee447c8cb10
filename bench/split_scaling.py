#!/usr/bin/env python3
"""Runs split over processes against one process, on this machine (issue 17).

Strong scaling: the same case as one process with one thread, one process with P threads, and P
processes (mpirun) with one thread each. Weak scaling: about the same number of particles per
process, the case at dp for one process and at dp / P^(1/D) for P processes. Prints for each run
the wall time, the steps, the particle-steps per second, the particles each process held (its
own, the copies in its halo, the dummies there: run.json's process_particles), the efficiency
against one process with one thread and, for a split run, the slowest process's wall time in the
steps' exchanges and the bytes all processes sent per step (run.json's exchange), and the
frames written with the wall time of the outputs per frame and in all (run.json's outputs: split
over processes, every process writes its rows of fields.h5, server/io/split_fields_writer.h, and
the probes are sampled from the parts of each process's particles: ProbeSampler::parts), with the
machine (CPU model, cores, memory, STREAM's triad) and the load average before and after. With
--baseline COMMIT, the strong-scaling runs are made with that commit's `cascade` too (built in a
worktree of its own, bench/compare_baseline.py), side by side. The figures of one run of this
script are comparable with each other; figures from another machine or another run are not.

usage: /usr/bin/python3 bench/split_scaling.py [--case cases/dam_break_3d.yaml] [--dp 0.0103]
           [--until 0.005] [--precision float] [--processes 2] [--frame-interval T]
           [--probe-interval T] [--baseline COMMIT]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from compare_baseline import ROOT, build_baseline, build_current, machine


def run(cascade, case, dp, until, precision, processes, threads, out, frame_interval, probe_interval):
    command = [str(cascade), "run", str(ROOT / case), "--out", str(out), "--until", str(until),
               "--precision", precision, "--threads", str(threads), "--set", f"dp={dp}"]
    if frame_interval:
        command += ["--set", f"output.interval={frame_interval}"]
    if probe_interval:
        command += ["--set", f"output.probe_interval={probe_interval}"]
    if processes > 1:
        command = [shutil.which("mpirun"), "--oversubscribe", "--allow-run-as-root", "-np", str(processes)] + command
    start = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - start
    if result.returncode != 0:
        sys.exit(f"split_scaling: {' '.join(command)} failed:\n{result.stderr}")
    return wall, json.loads((out / "run.json").read_text())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", default="cases/dam_break_3d.yaml")
    parser.add_argument("--dp", type=float, default=0.0103)
    parser.add_argument("--until", type=float, default=0.005)
    parser.add_argument("--precision", default="float")
    parser.add_argument("--processes", type=int, default=2)
    parser.add_argument("--frame-interval", type=float, default=0.0,
                        help="output.interval of the case (s); the case's own when 0")
    parser.add_argument("--probe-interval", type=float, default=0.0,
                        help="output.probe_interval of the case (s); the case's own when 0")
    parser.add_argument("--baseline", help="a commit whose strong-scaling runs to make side by side")
    args = parser.parse_args()
    if shutil.which("mpirun") is None:
        sys.exit("split_scaling: mpirun is missing (openmpi-bin)")

    builds = [("this tree", build_current())]
    if args.baseline:
        commit, baseline = build_baseline(args.baseline)
        builds.append((commit, baseline))
    dimensions = 3 if "3d" in args.case else 2
    p = args.processes
    print(f"machine: {machine(1)}")
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"case: {args.case} --until {args.until} --precision {args.precision}")
    print(f"{'build':<12} {'kind':<7} {'dp':>8} {'processes':>9} {'threads':>7} {'wall s':>8} {'steps':>6} {'particles':>10} "
          f"{'particle-steps/s':>17} {'efficiency':>10} {'exchange s':>10} {'MB/step':>8} {'frames':>6} "
          f"{'s/frame':>8} {'out s':>6}  held per process")
    runs = [(builds[0], "strong", args.dp, 1, 1), (builds[0], "strong", args.dp, 1, p),
            (builds[0], "strong", args.dp, p, 1), (builds[0], "weak", args.dp * p ** (1 / dimensions), 1, 1),
            (builds[0], "weak", args.dp, p, 1)]
    for build in builds[1:]:
        runs += [(build, "strong", args.dp, 1, 1), (build, "strong", args.dp, p, 1)]
    with tempfile.TemporaryDirectory(prefix="split_scaling.") as scratch:
        reference = {}
        for k, ((name, cascade), kind, dp, processes, threads) in enumerate(runs):
            wall, summary = run(cascade, args.case, dp, args.until, args.precision, processes, threads,
                                Path(scratch) / str(k), args.frame_interval, args.probe_interval)
            rate = summary["particles"]["total"] * summary["steps"] / wall
            workers = processes * threads
            if workers == 1:
                reference[name, kind] = rate
            efficiency = rate / (workers * reference[name, kind])
            held = summary.get("process_particles", [summary["particles"]["total"]])
            exchange = summary.get("exchange", {"seconds": 0.0, "bytes": 0})
            megabytes = exchange["bytes"] / max(1, summary["steps"]) / 1e6
            outputs = summary.get("outputs", {"frames": 0, "seconds": 0.0})  # none before 04b0b91
            per_frame = outputs["seconds"] / max(1, outputs["frames"])
            print(f"{name:<12} {kind:<7} {dp:8.5f} {processes:9d} {threads:7d} {wall:8.1f} {summary['steps']:6d} "
                  f"{summary['particles']['total']:10d} {rate:17.3g} {efficiency:10.2f} {exchange['seconds']:10.1f} "
                  f"{megabytes:8.2f} {outputs['frames']:6d} {per_frame:8.3f} {outputs['seconds']:6.1f}  {held}", flush=True)
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
