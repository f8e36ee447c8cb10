"""PNG snapshots from a real cascade-server (RenderSnapshot, StreamSnapshots; docs/rendering.md):
an image of the requested size that is not blank, with its metadata; four streams at once while
the simulation runs, frames in order; a run with streams attached gives the same bits as one
without; bad requests name the field; viewers may call them; a server without EGL answers
UNAVAILABLE and goes on serving."""

import math
import threading
import time
import unittest

import clitest

STREAMS = 4


def import_api():
    clitest.use_python_client()
    import grpc
    import cascade_client
    from cascade.v1 import scenario_pb2, simulation_pb2 as pb
    return grpc, cascade_client, scenario_pb2, pb


def read_stream(stream, frames, errors):
    try:
        for frame in stream:
            frames.append((frame.time, frame.step, len(frame.png)))
    except Exception as e:  # noqa: BLE001  (reported by the test)
        errors.append(e)


def attach_streams(sim, count, **interval):
    """`count` snapshot streams read on threads: (threads, per-stream frame lists, errors)."""
    frames, errors, threads = [[] for _ in range(count)], [], []
    for k in range(count):
        stream = sim.snapshots(**interval, field="pore_pressure", width=160, height=100)
        threads.append(threading.Thread(target=read_stream, args=(stream, frames[k], errors)))
        threads[-1].start()
    return threads, frames, errors


def end_fields(sim):
    return sim.query("pore_pressure", "saturation", "velocity", "density", "pressure")


class Snapshots(unittest.TestCase):
    def test_render_snapshot_is_a_png_of_the_requested_size_and_not_blank(self):
        _, cascade_client, _, _ = import_api()
        with clitest.Server("render") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            sim.step(10)
            image = sim.snapshot(metadata=True, field="pore_pressure", width=320, height=200)
            width, height, rows = clitest.png_pixels(image.png)
            self.assertEqual((width, height), (320, 200))
            self.assertEqual((image.width, image.height), (320, 200))
            white = b"\xff\xff\xff"
            drawn = sum(1 for row in rows for x in range(0, len(row), 3) if row[x:x + 3] != white)
            self.assertGreater(drawn, 0.3 * width * height)  # the column fills much of the picture
            self.assertEqual((image.step, image.time), (10, 20.0))
            self.assertEqual((image.field, image.units, image.camera), ("pore_pressure", "Pa", "side"))
            self.assertLess(image.range_min, image.range_max)
            self.assertEqual(image.drawn_particles, 120)  # the soil; the boundary is not drawn
            # The CLI writes the same kind of file.
            out = clitest.WORK_DIR / "cli_snapshot.png"
            p = server.cli("snapshot", sim.name, "--field", "saturation", "--width", "200", "--height", "120",
                           "--out", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(clitest.png_pixels(out.read_bytes())[:2], (200, 120))
            self.assertIn("step 10", p.stdout)

    def test_concurrent_streams_while_running_arrive_in_order(self):
        _, cascade_client, _, _ = import_api()
        with clitest.Server("streams") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            threads, frames, errors = attach_streams(sim, STREAMS, every_simulated_seconds=20)
            frames_dir = clitest.WORK_DIR / "watch_frames"
            watch = clitest.subprocess.Popen([str(clitest.CASCADE), "watch", sim.name, "--frames", str(frames_dir),
                                              "--every-wall", "0.05", "--server", server.address],
                                             stdout=clitest.subprocess.PIPE, stderr=clitest.subprocess.PIPE, text=True)
            deadline = time.monotonic() + 30
            while not all(frames) and time.monotonic() < deadline:  # each stream's first frame, then run
                time.sleep(0.02)
            sim.start()
            for t in threads:
                t.join(timeout=120)
            out, err = watch.communicate(timeout=60)
            self.assertEqual(errors, [])
            for stream in frames:
                self.assertGreaterEqual(len(stream), 2)
                self.assertEqual(stream[0][1], 0)  # the first frame at once, from the created state
                for (t0, s0, _), (t1, s1, size) in zip(stream, stream[1:]):
                    self.assertLessEqual(t0, t1)
                    self.assertLess(s0, s1)
                    self.assertGreater(size, 0)
            self.assertEqual(watch.returncode, 0, err)
            written = sorted(frames_dir.glob("frame_*.png"))
            self.assertGreaterEqual(len(written), 1)
            self.assertEqual(len(written), len(out.splitlines()))
            self.assertEqual(clitest.png_pixels(written[-1].read_bytes())[:2], (1280, 720))

    def test_streams_leave_the_fields_bit_identical(self):
        _, cascade_client, _, _ = import_api()
        with clitest.Server("identical") as server, cascade_client.Client(server.address) as client:
            plain = client.create(clitest.fixture("rain_column"), simulation_id="plain")
            watched = client.create(clitest.fixture("rain_column"), simulation_id="watched")
            threads, frames, errors = attach_streams(watched, STREAMS, every_wall_seconds=0.05)
            for sim in (plain, watched):
                sim.run_until(400)  # PAUSED there: the fields are compared at the same step
            ends = {sim.name: end_fields(sim) for sim in (plain, watched)}
            watched.delete()  # ends the streams
            for t in threads:
                t.join(timeout=60)
            self.assertEqual(errors, [])
            self.assertTrue(all(len(f) >= 1 for f in frames))
            a, b = ends[plain.name], ends[watched.name]
            self.assertEqual(a["step"], b["step"])
            for key in ("id", "position", "pore_pressure", "saturation", "velocity", "density", "pressure"):
                self.assertEqual(a[key].tobytes(), b[key].tobytes(), key)

    def test_bad_requests_name_the_field(self):
        grpc, cascade_client, scenario_pb2, pb = import_api()
        C = grpc.StatusCode
        with clitest.Server("bad") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            S = scenario_pb2.Snapshot
            bad_snapshots = [
                (S(width=3841), "snapshot.width"), (S(height=2161), "snapshot.height"), (S(width=-1), "snapshot.width"),
                (S(field="lava"), "snapshot.field"), (S(field="velocity_y"), "snapshot.field"),
                (S(phase="magma"), "snapshot.phase"), (S(translucent=["air"]), "snapshot.translucent[0]"),
                (S(min=math.nan), "snapshot.min"), (S(max=math.inf), "snapshot.max"),
                (S(min=1, max=0), "snapshot.max"), (S(camera="orbit"), "snapshot.camera"),
                (S(colour_map="jet"), "snapshot.colour_map"), (S(background=[2, 0, 0]), "snapshot.background[0]"),
                (S(background=[1, 1]), "snapshot.background"),
            ]
            for snapshot, field in bad_snapshots:
                with self.subTest(field=field, snapshot=str(snapshot)):
                    with self.assertRaises(grpc.RpcError) as raised:
                        client.call("RenderSnapshot", pb.RenderSnapshotRequest(name=sim.name, snapshot=snapshot))
                    self.assertEqual(raised.exception.code(), C.INVALID_ARGUMENT)
                    self.assertTrue(raised.exception.details().startswith(field + ":"), raised.exception.details())
                    with self.assertRaises(grpc.RpcError) as raised:
                        list(sim.snapshots(every_wall_seconds=1, **{f.name: v for f, v in snapshot.ListFields()}))
                    self.assertEqual(raised.exception.code(), C.INVALID_ARGUMENT)
                    self.assertTrue(raised.exception.details().startswith(field + ":"), raised.exception.details())
            bad_intervals = [({}, "interval"), ({"every_simulated_seconds": 0}, "every_simulated_seconds"),
                             ({"every_simulated_seconds": math.nan}, "every_simulated_seconds"),
                             ({"every_simulated_seconds": -1}, "every_simulated_seconds"),
                             ({"every_wall_seconds": 0.01}, "every_wall_seconds"),
                             ({"every_wall_seconds": 7200}, "every_wall_seconds"),
                             ({"every_wall_seconds": math.nan}, "every_wall_seconds")]
            for interval, field in bad_intervals:
                with self.subTest(field=field, interval=interval):
                    with self.assertRaises(grpc.RpcError) as raised:
                        list(sim.snapshots(**interval))
                    self.assertEqual(raised.exception.code(), C.INVALID_ARGUMENT)
                    self.assertTrue(raised.exception.details().startswith(field + ":"), raised.exception.details())
            for name, code in (("simulations/missing", C.NOT_FOUND), ("bad name", C.INVALID_ARGUMENT)):
                with self.assertRaises(grpc.RpcError) as raised:
                    client.call("RenderSnapshot", pb.RenderSnapshotRequest(name=name))
                self.assertEqual(raised.exception.code(), code)
                self.assertIn("name", raised.exception.details())
            self.assertEqual(len(clitest.png_pixels(sim.snapshot())[2]), 720)  # still serving

    def test_viewers_may_render(self):
        _, cascade_client, _, _ = import_api()
        with clitest.Server("viewer", "--tokens", clitest.token_file()) as server:
            with cascade_client.Client(server.address, token=clitest.OPERATOR_TOKEN) as operator:
                name = operator.create(clitest.fixture("rain_column")).name
            with cascade_client.Client(server.address, token=clitest.VIEWER_TOKEN) as viewer:
                sim = viewer.simulation(name)
                self.assertEqual(clitest.png_pixels(sim.snapshot(width=64, height=48))[:2], (64, 48))
                first = next(iter(sim.snapshots(every_wall_seconds=1, width=64, height=48)))
                self.assertEqual(first.step, 0)

    def test_without_egl_the_rpc_is_unavailable_and_the_server_serves_on(self):
        grpc, cascade_client, _, _ = import_api()
        no_egl = {"__EGL_VENDOR_LIBRARY_DIRS": "/nonexistent", "__EGL_VENDOR_LIBRARY_FILENAMES": "/nonexistent.json"}
        with clitest.Server("no_egl", env=no_egl) as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            with self.assertRaises(grpc.RpcError) as raised:
                sim.snapshot()
            self.assertEqual(raised.exception.code(), grpc.StatusCode.UNAVAILABLE)
            self.assertIn("EGL", raised.exception.details())
            self.assertEqual(sim.step(5).status.step, 5)


if __name__ == "__main__":
    clitest.main()
