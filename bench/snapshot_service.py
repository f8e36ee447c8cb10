"""The snapshot RPCs' cost on a real cascade-server (docs/performance.md): the round trip of
RenderSnapshot (request → frame copied at a step boundary → render thread → PNG → client), and
the solver's steps/s with 0 and 4 StreamSnapshots streams attached.

    OMP_NUM_THREADS=1 /usr/bin/python3 bench/snapshot_service.py --build build/release [--set dp=0.05]
"""

import argparse
import pathlib
import statistics
import subprocess
import sys
import tempfile
import threading
import time

parser = argparse.ArgumentParser()
parser.add_argument("--build", default="build/release")
parser.add_argument("--case", default="tests/cli/fixtures/rain_column.yaml")
parser.add_argument("--set", action="append", default=["end_time=1e6"], help="case overrides, as cascade run --set")
parser.add_argument("--steps", type=int, default=2000)
args = parser.parse_args()
build = pathlib.Path(args.build).resolve()
sys.path[:0] = [str(build / "python"), str(pathlib.Path(__file__).resolve().parent.parent / "clients" / "python")]
import cascade_client  # noqa: E402
import grpc  # noqa: E402


def count_frames(stream, count):
    try:
        for _ in stream:
            count[0] += 1
    except grpc.RpcError:  # cancelled at the end of the measurement
        pass


def steps_per_second(sim, streams):
    readers = []
    for _ in range(streams):
        stream = sim.snapshots(every_wall_seconds=0.05, field="pore_pressure", width=640, height=360)
        count = [0]
        readers.append((stream, count, threading.Thread(target=count_frames, args=(stream, count))))
        readers[-1][2].start()
    time.sleep(0.5)  # the streams' first frames
    start = time.perf_counter()
    sim.step(args.steps)
    rate = args.steps / (time.perf_counter() - start)
    frames = [c[0] for _, c, _ in readers]
    for stream, _, thread in readers:
        stream.cancel()
        thread.join()
    return rate, frames


with tempfile.TemporaryDirectory() as data:
    server = subprocess.Popen([str(build / "bin" / "cascade-server"), "--listen", "127.0.0.1:0", "--data-dir", data,
                               "--threads", "1"], stderr=subprocess.PIPE, text=True)
    address = server.stderr.readline().split("listening on ")[1].split(",")[0]
    try:
        with cascade_client.Client(address) as client:
            sim = client.create(args.case, overrides=args.set)
            print(f"{args.case} {' '.join(args.set)}: {sim.get().particle_count} particles")
            sim.snapshot(width=64, height=64)  # the EGL context is made at the first render
            for width, height in ((640, 360), (1280, 720)):
                times = []
                for _ in range(20):
                    start = time.perf_counter()
                    sim.snapshot(field="pore_pressure", width=width, height=height)
                    times.append(time.perf_counter() - start)
                print(f"RenderSnapshot {width}x{height}: median {1e3 * statistics.median(times):.1f} ms, "
                      f"min {1e3 * min(times):.1f} ms (20 calls, paused simulation)")
            for streams in (0, 4, 0):
                rate, frames = steps_per_second(sim, streams)
                print(f"{streams} streams (640x360 every 0.05 s of wall time): {rate:.0f} steps/s over {args.steps} steps"
                      + (f", frames received per stream {frames}" if frames else ""))
    finally:
        server.terminate()
        server.wait(timeout=30)
