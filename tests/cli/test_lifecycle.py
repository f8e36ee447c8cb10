"""A completed run and the effect of --until and --set: exit status, run.json, probes.csv, fields.h5,
fields.xdmf."""

import json
import math
import unittest

import clitest

BASE = "hydrostatic_tank_2d"
PROBES = ["p_x0.5_z0.1", "p_mean"]  # in the case file's order
FIELDS = ["position", "velocity", "phase", "id", "pressure", "density"]


def run_ok(test, name, *args):
    """Runs the base case with ARGS into a fresh folder, asserts exit 0 and returns (folder, run.json)."""
    out = clitest.out_dir(name)
    p = clitest.run("run", clitest.case(BASE), "--out", out, "--threads", "1", *args)
    test.assertEqual(p.returncode, 0, p.stderr)
    test.assertRegex(p.stderr, r"cascade run: completed: ")
    summary = json.loads((out / "run.json").read_text())
    test.assertEqual(summary["status"], "completed", summary)
    test.assertNotIn("error", summary)
    return out, summary


class CompletedRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out, cls.summary = run_ok(cls(), "completed", "--until", "0.002")

    def test_run_json(self):
        s = self.summary
        self.assertEqual(s["case"], BASE)
        self.assertEqual(s["precision"], "double")
        self.assertGreaterEqual(s["sim_time"], 0.002)
        self.assertLess(s["sim_time"], 0.003)
        self.assertGreater(s["steps"], 0)
        self.assertEqual(s["lost_particles"], 0)
        n = s["particles"]
        self.assertEqual(n["total"], n["water"] + n["soil"] + n["boundary"])
        # 1.0 m x 0.5 m of water at dp = 0.02 m: 50 x 25.
        self.assertEqual(n["water"], 50 * 25)
        self.assertGreater(n["boundary"], 0)

    def test_probes_csv(self):
        header, rows = clitest.read_probes(self.out / "probes.csv")
        self.assertEqual(header, ["time"] + PROBES)
        self.assertGreaterEqual(len(rows), 2)
        times = [r[0] for r in rows]
        self.assertEqual(times[0], 0.0)
        self.assertEqual(times, sorted(times))
        self.assertEqual(len(set(times)), len(times), "a time sampled twice")
        self.assertAlmostEqual(times[-1], self.summary["sim_time"], places=12)
        for r in rows:
            self.assertEqual(len(r), 1 + len(PROBES))
            self.assertTrue(all(math.isfinite(v) for v in r))
        # The last row after a few steps: near hydrostatic ρ g (0.5 - 0.1) = 3924 Pa and ρ g H / 2.
        self.assertAlmostEqual(rows[-1][1], 3924, delta=400)
        self.assertAlmostEqual(rows[-1][2], 2452.5, delta=250)

    def test_fields_h5(self):
        h5py = clitest.import_h5py()
        with h5py.File(self.out / "fields.h5", "r") as f:
            frames = sorted(f["frames"])
            # The start and the end of the run (output.interval is 0.02 s, past --until).
            self.assertEqual(frames, ["000000", "000001"])
            total = self.summary["particles"]["total"]
            times = []
            for name in frames:
                g = f["frames"][name]
                for field in FIELDS:
                    self.assertIn(field, g, f"/frames/{name}/{field}")
                    self.assertEqual(g[field].shape[0], total, f"/frames/{name}/{field}")
                self.assertEqual(g["position"].shape, (total, 3))
                self.assertEqual(g["velocity"].shape, (total, 3))
                self.assertEqual(sorted(g["id"][()].tolist()), list(range(total)))
                times.append(float(g.attrs["time"]))
            self.assertEqual(times[0], 0.0)
            self.assertAlmostEqual(times[-1], self.summary["sim_time"], places=12)

    def test_fields_xdmf(self):
        xdmf = (self.out / "fields.xdmf").read_text()
        self.assertIn("<Xdmf", xdmf)
        self.assertIn("fields.h5:/frames/000000/position", xdmf)
        self.assertIn("fields.h5:/frames/000001/position", xdmf)


class OverridesAndUntil(unittest.TestCase):
    def test_set_dp_changes_particle_count(self):
        _, default = run_ok(self, "dp_default", "--until", "0.0005")
        _, coarse = run_ok(self, "dp_coarse", "--until", "0.0005", "--set", "dp=0.04")
        self.assertEqual(default["particles"]["water"], 50 * 25)
        self.assertEqual(coarse["particles"]["water"], 25 * 13)  # 0.5 / 0.04 = 12.5 → 13 rows
        self.assertLess(coarse["particles"]["total"], default["particles"]["total"])

    def test_until(self):
        out, s = run_ok(self, "until", "--until", "0.01", "--set", "dp=0.04")
        self.assertGreaterEqual(s["sim_time"], 0.01)
        self.assertLess(s["sim_time"], 0.01 + 1e-3)
        _, rows = clitest.read_probes(out / "probes.csv")
        self.assertAlmostEqual(rows[-1][0], s["sim_time"], places=12)
        # probe_interval defaults to output.interval / 10 = end_time / 1000 = 0.002 s: 0, 0.002, ... 0.01, end.
        self.assertGreaterEqual(len(rows), 6)

    def test_set_nested_value(self):
        # A nested --set that changes the geometry: a water column half as wide.
        _, s = run_ok(self, "set_nested", "--until", "0.0005", "--set", "dp=0.04",
                      "--set", "bodies[1].shape.box.max=[0.52, 0.5]")
        self.assertEqual(s["particles"]["water"], 13 * 13)


if __name__ == "__main__":
    clitest.main()
