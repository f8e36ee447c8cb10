"""32 concurrent clients against one running simulation (issue 14, item 10; docs/performance.md,
"32 clients"): 8 GetSimulation loops, 8 ListProbes loops, 8 WatchSimulation streams, 4 QueryFields
loops and 4 RenderSnapshot loops, back to back for --seconds: with --clients native (the default)
threads of one C++ process (bench/load_clients.cpp), with --clients python each a Python process
of its own (the clients then take most of their core themselves). The
simulation's solver thread (named cascade-solver) has a core of its own; the server's handlers and
the clients share the others ("one thread fewer than the cores"). Reports the solver's steps/s
alone before, under load and alone after (from the step counter, side by side in one run), the
errors, GetSimulation's latency percentiles, and the server's resident memory over the requests.

    /usr/bin/python3 bench/server_clients.py --build build/release [--seconds 60] [--clients native|python]
"""

import argparse
import json
import multiprocessing
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import python_client

parser = argparse.ArgumentParser()
python_client.add_running_case_arguments(parser)
parser.add_argument("--seconds", type=float, default=60.0, help="duration of the load")
parser.add_argument("--alone-seconds", type=float, default=15.0, help="duration of each measurement alone")
parser.add_argument("--clients", choices=["native", "python"], default="native",
                    help="the 32 clients as threads of bench/load_clients.cpp, or as Python processes")
args = parser.parse_args()
build = python_client.use_client(args.build)
import cascade_client  # noqa: E402
import grpc  # noqa: E402

CORES = sorted(os.sched_getaffinity(0))
SOLVER_CORE, OTHER_CORES = CORES[0], set(CORES[1:])
KINDS = ["get"] * 8 + ["probes"] * 8 + ["watch"] * 8 + ["query"] * 4 + ["snapshot"] * 4


def client_loop(kind, address, name, ready, stop, results):
    """One client, back to back until `stop` is set; puts (kind, requests, errors, Get latencies in
    s). It runs on the cores of the process that started it (main() leaves the solver's core out)."""
    requests, errors, latencies = 0, [], []
    with cascade_client.Client(address) as client:
        sim = client.simulation(name)
        sim.get()  # connected
        ready.wait()  # every client connected: the load starts at once
        try:
            if kind == "watch":
                for _ in sim.watch(interval=0.05, events=True):
                    requests += 1
                    if stop.is_set():
                        break
            while kind != "watch" and not stop.is_set():
                start = time.perf_counter()
                if kind == "get":
                    sim.get()
                    latencies.append(time.perf_counter() - start)
                elif kind == "probes":
                    sim.probes()
                elif kind == "query":
                    sim.query("pore_pressure", "velocity", phase="soil")
                else:
                    sim.snapshot(field="pore_pressure", phase="soil", width=320, height=180)
                requests += 1
        except grpc.RpcError as e:
            errors.append(f"{kind}: {e.code()} {e.details()}")
        except Exception as e:  # noqa: BLE001  (reported, not lost)
            errors.append(f"{kind}: {type(e).__name__}: {e}")
    results.put((kind, requests, errors, latencies))


def resident_mb(pid):
    for line in pathlib.Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def solver_tid(pid):
    for task in pathlib.Path(f"/proc/{pid}/task").iterdir():
        if (task / "comm").read_text().strip() == "cascade-solver":
            return int(task.name)
    raise SystemExit("no thread named cascade-solver")


def scheduled_seconds(pid, tid):
    """(seconds on a core, seconds runnable but waiting for one) of a thread, from the kernel's
    scheduler accounts (Documentation/scheduler/sched-stats.rst)."""
    on_core, waiting = (int(x) / 1e9 for x in pathlib.Path(f"/proc/{pid}/task/{tid}/schedstat").read_text().split()[:2])
    return on_core, waiting


class SolverClock:
    """How the solver thread spends a stretch of wall time: on its core, waiting for it, blocked."""

    def __init__(self, pid, tid):
        self.pid, self.tid = pid, tid
        self.start = (time.time(), *scheduled_seconds(pid, tid))

    def fractions(self):
        now, on_core, waiting = time.time(), *scheduled_seconds(self.pid, self.tid)
        wall = now - self.start[0]
        on, wait = (on_core - self.start[1]) / wall, (waiting - self.start[2]) / wall
        return f"on its core {100 * on:.1f}%, waiting for it {100 * wait:.1f}%, blocked {100 * (1 - on - wait):.1f}%"


def rate(sim, seconds):
    first, start = sim.get().status.step, time.time()
    time.sleep(seconds)
    return (sim.get().status.step - first) / (time.time() - start)


def main():
    if len(CORES) < 2:
        raise SystemExit("needs two cores: one for the solver, one for the handlers and the clients")
    data_dir = tempfile.TemporaryDirectory(prefix="cascade-clients-")  # the server's journals, removed after
    data = data_dir.name
    server = subprocess.Popen(["taskset", "-c", ",".join(map(str, sorted(OTHER_CORES))),
                               str(build / "bin" / "cascade-server"), "--listen", "127.0.0.1:0", "--data-dir", data,
                               "--threads", "1"], stderr=subprocess.PIPE, text=True)
    line = server.stderr.readline()
    address = "127.0.0.1:" + line.split("listening on ")[1].split(",")[0].rsplit(":", 1)[1]
    try:
        with cascade_client.Client(address) as client:
            sim = client.create(args.case, overrides=args.set)
            sim.start()
            solver = solver_tid(server.pid)
            os.sched_setaffinity(solver, {SOLVER_CORE})
            os.sched_setaffinity(0, OTHER_CORES)
            time.sleep(1.0)
            clock = SolverClock(server.pid, solver)
            before = rate(sim, args.alone_seconds)
            solver_before = clock.fractions()
            if args.clients == "native":
                native = subprocess.Popen([str(build / "bin" / "load_clients"), "--address", address, "--name", sim.name,
                                           "--seconds", str(args.seconds)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                          text=True)
                if native.stdout.readline().strip() != "ready":
                    raise SystemExit("load_clients did not connect")
                native.stdin.write("go\n")
                native.stdin.flush()
            else:
                results, ready, stop = multiprocessing.Queue(), multiprocessing.Barrier(len(KINDS) + 1), multiprocessing.Event()
                clients = [multiprocessing.Process(target=client_loop, args=(k, address, sim.name, ready, stop, results))
                           for k in KINDS]
                for c in clients:
                    c.start()
                ready.wait(timeout=300)  # the clients have started (imports take seconds each) and connected
            first_step, start = sim.get().status.step, time.time()
            clock = SolverClock(server.pid, solver)
            memory = []  # (seconds into the load, MB)
            while time.time() < start + args.seconds:
                memory.append((time.time() - start, resident_mb(server.pid)))
                time.sleep(1.0)
            loaded = (sim.get().status.step - first_step) / (time.time() - start)
            solver_loaded = clock.fractions()
            if args.clients == "native":
                report = json.loads(native.stdout.readline())
                native.wait(timeout=60)
                outcomes = [(k, n, [], []) for k, n in report["requests"].items()]
                outcomes.append(("get", 0, report["errors"], [ms / 1e3 for ms in report["get_latencies_ms"]]))
            else:
                stop.set()
                outcomes = [results.get(timeout=60) for _ in clients]
                for c in clients:
                    c.join()
            after = rate(sim, args.alone_seconds)
            state = cascade_client.State.Name(sim.get().state)
    finally:
        server.terminate()
        server.wait(timeout=30)
        data_dir.cleanup()

    requests = {k: sum(o[1] for o in outcomes if o[0] == k) for k in dict.fromkeys(KINDS)}
    errors = [e for o in outcomes for e in o[2]]
    latencies = sorted(x for o in outcomes for x in o[3])
    percentile = lambda q: latencies[min(len(latencies) - 1, int(q * len(latencies)))] * 1e3  # noqa: E731
    total = sum(requests.values())
    print(f"case {args.case} {' '.join(args.set)}; clients {args.clients}; solver on core {SOLVER_CORE}, server handlers and 32 clients "
          f"on {sorted(OTHER_CORES)}; load {os.getloadavg()[0]:.1f}")
    print(f"solver steps/s: alone before {before:.0f}, with 32 clients {loaded:.0f} "
          f"({100 * (loaded / before - 1):+.1f}%), alone after {after:.0f}; state {state}")
    print(f"solver thread alone: {solver_before}; with the clients: {solver_loaded}")
    print("requests: " + ", ".join(f"{k} {n}" for k, n in requests.items()) + f"; total {total}; errors {len(errors)}")
    for e in errors[:5]:
        print("  ", e)
    print(f"GetSimulation latency: p50 {percentile(0.5):.2f} ms, p99 {percentile(0.99):.2f} ms, "
          f"max {latencies[-1] * 1e3:.2f} ms over {len(latencies)} calls")
    settled = [m for t, m in memory if t >= 5.0] or [m for _, m in memory]  # a short run: all of it
    print(f"server resident memory: {memory[0][1]:.1f} MB at the start of the load, {settled[0]:.1f} MB after 5 s, "
          f"{memory[-1][1]:.1f} MB at the end ({total} requests); largest {max(m for _, m in memory):.1f} MB; "
          f"median {statistics.median(settled):.1f} MB")


if __name__ == "__main__":
    multiprocessing.set_start_method("spawn")  # gRPC does not survive a fork
    main()
