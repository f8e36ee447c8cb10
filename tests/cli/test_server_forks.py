"""What-if forks on a real cascade-server (issue 15, item 3; docs/api.md, ForkSimulation):

- fork at step N, run parent and fork K steps without a change: the fields are bit-identical to each
  other and to a simulation that ran N + K steps unforked (a moving dam break);
- a fork with the case's rain series times 3 (rainfall.factor): identical to the parent up to the
  fork, different after; the rain that entered is the series times 3 from the fork on; `cascade run
  --replay` of the fork's journal gives the same bits; the journals name parent, fork and step;
- bad requests: INVALID_ARGUMENT naming the field, NOT_FOUND, ALREADY_EXISTS, PERMISSION_DENIED for
  a viewer, and the server goes on;
- the ensemble helpers (`cascade ensemble`, cascade_client.ensemble): branches from one step with
  rain factors and a hyetograph, side by side; the unchanged branch equals the parent run on, bit
  for bit; the heavy branches pond, the unchanged one does not."""

import json
import unittest

import clitest

FORK_STEP, AFTER = 60, 40
# The rain column with a series (1e-6 m/s, then 4e-6 m/s from t = 300 s) and the ponding event.
SERIES_CASE = """
hydraulics:
  rainfall:
    - {time: 0, intensity: 1e-6}
    - {time: 300, intensity: 4e-6}
  ponding_pressure: 0

events: {ponding_started: true}
"""
SERIES_FORK_STEP = 100  # dt is max_dt = 2 s: t = 200 s
FACTOR = 3.0


def series_case():
    """tests/cli/fixtures/rain_column.yaml with SERIES_CASE for its hydraulics."""
    text = clitest.fixture("rain_column").read_text()
    head, rest = text.split("hydraulics:", 1)
    tail = rest[rest.index("output:"):]
    path = clitest.WORK_DIR / "rain_series_column.yaml"
    path.write_text(head + SERIES_CASE.lstrip("\n") + "\n" + tail)
    return path


def query(server, name, out, *fields):
    h5py = clitest.import_h5py()
    p = server.cli("query", name, *fields, "--out", out)
    assert p.returncode == 0, p.stderr
    with h5py.File(out) as f:
        frame = f["frames"]["000000"]
        return {k: frame[k][()] for k in ("id", "position", *fields)}, frame.attrs["time"]


def journal(path):
    with open(path) as lines:
        return [json.loads(line) for line in lines]


class ForkWithoutChange(unittest.TestCase):
    """A dam break (water moving everywhere): parent, fork and an unforked run agree to the bit."""

    @classmethod
    def setUpClass(cls):
        fields = ("velocity", "pressure", "density")
        case = clitest.case("dam_break_2d")
        with clitest.Server("forks") as server:
            for sim in ("parent", "plain"):
                p = server.cli("create", case, "--set", "dp=0.02", "--id", sim)
                assert p.returncode == 0, p.stderr
            assert server.cli("step", "parent", str(FORK_STEP)).returncode == 0
            p = server.cli("fork", "parent", "--id", "branch", "--json")
            assert p.returncode == 0, p.stderr
            cls.fork_reply = json.loads(p.stdout)
            for sim, steps in (("parent", AFTER), ("branch", AFTER), ("plain", FORK_STEP + AFTER)):
                assert server.cli("step", sim, str(steps)).returncode == 0
            cls.frames = {sim: query(server, sim, clitest.WORK_DIR / f"{sim}.h5", *fields)[0]
                          for sim in ("parent", "branch", "plain")}
            cls.journals = {sim: journal(json.loads(server.cli("get", sim, "--json").stdout)["journal_path"])
                            for sim in ("parent", "branch")}
            cls.fields = ("position",) + fields

    def test_fork_starts_paused_at_the_parents_step(self):
        self.assertEqual(self.fork_reply["name"], "simulations/branch")
        self.assertEqual(self.fork_reply["state"], "PAUSED")
        self.assertEqual(int(self.fork_reply["status"]["step"]), FORK_STEP)

    def test_fields_are_bit_identical_to_the_parent_and_to_an_unforked_run(self):
        for key in self.fields:
            parent = self.frames["parent"][key].tobytes()
            self.assertEqual(self.frames["branch"][key].tobytes(), parent, key)
            self.assertEqual(self.frames["plain"][key].tobytes(), parent, key)
        # The comparison can fail: the water moved between the fork and the end.
        self.assertGreater(abs(self.frames["parent"]["velocity"]).max(), 0.1)

    def test_journals_name_parent_fork_and_step(self):
        parent = [(e["command"], e.get("detail", ""), int(e.get("step", 0))) for e in self.journals["parent"]]
        self.assertIn(("fork", "simulations/branch", FORK_STEP), parent)
        branch = [(e["command"], e.get("detail", ""), int(e.get("step", 0))) for e in self.journals["branch"]]
        # The parent's journal up to and with its `fork` entry, then the fork's own.
        k = branch.index(("forked_from", f"simulations/parent at step {FORK_STEP}", FORK_STEP))
        self.assertEqual(branch[:k], parent[:k])
        self.assertEqual(branch[k - 1][0], "fork")
        self.assertEqual(branch[k + 1:], [("step", str(AFTER), FORK_STEP)])


class ForkOfRunningSimulation(unittest.TestCase):
    """Forked while it runs: the parent goes on running to its end, the fork starts PAUSED at the
    step where the parent took it, and resumed to the end it ends with the parent's bits."""

    def test_the_running_parent_goes_on_and_the_fork_ends_as_it_does(self):
        with clitest.Server("running_fork") as server:
            # 3,000 steps of 2 s: long enough that the fork lands while the parent runs.
            assert server.cli("create", clitest.fixture("rain_column"), "--set", "end_time=6000", "--id",
                              "parent").returncode == 0
            assert server.cli("start", "parent").returncode == 0
            p = server.cli("fork", "parent", "--id", "branch", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            fork = json.loads(p.stdout)
            self.assertEqual(fork["state"], "PAUSED")
            step = int(fork["status"].get("step", 0))
            assert server.cli("resume", "branch").returncode == 0
            for sim in ("parent", "branch"):
                assert server.cli("watch", sim, "--interval", "0.1").returncode == 0  # to the end
            ends = {sim: json.loads(server.cli("get", sim, "--json").stdout) for sim in ("parent", "branch")}
            frames = {sim: query(server, sim, clitest.WORK_DIR / f"running_{sim}.h5", "pore_pressure")[0]
                      for sim in ("parent", "branch")}
            parent_journal = journal(ends["parent"]["journal_path"])
        self.assertEqual([e["state"] for e in ends.values()], ["COMPLETED", "COMPLETED"])
        # The parent journaled the fork while running, at the fork's step.
        forks = [e for e in parent_journal if e["command"] == "fork"]
        self.assertEqual([(e["detail"], int(e.get("step", 0))) for e in forks], [("simulations/branch", step)])
        self.assertLess(step, 3000)  # taken before the end
        self.assertEqual(frames["branch"]["pore_pressure"].tobytes(), frames["parent"]["pore_pressure"].tobytes())


class ForkOfStagedRun(unittest.TestCase):
    """A fork in the implicit pore-water stage (tests/cli/fixtures/staged_column.yaml): the stage,
    its next step and the hand-over to the dynamic stage go on as in the parent and in a run that
    was never forked."""

    def test_fork_in_the_implicit_stage_goes_on_bit_identically(self):
        fields = ("velocity", "pore_pressure", "saturation", "effective_stress")
        with clitest.Server("staged_forks") as server:
            for sim in ("parent", "plain"):
                assert server.cli("create", clitest.fixture("staged_column"), "--id", sim).returncode == 0
            assert server.cli("step", "parent", "5").returncode == 0
            p = server.cli("fork", "parent", "--id", "branch", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(json.loads(p.stdout)["status"]["stage_name"], "soak")
            at_fork = query(server, "parent", clitest.WORK_DIR / "staged_at_fork.h5", *fields)[0]
            for sim, first in (("parent", 5), ("branch", 5), ("plain", 10)):
                assert server.cli("step", sim, str(first)).returncode == 0
                assert server.cli("advance-stage", sim).returncode == 0
                assert server.cli("step", sim, "20").returncode == 0
            frames = {sim: query(server, sim, clitest.WORK_DIR / f"staged_{sim}.h5", *fields)[0]
                      for sim in ("parent", "branch", "plain")}
            stages = {sim: json.loads(server.cli("get", sim, "--json").stdout)["status"]["stage_name"]
                      for sim in ("parent", "branch", "plain")}
        self.assertEqual(set(stages.values()), {"dynamic"})
        for key in ("position",) + fields:
            self.assertEqual(frames["branch"][key].tobytes(), frames["parent"][key].tobytes(), key)
            self.assertEqual(frames["plain"][key].tobytes(), frames["parent"][key].tobytes(), key)
        # The comparison can fail: the pore pressure changed after the fork.
        self.assertNotEqual(frames["parent"]["pore_pressure"].tobytes(), at_fork["pore_pressure"].tobytes())


class ForkWithRainFactor(unittest.TestCase):
    """The case's rain series times 3 from the fork on (rainfall.factor)."""

    @classmethod
    def setUpClass(cls):
        cls.case = series_case()
        with clitest.Server("factor") as server:
            assert server.cli("create", cls.case, "--id", "parent").returncode == 0
            assert server.cli("step", "parent", str(SERIES_FORK_STEP)).returncode == 0
            p = server.cli("fork", "parent", f"rainfall.factor={FACTOR}", "--id", "wet", "--json")
            assert p.returncode == 0, p.stderr
            cls.fork_reply = json.loads(p.stdout)
            for sim in ("parent", "wet"):
                assert server.cli("resume", sim).returncode == 0
                assert server.cli("watch", sim, "--interval", "0.1").returncode == 0  # to the end
            cls.probes = {sim: json.loads(server.cli("probes", sim, "--json").stdout)["samples"] for sim in ("parent", "wet")}
            cls.end, cls.end_time = query(server, "wet", clitest.WORK_DIR / "wet.h5", "pore_pressure", "saturation")
            wet = json.loads(server.cli("get", "wet", "--json").stdout)
            cls.pore_water, cls.journal, cls.forcing = wet["status"]["pore_water"], wet["journal_path"], wet["forcing"]
            cls.parent_pore_water = json.loads(server.cli("get", "parent", "--json").stdout)["status"]["pore_water"]

    def test_the_fork_reports_the_factor(self):
        self.assertEqual(self.fork_reply["forcing"]["rainfall"]["factor"], FACTOR)
        self.assertEqual(self.fork_reply["forcing"]["rainfall"]["intensity"], FACTOR * 1e-6)
        self.assertEqual(self.forcing["rainfall"]["intensity"], FACTOR * 4e-6)  # the series' second block

    def test_identical_up_to_the_fork_different_after(self):
        fork_time = 2.0 * SERIES_FORK_STEP
        parent, wet = self.probes["parent"], self.probes["wet"]
        before = [s for s in parent if s.get("time", 0.0) <= fork_time]
        self.assertGreater(len(before), 10)
        self.assertEqual(wet[:len(before)], before)
        # Every sample after the fork differs (the rain reaches the top probe within one probe
        # interval), and three times the rain leaves the top wetter.
        self.assertEqual(len(wet), len(parent))
        for a, b in zip(parent[len(before):], wet[len(before):]):
            self.assertEqual(a["time"], b["time"])
            self.assertNotEqual(a["values"][0], b["values"][0], f"p_top at t = {a['time']}")
        self.assertGreater(wet[-1]["values"][0], parent[-1]["values"][0])

    def test_the_rain_that_entered_is_the_series_times_the_factor_from_the_fork(self):
        # The column's 12 top particles over its 1.2 m width; nothing ponds (the ponding event is off
        # in both: checked by the ensemble tests below at heavier rain).
        fork_time = 2.0 * SERIES_FORK_STEP
        parent = 1.2 * (1e-6 * 300 + 4e-6 * 300)
        wet = 1.2 * (1e-6 * fork_time + FACTOR * 1e-6 * (300 - fork_time) + FACTOR * 4e-6 * 300)
        self.assertAlmostEqual(self.parent_pore_water["rain"], parent, delta=1e-9 * parent)
        self.assertAlmostEqual(self.pore_water["rain"], wet, delta=1e-9 * wet)

    def test_replay_of_the_forks_journal_is_bit_identical(self):
        h5py = clitest.import_h5py()
        out = clitest.out_dir("fork_replay")
        p = clitest.run("run", self.case, "--out", out, "--threads", "1", "--replay", self.journal)
        self.assertEqual(p.returncode, 0, p.stderr)
        with h5py.File(out / "fields.h5") as f:
            last = f["frames"][sorted(f["frames"].keys())[-1]]
            self.assertEqual(last.attrs["time"], self.end_time)
            for key in ("id", "position", "pore_pressure", "saturation"):
                self.assertEqual(last[key][()].tobytes(), self.end[key].tobytes(), key)
        # Without the journal the run differs: the comparison can fail.
        plain = clitest.out_dir("fork_plain")
        self.assertEqual(clitest.run("run", self.case, "--out", plain, "--threads", "1").returncode, 0)
        with h5py.File(plain / "fields.h5") as f:
            last = f["frames"][sorted(f["frames"].keys())[-1]]
            self.assertNotEqual(last["pore_pressure"][()].tobytes(), self.end["pore_pressure"].tobytes())


class BadForks(unittest.TestCase):
    def test_each_bad_request_gets_its_error_and_the_server_goes_on(self):
        token = clitest.token_file()
        with clitest.Server("bad_forks", "--tokens", token) as server:
            op = clitest.OPERATOR_TOKEN
            self.assertEqual(server.cli("create", clitest.fixture("rain_column"), "--id", "p", token=op).returncode, 0)
            cases = [
                (("fork", "p", "rainfall.factor=-1"), "INVALID_ARGUMENT: forcing.rainfall.factor: must be in [0, 100]"),
                (("fork", "p", "rainfall.factor=200"), "INVALID_ARGUMENT: forcing.rainfall.factor"),
                (("fork", "p", "rainfall.factor=2", "rainfall.intensity=1e-5"),
                 "INVALID_ARGUMENT: update_mask.paths[0]: rainfall.factor scales the case's rain"),
                (("fork", "p", "rainfall.intensity=5"), "INVALID_ARGUMENT: forcing.rainfall.intensity"),
                (("fork", "p", "--id", "Not-An-Id"), "INVALID_ARGUMENT: simulation_id"),
                (("fork", "p", "--id", "p"), "ALREADY_EXISTS: simulation_id: simulations/p exists"),
                (("fork", "nobody"), "NOT_FOUND: name: no simulation simulations/nobody"),
            ]
            for args, expected in cases:
                p = server.cli(*args, token=op)
                self.assertEqual(p.returncode, 1, args)
                self.assertIn(expected, p.stderr, args)
            p = server.cli("fork", "p", token=clitest.VIEWER_TOKEN)
            self.assertEqual(p.returncode, 1)
            self.assertIn("PERMISSION_DENIED", p.stderr)
            # Through the Python client: a forcing without a mask names the mask.
            clitest.use_python_client()
            import cascade_client
            import grpc
            from cascade.v1 import journal_pb2
            from cascade.v1 import simulation_pb2 as pb
            with cascade_client.Client(server.address, token=op) as client:
                with self.assertRaises(grpc.RpcError) as raised:
                    client.call("ForkSimulation", pb.ForkSimulationRequest(
                        name="simulations/p", forcing=journal_pb2.Forcing(rainfall=journal_pb2.Rainfall(intensity=1e-5))))
                self.assertEqual(raised.exception.code(), grpc.StatusCode.INVALID_ARGUMENT)
                self.assertTrue(raised.exception.details().startswith("update_mask:"), raised.exception.details())
            # No fork was made by any of them, and the server still forks.
            listed = json.loads(server.cli("list", "--json", token=op).stdout)["simulations"]
            self.assertEqual([s["name"] for s in listed], ["simulations/p"])
            self.assertEqual(server.cli("fork", "p", "--id", "ok", token=op).returncode, 0)


class RunUntilAnEvent(unittest.TestCase):
    def test_run_until_stops_after_the_event_and_refuses_an_unknown_kind(self):
        with clitest.Server("stop_after") as server:
            case = clitest.WORK_DIR / "stop_column.yaml"
            case.write_text(series_case().read_text().replace("intensity: 1e-6}", "intensity: 2.5e-4}"))
            assert server.cli("create", case, "--id", "c").returncode == 0
            p = server.cli("run-until", "c", "500", "--stop-after", "ponding_started:10", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            stopped = json.loads(p.stdout)
            ponding = [e for e in json.loads(server.cli("events", "c", "--json").stdout)["events"]
                       if e["kind"] == "ponding_started"]
            self.assertEqual(len(ponding), 1)
            self.assertEqual(stopped["state"], "PAUSED")
            self.assertGreaterEqual(stopped["status"]["time"], ponding[0]["time"] + 10.0)
            self.assertLessEqual(stopped["status"]["time"], ponding[0]["time"] + 12.0)  # steps of at most 2 s
            for args, field in ((("--stop-after", "landslide:1"), "stop_after_event.kind"),
                                (("--stop-after", "ponding_started:-1"), "stop_after_event.seconds")):
                p = server.cli("run-until", "c", "600", *args)
                self.assertEqual(p.returncode, 1)
                self.assertIn(f"INVALID_ARGUMENT: {field}", p.stderr)


class Ensembles(unittest.TestCase):
    """Branches at 1 and 50 times the rain and a hyetograph of 8e-4 m/s from t = 300 s, forked from
    the column at t = 200 s (its own rain 5e-6 m/s, K_sat 1e-4 m/s), run side by side to 500 s."""

    UNTIL = 500.0

    @classmethod
    def setUpClass(cls):
        text = series_case().read_text().replace(SERIES_CASE.lstrip("\n"), """hydraulics:
  rainfall_intensity: 5e-6
  ponding_pressure: 0

events: {ponding_started: true}
""")
        cls.case = clitest.WORK_DIR / "ponding_column.yaml"
        cls.case.write_text(text)
        cls.hyetograph = clitest.WORK_DIR / "storm.csv"
        cls.hyetograph.write_text("time,intensity\n0,18\n300,2880\n")  # mm/h: 5e-6, then 8e-4 m/s

    def check_branches(self, rows, server, parent, stop_after=None):
        """Each branch ran to UNTIL, or with stop_after = seconds, ended that long after its own
        ponding, at the first step boundary at or after it (steps of at most 2 s)."""
        by_label = {row["branch"]: row for row in rows}
        self.assertEqual(set(by_label), {"rain x1", "rain x50", "storm.csv"})
        for row in rows:
            if stop_after is None or row["ponding"] is None:
                self.assertGreaterEqual(row["time"], self.UNTIL, row["branch"])
            else:
                self.assertGreaterEqual(row["time"], row["ponding"] + stop_after, row["branch"])
                self.assertLessEqual(row["time"], row["ponding"] + stop_after + 2.0, row["branch"])
        self.assertIsNone(by_label["rain x1"]["ponding"])
        self.assertGreater(by_label["rain x50"]["ponding"], 2.0 * SERIES_FORK_STEP)
        self.assertGreater(by_label["storm.csv"]["ponding"], 300.0)
        # The unchanged branch is the parent run on to the same time, bit for bit.
        assert server.cli("run-until", parent, str(self.UNTIL)).returncode == 0
        unchanged, _ = query(server, by_label["rain x1"]["simulation"], clitest.WORK_DIR / "x1.h5", "pore_pressure")
        ran_on, _ = query(server, parent, clitest.WORK_DIR / "parent_on.h5", "pore_pressure")
        self.assertEqual(unchanged["pore_pressure"].tobytes(), ran_on["pore_pressure"].tobytes())

    def test_cli_ensemble(self):
        with clitest.Server("ensemble_cli", "--threads", "2") as server:
            assert server.cli("create", self.case, "--id", "p").returncode == 0
            assert server.cli("step", "p", str(SERIES_FORK_STEP)).returncode == 0
            table = clitest.WORK_DIR / "ensemble.csv"
            p = server.cli("ensemble", "p", "--rain-factors", "1,50", "--hyetograph", self.hyetograph,
                           "--time-unit", "s", "--intensity-unit", "mm/h", "--until", str(self.UNTIL),
                           "--out", table, "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            reply = json.loads(p.stdout)
            self.assertEqual(reply["fork_time"], 2.0 * SERIES_FORK_STEP)
            rows = [{"branch": b["branch"], "simulation": b["simulation"], "time": b["time_s"],
                     "ponding": b["ponding_s"]} for b in reply["branches"]]
            self.assertEqual(len(table.read_text().splitlines()), 4)
            self.check_branches(rows, server, "p")
            # The hyetograph's second row applied at the first step boundary at or after 300 s.
            storm = next(b for b in reply["branches"] if b["branch"] == "storm.csv")
            entries = journal(json.loads(server.cli("get", storm["simulation"], "--json").stdout)["journal_path"])
            changes = [e for e in entries if e["command"] == "update_forcing"]
            intensities = [e["new_forcing"]["rainfall"]["intensity"] for e in changes]
            self.assertEqual(len(intensities), 2)
            for got, want in zip(intensities, (5e-6, 8e-4)):
                self.assertAlmostEqual(got, want, delta=1e-15 * want)  # mm/h to m/s: one division
            self.assertGreaterEqual(changes[1]["time"], 300.0)

    def test_python_ensemble_table_and_plot(self):
        clitest.use_python_client()
        import cascade_client
        from cascade_client.ensemble import ensemble

        with clitest.Server("ensemble_python", "--threads", "2") as server, cascade_client.Client(server.address) as client:
            sim = client.create(self.case, simulation_id="p")
            sim.step(SERIES_FORK_STEP)
            result = ensemble(sim, rain_factors=[1, 50], hyetographs={"storm.csv": [(0.0, 5e-6), (300.0, 8e-4)]},
                              until=self.UNTIL, stop_after=("ponding_started", 20.0))
            rows = [{"branch": r["branch"], "simulation": r["simulation"], "time": r["time"],
                     "ponding": None if r["ponding_started"] != r["ponding_started"] else r["ponding_started"]}
                    for r in result.rows]
            self.assertIn("ponding_s", result.table().splitlines()[0])
            png = clitest.WORK_DIR / "ensemble.png"
            result.plot(png, probes=["p_top", "p_mid"])
            self.assertEqual(png.read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            self.check_branches(rows, server, "p", stop_after=20.0)


if __name__ == "__main__":
    clitest.main()
