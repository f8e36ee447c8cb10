#!/usr/bin/env python3
"""Time to solution against a baseline commit, side by side on this machine (issue 16).

Builds the `cascade` tool of the baseline commit in a git worktree of its own
(build/baseline/<commit>/, its `release` preset) and of this tree (build/release/), then runs the
same case with each, one after the other and alternating, and prints for every run the wall time,
the steps, the particle-steps per second and the peak resident memory, with the machine: CPU
model, cores, memory, STREAM's triad bandwidth at the run's thread count (bench/stream_triad.cpp)
and the load average before and after. Bytes per particle are each build's own count of its
arrays (run.json); the peak resident memory is the whole process's. The figures of one run of this script are comparable with
each other; figures from another machine or another run are not (docs/performance.md).

usage: /usr/bin/python3 bench/compare_baseline.py [--base 310eed8] [--case cases/dam_break_3d.yaml]
           [--until 0.05] [--precision float] [--threads 2] [--repeats 1]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def sh(*command, cwd=ROOT, env=None):
    subprocess.run(command, cwd=cwd, env=env, check=True, stdout=subprocess.DEVNULL)


def build_current():
    sh("cmake", "--preset", "release")
    sh("cmake", "--build", "--preset", "release", "-j", str(os.cpu_count()), "--target", "cascade", "stream_triad")
    return ROOT / "build/release/bin/cascade"


def build_baseline(commit):
    """The baseline's own tree and build, reused when they exist."""
    full = subprocess.run(["git", "rev-parse", "--verify", commit + "^{commit}"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout.strip()
    tree = ROOT / "build/baseline" / full[:12]
    if not (tree / ".git").exists():
        tree.parent.mkdir(parents=True, exist_ok=True)
        sh("git", "worktree", "add", "--detach", "--force", str(tree), full)
    sh("cmake", "--preset", "release", cwd=tree)
    sh("cmake", "--build", "--preset", "release", "-j", str(os.cpu_count()), "--target", "cascade", cwd=tree)
    return full[:12], tree / "build/release/bin/cascade"


def machine(threads):
    model = "unknown"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    with open("/proc/meminfo") as f:
        memory_kib = int(next(line for line in f if line.startswith("MemTotal")).split()[1])
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    triad = subprocess.run([str(ROOT / "build/release/bin/stream_triad")], env=env, check=True, capture_output=True,
                           text=True).stdout.strip()
    return f"{model}, {os.cpu_count()} cores, {memory_kib / 2**20:.1f} GiB; {triad}"


def run(cascade, args, out):
    """One run: wall seconds, run.json's figures, peak resident memory (MiB)."""
    command = [str(cascade), "run", str(ROOT / args.case), "--out", str(out), "--until", str(args.until),
               "--precision", args.precision, "--threads", str(args.threads)]
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"compare_baseline: {' '.join(command)} failed:\n{process.stderr.read().decode()}")
    summary = json.loads((out / "run.json").read_text())
    return wall, summary, usage.ru_maxrss / 1024


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", default="310eed8")
    parser.add_argument("--case", default="cases/dam_break_3d.yaml")
    parser.add_argument("--until", type=float, default=0.05)
    parser.add_argument("--precision", default="float")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=1)
    args = parser.parse_args()

    current = build_current()
    base_name, base = build_baseline(args.base)
    head = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=ROOT, check=True, capture_output=True,
                          text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=ROOT, check=True,
                           capture_output=True, text=True).stdout.strip()
    names = {"baseline": base_name, "current": head + (" + uncommitted changes" if dirty else "")}
    print(f"machine: {machine(args.threads)}")
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(f"case: {args.case} --until {args.until} --precision {args.precision} --threads {args.threads}")
    print(f"{'build':<10} {'commit':<36} {'wall s':>8} {'steps':>7} {'particles':>10} {'particle-steps/s':>17} "
          f"{'peak MiB':>9} {'B/part.':>8}")
    walls = {"baseline": [], "current": []}
    with tempfile.TemporaryDirectory(prefix="compare_baseline.") as scratch:
        for repeat in range(args.repeats):
            for build, cascade in (("baseline", base), ("current", current)):
                out = Path(scratch) / f"{build}{repeat}"
                wall, summary, peak = run(cascade, args, out)
                walls[build].append(wall)
                steps = summary["steps"]
                particles = summary["particles"]["total"]
                print(f"{build:<10} {names[build]:<36} {wall:8.1f} {steps:7d} {particles:10d} "
                      f"{particles * steps / wall:17.3g} {peak:9.0f} {summary['bytes_per_particle']:8.0f}", flush=True)
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    ratio = statistics.median(walls["baseline"]) / statistics.median(walls["current"])
    print(f"time to solution: the current build is {ratio:.2f} times as fast as {base_name} (median wall times)")


if __name__ == "__main__":
    main()
