"""The README's main job on a real cascade-server: scripts/cascade_demo.py runs
cases/cascade_storm_2d.yaml (a 12 h storm on a sand slope at its real K_sat: geostatic start,
implicit rain stage, failure, slide into the channel, wave at the far bank), with the operator
raising the rain mid-storm, while a second simulation of the same case runs beside it without the
change.

Checks: the stages come in order (geostatic -> rain -> slide), the failure hours after the storm
began; after it the cascade's events in order (landslide onset, water impact, wave at the far gauge,
overtopping); the raised rain brings the failure earlier than in the run without the change; the
rain stage's water balance closes to 0.1% of the rain (issue 12); no particle of either phase is
created or destroyed (each particle's mass is the fixed ρ_w0 dp^d, so the phase's mass is its
count); the demo's outputs exist (snapshots and plots as PNG, probes, summary); no particle leaves
the domain (walls that hold, issue 13; that no particle gets inside the walls is counted by
tests/validation/test_walls.cpp on the same case)."""

import json
import os
import subprocess
import sys
import time
import unittest

import clitest

STAGES = ["geostatic", "rain", "slide"]
AFTER_FAILURE = ["landslide_onset", "water_impact", "wave_at_gauge", "overtopping"]
RAISE_AT_H = 2.0   # the demo's default: the rain raised to 90 mm/h at 2 h
STORM_H = 12.0     # the case's storm
CASE_NAME = "Storm cascade demo (cases/cascade_storm_2d.yaml, scripts/demo.sh)"


def failure_time(events):
    """The time of the hand-over to the slide stage, or None."""
    for e in events:
        if e.kind == "stage_changed" and e.message.startswith("rain -> slide"):
            return e.time
    return None


class CascadeDemo(unittest.TestCase):
    """One demo run and one plain run, shared by the checks below (setUpClass)."""

    @classmethod
    def setUpClass(cls):
        clitest.use_python_client()
        sys.path.insert(0, str(clitest.SOURCE_DIR / "scripts"))
        from cascade_client import Client
        from cascade_demo import phase_counts

        case = clitest.case("cascade_storm_2d")
        cls.out = clitest.out_dir("demo")
        with clitest.Server("server") as server, Client(server.address) as client:
            # The run without the change, beside the demo's.
            plain = client.create(str(case))
            cls.counts0 = phase_counts(plain)
            plain.start()
            env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
            cls.demo = subprocess.run(
                [sys.executable, str(clitest.SOURCE_DIR / "scripts" / "cascade_demo.py"), "--server", server.address,
                 "--case", str(case), "--out", str(cls.out), "--raise-at", f"{RAISE_AT_H} h"],
                capture_output=True, text=True, timeout=1500, env=env)
            print(cls.demo.stdout + cls.demo.stderr)
            if cls.demo.returncode != 0:
                return
            cls.summary = json.loads((cls.out / "summary.json").read_text())

            # The plain run to its own failure.
            deadline = time.monotonic() + 900
            cls.plain_failure = None
            while cls.plain_failure is None and time.monotonic() < deadline:
                cls.plain_failure = failure_time(plain.events())
                if cls.plain_failure is None and plain.get().status.time > STORM_H * 3600:
                    break
                time.sleep(0.5)
            plain.pause()
            cls.plain_counts = phase_counts(plain)
            cls.plain_events = list(plain.events())

    def setUp(self):
        self.assertEqual(self.demo.returncode, 0, self.demo.stdout + self.demo.stderr)

    def test_stages_failure_and_cascade_in_order(self):
        events = self.summary["events"]
        stages = [e["message"].split(":")[0] for e in events if e["kind"] == "stage_changed"]
        self.assertEqual(stages, ["start", "geostatic -> rain", "rain -> slide"], events)
        failure_h = self.summary["time_of_failure_h"]
        self.assertGreater(failure_h, RAISE_AT_H)
        self.assertLess(failure_h, STORM_H)
        first = {}
        for e in events:
            if e["kind"] in AFTER_FAILURE:
                first.setdefault(e["kind"], e["time_s"])
        self.assertEqual(sorted(first, key=first.get), AFTER_FAILURE, events)
        self.assertGreaterEqual(min(first.values()), failure_h * 3600)
        self.assertGreaterEqual(self.summary["rainfall_change"]["time_s"], RAISE_AT_H * 3600)

    def test_rain_stage_water_balance_closes(self):
        balance = self.summary["rain_stage_water_balance"]
        self.assertGreater(balance["rain"], 0)
        self.assertTrue(clitest.record_validation(
            self, CASE_NAME, "conservation of the pore water: rain in = storage change + outflow",
            "rain stage's water balance error / rain volume", abs(balance["error"]) / balance["rain"], 1e-3,
            bound="at_most", tolerance_source="issue 12's bound for the implicit stage (0.1% of the rain)"), balance)

    def test_raised_rain_brings_the_failure_earlier(self):
        failure_s = self.summary["time_of_failure_h"] * 3600
        print(f"failure with the rain raised at {RAISE_AT_H} h: {failure_s / 3600:.2f} h; without: "
              f"{'none' if self.plain_failure is None else f'{self.plain_failure / 3600:.2f} h'}")
        self.assertIsNotNone(self.plain_failure)
        self.assertGreater(self.plain_failure, failure_s)

    def test_outputs_and_phase_masses(self):
        # Each particle's mass is the fixed ρ_w0 dp^d: a phase's mass is its count, lost ones included.
        self.assertEqual(self.summary["phase_particles"]["end"], self.summary["phase_particles"]["start"])
        self.assertEqual(self.summary["phase_particles"]["start"], self.counts0)
        self.assertEqual(self.plain_counts, self.counts0)
        for name in ("storm.png", "soil_speed.png", "wave_elevation.png"):
            self.assertEqual((self.out / name).read_bytes()[:8], b"\x89PNG\r\n\x1a\n", name)
        snapshots = sorted(p.name for p in (self.out / "snapshots").glob("*.png"))
        for kind in AFTER_FAILURE + ["stage"]:
            self.assertTrue(any(kind in s for s in snapshots), (kind, snapshots))
        header = (self.out / "probes.csv").read_text().splitlines()[0]
        self.assertIn("gauge_far", header)

    # Walls that hold (issue 13): no particle leaves the domain in the demo or the run beside it.
    # A known failure until 2026-12-03 (6 to 14 particles lost in the seconds after the slide
    # entered the channel, water on the channel floor sinking through its dummy layers); it holds
    # since the impenetrable walls (docs/physics.md, "Impenetrable walls").
    def test_no_particle_leaves_the_domain(self):
        lost = [e for e in self.summary["events"] if e["kind"] == "particles_lost"]
        lost += [e for e in self.plain_events if e.kind == "particles_lost"]
        self.assertTrue(clitest.record_validation(
            self, CASE_NAME, "no particle leaves the domain (walls hold)",
            "particles_lost events in the demo and the run beside it", float(len(lost)), 0.0, bound="at_most",
            tolerance_source="exact: a particle that leaves is lost"), lost)


if __name__ == "__main__":
    clitest.main()
