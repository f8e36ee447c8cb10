"""A simulation's whole life on a real cascade-server, through the CLI and through the Python client:
create, step, pause holding state exactly, steer, query, run to completion, probes, events, watch,
delete; the journal; SIGTERM; health checking and reflection."""

import json
import unittest

import clitest


class CliLifecycle(unittest.TestCase):
    def test_lifecycle(self):
        with clitest.Server("cli_lifecycle") as server:
            p = server.cli("create", clitest.fixture("rain_column"), "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            sim = json.loads(p.stdout)
            name = sim["name"]
            self.assertEqual(sim["state"], "CREATED")
            self.assertEqual(sim["case_name"], "rain_column")

            p = server.cli("step", name, "20", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            s = json.loads(p.stdout)
            self.assertEqual(s["state"], "PAUSED")
            self.assertEqual(int(s["status"]["step"]), 20)

            # Paused: two queries give the same bits.
            a, b = clitest.WORK_DIR / "a.csv", clitest.WORK_DIR / "b.csv"
            for out in (a, b):
                p = server.cli("query", name, "pore_pressure", "--phase", "soil", "--out", out)
                self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(a.read_text(), b.read_text())
            self.assertEqual(len(a.read_text().splitlines()), 1 + 120)

            p = server.cli("set", name, "rainfall.intensity=2e-5", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            change = json.loads(p.stdout)
            self.assertEqual(int(change["effective_step"]), 21)
            self.assertEqual(change["forcing"]["rainfall"]["intensity"], 2e-5)

            p = server.cli("run-until", name, "100")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertIn("PAUSED", p.stdout)

            p = server.cli("resume", name)
            self.assertEqual(p.returncode, 0, p.stderr)
            p = server.cli("watch", name, "--interval", "0.1", "--json")
            self.assertEqual(p.returncode, 0, p.stderr)
            updates = [json.loads(line) for line in p.stdout.splitlines()]
            statuses = [u["status"] for u in updates if "status" in u]
            self.assertEqual(statuses[-1]["state"], "COMPLETED")
            self.assertEqual(statuses[-1]["time"], 600)

            p = server.cli("probes", name, "--json")
            probes = json.loads(p.stdout)
            self.assertEqual(probes["probe_names"], ["p_top", "p_mid"])
            self.assertGreater(len(probes["samples"]), 100)

            p = server.cli("events", name, "--json")
            kinds = [e["kind"] for e in json.loads(p.stdout)["events"]]
            self.assertIn("forcing", kinds)

            p = server.cli("list", "--json")
            self.assertEqual([s["name"] for s in json.loads(p.stdout)["simulations"]], [name])

            p = server.cli("get", name, "--json")
            journal = json.loads(p.stdout)["journal_path"]
            with open(journal) as f:
                commands = [json.loads(line)["command"] for line in f]
            self.assertEqual(commands, ["create", "step", "update_forcing", "run_until", "resume", "completed"])

            p = server.cli("delete", name)
            self.assertEqual(p.returncode, 0, p.stderr)
            p = server.cli("get", name)
            self.assertEqual(p.returncode, 1)
            self.assertIn("NOT_FOUND", p.stderr)

    def test_sigterm_stops_running_simulations_and_exits_0(self):
        with clitest.Server("cli_sigterm") as server:
            p = server.cli("create", clitest.fixture("rain_column"), "--set", "end_time=1e7", "--set",
                           "numerics.max_dt=0.01", "--json")
            name = json.loads(p.stdout)["name"]
            journal = json.loads(p.stdout)["journal_path"]
            self.assertEqual(server.cli("start", name).returncode, 0)
            code, stderr = server.stop()
            self.assertEqual(code, 0, stderr)
            with open(journal) as f:
                last = json.loads(f.read().splitlines()[-1])
            self.assertEqual(last["command"], "shutdown")
            self.assertGreater(int(last["step"]), 0)


class PythonLifecycle(unittest.TestCase):
    def test_lifecycle(self):
        clitest.use_python_client()
        import cascade_client
        import numpy as np

        with clitest.Server("python_lifecycle") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            self.assertEqual(sim.get().state, cascade_client.State.CREATED)
            sim.step(10)
            first = sim.query("pore_pressure", "velocity", phase="soil")
            again = sim.query("pore_pressure", "velocity", phase="soil")
            self.assertEqual(first["step"], 10)
            self.assertEqual(first["pore_pressure"].shape, (120,))
            self.assertEqual(first["velocity"].shape, (120, 3))
            self.assertTrue(np.array_equal(first["pore_pressure"], again["pore_pressure"]))
            self.assertTrue(np.all(first["phase"] == 1))
            change = sim.set_rainfall(3e-5)
            self.assertEqual(change.effective_step, 11)
            sim.resume()
            statuses = list(sim.watch(interval=0.1))
            self.assertEqual(statuses[-1].state, cascade_client.State.COMPLETED)
            names, times, steps, values = sim.probes()
            self.assertEqual(values.shape, (len(times), 2))
            self.assertEqual(len(client.list()), 1)
            sim.delete()
            self.assertEqual(client.list(), [])

    def test_health_and_reflection(self):
        import grpc
        with clitest.Server("health") as server:
            channel = grpc.insecure_channel(server.address)
            check = channel.unary_unary("/grpc.health.v1.Health/Check")
            self.assertEqual(check(b""), b"\x08\x01")  # status: SERVING
            reflect = channel.stream_stream("/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo")
            reply = next(reflect(iter([b"\x3a\x00"])))  # list_services: ""
            self.assertIn(b"cascade.v1.SimulationService", reply)
            channel.close()


if __name__ == "__main__":
    clitest.main()
