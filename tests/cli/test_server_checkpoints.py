"""Checkpoints on a real cascade-server: restore, then N steps gives the same bits as the N steps
that followed the checkpoint; SIGTERM checkpoints a running simulation, exits 0, and a new server
process on the same data dir restores it and goes on as an uninterrupted run would."""

import json
import time
import unittest

import clitest

FIELDS = ("pore_pressure", "saturation", "seepage", "porosity", "velocity", "density", "effective_stress")


def query(server, name, out_name):
    """The fields (and positions, ids) at the simulation's current step, as numpy arrays."""
    return clitest.query_frame(server, name, out_name, FIELDS)


class CheckpointTest(unittest.TestCase):
    def assert_same_bits(self, a, b):
        for key in a:
            self.assertEqual(a[key].tobytes(), b[key].tobytes(), key)

    def json_of(self, p):
        self.assertEqual(p.returncode, 0, p.stderr)
        return json.loads(p.stdout)


class RestoreOnTheSameServer(CheckpointTest):
    def test_restore_then_steps_equal_the_steps_after_the_checkpoint(self):
        with clitest.Server("same_server") as server:
            name = self.json_of(server.cli("create", clitest.fixture("rain_column"), "--id", "col", "--json"))["name"]
            self.assertEqual(server.cli("step", name, "50").returncode, 0)
            at_checkpoint, _ = query(server, name, "at_checkpoint")
            checkpoint = self.json_of(server.cli("checkpoint", name, "--json"))
            self.assertEqual(checkpoint["name"], f"{name}/checkpoints/ckpt-0001")
            self.assertEqual(int(checkpoint["step"]), 50)
            self.assertEqual(server.cli("step", name, "40").returncode, 0)
            after_checkpoint, step = query(server, name, "continued")
            self.assertEqual(step, 90)

            restored = self.json_of(server.cli("restore", name, "ckpt-0001", "--json"))
            self.assertEqual(restored["state"], "PAUSED")
            self.assertEqual(int(restored["status"]["step"]), 50)
            self.assertEqual(server.cli("step", name, "40").returncode, 0)
            after_restore, step = query(server, name, "restored")
            self.assertEqual(step, 90)
            self.assert_same_bits(after_checkpoint, after_restore)
            # The 40 steps changed the state: the comparison is not of two untouched frames.
            self.assertNotEqual(at_checkpoint["pore_pressure"].tobytes(), after_restore["pore_pressure"].tobytes())

            listed = self.json_of(server.cli("checkpoints", name, "--json"))["checkpoints"]
            self.assertEqual([c["name"] for c in listed], [checkpoint["name"]])
            # The journal is the checkpoint's, then the restore; the steps it undid are kept aside.
            journal = [json.loads(line)["command"] for line in open(restored["journal_path"])]
            self.assertEqual(journal, ["create", "step", "checkpoint", "restore", "step"])
            replaced = [json.loads(line)["command"] for line in open(restored["journal_path"] + ".replaced-1")]
            self.assertEqual(replaced, ["create", "step", "checkpoint", "step", "restore"])

    def test_checkpoint_file_holds_the_state_case_and_journal(self):
        h5py = clitest.import_h5py()
        with clitest.Server("file") as server:
            name = self.json_of(server.cli("create", clitest.fixture("rain_column"), "--json"))["name"]
            self.assertEqual(server.cli("step", name, "5").returncode, 0)
            checkpoint = self.json_of(server.cli("checkpoint", name, "--json"))
        with h5py.File(checkpoint["path"]) as f:
            self.assertEqual(f.attrs["format"], "cascade-checkpoint-1")
            self.assertEqual(int(f.attrs["step"]), 5)
            self.assertGreater(f.attrs["last_dt"], 0)
            for array in ("position", "velocity", "listed_position", "porosity", "seepage", "surface_state",
                          "skeleton_acceleration", "effective_stress", "plastic_strain", "id"):
                self.assertIn(array, f["engine"])
            self.assertEqual(f["forcing"].attrs["rainfall_intensity"], 1e-6)
            journal = f["journal"][()].tobytes().decode().splitlines()
            self.assertEqual([json.loads(line)["command"] for line in journal], ["create", "step", "checkpoint"])
            self.assertGreater(len(f["case_spec"][()]), 0)


class PythonClientCheckpoints(CheckpointTest):
    def test_checkpoint_and_restore_through_python(self):
        clitest.use_python_client()
        import cascade_client

        with clitest.Server("python") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"))
            sim.step(20)
            checkpoint = sim.checkpoint()
            self.assertEqual(checkpoint.step, 20)
            sim.step(15)
            continued = sim.query("pore_pressure", "saturation")
            restored = sim.restore(checkpoint.name.split("/")[-1])
            self.assertEqual((restored.state, restored.status.step), (cascade_client.State.PAUSED, 20))
            sim.step(15)
            again = sim.query("pore_pressure", "saturation")
            for key in ("pore_pressure", "saturation"):
                self.assertEqual(continued[key].tobytes(), again[key].tobytes(), key)
            self.assertEqual([c.name for c in sim.checkpoints()], [checkpoint.name])


class DamagedCheckpoints(CheckpointTest):
    """Issue 14: one unreadable checkpoint made ListCheckpoints fail for all of them, and a file with
    its last 4 KiB flipped restored without an error."""

    def test_damaged_files_are_listed_with_their_error_and_not_restored(self):
        import pathlib
        import grpc
        clitest.use_python_client()
        import cascade_client

        with clitest.Server("damaged") as server, cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"), simulation_id="col")
            sim.step(10)
            good = sim.checkpoint()
            sim.step(10)
            flipped = sim.checkpoint()
            path = pathlib.Path(flipped.path)
            data = bytearray(path.read_bytes())
            for k in range(len(data) - 4096, len(data)):
                data[k] ^= 0xFF
            path.write_bytes(bytes(data))
            (path.parent / "ckpt-0003.h5").write_bytes(b"not an HDF5 file")

            listed = sim.checkpoints()
            self.assertEqual([c.name.split("/")[-1] for c in listed], ["ckpt-0001", "ckpt-0002", "ckpt-0003"])
            self.assertEqual(listed[0].error, "")
            self.assertEqual(listed[0].step, good.step)
            self.assertNotEqual(listed[2].error, "")
            for damaged in ("ckpt-0002", "ckpt-0003"):
                with self.subTest(checkpoint=damaged), self.assertRaises(grpc.RpcError) as raised:
                    sim.restore(damaged)
                self.assertEqual(raised.exception.code(), grpc.StatusCode.DATA_LOSS)
                self.assertTrue(raised.exception.details().startswith("name: checkpoint "), raised.exception.details())
            self.assertIn("damaged", self.last_details(sim, "ckpt-0002"))
            restored = sim.restore("ckpt-0001")
            self.assertEqual(restored.status.step, good.step)

    @staticmethod
    def last_details(sim, checkpoint):
        import grpc
        try:
            sim.restore(checkpoint)
        except grpc.RpcError as e:
            return e.details()
        return ""


class SigtermCheckpoints(CheckpointTest):
    def test_sigterm_checkpoints_and_a_new_server_goes_on_bit_identically(self):
        long_run = ("--set", "end_time=1e6")
        with clitest.Server("sigterm") as server:
            name = self.json_of(server.cli("create", clitest.fixture("rain_column"), *long_run, "--id", "run", "--json"))["name"]
            self.assertEqual(server.cli("start", name).returncode, 0)
            deadline = time.time() + 30
            while int(self.json_of(server.cli("get", name, "--json"))["status"].get("step", 0)) < 20:
                self.assertLess(time.time(), deadline)
                time.sleep(0.05)
            code, stderr = server.stop()
            self.assertEqual(code, 0, stderr)
        files = list((server.data_dir / "simulations" / "run" / "checkpoints").glob("*.h5"))
        self.assertEqual(len(files), 1)

        with clitest.Server("sigterm") as again:  # the same data dir
            listed = self.json_of(again.cli("checkpoints", name, "--json"))["checkpoints"]
            self.assertEqual(len(listed), 1)
            step = int(listed[0]["step"])
            self.assertGreaterEqual(step, 20)
            restored = self.json_of(again.cli("restore", name, listed[0]["name"], "--json"))
            self.assertEqual(int(restored["status"]["step"]), step)
            self.assertEqual(again.cli("step", name, "30").returncode, 0)
            continued, _ = query(again, name, "after_sigterm")
            # The same case from the start, without interruption.
            fresh = self.json_of(again.cli("create", clitest.fixture("rain_column"), *long_run, "--id", "fresh", "--json"))["name"]
            self.assertEqual(again.cli("step", fresh, str(step + 30)).returncode, 0)
            uninterrupted, _ = query(again, fresh, "uninterrupted")
            self.assert_same_bits(continued, uninterrupted)


if __name__ == "__main__":
    clitest.main()
