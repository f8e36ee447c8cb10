"""What a browser's user may do, decided by the server: the dashboard forwards the user's token
with every call (authorization: Bearer TOKEN), so a viewer's request is refused by cascade-server
itself (PERMISSION_DENIED), whatever the page shows. The server's error message goes back to the
page as it is."""

import math
import threading
import time

import grpc

from cascade.v1 import simulation_pb2 as pb

MM_PER_HOUR = 3.6e6
ROLE_SECONDS = 30.0  # how long a token's role is trusted before the server is asked again

# gRPC code → HTTP status of the dashboard's JSON answer.
HTTP_STATUS = {
    grpc.StatusCode.INVALID_ARGUMENT: 400, grpc.StatusCode.UNAUTHENTICATED: 401,
    grpc.StatusCode.PERMISSION_DENIED: 403, grpc.StatusCode.NOT_FOUND: 404,
    grpc.StatusCode.ALREADY_EXISTS: 409, grpc.StatusCode.FAILED_PRECONDITION: 409,
    grpc.StatusCode.RESOURCE_EXHAUSTED: 429, grpc.StatusCode.UNAVAILABLE: 503,
    grpc.StatusCode.DEADLINE_EXCEEDED: 504,
}


class Refused(Exception):
    """A request the dashboard or the server refused: HTTP status, gRPC code name, message."""

    def __init__(self, status, code, message):
        super().__init__(message)
        self.status, self.code, self.message = status, code, message

    @staticmethod
    def of(error):
        return Refused(HTTP_STATUS.get(error.code(), 500), error.code().name, error.details() or str(error))


class Access:
    """Each token's role, asked of the server with a harmless operator call: PauseSimulation of
    the empty name is refused after the token is checked, with INVALID_ARGUMENT for an operator
    (the name is bad), PERMISSION_DENIED for a viewer, UNAUTHENTICATED for an unknown token."""

    def __init__(self, client):
        self.client = client
        self.roles = {}  # token -> (role, when asked)
        self.lock = threading.Lock()

    def role(self, token):
        with self.lock:
            known = self.roles.get(token)
        if known and time.monotonic() - known[1] < ROLE_SECONDS:
            return known[0]
        try:
            self.client.with_token(token).call("PauseSimulation", pb.PauseSimulationRequest(name=""), timeout=5)
            raise Refused(500, "INTERNAL", "the server paused the simulation named ''?")
        except grpc.RpcError as e:
            if e.code() == grpc.StatusCode.INVALID_ARGUMENT:
                role = "operator"
            elif e.code() == grpc.StatusCode.PERMISSION_DENIED:
                role = "viewer"
            elif e.code() in (grpc.StatusCode.UNAVAILABLE, grpc.StatusCode.DEADLINE_EXCEEDED) and known:
                return known[0]  # the server is away: the page still shows what the dashboard holds
            else:
                raise Refused.of(e)
        with self.lock:
            self.roles[token] = (role, time.monotonic())
        return role


def finite(body, key, low=-math.inf, high=math.inf):
    """body[key] as a finite float; a clear error naming the key otherwise."""
    try:
        value = float(body[key])
    except (KeyError, TypeError, ValueError):
        raise Refused(400, "INVALID_ARGUMENT", f"{key}: expected a number, got {body.get(key)!r}")
    if not math.isfinite(value) or not low <= value <= high:
        raise Refused(400, "INVALID_ARGUMENT", f"{key}: {value} is not a finite number in [{low}, {high}]")
    return value


def act(client, token, body):
    """Runs one operator action of the page (a JSON object: simulation, action, its values) with
    the user's token; returns a line that says what happened."""
    name = body.get("simulation")
    if not isinstance(name, str) or not name.startswith("simulations/"):
        raise Refused(400, "INVALID_ARGUMENT", f"simulation: expected simulations/ID, got {name!r}")
    sim = client.with_token(token).simulation(name)
    action = body.get("action")
    try:
        if action in ("start", "pause", "resume"):
            reply = getattr(sim, action)()
            return f"{name}: {pb.Simulation.State.Name(reply.state)} at t = {reply.status.time:g} s"
        if action == "rain":
            mm_h = finite(body, "intensity_mm_h")
            reply = sim.update_forcing(rainfall__intensity=mm_h / MM_PER_HOUR)
            return f"{name}: rain {mm_h:g} mm/h from step {reply.effective_step} (t = {reply.effective_time:g} s)"
        if action == "rain_factor":
            factor = finite(body, "factor")
            reply = sim.update_forcing(rainfall__factor=factor)
            return f"{name}: the case's rain times {factor:g} from step {reply.effective_step}"
        if action == "ponding":
            p_max = finite(body, "p_max")
            reply = sim.update_forcing(ponding__p_max=p_max)
            return f"{name}: ponding p_max {p_max:g} Pa from step {reply.effective_step}"
        if action == "checkpoint":
            reply = sim.checkpoint()
            return f"{reply.name} at t = {reply.time:g} s, step {reply.step}"
        if action == "fork":
            changes = {"rainfall__factor": finite(body, "factor")} if body.get("factor") not in (None, "") else {}
            fork_id = body.get("id") or ""
            if not isinstance(fork_id, str):
                raise Refused(400, "INVALID_ARGUMENT", f"id: expected text, got {fork_id!r}")
            reply = sim.fork(simulation_id=fork_id, **changes)
            return f"{reply.name}: forked from {name} at step {reply.status.step}"
    except grpc.RpcError as e:
        raise Refused.of(e)
    raise Refused(400, "INVALID_ARGUMENT",
                  f"action: {action!r} is not one of start, pause, resume, rain, rain_factor, ponding, "
                  "checkpoint, fork")
