"""Sharing the cores (docs/performance.md, "Sharing the cores"; issue 14 item 11).

1. `cascade run CASE --until T` alone and beside a process that keeps one core busy, at
   --threads 1, at --threads N (all cores) and without --threads (the team sized to the cores that
   other processes leave free, server/core/free_cores.h): wall seconds of each.
2. Two simulations of CASE on one cascade-server, STEPS steps each, run together (two clients
   stepping at once) and one after the other; the server without --threads, and with --threads N
   (every simulation a team of all cores, as before free_cores.h).

    /usr/bin/python3 bench/shared_cores.py --build build/release [--until 0.1] [--steps 2000]
"""

import argparse
import os
import subprocess
import sys
import tempfile
import threading
import time

import python_client

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build/release")
parser.add_argument("--case", default="cases/dam_break_2d.yaml")
parser.add_argument("--until", type=float, default=0.1, help="simulated seconds of each `cascade run`")
parser.add_argument("--steps", type=int, default=2000, help="steps of each server simulation")
args = parser.parse_args()
build = python_client.use_client(args.build)
import cascade_client  # noqa: E402

cores = len(os.sched_getaffinity(0))


class BusyCore:
    """A process that keeps one core busy for the duration of the `with` block."""

    def __enter__(self):
        self.process = subprocess.Popen([sys.executable, "-c", "while True: pass"])
        time.sleep(1.0)
        return self

    def __exit__(self, *exc):
        self.process.kill()
        self.process.wait()


def cascade_run(threads):
    with tempfile.TemporaryDirectory() as out:
        command = [str(build / "bin" / "cascade"), "run", args.case, "--out", out, "--until", str(args.until),
                   "--set", "output.interval=1e9"]
        if threads:
            command += ["--threads", str(threads)]
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        return time.perf_counter() - start


def run_table():
    print(f"1. cascade run {args.case} --until {args.until}, {cores} cores")
    print("   threads          alone (s)   beside a busy core (s)")
    for threads, label in [(1, "--threads 1"), (cores, f"--threads {cores}"), (0, "free cores")]:
        alone = cascade_run(threads)
        with BusyCore():
            beside = cascade_run(threads)
        print(f"   {label:15s} {alone:9.1f}   {beside:9.1f}")


def two_simulations(server_threads):
    with tempfile.TemporaryDirectory() as data:
        command = [str(build / "bin" / "cascade-server"), "--listen", "127.0.0.1:0", "--data-dir", data]
        if server_threads:
            command += ["--threads", str(server_threads)]
        server = subprocess.Popen(command, stderr=subprocess.PIPE, text=True)
        address = server.stderr.readline().split("listening on ")[1].split(",")[0]
        try:
            with cascade_client.Client(address) as client:
                sims = [client.create(args.case, overrides=["end_time=1e6"]) for _ in range(2)]
                for sim in sims:
                    sim.step(20)  # warm-up
                start = time.perf_counter()
                for sim in sims:
                    sim.step(args.steps)
                after = time.perf_counter() - start
                start = time.perf_counter()
                steppers = [threading.Thread(target=sim.step, args=(args.steps,)) for sim in sims]
                for t in steppers:
                    t.start()
                for t in steppers:
                    t.join()
                together = time.perf_counter() - start
                return after, together
        finally:
            server.terminate()
            server.wait(timeout=60)


def server_table():
    print(f"2. two simulations of {args.case} on one cascade-server, {args.steps} steps each")
    print("   server              one after the other (s)   together (s)")
    for threads, label in [(cores, f"--threads {cores}"), (0, "free cores")]:
        after, together = two_simulations(threads)
        print(f"   {label:18s} {after:12.1f}             {together:9.1f}")


run_table()
server_table()
