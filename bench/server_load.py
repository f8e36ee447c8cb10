"""The steering server under load (docs/performance.md, "Steering server"): the solver's steps/s
with 0, 16, and 8 watchers plus 2 query loops attached; and how long an UpdateForcing waits for
the step boundary at which it takes effect, on a running simulation.

    OMP_NUM_THREADS=1 /usr/bin/python3 bench/server_load.py --build build/release [--set dp=0.05]
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile
import threading
import time

import python_client

parser = argparse.ArgumentParser()
python_client.add_running_case_arguments(parser)
parser.add_argument("--steps", type=int, default=4000, help="steps per throughput measurement")
parser.add_argument("--changes", type=int, default=50, help="UpdateForcing requests timed")
parser.add_argument("--query-interval", type=float, default=0.0,
                    help="seconds between a query loop's queries (0: back to back)")
parser.add_argument("--server-cpus", default="",
                    help="run the server under taskset -c CPUS (and pin the clients elsewhere yourself)")
args = parser.parse_args()
build = python_client.use_client(args.build)
import cascade_client  # noqa: E402
import grpc  # noqa: E402


def watch(sim, stop, count):
    try:
        for _ in sim.watch(interval=0.05, events=True):
            count[0] += 1
            if stop.is_set():
                return
    except grpc.RpcError:
        pass


def query(sim, stop, count):
    while not stop.is_set():
        sim.query("pore_pressure", "velocity", phase="soil")
        count[0] += 1
        stop.wait(args.query_interval)


def steps_per_second(sim, watchers, queriers):
    """StepSimulation of --steps steps timed at the client, with the clients attached."""
    stop = threading.Event()
    counts = [[0] for _ in range(watchers + queriers)]
    threads = [threading.Thread(target=watch if k < watchers else query, args=(sim, stop, counts[k]))
               for k in range(watchers + queriers)]
    for t in threads:
        t.start()
    time.sleep(0.5)  # the streams are open
    start = time.perf_counter()
    sim.step(args.steps)
    rate = args.steps / (time.perf_counter() - start)
    stop.set()
    for t in threads:
        t.join()
    return rate, [c[0] for c in counts]


def steering_latency(sim):
    """UpdateForcing on the running simulation: per request, the steps finished between the status
    read just before it and its application (1: applied at the end of the step that was running,
    the next step boundary), and the wall times from sending to applying (the journal's wall_time)
    and to the reply."""
    requests = []  # (step reported before, wall time sent, effective step, wall time of the reply)
    for k in range(args.changes):
        before = sim.get().status.step
        sent = time.time()
        reply = sim.set_rainfall(1e-6 * (1 + k % 2))
        requests.append((before, sent, int(reply.effective_step), time.time()))
        time.sleep(0.02)
    journal = [json.loads(line) for line in pathlib.Path(sim.get().journal_path).read_text().splitlines()]
    applied = [e["wall_time"] for e in journal if e["command"] == "update_forcing"][-args.changes:]
    waited = [effective - 1 - before for before, _, effective, _ in requests]
    to_applied = [1e3 * (a - sent) for a, (_, sent, _, _) in zip(applied, requests)]
    to_reply = [1e3 * (replied - sent) for _, sent, _, replied in requests]
    return waited, to_applied, to_reply


def summary(values, unit):
    return f"median {statistics.median(values):.2f} {unit}, max {max(values):.2f} {unit}"


with tempfile.TemporaryDirectory() as data:
    pin = ["taskset", "-c", args.server_cpus] if args.server_cpus else []
    server = subprocess.Popen(pin + [str(build / "bin" / "cascade-server"), "--listen", "127.0.0.1:0", "--data-dir",
                                     data, "--threads", "1"], stderr=subprocess.PIPE, text=True)
    address = server.stderr.readline().split("listening on ")[1].split(",")[0]
    try:
        with cascade_client.Client(address) as client:
            sim = client.create(args.case, overrides=args.set)
            print(f"{args.case} {' '.join(args.set)}: {sim.get().particle_count} particles")
            sim.step(200)  # warm-up
            for watchers, queriers in [(0, 0), (16, 0), (8, 2), (0, 0)]:
                rate, counts = steps_per_second(sim, watchers, queriers)
                print(f"{watchers:2d} watchers, {queriers} query loops: {rate:7.0f} steps/s"
                      + (f"  (messages per client: {min(counts)}-{max(counts)})" if counts else ""))
            paused = sim.get().status.step
            print(f"UpdateForcing while paused at step {paused}: effective from step "
                  f"{sim.set_rainfall(1e-6).effective_step}")
            sim.resume()
            time.sleep(0.5)
            waited, to_applied, to_reply = steering_latency(sim)
            steps_per_s = sim.get().status.steps_per_second
            print(f"UpdateForcing while running at {steps_per_s:.0f} steps/s, {args.changes} requests:")
            tenth = statistics.quantiles(waited, n=10)
            print(f"  steps finished from the status read before it to its application: min {min(waited)}, "
                  f"median {statistics.median(waited):.0f}, 90% {tenth[-1]:.0f}, max {max(waited)} (with the steps "
                  "run while the client went from its Get to the request)")
            print(f"  sent -> applied at a step boundary: {summary(to_applied, 'ms')}")
            print(f"  sent -> reply (after the journal's fsync): {summary(to_reply, 'ms')}")
    finally:
        server.terminate()
        server.wait(timeout=30)
