"""The README's main job on a real cascade-server: scripts/cascade_demo.py runs
cases/cascade_demo_2d.yaml (rain on a slope, the rainfall raised part-way, landslide, wave at the
far bank) while a second simulation of the same case runs beside it without the change.

Checks: the cascade's events arrive in order (ponding, landslide onset, water impact, wave at the
far gauge, overtopping); the raised rainfall brings the landslide onset earlier than in the run
without the change; no particle of either phase is lost or created (each particle's mass is the
fixed ρ_w0 dp^d, so the phase's mass is its count); the demo's outputs exist (snapshots and plots
as PNG, probes, summary)."""

import json
import os
import subprocess
import sys
import unittest

import clitest

ORDER = ["ponding_started", "landslide_onset", "water_impact", "wave_at_gauge", "overtopping"]
RAISE_AT = 5.0  # s, the demo's default


class CascadeDemo(unittest.TestCase):
    def test_events_in_order_and_rain_brings_onset_earlier(self):
        clitest.use_python_client()
        sys.path.insert(0, str(clitest.SOURCE_DIR / "scripts"))
        from cascade_client import Client
        from cascade_demo import phase_counts

        case = clitest.case("cascade_demo_2d")
        out = clitest.out_dir("demo")
        with clitest.Server("server") as server, Client(server.address) as client:
            # The run without the change, beside the demo's.
            plain = client.create(str(case))
            counts0 = phase_counts(plain)
            plain.start()
            env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
            demo = subprocess.run(
                [sys.executable, str(clitest.SOURCE_DIR / "scripts" / "cascade_demo.py"), "--server", server.address,
                 "--case", str(case), "--out", str(out), "--raise-at", str(RAISE_AT)],
                capture_output=True, text=True, timeout=1500, env=env)
            self.assertEqual(demo.returncode, 0, demo.stdout + demo.stderr)
            print(demo.stdout)
            summary = json.loads((out / "summary.json").read_text())
            events = summary["events"]
            first = {}
            for e in events:
                first.setdefault(e["kind"], e["time_s"])
            self.assertEqual(sorted(first, key=first.get), ORDER, events)
            self.assertGreaterEqual(summary["rainfall_change"]["time_s"], RAISE_AT)

            # The plain run to a little past the demo's onset: its onset, if any, comes later.
            onset = first["landslide_onset"]
            plain.pause()
            if plain.get().status.time < onset + 1.0:
                plain.run_until(onset + 1.0)
            plain_onsets = [e.time for e in plain.events() if e.kind == "landslide_onset"]
            print(f"onset with the rainfall raised at {summary['rainfall_change']['time_s']:.2f} s: {onset:.2f} s; "
                  f"without: {plain_onsets[0] if plain_onsets else 'none by'} {plain.get().status.time:.2f} s")
            self.assertTrue(not plain_onsets or plain_onsets[0] > onset + 0.5, plain_onsets)
            self.assertEqual(phase_counts(plain), counts0)
            self.assertFalse([e for e in plain.events() if e.kind == "particles_lost"])

        # The demo's run: nothing lost through the whole cascade (its summary lists every event).
        self.assertFalse([e for e in events if e["kind"] == "particles_lost"], events)
        self.assertEqual(summary["phase_particles"]["end"], summary["phase_particles"]["start"])
        self.assertEqual(summary["phase_particles"]["start"], counts0)
        for name in ("pore_pressure.png", "soil_speed.png", "wave_elevation.png"):
            self.assertEqual((out / name).read_bytes()[:8], b"\x89PNG\r\n\x1a\n", name)
        snapshots = sorted(p.name for p in (out / "snapshots").glob("*.png"))
        for kind in ORDER:
            self.assertTrue(any(kind in s for s in snapshots), (kind, snapshots))
        header = (out / "probes.csv").read_text().splitlines()[0]
        self.assertIn("gauge_far", header)


if __name__ == "__main__":
    clitest.main()
