"""`mpirun -np N cascade-server` (issue 17): a server split over processes answers as one process's.

Real processes: cascade-server under mpirun at 2 to 4 processes (one thread each, more processes than
cores with --oversubscribe) and alone, driven by the `cascade` client over loopback gRPC; their
query files, checkpoints and journals read back. Registered only in builds with CASCADE_MPI
(tests/CMakeLists.txt).

- The 2D dam break (dp = a/20) run to t = 0.03 s and 100 steps on: the fields and probe samples of
  the split server as the one-process server's, to round-off (positions within 1e-9 dp, every other field within
  1e-7 of its range: sums in another order, tests/parallel/test_split_run.cpp).
- A checkpoint written by the split server at 3 processes restores on a server at 2 processes and
  on one process (a new server on the same data dir) and goes on as the run that never stopped.
- A case with an implicit pore-water stage: the same fields at 3 processes as in one.
- A fork of a split simulation, its rain changed, and its parent: both as on one process.
- The journal of a steered run on the split server at 4 processes (the rain changed at step 40 of
  the rain column) replays in `cascade run --replay` as one process and at 2: the change at the
  same step, the same event, the same fields to round-off.
"""

import json
import unittest

import clitest

DP = 0.0073  # cases/dam_break_2d.yaml at dp = a/20, half its resolution
STEPS_ON = 100
WATER = ("velocity", "pressure", "density", "numerical_density")
SOIL = ("pore_pressure", "saturation", "seepage", "porosity", "velocity", "density", "effective_stress")


def query(server, name, out_name, fields=WATER):
    return clitest.query_frame(server, name, out_name, fields)


def json_of(p):
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


class SplitServer(unittest.TestCase):
    def assert_round_off(self, split, alone, dp, what):
        import numpy as np
        self.assertEqual(sorted(split), sorted(alone), what)
        compared = 0
        for key, values in alone.items():
            other = split[key]
            self.assertEqual(np.shape(other), np.shape(values), f"{what}: {key}")
            if not np.issubdtype(np.asarray(values).dtype, np.floating):
                self.assertTrue(np.array_equal(other, values), f"{what}: {key} differs")
            elif key == "position":
                self.assertLess(np.max(np.abs(other - values)) / dp, 1e-9, f"{what}: {key}")
            else:
                span = np.ptp(values) if np.size(values) else 0.0
                self.assertLessEqual(np.max(np.abs(other - values), initial=0.0), 1e-7 * span, f"{what}: {key}")
            compared += 1
        self.assertGreaterEqual(compared, 5)

    def assert_same_probes(self, split, alone):
        """The probes' samples, taken from each process's parts (server/io/sample_parts.h): the same
        steps, values to round-off (sums in another order), as in tests/cli/test_split_run.py."""
        import math
        self.assertEqual(split["probe_names"], alone["probe_names"])
        self.assertGreater(len(alone["samples"]), 2)
        self.assertEqual([s.get("step") for s in split["samples"]], [s.get("step") for s in alone["samples"]])
        for one, many in zip(alone["samples"], split["samples"]):
            for a, b in zip(one["values"], many["values"]):
                if isinstance(a, str) or math.isnan(a):  # a probe with no particle to read
                    self.assertTrue(isinstance(b, str) or math.isnan(b), (a, b))
                else:
                    self.assertAlmostEqual(b, a, delta=1e-9 * max(1.0, abs(a)))

    def test_fields_and_checkpoints_as_one_process(self):
        case = ["create", clitest.case("dam_break_2d"), "--set", f"dp={DP}", "--id", "db", "--json"]
        with clitest.Server("split_server_db", processes=3) as split:
            self.assertTrue(any("split over 3 processes" in line for line in split.notes), split.notes)
            self.assertEqual(json_of(split.cli(*case))["particle_count"], "1494")
            self.assertEqual(split.cli("run-until", "db", "0.03").returncode, 0)
            split_probes = json_of(split.cli("probes", "db", "--json"))
            split_at, step = query(split, "db", "split_at_checkpoint")
            checkpoint = json_of(split.cli("checkpoint", "db", "--json"))
            self.assertEqual(int(checkpoint["step"]), step)
            self.assertEqual(split.cli("step", "db", str(STEPS_ON)).returncode, 0)
            split_on, step_on = query(split, "db", "split_on")
            self.assertEqual(step_on, step + STEPS_ON)
            code, stderr = split.stop()  # SIGTERM to mpirun: it passes it on, and every process ends
            self.assertTrue(split.stopped_cleanly(code, stderr), stderr)

        with clitest.Server("split_server_alone") as alone:
            json_of(alone.cli(*case))
            self.assertEqual(alone.cli("run-until", "db", "0.03").returncode, 0)
            alone_probes = json_of(alone.cli("probes", "db", "--json"))
            alone_at, alone_step = query(alone, "db", "alone_at_checkpoint")
            self.assertEqual(alone_step, step)
            self.assertEqual(alone.cli("step", "db", str(STEPS_ON)).returncode, 0)
            alone_on, _ = query(alone, "db", "alone_on")
        self.assert_same_probes(split_probes, alone_probes)
        self.assert_round_off(split_at, alone_at, DP, "3 processes at the checkpoint")
        self.assert_round_off(split_on, alone_on, DP, f"3 processes {STEPS_ON} steps on")

        for processes in (2, None):  # the split server's checkpoint, on the same data dir
            with clitest.Server("split_server_db", processes=processes) as again:
                restored = json_of(again.cli("restore", "db", "ckpt-0001", "--json"))
                self.assertEqual((restored["state"], int(restored["status"]["step"])), ("PAUSED", step))
                self.assertEqual(again.cli("step", "db", str(STEPS_ON)).returncode, 0)
                restored_on, restored_step = query(again, "db", f"restored_{processes or 1}")
                self.assertEqual(restored_step, step + STEPS_ON)
            self.assert_round_off(restored_on, alone_on, DP, f"restored at {processes or 1} processes")

    def test_journal_of_a_steered_split_run_replays_at_any_count(self):
        with clitest.Server("split_server_steered", processes=4) as split:
            name = json_of(split.cli("create", clitest.fixture("rain_column"), "--id", "rain", "--json"))["name"]
            self.assertEqual(split.cli("step", name, "40").returncode, 0)
            self.assertEqual(split.cli("set", name, "rainfall.intensity=4e-6").returncode, 0)
            self.assertEqual(split.cli("step", name, "60").returncode, 0)
            end, step = query(split, name, "steered_split", SOIL)
            events = json_of(split.cli("events", name, "--json"))["events"]
            journal = json_of(split.cli("get", name, "--json"))["journal_path"]
        self.assertEqual(step, 100)
        changes = [e for e in events if e["kind"] == "forcing"]
        self.assertEqual(len(changes), 1, events)
        self.assertEqual(int(changes[0]["step"]), 40)

        replay_args = ("run", clitest.fixture("rain_column"), "--threads", "1", "--replay", journal,
                       "--until", repr(end_time(out_name="steered_split")))
        for processes in (None, 2):  # one process, and 2 under mpirun
            out = clitest.out_dir(f"split_server_replay_{processes or 1}")
            p = (clitest.mpirun(processes, *replay_args, "--out", out, timeout=120) if processes
                 else clitest.run(*replay_args, "--out", out, timeout=120))
            self.assertEqual(p.returncode, 0, p.stderr)
            summary = json.loads((out / "run.json").read_text())
            self.assertEqual(summary["steps"], step)
            replayed = [e for e in summary["events"] if e["kind"] == "forcing"]
            self.assertEqual([int(e["step"]) for e in replayed], [40], summary["events"])
            h5py = clitest.import_h5py()
            with h5py.File(out / "fields.h5") as f:
                last = f["frames"][sorted(f["frames"].keys())[-1]]
                self.assertEqual(int(last.attrs["step"]), step)
                replay = {k: last[k][()] for k in end if k in last}
            self.assert_round_off({k: end[k] for k in replay}, replay, 0.1, f"the replay at {processes or 1} processes")


    def test_a_staged_case_on_the_split_server_as_one_process(self):
        # The implicit pore-water stage runs on process 0 above the split engine; its states reach
        # the other processes as restores.
        frames = {}
        for processes in (3, None):
            with clitest.Server(f"split_server_staged_{processes or 1}", processes=processes) as server:
                json_of(server.cli("create", clitest.fixture("staged_column"), "--id", "soak", "--json"))
                self.assertEqual(server.cli("run-until", "soak", "100").returncode, 0)
                frames[processes], _ = query(server, "soak", f"staged_{processes or 1}", SOIL)
        self.assert_round_off(frames[3], frames[None], 0.05, "the staged column at 3 processes")

    def test_a_fork_of_a_split_simulation_as_one_process(self):
        # The fork is an engine of its own over all processes, restored from its parent's state.
        frames = {}
        for processes in (3, None):
            with clitest.Server(f"split_server_fork_{processes or 1}", processes=processes) as server:
                json_of(server.cli("create", clitest.fixture("rain_column"), "--id", "parent", "--json"))
                self.assertEqual(server.cli("step", "parent", "40").returncode, 0)
                json_of(server.cli("fork", "parent", "--id", "branch", "--json"))
                self.assertEqual(server.cli("set", "branch", "rainfall.intensity=4e-6").returncode, 0)
                for name in ("parent", "branch"):
                    self.assertEqual(server.cli("step", name, "60").returncode, 0)
                    frames[processes, name], step = query(server, name, f"fork_{name}_{processes or 1}", SOIL)
                    self.assertEqual(step, 100)
        for name in ("parent", "branch"):
            self.assert_round_off(frames[3, name], frames[None, name], 0.1, f"the {name} at 3 processes")
        # The fork's rain changed it: the comparison can fail.
        self.assertNotEqual(frames[None, "parent"]["pore_pressure"].tobytes(),
                            frames[None, "branch"]["pore_pressure"].tobytes())


def end_time(out_name):
    """The time of a query file's frame."""
    h5py = clitest.import_h5py()
    with h5py.File(clitest.WORK_DIR / f"{out_name}.h5") as f:
        return float(f["frames"]["000000"].attrs["time"])


if __name__ == "__main__":
    clitest.main()
