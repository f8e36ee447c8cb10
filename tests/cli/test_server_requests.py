"""Bad requests to a real cascade-server, each answered with the right status code and a message
that names the field, the server still serving afterwards; tokens and roles; limits."""

import math
import unittest

import clitest

OPERATOR, VIEWER = clitest.OPERATOR_TOKEN, clitest.VIEWER_TOKEN


def import_api():
    clitest.use_python_client()
    import grpc
    from google.protobuf import field_mask_pb2
    from cascade.v1 import journal_pb2, simulation_pb2 as pb
    return grpc, field_mask_pb2, journal_pb2, pb


class BadRequests(unittest.TestCase):
    def test_catalogue(self):
        grpc, field_mask_pb2, journal_pb2, pb = import_api()
        import cascade_client
        C = grpc.StatusCode
        with clitest.Server("bad_requests", "--max-simulations", "2", "--max-particles", "1000") as server, \
                cascade_client.Client(server.address) as client:
            sim = client.create(clitest.fixture("rain_column"), simulation_id="good")
            name = sim.name
            case = clitest.fixture("rain_column").read_text()

            def forcing(mask, **kw):
                f = journal_pb2.Forcing()
                if "intensity" in kw:
                    f.rainfall.intensity = kw["intensity"]
                if "p_max" in kw:
                    f.ponding.p_max = kw["p_max"]
                if "p_min" in kw:
                    f.ponding.p_min = kw["p_min"]
                if "region" in kw:
                    f.rainfall.region.min[:], f.rainfall.region.max[:] = kw["region"]
                return pb.UpdateForcingRequest(name=name, forcing=f, update_mask=field_mask_pb2.FieldMask(paths=mask))

            # The 3D dam break with its obstacle as a mesh: an STL file named in a text, which the
            # server never reads, and a box's mesh with its top's second triangle missing (open).
            dam = (clitest.SOURCE_DIR / "cases" / "dam_break_3d.yaml").read_text()
            obstacle = "shape: {box: {min: [0.9, 0.24, 0.0], max: [1.02, 0.36, 0.45]}}"
            assert obstacle in dam
            box = [0.9, 0.24, 0.0, 1.02, 0.24, 0.0, 1.02, 0.36, 0.0, 0.9, 0.36, 0.0,
                   0.9, 0.24, 0.45, 1.02, 0.24, 0.45, 1.02, 0.36, 0.45, 0.9, 0.36, 0.45]
            open_box = [0, 2, 1, 0, 3, 2, 4, 5, 6, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6,
                        3, 0, 4, 3, 4, 7]  # 11 triangles: 4, 6, 7 of the top is missing
            stl_text = dam.replace(obstacle, "shape: {mesh: {stl_file: obstacle.stl}}")
            open_text = dam.replace(obstacle, f"shape: {{mesh: {{vertices: {box}, triangles: {open_box}}}}}")

            nan, inf = math.nan, math.inf
            catalogue = [
                ("GetSimulation", pb.GetSimulationRequest(name=""), C.INVALID_ARGUMENT, "name"),
                ("GetSimulation", pb.GetSimulationRequest(name="good"), C.INVALID_ARGUMENT, "name"),
                ("GetSimulation", pb.GetSimulationRequest(name="simulations/UPPER"), C.INVALID_ARGUMENT, "name"),
                ("GetSimulation", pb.GetSimulationRequest(name="simulations/a/b"), C.INVALID_ARGUMENT, "name"),
                ("GetSimulation", pb.GetSimulationRequest(name="simulations/" + "x" * 64), C.INVALID_ARGUMENT, "name"),
                ("GetSimulation", pb.GetSimulationRequest(name="simulations/missing"), C.NOT_FOUND, "name"),
                ("DeleteSimulation", pb.DeleteSimulationRequest(name="simulations/missing"), C.NOT_FOUND, "name"),
                ("StartSimulation", pb.StartSimulationRequest(name="simulations/-x"), C.INVALID_ARGUMENT, "name"),
                ("StepSimulation", pb.StepSimulationRequest(name=name, steps=0), C.INVALID_ARGUMENT, "steps"),
                ("StepSimulation", pb.StepSimulationRequest(name=name, steps=10**8), C.INVALID_ARGUMENT, "steps"),
                ("RunSimulationUntil", pb.RunSimulationUntilRequest(name=name, time=nan), C.INVALID_ARGUMENT, "time"),
                ("RunSimulationUntil", pb.RunSimulationUntilRequest(name=name, time=inf), C.INVALID_ARGUMENT, "time"),
                ("RunSimulationUntil", pb.RunSimulationUntilRequest(name=name, time=-1), C.INVALID_ARGUMENT, "time"),
                ("RunSimulationUntil", pb.RunSimulationUntilRequest(name=name, time=1e9), C.INVALID_ARGUMENT, "time"),
                ("PauseSimulation", pb.PauseSimulationRequest(name=name), C.FAILED_PRECONDITION, "pause"),
                ("ResumeSimulation", pb.ResumeSimulationRequest(name=name), C.FAILED_PRECONDITION, "resume"),
                ("UpdateForcing", forcing([]), C.INVALID_ARGUMENT, "update_mask"),
                ("UpdateForcing", forcing(["rainfall.colour"]), C.INVALID_ARGUMENT, "update_mask.paths[0]"),
                ("UpdateForcing", forcing(["rainfall.intensity", "rainfall.intensity"], intensity=1e-5),
                 C.INVALID_ARGUMENT, "update_mask.paths[0]"),
                ("UpdateForcing", forcing(["rainfall.intensity"], intensity=nan), C.INVALID_ARGUMENT,
                 "forcing.rainfall.intensity"),
                ("UpdateForcing", forcing(["rainfall.intensity"], intensity=inf), C.INVALID_ARGUMENT,
                 "forcing.rainfall.intensity"),
                ("UpdateForcing", forcing(["rainfall.intensity"], intensity=5.0), C.INVALID_ARGUMENT,
                 "forcing.rainfall.intensity"),
                ("UpdateForcing", forcing(["rainfall.intensity"], intensity=-5.0), C.INVALID_ARGUMENT,
                 "forcing.rainfall.intensity"),
                ("UpdateForcing", forcing(["ponding.p_max"], p_max=nan), C.INVALID_ARGUMENT, "forcing.ponding.p_max"),
                ("UpdateForcing", forcing(["ponding.p_max"], p_max=1e12), C.INVALID_ARGUMENT, "forcing.ponding.p_max"),
                ("UpdateForcing", forcing(["ponding.p_min"], p_min=-inf), C.INVALID_ARGUMENT, "forcing.ponding.p_min"),
                ("UpdateForcing", forcing(["ponding.p_min"], p_min=10.0), C.INVALID_ARGUMENT, "forcing.ponding.p_min"),
                ("UpdateForcing", forcing(["rainfall.region"], region=([0.0], [1.0])), C.INVALID_ARGUMENT,
                 "forcing.rainfall.region"),
                ("UpdateForcing", forcing(["rainfall.region"], region=([0.0, 1.0], [1.0, 0.5])), C.INVALID_ARGUMENT,
                 "forcing.rainfall.region.max[1]"),
                ("UpdateForcing", forcing(["rainfall.region"], region=([0.0, nan], [1.0, 2.0])), C.INVALID_ARGUMENT,
                 "forcing.rainfall.region.min[1]"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, fields=["pore_pressure", "colour"]),
                 C.INVALID_ARGUMENT, "fields[1]"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, phase="air"), C.INVALID_ARGUMENT, "phase"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, stride=10**7), C.INVALID_ARGUMENT, "stride"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, box={"min": [0, 0], "max": [1, 1]}),
                 C.INVALID_ARGUMENT, "box"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, box={"min": [0, 0, inf], "max": [1, 1, 1]}),
                 C.INVALID_ARGUMENT, "box.min[2]"),
                ("QueryFields", pb.QueryFieldsRequest(name=name, box={"min": [0, 0, 1], "max": [1, 1, 0]}),
                 C.INVALID_ARGUMENT, "box.max[2]"),
                ("QueryFields", pb.QueryFieldsRequest(name="simulations/missing"), C.NOT_FOUND, "name"),
                ("ListProbes", pb.ListProbesRequest(name=name, since_time=nan), C.INVALID_ARGUMENT, "since_time"),
                ("ListEvents", pb.ListEventsRequest(name=name, since_time=nan), C.INVALID_ARGUMENT, "since_time"),
                ("WatchSimulation", pb.WatchSimulationRequest(name=name, interval_seconds=0.001), C.INVALID_ARGUMENT,
                 "interval_seconds"),
                ("WatchSimulation", pb.WatchSimulationRequest(name=name, interval_seconds=nan), C.INVALID_ARGUMENT,
                 "interval_seconds"),
                ("CreateSimulation", pb.CreateSimulationRequest(), C.INVALID_ARGUMENT, "scenario"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case, simulation_id="Bad_Id"),
                 C.INVALID_ARGUMENT, "simulation_id"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case, simulation_id="good"),
                 C.ALREADY_EXISTS, "simulation_id"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case + "\ncolour: red\n"),
                 C.INVALID_ARGUMENT, "colour"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case, overrides=["dp=-1"]),
                 C.INVALID_ARGUMENT, "dp"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case, overrides=["no equals sign"]),
                 C.INVALID_ARGUMENT, "overrides[0]"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=case, overrides=["dp=0.02"]),
                 C.RESOURCE_EXHAUSTED, "particles"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml="x" * (2 << 20)),
                 C.RESOURCE_EXHAUSTED, "case_yaml"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=stl_text),
                 C.INVALID_ARGUMENT, "bodies[1].shape.mesh.stl_file"),
                ("CreateSimulation", pb.CreateSimulationRequest(case_yaml=open_text),
                 C.INVALID_ARGUMENT, "bodies[1].shape.mesh': the edge"),
            ]
            self.assertGreaterEqual(len(catalogue), 40)
            for method, request, code, field in catalogue:
                with self.subTest(method=method, field=field):
                    with self.assertRaises(grpc.RpcError) as raised:
                        reply = client.call(method, request)
                        if method in ("QueryFields", "WatchSimulation"):
                            list(reply)
                    self.assertEqual(raised.exception.code(), code, raised.exception.details())
                    self.assertIn(field, raised.exception.details())

            # Limits on simulations: two at most.
            client.create(clitest.fixture("rain_column"))
            with self.assertRaises(grpc.RpcError) as raised:
                client.create(clitest.fixture("rain_column"))
            self.assertEqual(raised.exception.code(), C.RESOURCE_EXHAUSTED)
            self.assertIn("simulations", raised.exception.details())
            # Still serving, and the good simulation is unharmed.
            sim.step(3)
            self.assertEqual(sim.get().status.step, 3)


class Tokens(unittest.TestCase):
    def test_roles(self):
        with clitest.Server("tokens", "--tokens", clitest.token_file()) as server:
            case = clitest.fixture("rain_column")
            p = server.cli("list")
            self.assertEqual(p.returncode, 1)
            self.assertIn("UNAUTHENTICATED", p.stderr)
            p = server.cli("list", token="wrong-token-0123456789")
            self.assertIn("UNAUTHENTICATED", p.stderr)
            p = server.cli("create", case, token=VIEWER)
            self.assertEqual(p.returncode, 1)
            self.assertIn("PERMISSION_DENIED", p.stderr)
            p = server.cli("create", case, "--id", "t", token=OPERATOR)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(server.cli("get", "t", token=VIEWER).returncode, 0)
            p = server.cli("set", "t", "rainfall.intensity=1e-5", token=VIEWER)
            self.assertIn("PERMISSION_DENIED", p.stderr)
            self.assertEqual(server.cli("step", "t", "2", token=OPERATOR).returncode, 0)
            journal = server.data_dir / "simulations" / "t" / "journal.jsonl"
            self.assertIn('"caller":"alice"', journal.read_text())


def unknown_varint_field(number, value=1):
    """The wire bytes of a varint field `number` (below 2048) = `value` (below 128): what a newer
    client's field looks like to this server."""
    tag = number << 3
    return (bytes([tag]) if tag < 128 else bytes([tag & 0x7F | 0x80, tag >> 7])) + bytes([value])


class UnknownFields(unittest.TestCase):
    def test_unknown_fields_are_refused_naming_the_number(self):
        grpc, field_mask_pb2, journal_pb2, pb = import_api()
        import cascade_client
        with clitest.Server("unknown_fields") as server, cascade_client.Client(server.address) as client, \
                grpc.insecure_channel(server.address) as channel:
            sim = client.create(clitest.fixture("rain_column"))

            def call(method, request_bytes):
                """The method with these bytes as its request, past the stubs' serializer."""
                return channel.unary_unary(f"/cascade.v1.SimulationService/{method}")(request_bytes, timeout=30)

            get = pb.GetSimulationRequest(name=sim.name).SerializeToString()
            call("GetSimulation", get)
            with self.assertRaises(grpc.RpcError) as raised:
                call("GetSimulation", get + unknown_varint_field(99))
            self.assertEqual(raised.exception.code(), grpc.StatusCode.INVALID_ARGUMENT)
            self.assertTrue(raised.exception.details().startswith("request: unknown field number 99"),
                            raised.exception.details())
            self.assertIn("cascade.v1.GetSimulationRequest", raised.exception.details())

            # Inside a nested message: a newer Rainfall with a field 17 beside the intensity.
            request = pb.UpdateForcingRequest(name=sim.name, update_mask=field_mask_pb2.FieldMask(
                paths=["rainfall.intensity"]))
            request.forcing.rainfall.MergeFromString(
                journal_pb2.Rainfall(intensity=4e-5).SerializeToString() + unknown_varint_field(17))
            with self.assertRaises(grpc.RpcError) as raised:
                call("UpdateForcing", request.SerializeToString())
            self.assertEqual(raised.exception.code(), grpc.StatusCode.INVALID_ARGUMENT)
            self.assertTrue(raised.exception.details().startswith("forcing.rainfall: unknown field number 17"),
                            raised.exception.details())
            self.assertNotEqual(sim.get().forcing.rainfall.intensity, 4e-5)   # not applied
            request.forcing.rainfall.DiscardUnknownFields()
            call("UpdateForcing", request.SerializeToString())
            self.assertEqual(sim.get().forcing.rainfall.intensity, 4e-5)


class UnparsableBytes(unittest.TestCase):
    """Issue 14: request bytes that do not parse were answered UNIMPLEMENTED with an empty message
    (gRPC's callback handlers do so: server/service/unparsable_request.h)."""

    def test_bytes_that_do_not_parse_are_invalid_argument_naming_the_method(self):
        grpc, _, _, pb = import_api()
        import cascade_client
        with clitest.Server("unparsable") as server, cascade_client.Client(server.address) as client, \
                grpc.insecure_channel(server.address) as channel:
            sim = client.create(clitest.fixture("rain_column"))
            name = pb.GetSimulationRequest(name=sim.name).SerializeToString()
            # A varint that never ends; a length past the end; a wire type 7 that does not exist; a
            # string field (name) holding a byte that is not UTF-8.
            garbage = [b"\xff\xff\xff", b"\x0a\x05ab", b"\x0f\x01", b"\x0a\x02\xe9a"]
            # Unary and server-streaming methods (WatchSimulation, QueryFields, StreamSnapshots).
            methods = [("GetSimulation", channel.unary_unary), ("DeleteSimulation", channel.unary_unary),
                       ("WatchSimulation", channel.unary_stream), ("QueryFields", channel.unary_stream)]
            checked = 0
            for method, kind in methods:
                for request in garbage:
                    with self.assertRaises(grpc.RpcError, msg=(method, request)) as raised:
                        reply = kind(f"/cascade.v1.SimulationService/{method}")(request, timeout=30)
                        if kind == channel.unary_stream:
                            next(iter(reply))
                    self.assertEqual(raised.exception.code(), grpc.StatusCode.INVALID_ARGUMENT, (method, request))
                    self.assertIn(f"do not parse as the request message of /cascade.v1.SimulationService/{method}",
                                  raised.exception.details())
                    checked += 1
            self.assertEqual(checked, 16)
            # A method that does not exist stays UNIMPLEMENTED; the simulation was not touched.
            with self.assertRaises(grpc.RpcError) as raised:
                channel.unary_unary("/cascade.v1.SimulationService/NoSuchMethod")(name, timeout=30)
            self.assertEqual(raised.exception.code(), grpc.StatusCode.UNIMPLEMENTED)
            self.assertEqual(channel.unary_unary("/cascade.v1.SimulationService/GetSimulation")(name, timeout=30),
                             sim.get().SerializeToString())


class OutputIntervals(unittest.TestCase):
    """Issue 14: `--set output.interval=1e-300` was accepted, and once it ran every request of every
    simulation hung and SIGTERM no longer stopped the server. Such intervals are now refused, and the
    shortest accepted one gives at most one output per step without holding other requests."""

    def test_tiny_interval_refused_and_the_shortest_one_keeps_the_server_serving(self):
        import time
        grpc, field_mask_pb2, journal_pb2, pb = import_api()
        import cascade_client
        with clitest.Server("output_intervals") as server, cascade_client.Client(server.address) as client:
            for key in ("output.interval", "output.probe_interval"):
                with self.subTest(key=key), self.assertRaises(grpc.RpcError) as raised:
                    client.create(clitest.fixture("rain_column"), overrides=[f"{key}=1e-300"])
                self.assertEqual(raised.exception.code(), grpc.StatusCode.INVALID_ARGUMENT)
                self.assertIn(key, raised.exception.details())
                self.assertIn("at least 1e-6 s", raised.exception.details())

            other = client.create(clitest.fixture("rain_column"), simulation_id="other")
            # t reaches 600 s in steps of 2 s: with probes every 1e-6 s the old schedule added the
            # interval some 2e6 times per step, under the session's lock.
            busy = client.create(clitest.fixture("rain_column"), simulation_id="busy",
                                 overrides=["output.probe_interval=1e-6"])
            busy.start()
            slowest = 0.0
            while busy.get().status.state != pb.Simulation.COMPLETED:
                begin = time.monotonic()
                other.get()
                client.list()
                slowest = max(slowest, time.monotonic() - begin)
                time.sleep(0.05)
            status = busy.get().status
            self.assertGreater(status.step, 100)
            self.assertLess(slowest, 1.0, "Get and List waited on the busy simulation's output phase")
            # One probe sample per step, not one per interval.
            _, _, steps, _ = busy.probes()
            self.assertEqual(len(set(steps)), len(steps))
            self.assertGreaterEqual(len(steps), status.step)
            code, rest = server.stop()
            self.assertEqual(code, 0, rest)


if __name__ == "__main__":
    clitest.main()
