"""SIGINT and SIGTERM stop a run cleanly: exit 1, run.json "failed" with an "interrupted" error, and
fields.h5 and probes.csv readable up to the moment of the signal."""

import json
import signal
import subprocess
import time
import unittest

import clitest

START_TIMEOUT = 30  # seconds for the run to write its first probe rows
STOP_TIMEOUT = 10   # seconds from the signal to the exit


def probe_lines(out):
    path = out / "probes.csv"
    return len(path.read_text().splitlines()) if path.exists() else 0


class Signals(unittest.TestCase):
    def interrupt(self, name, sig, case, *args):
        """Starts CASE, waits for two probe rows, sends SIG; returns (folder, run.json, stderr)."""
        out = clitest.out_dir(name)
        with open(clitest.WORK_DIR / f"{name}.stderr", "w+") as err:
            proc = subprocess.Popen([str(clitest.CASCADE), "run", str(clitest.case(case)), "--out", str(out),
                                     "--threads", "1", *args],
                                    stdout=subprocess.DEVNULL, stderr=err, cwd=clitest.WORK_DIR)
            try:
                deadline = time.monotonic() + START_TIMEOUT
                while probe_lines(out) < 3 and proc.poll() is None and time.monotonic() < deadline:
                    time.sleep(0.05)
                self.assertIsNone(proc.poll(), "the run ended before the signal")
                self.assertGreaterEqual(probe_lines(out), 3, f"no probe rows after {START_TIMEOUT} s")
                proc.send_signal(sig)
                sent = time.monotonic()
                code = proc.wait(timeout=STOP_TIMEOUT)
                self.assertLess(time.monotonic() - sent, STOP_TIMEOUT)
            finally:
                if proc.poll() is None:
                    proc.kill()
                    proc.wait()
            err.seek(0)
            stderr = err.read()
        self.assertEqual(code, 1, stderr)
        self.assertIn("cascade run: failed: interrupted", stderr)
        summary = json.loads((out / "run.json").read_text())
        return out, summary, stderr

    def check_outputs(self, out, summary, end_time):
        self.assertGreater(summary["sim_time"], 0)
        self.assertLess(summary["sim_time"], end_time)
        self.assertGreater(summary["steps"], 0)

        header, rows = clitest.read_probes(out / "probes.csv")
        self.assertEqual(header[0], "time")
        self.assertGreaterEqual(len(rows), 2)
        # The outputs hold the run up to the signal: the last probe row is at the final time.
        self.assertAlmostEqual(rows[-1][0], summary["sim_time"], places=12)

        h5py = clitest.import_h5py()
        with h5py.File(out / "fields.h5", "r") as f:
            frames = sorted(f["frames"])
            self.assertGreaterEqual(len(frames), 1)
            self.assertEqual(float(f["frames"][frames[0]].attrs["time"]), 0.0)
            last = f["frames"][frames[-1]]
            self.assertAlmostEqual(float(last.attrs["time"]), summary["sim_time"], places=12)
            self.assertEqual(last["position"].shape[0], summary["particles"]["total"])
        xdmf = (out / "fields.xdmf").read_text()
        self.assertIn(f"fields.h5:/frames/{frames[-1]}/position", xdmf)

    def test_sigint(self):
        out, summary, _ = self.interrupt("sigint", signal.SIGINT, "dam_break_2d", "--set", "dp=0.0073")
        self.assertEqual(summary["status"], "failed")
        self.assertRegex(summary["error"], r"^interrupted by signal 2 ")
        self.assertEqual(summary["case"], "dam_break_2d")
        self.check_outputs(out, summary, 0.4)
        header, _ = clitest.read_probes(out / "probes.csv")
        self.assertEqual(header, ["time", "front_x", "column_height", "p_right_wall"])

    def test_sigterm(self):
        out, summary, _ = self.interrupt("sigterm", signal.SIGTERM, "hydrostatic_tank_2d")
        self.assertEqual(summary["status"], "failed")
        self.assertRegex(summary["error"], r"^interrupted by signal 15 ")
        self.check_outputs(out, summary, 2.0)


if __name__ == "__main__":
    clitest.main()
