"""Python client of cascade-server (the cascade.v1 API; docs/api.md).

    from cascade_client import Client
    client = Client("127.0.0.1:50051", token=None)
    sim = client.create("cases/infiltration_1d.yaml")
    sim.step(100)
    sim.set_rainfall(5e-5)            # m/s, from the next step boundary
    sim.start()
    for status in sim.watch(interval=0.5):
        print(status.time, status.step)
    pore_pressure = sim.query("pore_pressure", phase="soil")   # numpy arrays
    png = sim.snapshot(field="pore_pressure", phase="soil", width=640, height=360)   # PNG bytes
    for frame in sim.snapshots(every_wall_seconds=1, field="velocity"):   # SnapshotImage
        open(f"{frame.step}.png", "wb").write(frame.png)
    branch = client.simulation(sim.fork(rainfall__factor=2).name)   # what if the rain doubles?

The generated stubs (cascade/v1/*_pb2.py) come from the build tree: put <build>/python on
PYTHONPATH beside this package's folder. Errors raise grpc.RpcError, whose .code() and
.details() say what was wrong and which field.
"""

import pathlib

import grpc
import numpy as np
from google.protobuf import field_mask_pb2

from cascade.v1 import checkpoint_pb2
from cascade.v1 import journal_pb2
from cascade.v1 import scenario_pb2
from cascade.v1 import simulation_pb2 as pb
from cascade.v1 import simulation_pb2_grpc as pb_grpc

State = pb.Simulation.State


class Client:
    """A connection to one cascade-server. `token`: a bearer token of its token file;
    `root_certificates`: PEM bytes of the CA for a TLS server; `options`: gRPC channel arguments,
    e.g. (("grpc.max_reconnect_backoff_ms", 2000),) to reconnect soon after a server restart."""

    def __init__(self, address, token=None, root_certificates=None, options=()):
        if root_certificates is None:
            self._channel = grpc.insecure_channel(address, options=list(options))
        else:
            self._channel = grpc.secure_channel(address, grpc.ssl_channel_credentials(root_certificates),
                                                options=list(options))
        self._stub = pb_grpc.SimulationServiceStub(self._channel)
        self._metadata = (("authorization", f"Bearer {token}"),) if token else ()

    def with_token(self, token):
        """A Client on this one's channel that sends `token` instead (a dashboard calling for each
        of its users, so that the server's roles decide); closing it closes the shared channel."""
        other = object.__new__(Client)
        other._channel, other._stub = self._channel, self._stub
        other._metadata = (("authorization", f"Bearer {token}"),) if token else ()
        return other

    def call(self, method, request, timeout=None):
        """A unary method of the stub by name, with the token."""
        return getattr(self._stub, method)(request, metadata=self._metadata, timeout=timeout)

    def stream(self, method, request, timeout=None):
        return getattr(self._stub, method)(request, metadata=self._metadata, timeout=timeout)

    def create(self, case_path, overrides=(), simulation_id=""):
        """A simulation of a case file (YAML); `overrides` as `cascade run --set`. The file's text is
        sent and the server loads it: a case whose rain is a `hyetograph` (a CSV file, which the
        server does not read) is refused with INVALID_ARGUMENT; create it with `cascade create`,
        which loads the case here and sends the expanded series."""
        text = pathlib.Path(case_path).read_text()
        reply = self.call("CreateSimulation", pb.CreateSimulationRequest(
            case_yaml=text, overrides=list(overrides), simulation_id=simulation_id))
        return Simulation(self, reply.name)

    def list(self):
        return list(self.call("ListSimulations", pb.ListSimulationsRequest()).simulations)

    def simulation(self, name):
        return Simulation(self, name if name.startswith("simulations/") else f"simulations/{name}")

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def forcing_change(fields):
    """(Forcing, mask paths) from keywords named as the mask paths with '__' for '.'."""
    forcing = journal_pb2.Forcing()
    paths = []
    for key, value in fields.items():
        path = key.replace("__", ".")
        paths.append(path)
        if path == "rainfall.intensity":
            forcing.rainfall.intensity = value
        elif path == "rainfall.factor":
            forcing.rainfall.factor = value
        elif path == "ponding.p_max":
            forcing.ponding.p_max = value
        elif path == "ponding.p_min":
            if value is not None:
                forcing.ponding.p_min = value
        elif path == "rainfall.region":
            if value is not None:
                forcing.rainfall.region.min[:] = value[0]
                forcing.rainfall.region.max[:] = value[1]
        else:
            raise ValueError(f"{path} is not steerable")
    return forcing, paths


class Simulation:
    """One simulation on the server, by name (simulations/{id})."""

    def __init__(self, client, name):
        self.client = client
        self.name = name

    def get(self):
        return self.client.call("GetSimulation", pb.GetSimulationRequest(name=self.name))

    def start(self):
        return self.client.call("StartSimulation", pb.StartSimulationRequest(name=self.name))

    def pause(self):
        return self.client.call("PauseSimulation", pb.PauseSimulationRequest(name=self.name))

    def resume(self):
        return self.client.call("ResumeSimulation", pb.ResumeSimulationRequest(name=self.name))

    def step(self, steps):
        """Runs `steps` steps and returns once they are done (the simulation is then PAUSED)."""
        return self.client.call("StepSimulation", pb.StepSimulationRequest(name=self.name, steps=steps))

    def run_until(self, time, stop_after=None):
        """Runs to `time` and returns the Simulation, PAUSED there; with stop_after=(kind, seconds)
        it stops earlier, `seconds` after the first cascade event `kind` of this run."""
        request = pb.RunSimulationUntilRequest(name=self.name, time=time)
        if stop_after is not None:
            request.stop_after_event.kind, request.stop_after_event.seconds = stop_after
        return self.client.call("RunSimulationUntil", request)

    def delete(self):
        self.client.call("DeleteSimulation", pb.DeleteSimulationRequest(name=self.name))

    def update_forcing(self, effective_time=None, **fields):
        """Steers the forcing: keyword names are the mask paths with '__' for '.', e.g.
        rainfall__intensity=1e-5, rainfall__factor=2 (the case's rain, series or constant, times
        2), ponding__p_max=0, ponding__p_min=None (no limit)."""
        forcing, paths = forcing_change(fields)
        request = pb.UpdateForcingRequest(name=self.name, forcing=forcing,
                                          update_mask=field_mask_pb2.FieldMask(paths=paths))
        if effective_time is not None:
            request.effective_time = effective_time
        return self.client.call("UpdateForcing", request)

    def fork(self, simulation_id="", **fields):
        """A what-if branch: a new simulation with this one's state at its next step boundary, bit
        for bit, PAUSED there, with the forcing changes of update_forcing's keywords applied before
        its first step; this one goes on as it was. Returns the fork's Simulation (.name)."""
        request = pb.ForkSimulationRequest(name=self.name, simulation_id=simulation_id)
        if fields:
            forcing, paths = forcing_change(fields)
            request.forcing.CopyFrom(forcing)
            request.update_mask.paths[:] = paths
        return self.client.call("ForkSimulation", request)

    def set_rainfall(self, intensity, effective_time=None):
        """Rainfall intensity (m/s) from the next step boundary (or `effective_time`); the reply
        says the step and time at which it took effect."""
        return self.update_forcing(effective_time, rainfall__intensity=intensity)

    def advance_stage(self, reason=""):
        """Hands over to the case's next stage (ScenarioSpec.stages) at the next step boundary;
        `reason` goes to the journal. Returns the Simulation (its status.stage and stage_name);
        FAILED_PRECONDITION at the last stage or when the run has ended."""
        return self.client.call("AdvanceStage", pb.AdvanceStageRequest(name=self.name, reason=reason))

    def query(self, *fields, phase="", box=None, stride=0):
        """Fields at one step boundary as numpy arrays: a dict with 'time', 'step', 'id',
        'phase', 'position' (N x 3) and one array per field (N, or N x components)."""
        request = pb.QueryFieldsRequest(name=self.name, fields=list(fields), phase=phase, stride=stride)
        if box is not None:
            request.box.min[:] = box[0]
            request.box.max[:] = box[1]
        chunks = list(self.client.stream("QueryFields", request))
        out = {"time": chunks[0].time, "step": chunks[0].step,
               "id": np.array([i for c in chunks for i in c.id], dtype=np.uint32),
               "phase": np.array([p for c in chunks for p in c.phase], dtype=np.uint8),
               "position": np.array([x for c in chunks for x in c.position], dtype=np.float64).reshape(-1, 3)}
        for k, name in enumerate(fields):
            components = chunks[0].fields[k].components
            values = np.array([v for c in chunks for v in c.fields[k].values], dtype=np.float64)
            out[name] = values if components == 1 else values.reshape(-1, components)
        return out

    def probes(self, since_time=float("-inf")):
        """(probe names, times, steps, values as an array samples x probes)."""
        reply = self.client.call("ListProbes", pb.ListProbesRequest(name=self.name, since_time=since_time))
        values = np.array([list(s.values) for s in reply.samples], dtype=np.float64).reshape(-1, len(reply.probe_names))
        return (list(reply.probe_names), np.array([s.time for s in reply.samples]),
                np.array([s.step for s in reply.samples]), values)

    def events(self, since_time=float("-inf")):
        return list(self.client.call("ListEvents", pb.ListEventsRequest(name=self.name, since_time=since_time)).events)

    def checkpoint(self):
        """Writes the complete state at the next step boundary; returns the Checkpoint (its .name
        is simulations/{id}/checkpoints/{checkpoint_id})."""
        return self.client.call("CreateCheckpoint", checkpoint_pb2.CreateCheckpointRequest(parent=self.name))

    def checkpoints(self):
        return list(self.client.call("ListCheckpoints", checkpoint_pb2.ListCheckpointsRequest(parent=self.name)).checkpoints)

    def restore(self, checkpoint):
        """Back to a checkpoint (its name, or its id such as "ckpt-0001"), PAUSED there."""
        name = checkpoint if "/" in checkpoint else f"{self.name}/checkpoints/{checkpoint}"
        return self.client.call("RestoreCheckpoint", checkpoint_pb2.RestoreCheckpointRequest(name=name))

    def watch(self, interval=1.0, events=False):
        """Statuses (and, with events=True, Events) as they come, until the simulation stops."""
        for update in self.client.stream("WatchSimulation", pb.WatchSimulationRequest(
                name=self.name, interval_seconds=interval)):
            if update.HasField("status"):
                yield update.status
            elif events:
                yield update.event

    def snapshot(self, metadata=False, **snapshot):
        """PNG bytes of the particles at the next step boundary, rendered on the server.
        Keywords are the fields of scenario.proto's Snapshot (docs/rendering.md): field, phase,
        translucent, colour_map, min, max, camera, orbit={...}, look_at={...}, clip, slab, width,
        height, background. With metadata=True the SnapshotImage (png, time, step, field, units,
        range, camera, size)."""
        image = self.client.call("RenderSnapshot", pb.RenderSnapshotRequest(
            name=self.name, snapshot=scenario_pb2.Snapshot(**snapshot)))
        return image if metadata else image.png

    def snapshots(self, every_simulated_seconds=None, every_wall_seconds=None, **snapshot):
        """SnapshotImages (.png, .time, .step, ...) every so many simulated or wall seconds, until
        the simulation stops; a slow reader gets the latest frame. Close the iterator (or break out
        of the loop and drop it) to end the stream."""
        request = pb.StreamSnapshotsRequest(name=self.name, snapshot=scenario_pb2.Snapshot(**snapshot))
        if every_simulated_seconds is not None:
            request.every_simulated_seconds = every_simulated_seconds
        if every_wall_seconds is not None:
            request.every_wall_seconds = every_wall_seconds
        return self.client.stream("StreamSnapshots", request)
