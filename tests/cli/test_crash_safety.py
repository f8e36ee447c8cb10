"""kill -9 of cascade-server mid-run, five times at seeded random moments, one of them right after a
checkpoint request (issue 14, item 8). After each crash, on the same data dir:
  - the journal parses line by line and holds every forcing change a client was told was applied;
  - a new server lists every checkpoint a client was told was written, none of them unreadable,
    and no partial file among them; the newest restores, and the run goes on from there;
and at the end `cascade run --replay` of the last crashed journal, run to the newest checkpoint's
time, gives the checkpoint's state to the bit."""

import json
import random
import time
import unittest

import clitest

ROUNDS = 5


class KillNine(unittest.TestCase):
    def test_five_crashes_lose_nothing_acknowledged(self):
        clitest.use_python_client()
        import grpc
        import cascade_client
        from cascade.v1 import checkpoint_pb2

        rng = random.Random(14)
        case = clitest.fixture("rain_column")
        overrides = ["end_time=1e6"]
        acknowledged_checkpoints = []  # (name, step, time) CreateCheckpoint acknowledged
        sim_dir = None
        for round_ in range(ROUNDS):
            server = clitest.Server("kill9")  # the same data dir every round
            server.__enter__()
            acknowledged_rain = []  # intensities UpdateForcing acknowledged in this round
            try:
                client = cascade_client.Client(server.address)
                sim = client.simulation("run")
                if round_ == 0:
                    sim = client.create(case, overrides=overrides, simulation_id="run")
                else:
                    listed = sim.checkpoints()
                    names = [c.name for c in listed]
                    for name, _, _ in acknowledged_checkpoints:
                        self.assertIn(name, names, f"round {round_}: an acknowledged checkpoint is missing")
                    for c in listed:
                        self.assertEqual(c.error, "", f"round {round_}: {c.name} is unreadable")
                        self.assertTrue(c.path.endswith(".h5"), c.path)
                    newest = acknowledged_checkpoints[-1]
                    restored = sim.restore(newest[0].split("/")[-1])
                    self.assertEqual(restored.status.step, newest[1])
                (sim.start if round_ == 0 else sim.resume)()
                sim_dir = server.data_dir / "simulations" / "run"
                # Steering and checkpoints while it runs, for a random time.
                deadline = time.monotonic() + rng.uniform(0.3, 1.2)
                while time.monotonic() < deadline:
                    intensity = round(rng.uniform(1e-6, 5e-5), 9)
                    sim.update_forcing(rainfall__intensity=intensity)
                    acknowledged_rain.append(intensity)
                    if rng.random() < 0.3 or len(acknowledged_rain) == 1:  # at least one per round
                        c = sim.checkpoint()
                        acknowledged_checkpoints.append((c.name, c.step, c.time))
                    time.sleep(rng.uniform(0, 0.02))
                if round_ == ROUNDS - 1:  # the kill lands while a checkpoint is being taken
                    client._stub.CreateCheckpoint.future(checkpoint_pb2.CreateCheckpointRequest(parent=sim.name))
                    time.sleep(rng.uniform(0, 0.005))
            finally:
                server.process.kill()
                server.process.wait(timeout=30)
                server.process.stderr.close()
                client.close()
            self.assertEqual(server.process.returncode, -9)

            # The journal as the crash left it.
            entries = [json.loads(line) for line in (sim_dir / "journal.jsonl").read_text().splitlines()]
            journaled = [e["new_forcing"]["rainfall"]["intensity"] for e in entries
                         if e["command"] == "update_forcing"]
            # Every change acknowledged in this round is there (earlier rounds' changes after their
            # newest checkpoint were undone by the restore and kept in journal.jsonl.replaced-N).
            for intensity in acknowledged_rain:
                self.assertIn(intensity, journaled, f"round {round_}: an acknowledged forcing change is missing")
            self.assertGreater(len(acknowledged_rain), 0)
            print(f"round {round_}: {len(acknowledged_rain)} forcing changes acknowledged, all in the journal of "
                  f"{len(entries)} entries; {len(acknowledged_checkpoints)} checkpoints so far", flush=True)

        # The last crashed journal, replayed to the newest checkpoint, gives the checkpoint's state.
        name, step, t = acknowledged_checkpoints[-1]
        out = clitest.out_dir("kill9_replay")
        p = clitest.run("run", case, "--set", overrides[0], "--out", out, "--threads", "1",
                        "--replay", sim_dir / "journal.jsonl", "--until", repr(t), timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(json.loads((out / "run.json").read_text())["steps"], step)
        h5py = clitest.import_h5py()
        with clitest.Server("kill9") as server, cascade_client.Client(server.address) as client:
            sim = client.simulation("run")
            sim.restore(name.split("/")[-1])
            restored = sim.query("pore_pressure", "velocity")
        with h5py.File(out / "fields.h5") as f:
            frames = f["frames"]
            last = frames[sorted(frames.keys())[-1]]
            self.assertEqual(int(last.attrs["step"]), step)
            rows = restored["id"]  # the file's rows are in id order
            self.assertEqual(len(rows), len(last["id"][()]))
            for field in ("pore_pressure", "velocity"):
                self.assertEqual(last[field][()][rows].tobytes(), restored[field].tobytes(), field)


if __name__ == "__main__":
    clitest.main()
