"""A case whose rain is a hyetograph (a CSV file beside it) on a real cascade-server and in
`cascade run`. `cascade create` loads the case on the client and sends the spec with the expanded
rain series, which the server applies as any `rainfall` series; the server reads no files that a
request names, so a case sent as text with a hyetograph (the Python client's create) is refused,
naming the key."""

import json
import unittest

import clitest

# 36 mm/h = 1e-5 m/s from 1 min to 3 min, none before or after.
STORM = "# a short storm\ntime_min,intensity_mm_per_h\n0,0\n1,36\n3,0\n"
HYETOGRAPH = "  hyetograph: {file: storm.csv, time_unit: min, intensity_unit: mm/h}\n"


def storm_case():
    """The rain_column fixture with the storm as its rain, in the work dir beside storm.csv."""
    (clitest.WORK_DIR / "storm.csv").write_text(STORM)
    text = clitest.fixture("rain_column").read_text()
    assert "  rainfall_intensity: 1e-6\n" in text
    case = clitest.WORK_DIR / "storm_column.yaml"
    case.write_text(text.replace("  rainfall_intensity: 1e-6\n", HYETOGRAPH))
    return case


class Hyetograph(unittest.TestCase):
    def test_create_sends_the_expanded_series(self):
        case = storm_case()
        storm = str(clitest.WORK_DIR / "storm.csv")
        with clitest.Server("hyetograph") as server:
            p = server.cli("create", case, "--id", "storm", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(server.cli("run-until", "storm", "200").returncode, 0)
            events = json.loads(server.cli("events", "storm", "--json").stdout)["events"]
            rain = [(e["time"], e["message"]) for e in events if e["kind"] == "forcing"]
            self.assertEqual(len(rain), 2, events)
            self.assertTrue(60 <= rain[0][0] < 62, rain)   # the first step boundary at or after 1 min
            self.assertEqual(rain[0][1], f"rain series: rainfall.intensity 0.000010 m/s (hyetograph {storm})")
            self.assertTrue(180 <= rain[1][0] < 182, rain)
            self.assertEqual(rain[1][1], f"rain series: rainfall.intensity 0.000000 m/s (hyetograph {storm})")

    def test_case_text_with_a_hyetograph_is_refused(self):
        case = storm_case()
        clitest.use_python_client()
        import grpc
        import cascade_client
        with clitest.Server("hyetograph_text") as server, cascade_client.Client(server.address) as client:
            with self.assertRaises(grpc.RpcError) as refused:
                client.create(case)
            self.assertEqual(refused.exception.code(), grpc.StatusCode.INVALID_ARGUMENT)
            self.assertRegex(refused.exception.details(),
                             r"^case_yaml: case_yaml:\d+:\d+: key 'hydraulics\.hyetograph': names a file, which only "
                             r"the loader of a case file reads")

    def test_run_reports_the_file(self):
        out = clitest.out_dir("storm_run")
        p = clitest.run("run", storm_case(), "--out", out, "--until", "200", "--threads", "1")
        self.assertEqual(p.returncode, 0, p.stderr)
        events = json.loads((out / "run.json").read_text())["events"]
        rain = [e["detail"] for e in events if e["kind"] == "forcing"]
        storm = str(clitest.WORK_DIR / "storm.csv")
        self.assertEqual(rain, [f"rainfall_intensity 0 -> 1e-05 m/s (hyetograph {storm})",
                                f"rainfall_intensity 1e-05 -> 0 m/s (hyetograph {storm})"])


if __name__ == "__main__":
    clitest.main()
