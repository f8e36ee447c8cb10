"""Steering on a real cascade-server: a rainfall increase takes effect at the next step boundary
and speeds the rise of pore pressure at a probe compared with the same run without it, and the
status counts the rain that entered; replaying
the steered run's journal with `cascade run --replay` gives the same bits; `cascade set
rainfall.region` confines the rain to a box."""

import json
import unittest

import clitest

CHANGE_STEP = 100  # dt is max_dt = 2 s in the fixture: t = 200 s
RAIN_BEFORE, RAIN_AFTER = 1e-6, 5e-5


def probe_column(server, name, probe):
    p = server.cli("probes", name, "--json")
    reply = json.loads(p.stdout)
    k = reply["probe_names"].index(probe)
    return [(s.get("time", 0.0), s["values"][k]) for s in reply["samples"]]


class RainfallIncrease(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        h5py = clitest.import_h5py()
        with clitest.Server("steering") as server:
            names = {}
            for run in ("baseline", "steered"):
                p = server.cli("create", clitest.fixture("rain_column"), "--id", run, "--json")
                assert p.returncode == 0, p.stderr
                names[run] = json.loads(p.stdout)["name"]
                assert server.cli("step", names[run], str(CHANGE_STEP)).returncode == 0
            p = server.cli("set", names["steered"], f"rainfall.intensity={RAIN_AFTER}", "--json")
            assert p.returncode == 0, p.stderr
            cls.change = json.loads(p.stdout)
            for run in names.values():
                assert server.cli("resume", run).returncode == 0
                assert server.cli("watch", run, "--interval", "0.1").returncode == 0  # to the end
            cls.baseline = probe_column(server, names["baseline"], "p_top")
            cls.steered = probe_column(server, names["steered"], "p_top")
            cls.events = json.loads(server.cli("events", names["steered"], "--json").stdout)["events"]
            out = clitest.WORK_DIR / "steered_end.h5"
            p = server.cli("query", names["steered"], "pore_pressure", "saturation", "seepage", "--out", out)
            assert p.returncode == 0, p.stderr
            with h5py.File(out) as f:
                frame = f["frames"]["000000"]
                cls.server_end = {k: frame[k][()] for k in ("id", "position", "pore_pressure", "saturation", "seepage")}
                cls.server_end_time = frame.attrs["time"]
            steered = json.loads(server.cli("get", names["steered"], "--json").stdout)
            cls.journal = steered["journal_path"]
            cls.pore_water = steered["status"]["pore_water"]

    def test_change_takes_effect_at_the_next_step_boundary(self):
        self.assertEqual(int(self.change["effective_step"]), CHANGE_STEP + 1)
        self.assertEqual(self.change["effective_time"], 2.0 * CHANGE_STEP)
        forcing = [e for e in self.events if e["kind"] == "forcing"]
        self.assertEqual(len(forcing), 1)
        self.assertEqual(int(forcing[0]["step"]), CHANGE_STEP)
        # Identical up to the change, different from the first sample after it.
        t_change = self.change["effective_time"]
        for (t, a), (t2, b) in zip(self.baseline, self.steered):
            self.assertEqual(t, t2)
            if t <= t_change:
                self.assertEqual(a, b, f"t = {t}")
        first_after = next(k for k, (t, _) in enumerate(self.steered) if t > t_change)
        self.assertGreater(self.steered[first_after][1], self.baseline[first_after][1])

    def test_rain_speeds_the_rise_of_pore_pressure(self):
        t_change = self.change["effective_time"]
        before = next(v for t, v in self.baseline if t >= t_change)
        rise_baseline = self.baseline[-1][1] - before
        rise_steered = self.steered[-1][1] - before
        self.assertGreater(rise_steered, 5 * max(rise_baseline, 1.0),
                           f"rise {rise_steered:.1f} Pa with more rain, {rise_baseline:.1f} Pa without")

    def test_status_counts_the_rain_that_entered(self):
        # The column's 12 top particles take the rain over the 1.2 m width: 1e-6 m/s for 200 s,
        # then 5e-5 m/s to the end at 600 s; its base is impermeable and nothing ponds.
        expected = 1.2 * (RAIN_BEFORE * 2.0 * CHANGE_STEP + RAIN_AFTER * (600.0 - 2.0 * CHANGE_STEP))
        self.assertAlmostEqual(self.pore_water["rain"], expected, delta=1e-9 * expected)
        self.assertEqual(self.pore_water.get("walls", 0.0), 0.0)
        self.assertEqual(self.pore_water.get("surface", 0.0), 0.0)

    def test_replay_of_the_journal_is_bit_identical(self):
        out = clitest.out_dir("replay")
        p = clitest.run("run", clitest.fixture("rain_column"), "--out", out, "--threads", "1", "--replay", self.journal)
        self.assertEqual(p.returncode, 0, p.stderr)
        h5py = clitest.import_h5py()
        with h5py.File(out / "fields.h5") as f:
            last = f["frames"][sorted(f["frames"].keys())[-1]]
            self.assertEqual(last.attrs["time"], self.server_end_time)
            for key in ("id", "position", "pore_pressure", "saturation", "seepage"):
                replayed = last[key][()]
                self.assertEqual(replayed.tobytes(), self.server_end[key].tobytes(), key)
        # Without the journal the run differs: the comparison can fail.
        plain = clitest.out_dir("plain")
        self.assertEqual(clitest.run("run", clitest.fixture("rain_column"), "--out", plain, "--threads", "1").returncode, 0)
        with h5py.File(plain / "fields.h5") as f:
            last = f["frames"][sorted(f["frames"].keys())[-1]]
            self.assertNotEqual(last["pore_pressure"][()].tobytes(), self.server_end["pore_pressure"].tobytes())


class RainfallRegion(unittest.TestCase):
    def test_rain_only_inside_the_region(self):
        h5py = clitest.import_h5py()
        with clitest.Server("region") as server:
            self.assertEqual(server.cli("create", clitest.fixture("rain_column"), "--id", "r").returncode, 0)
            # The left third of the column's top (x < 0.4 m) gets heavy rain, the rest none.
            p = server.cli("set", "r", f"rainfall.intensity={RAIN_AFTER}", "rainfall.region=0,0.5,0.4,1.1", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            region = json.loads(p.stdout)["forcing"]["rainfall"]["region"]
            self.assertEqual((region["min"], region["max"]), ([0, 0.5], [0.4, 1.1]))
            self.assertEqual(server.cli("step", "r", "150").returncode, 0)
            out = clitest.WORK_DIR / "region.h5"
            p = server.cli("query", "r", "pore_pressure", "--phase", "soil", "--out", out)
            self.assertEqual(p.returncode, 0, p.stderr)
            with h5py.File(out) as f:
                frame = f["frames"]["000000"]
                x, z = frame["position"][:, 0], frame["position"][:, 2]
                pressure = frame["pore_pressure"][()].ravel()
            top = z > 0.8
            wet = pressure[top & (x < 0.4)].mean()
            dry = pressure[top & (x > 0.6) & (x < 1.0)].mean()
            self.assertGreater(wet - dry, 1000.0, f"{wet:.0f} Pa under the rain, {dry:.0f} Pa beside it")

            p = server.cli("set", "r", "rainfall.region=none", "--json")
            self.assertNotIn("region", json.loads(p.stdout)["forcing"]["rainfall"])
            p = server.cli("set", "r", "rainfall.region=0,0.5,0.4")
            self.assertEqual(p.returncode, 2)
            self.assertIn("rainfall.region needs X0,Z0,X1,Z1 (2D) or X0,Y0,Z0,X1,Y1,Z1 (3D)", p.stderr)
            p = server.cli("set", "r", "rainfall.region=0,0,0.5,0.4,1,1.1")   # 3D in a 2D simulation
            self.assertEqual(p.returncode, 1)
            self.assertIn("INVALID_ARGUMENT", p.stderr)
            self.assertIn("forcing.rainfall.region", p.stderr)


if __name__ == "__main__":
    clitest.main()
