"""How long a snapshot frame takes from its step to the browser, through the dashboard
(docs/performance.md, "Dashboard"). Not a test: a measurement, run by hand:

    /usr/bin/python3 tests/browser/measure_frame_latency.py --cascade build/release/bin/cascade \
        --source-dir . --work-dir /tmp/frame_latency [--case cases/dam_break_2d.yaml --set dp=0.0007]

A cascade-server runs the case (default: the 2D dam break at about 10^5 particles), the dashboard
serves one headless Chromium page that shows it, and a watch stream at 0.05 s records the wall
time of each step boundary the server reports (Status.wall_time). For every frame the page shows
(window.dashboard.frames: the frame's step and the wall time it was drawn), the latency is the
time drawn minus the wall time of the last reported step at or before the frame's step (an upper
bound: that step ended no later than the frame's). The dashboard's receipt time splits it into the
server's part (copy, render, PNG, gRPC) and the dashboard's and browser's (long poll, fetch, decode).
"""

import bisect
import os
import statistics
import sys
import threading
import time
import unittest

import test_dashboard as td
from test_dashboard import clitest

SECONDS = 40.0


class FrameLatency(unittest.TestCase):
    def test_measure(self):
        case = os.environ.get("LATENCY_CASE", str(clitest.case("dam_break_2d")))
        overrides = os.environ.get("LATENCY_SET", "dp=0.0007").split()
        clitest.use_python_client()
        import cascade_client
        clitest.token_file()
        server = clitest.Server("server", "--tokens", clitest.WORK_DIR / "tokens.txt").__enter__()
        client = cascade_client.Client(server.address, token=clitest.OPERATOR_TOKEN)
        sim = client.create(case, overrides=overrides, simulation_id="big")
        particles = sim.get().particle_count
        steps, walls = [], []

        def watch():
            for status in sim.watch(interval=0.05):
                if not steps or status.step > steps[-1]:
                    steps.append(status.step)
                    walls.append(status.wall_time)

        td.Dashboard.server = server
        dashboard, url = td.Dashboard.start_dashboard()
        driver = td.browser("latency")
        try:
            driver.get(url)
            driver.find_element(td.By.ID, "token").send_keys(clitest.VIEWER_TOKEN)
            driver.find_element(td.By.ID, "signin").click()
            td.WebDriverWait(driver, 60).until(lambda d: d.find_element(td.By.ID, "state").text == "CREATED")
            sim.start()
            threading.Thread(target=watch, daemon=True).start()
            time.sleep(SECONDS)
            frames = driver.execute_script("return window.dashboard.frames")
            speed = sim.get().status.steps_per_second
        finally:
            driver.quit()
            dashboard.terminate()
            client.close()
            server.__exit__(None, None, None)
        latencies, server_parts = [], []
        for f in frames:
            k = bisect.bisect_right(steps, f["step"]) - 1
            if k < 0 or f.get("received") is None:
                continue  # a frame of a step before the watch began
            latencies.append(f["shown"] - walls[k])
            server_parts.append(f["received"] - walls[k])
        latencies.sort()
        print(f"\n{particles} particles, {speed:.2f} steps/s, {len(latencies)} frames in {SECONDS:.0f} s: "
              f"step to page median {statistics.median(latencies):.3f} s, 90th percentile "
              f"{latencies[int(0.9 * (len(latencies) - 1))]:.3f} s, max {latencies[-1]:.3f} s; step to dashboard "
              f"median {statistics.median(server_parts):.3f} s, max {max(server_parts):.3f} s")
        self.assertGreater(len(latencies), 5)


if __name__ == "__main__":
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    clitest.main()
