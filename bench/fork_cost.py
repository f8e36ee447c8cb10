"""What a fork costs on the server (docs/performance.md, "Forks"; issue 15: under 1 s and one copy
of the state for a 10^6-particle 3D simulation): a simulation of the case is created and stepped
once, then forked; timed are the ForkSimulation reply and the moment the fork's engine holds the
state (its "forked from" event), then one step of the fork (which lists its particles first: the
clone does not copy the neighbour lists) and of the parent. Memory is the
server's resident set (VmRSS) before and after the fork and after the fork's first step, and its
peak (VmHWM), against what the parent's creation added.

    /usr/bin/python3 bench/fork_cost.py --build build/release        # cases/dam_break_3d.yaml at dp 0.0054
"""

import argparse
import pathlib
import time

import python_client

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build/release")
parser.add_argument("--case", default="cases/dam_break_3d.yaml")
parser.add_argument("--set", action="append", default=["dp=0.0054"], help="case overrides, as cascade run --set")
parser.add_argument("--threads", type=int, default=2)
args = parser.parse_args()
build = python_client.use_client(args.build)
import cascade_client  # noqa: E402


def memory(pid):
    """(VmRSS, VmHWM) of the process in MiB."""
    fields = dict(line.split(":", 1) for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines())
    return tuple(int(fields[k].split()[0]) / 1024 for k in ("VmRSS", "VmHWM"))


def cpu_model():
    for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown"


with python_client.server(build, args.threads) as (server, address):
    with cascade_client.Client(address) as client:
        idle, _ = memory(server.pid)
        start = time.perf_counter()
        parent = client.create(args.case, overrides=args.set)
        particles = parent.get().particle_count
        created = time.perf_counter() - start
        start = time.perf_counter()
        parent.step(1)
        parent_step = time.perf_counter() - start
        before, before_peak = memory(server.pid)
        start = time.perf_counter()
        fork = client.simulation(parent.fork().name)
        replied = time.perf_counter() - start
        while not any("forked from" in e.message for e in fork.events()):
            time.sleep(0.01)
        ready = time.perf_counter() - start
        after, peak = memory(server.pid)
        start = time.perf_counter()
        fork.step(1)
        fork_step = time.perf_counter() - start
        stepped, stepped_peak = memory(server.pid)  # the fork's neighbour lists built (Simulation::clone)
        start = time.perf_counter()
        parent.step(1)
        parent_second_step = time.perf_counter() - start
        print(f"machine: {cpu_model()}, load average {pathlib.Path('/proc/loadavg').read_text().split()[0]}; "
              f"{args.case} {' '.join(args.set)}: {particles} particles, {args.threads} threads")
        print(f"create {created:.2f} s (builds the case); one step: parent {parent_step:.3f} s, fork's first "
              f"{fork_step:.3f} s (lists its particles), parent's next {parent_second_step:.3f} s")
        print(f"fork: reply {replied:.3f} s, engine holding the state {ready:.3f} s")
        print(f"server resident: idle {idle:.0f} MiB, with the parent {before:.0f} MiB (+{before - idle:.0f}, "
              f"peak {before_peak:.0f}), "
              f"with the fork {after:.0f} MiB (+{after - before:.0f}, {1048576 * (after - before) / particles:.0f} "
              f"bytes/particle), peak {peak:.0f} MiB")
        print(f"after the fork's first step: {stepped:.0f} MiB (+{stepped - before:.0f}, "
              f"{1048576 * (stepped - before) / particles:.0f} bytes/particle), peak {stepped_peak:.0f} MiB")
