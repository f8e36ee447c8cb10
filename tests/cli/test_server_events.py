"""The cascade's events on a real cascade-server and in `cascade run`: a granular column collapse
with a landslide_onset criterion (scenario.proto, CascadeEvents) reports the event once, in the
server's event list, its journal and run.json alike."""

import json
import unittest

import clitest

OVERRIDES = ("--set", "dp=0.01", "--set", "events={landslide_onset: {plastic_strain: 0.01, speed: 0.1, volume: 1e-3}}")


class LandslideOnset(unittest.TestCase):
    def test_server_reports_it_in_events_and_journal(self):
        with clitest.Server("events") as server:
            p = server.cli("create", clitest.case("column_collapse_2d"), *OVERRIDES, "--id", "collapse", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            name = json.loads(p.stdout)["name"]
            self.assertEqual(server.cli("step", name, "1500").returncode, 0)
            events = json.loads(server.cli("events", name, "--json").stdout)["events"]
            onsets = [e for e in events if e["kind"] == "landslide_onset"]
            self.assertEqual(len(onsets), 1, events)
            self.assertIn("faster than 0.1 m/s", onsets[0]["message"])
            self.assertEqual(onsets[0]["caller"], "solver")
            journal = json.loads(server.cli("get", name, "--json").stdout)["journal_path"]
            with open(journal) as f:
                entries = [json.loads(line) for line in f]
            self.assertEqual([e["command"] for e in entries].count("landslide_onset"), 1)

    def test_run_writes_it_to_run_json(self):
        out = clitest.out_dir("collapse_run")
        p = clitest.run("run", clitest.case("column_collapse_2d"), "--out", out, "--until", "0.05", "--threads", "1",
                        *OVERRIDES)
        self.assertEqual(p.returncode, 0, p.stderr)
        events = json.loads((out / "run.json").read_text())["events"]
        self.assertEqual([e["kind"] for e in events].count("landslide_onset"), 1, events)


if __name__ == "__main__":
    clitest.main()
