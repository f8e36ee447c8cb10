"""The operator's hand-over to the next stage on a real cascade-server (AdvanceStage): through the
CLI on a paused simulation and through the Python client on a running one and a created one, the
switch is journaled (`advance_stage` with the caller and the reason, then `stage_changed`),
reported as an event with the caller and shown in the status (stage, stage_name) to watchers;
refusals (last stage, ended run, a case without stages, viewer, bad name, bad reason) have their
codes; a checkpoint keeps the stage; `cascade run --replay` of the journal switches at the same step and ends with the same bits.

tests/cli/fixtures/staged_column.yaml: stages soak (pore water, no end criterion) and dynamic."""

import json
import unittest

import clitest

OPERATOR, VIEWER = clitest.OPERATOR_TOKEN, clitest.VIEWER_TOKEN
ADVANCE_STEP = 5   # the CLI's hand-over, while paused there; dt is 2 s in both stages
REASON = "wetting front at the base"
FIELDS = ("id", "position", "pore_pressure", "saturation", "seepage")


def staged_case():
    return clitest.fixture("staged_column")


def journal_entries(path):
    with open(path) as lines:
        return [json.loads(line) for line in lines]


def final_frame(h5py, path):
    """The last frame of a fields.h5 (the runner's) or the one frame of a query."""
    with h5py.File(path) as f:
        frame = f["frames"][sorted(f["frames"].keys())[-1]]
        return frame.attrs["time"], {k: frame[k][()] for k in FIELDS}


def stage_events(events):
    """(step, message) of the stage switches after the run's start."""
    return [(int(e.get("step", 0)), e.get("detail", e.get("message"))) for e in events
            if e["kind"] == "stage_changed" and not e.get("detail", e.get("message", "")).startswith("start:")]


class AdvanceThroughTheCli(unittest.TestCase):
    """Paused at step 5, the operator hands over; the run goes on to the end in the dynamic stage."""

    @classmethod
    def setUpClass(cls):
        h5py = clitest.import_h5py()
        with clitest.Server("cli", "--tokens", clitest.token_file()) as server:
            assert server.cli("create", staged_case(), "--id", "s", token=OPERATOR).returncode == 0
            p = server.cli("step", "s", str(ADVANCE_STEP), "--json", token=OPERATOR)
            assert p.returncode == 0, p.stderr
            cls.before = json.loads(p.stdout)
            cls.viewer = server.cli("advance-stage", "s", token=VIEWER)
            cls.bad_reason = server.cli("advance-stage", "s", "--reason", "x" * 501, token=OPERATOR)
            cls.bad_name = server.cli("advance-stage", "simulations/Bad_Name", token=OPERATOR)
            cls.unknown = server.cli("advance-stage", "missing", token=OPERATOR)
            cls.advanced = server.cli("advance-stage", "s", "--reason", REASON, "--json", token=OPERATOR)
            cls.printed = server.cli("get", "s", token=VIEWER)
            cls.at_last = server.cli("advance-stage", "s", token=OPERATOR)
            assert server.cli("resume", "s", token=OPERATOR).returncode == 0
            assert server.cli("watch", "s", "--interval", "0.1", token=VIEWER).returncode == 0  # to the end
            cls.after_end = server.cli("advance-stage", "s", token=OPERATOR)
            cls.events = json.loads(server.cli("events", "s", "--json", token=VIEWER).stdout)["events"]
            cls.end = json.loads(server.cli("get", "s", "--json", token=VIEWER).stdout)
            out = clitest.WORK_DIR / "server_end.h5"
            p = server.cli("query", "s", *FIELDS[2:], "--out", out, token=VIEWER)
            assert p.returncode == 0, p.stderr
            cls.server_end_time, cls.server_end = final_frame(h5py, out)
            cls.journal = cls.end["journal_path"]

    def test_the_reply_shows_the_new_stage(self):
        self.assertEqual(self.before["status"]["stage_name"], "soak")
        self.assertNotIn("stage", self.before["status"])   # 0, the default, is not written
        self.assertEqual(self.advanced.returncode, 0, self.advanced.stderr)
        reply = json.loads(self.advanced.stdout)
        self.assertEqual(reply["status"]["stage"], 1)
        self.assertEqual(reply["status"]["stage_name"], "dynamic")
        self.assertEqual(int(reply["status"]["step"]), ADVANCE_STEP)   # at the paused step boundary
        self.assertEqual(reply["state"], "PAUSED")
        self.assertIn("stage dynamic", self.printed.stdout)
        self.assertEqual(self.end["status"]["stage_name"], "dynamic")
        self.assertEqual(self.end["state"], "COMPLETED")

    def test_event_and_journal_name_the_caller(self):
        self.assertEqual([(e["kind"], int(e.get("step", 0)), e["caller"]) for e in self.events if e["kind"] == "stage_changed"],
                         [("stage_changed", 0, "solver"), ("stage_changed", ADVANCE_STEP, "alice")])
        [(_, message)] = stage_events(self.events)
        self.assertTrue(message.startswith("soak -> dynamic: requested by alice; "), message)
        entries = journal_entries(self.journal)
        advance = [e for e in entries if e["command"] == "advance_stage"]
        self.assertEqual(len(advance), 1)
        self.assertEqual((int(advance[0]["step"]), advance[0]["caller"], advance[0]["detail"]),
                         (ADVANCE_STEP, "alice", REASON))
        # The command, then the switch it made, at the same step.
        k = entries.index(advance[0])
        self.assertEqual((entries[k + 1]["command"], entries[k + 1]["caller"], int(entries[k + 1]["step"])),
                         ("stage_changed", "alice", ADVANCE_STEP))

    def test_refusals(self):
        for p, code, words in ((self.viewer, "PERMISSION_DENIED", "viewer"),
                               (self.bad_reason, "INVALID_ARGUMENT", "reason: at most 500 bytes"),
                               (self.bad_name, "INVALID_ARGUMENT", "name: "),
                               (self.unknown, "NOT_FOUND", "name: no simulation simulations/missing"),
                               (self.at_last, "FAILED_PRECONDITION", "the dynamic stage is the run's last"),
                               (self.after_end, "FAILED_PRECONDITION", "is completed")):
            with self.subTest(code=code, words=words):
                self.assertEqual(p.returncode, 1, p.stdout)
                self.assertIn(f"cascade advance-stage: {code}: ", p.stderr)
                self.assertIn(words, p.stderr)
        self.assertEqual(len([e for e in journal_entries(self.journal) if e["command"] == "advance_stage"]), 1)

    def test_replay_switches_at_the_same_step_with_the_same_bits(self):
        h5py = clitest.import_h5py()
        out = clitest.out_dir("replay")
        p = clitest.run("run", staged_case(), "--out", out, "--threads", "1", "--replay", self.journal)
        self.assertEqual(p.returncode, 0, p.stderr)
        replayed = json.loads((out / "run.json").read_text())["events"]
        self.assertEqual(stage_events(replayed), stage_events(self.events))
        time, fields = final_frame(h5py, out / "fields.h5")
        self.assertEqual(time, self.server_end_time)
        for key in FIELDS:
            self.assertEqual(fields[key].tobytes(), self.server_end[key].tobytes(), key)
        # Without the journal the run stays in the pore-water stage and ends elsewhere.
        plain = clitest.out_dir("plain")
        self.assertEqual(clitest.run("run", staged_case(), "--out", plain, "--threads", "1").returncode, 0)
        self.assertEqual(stage_events(json.loads((plain / "run.json").read_text())["events"]), [])
        _, fields = final_frame(h5py, plain / "fields.h5")
        self.assertNotEqual(fields["pore_pressure"].tobytes(), self.server_end["pore_pressure"].tobytes())


class AdvanceThroughPython(unittest.TestCase):
    def test_while_running_the_watchers_see_the_switch_and_the_replay_repeats_it(self):
        clitest.use_python_client()
        import cascade_client
        from cascade.v1 import simulation_pb2 as pb
        h5py = clitest.import_h5py()
        # Long enough (2000 steps) to be still running when the hand-over comes.
        overrides = ["end_time=4000"]
        with clitest.Server("python", "--tokens", clitest.token_file()) as server, \
                cascade_client.Client(server.address, token=OPERATOR) as client:
            sim = client.create(staged_case(), overrides=overrides, simulation_id="r")
            sim.start()
            statuses, advanced = [], None
            for update in sim.watch(interval=0.05, events=True):
                if isinstance(update, pb.Status):
                    statuses.append(update)
                    if advanced is None and update.step >= 20:
                        advanced = sim.advance_stage("by script")
            self.assertEqual(statuses[-1].state, pb.Simulation.COMPLETED)
            self.assertEqual((advanced.status.stage, advanced.status.stage_name), (1, "dynamic"))
            switch = [e for e in sim.events() if e.kind == "stage_changed" and e.caller == "alice"]
            self.assertEqual(len(switch), 1)
            self.assertGreaterEqual(switch[0].step, 20)
            self.assertLess(switch[0].time, 4000)
            # The watchers' statuses: soak before the switch, dynamic after it (at its step, either:
            # the status published after the step, or the one after the switch).
            before = [(s.stage, s.stage_name) for s in statuses if s.step < switch[0].step]
            after = [(s.stage, s.stage_name) for s in statuses if s.step > switch[0].step]
            self.assertTrue(before and after, [s.step for s in statuses])
            self.assertEqual(set(before), {(0, "soak")})
            self.assertEqual(set(after), {(1, "dynamic")})
            entry = next(e for e in journal_entries(sim.get().journal_path) if e["command"] == "advance_stage")
            self.assertEqual((int(entry["step"]), entry["caller"], entry["detail"]), (switch[0].step, "alice", "by script"))
            out = clitest.WORK_DIR / "running_end.h5"
            self.assertEqual(server.cli("query", "r", *FIELDS[2:], "--out", out, token=VIEWER).returncode, 0)
            server_time, server_fields = final_frame(h5py, out)

            replay = clitest.out_dir("running_replay")
            p = clitest.run("run", staged_case(), "--set", overrides[0], "--out", replay, "--threads", "1",
                            "--replay", sim.get().journal_path)
            self.assertEqual(p.returncode, 0, p.stderr)
            replayed = [e for e in json.loads((replay / "run.json").read_text())["events"] if e["kind"] == "stage_changed"]
            self.assertEqual([int(e.get("step", 0)) for e in replayed], [0, switch[0].step])
            time, fields = final_frame(h5py, replay / "fields.h5")
            self.assertEqual(time, server_time)
            for key in FIELDS:
                self.assertEqual(fields[key].tobytes(), server_fields[key].tobytes(), key)

    def test_created_refusals_and_a_case_without_stages(self):
        clitest.use_python_client()
        import grpc
        import cascade_client
        with clitest.Server("python_refusals", "--tokens", clitest.token_file()) as server, \
                cascade_client.Client(server.address, token=OPERATOR) as client, \
                cascade_client.Client(server.address, token=VIEWER) as viewer:
            sim = client.create(staged_case(), simulation_id="c")
            reply = sim.advance_stage()   # CREATED: at once, at step 0
            self.assertEqual((reply.state, reply.status.step, reply.status.stage_name), (reply.CREATED, 0, "dynamic"))
            entry = next(e for e in journal_entries(reply.journal_path) if e["command"] == "advance_stage")
            self.assertEqual((int(entry.get("step", 0)), entry["caller"], entry.get("detail", "")), (0, "alice", ""))
            # A checkpoint carries the stage: restored, the simulation is still in the dynamic stage.
            sim.step(2)
            restored = sim.restore(sim.checkpoint().name)
            self.assertEqual((restored.status.step, restored.status.stage, restored.status.stage_name), (2, 1, "dynamic"))
            self.assertEqual(sim.step(1).status.stage_name, "dynamic")

            refusals = (
                (client.simulation("c"), {}, grpc.StatusCode.FAILED_PRECONDITION, "simulations/c: the dynamic stage"),
                (client.create(clitest.fixture("rain_column"), simulation_id="plain"), {},
                 grpc.StatusCode.FAILED_PRECONDITION, "simulations/plain: the run has no further stage"),
                (viewer.simulation("c"), {}, grpc.StatusCode.PERMISSION_DENIED, "bob is a viewer"),
                (client.simulation("simulations/c/x"), {}, grpc.StatusCode.INVALID_ARGUMENT, "name: "),
                (client.simulation("nothing"), {}, grpc.StatusCode.NOT_FOUND, "name: no simulation"),
                (client.simulation("c"), {"reason": "two\nlines"}, grpc.StatusCode.INVALID_ARGUMENT,
                 "reason: holds a control character (code 10) at byte 3"),
            )
            for target, arguments, code, words in refusals:
                with self.subTest(code=code, words=words):
                    with self.assertRaises(grpc.RpcError) as raised:
                        target.advance_stage(**arguments)
                    self.assertEqual(raised.exception.code(), code, raised.exception.details())
                    self.assertIn(words, raised.exception.details())
            self.assertEqual(client.simulation("plain").get().status.stage_name, "dynamic")


if __name__ == "__main__":
    clitest.main()
