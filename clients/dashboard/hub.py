"""The dashboard's one view of a cascade-server, shared by every browser (docs/dashboard.md).

A single thread polls the server (ListSimulations, then ListEvents and ListProbes of each
simulation since the last sample it holds) and keeps what it learnt; browsers read that copy.
So the server sees the same few calls a second whether one browser is open or ten, and a viewer
cannot slow the solver. Frames come from one StreamSnapshots per (simulation, field, camera)
that some browser asked for in the last FEED_IDLE_SECONDS (frames.py).

When a call fails with UNAVAILABLE the hub marks the server unreachable and keeps polling; when
it answers again, everything is read afresh (a restarted server has other simulations, or the
same ones restored from checkpoints with a new history).
"""

import math
import re
import threading
import time

import grpc
from google.protobuf import text_format

from cascade.v1 import journal_pb2
from cascade.v1 import simulation_pb2 as pb
from cascade_client import State

POLL_SECONDS = 0.5
MAX_SAMPLES = 100_000      # per simulation; beyond it every other sample is dropped (charts show at most ~600)
MAX_EVENTS = 2_000         # per simulation, the latest kept
MM_PER_HOUR = 3.6e6        # (mm/h) per (m/s)
FORKED_FROM = re.compile(r"forked from (simulations/[a-z0-9-]+) at step (\d+)")


def state_name(state):
    return State.Name(state)


def number(value):
    """A float for JSON: NaN and infinities (a probe with nothing to measure) become None."""
    return value if math.isfinite(value) else None


class SimulationView:
    """What the hub knows of one simulation: its last Simulation message, its history of probe
    samples and events since the hub first saw it, the rain as applied (the hyetograph) and the
    simulation it was forked from."""

    def __init__(self, name):
        self.name = name
        self.simulation = None
        self.probe_names = []
        self.sample_times, self.sample_values = [], []
        self.events = []
        self.event_keys = set()
        self.rain = []              # (simulated time, intensity in mm/h), a step function
        self.parent, self.fork_step = None, None

    def last_event_time(self):
        return self.events[-1]["time"] if self.events else -math.inf

    def add_events(self, events):
        for e in events:
            key = (e.time, e.step, e.wall_time, e.kind, e.message)
            if key in self.event_keys:  # ListEvents' since_time is inclusive
                continue
            self.event_keys.add(key)
            self.events.append({"time": e.time, "step": e.step, "wall_time": e.wall_time, "kind": e.kind,
                                "message": e.message, "caller": e.caller})
            found = FORKED_FROM.search(e.message) if e.kind == "state" else None
            if found:  # the last one names this simulation's own parent (earlier ones are its history)
                self.parent, self.fork_step = found.group(1), int(found.group(2))
        if len(self.events) > MAX_EVENTS:
            del self.events[:len(self.events) - MAX_EVENTS]

    def add_samples(self, names, samples):
        self.probe_names = list(names)
        last = self.sample_times[-1] if self.sample_times else -math.inf
        for s in samples:
            if s.time > last:  # since_time is inclusive; a pause samples the same time again
                self.sample_times.append(s.time)
                self.sample_values.append([number(v) for v in s.values])
                last = s.time
        if len(self.sample_times) > MAX_SAMPLES:
            self.sample_times, self.sample_values = self.sample_times[::2], self.sample_values[::2]

    def note_rain(self, simulation):
        """Extends the hyetograph when the intensity in force changed: from the time of the latest
        `forcing` event after the last point (a steering or the case's series), else from now. On
        first sight the steerings before it are read back from their events (their messages hold
        the old and new Forcing); changes of the case's own series before it are not."""
        intensity = simulation.forcing.rainfall.intensity * MM_PER_HOUR
        if not self.rain:
            self.rain = self._steered_rain(intensity)
        if self.rain and self.rain[-1][1] == intensity:
            return
        since = self.rain[-1][0] if self.rain else -math.inf
        changes = [e["time"] for e in self.events if e["kind"] == "forcing" and e["time"] > since]
        at = changes[-1] if changes and self.rain else simulation.status.time
        self.rain.append((at, intensity))

    def _steered_rain(self, intensity_now):
        steps = []
        for e in self.events:
            if e["kind"] != "forcing" or " -> " not in e["message"]:
                continue
            try:
                old, new = (text_format.Parse(part, journal_pb2.Forcing()).rainfall.intensity * MM_PER_HOUR
                            for part in e["message"].split(": ", 1)[1].split(" -> "))
            except (IndexError, text_format.ParseError, ValueError):
                continue
            steps.append((e["time"], old, new))
        start = min([0.0] + [e["time"] for e in self.events])
        rain = [(start, steps[0][1] if steps else intensity_now)]
        rain += [(t, new) for t, _, new in steps if new != rain[-1][1]]
        return rain

    def summary(self):
        """The JSON of the simulation list: state, time, speed, forcing, family."""
        s = self.simulation
        return {"name": s.name, "id": s.name.split("/", 1)[1], "case": s.case_name, "state": state_name(s.state),
                "failure_reason": s.failure_reason, "time": s.status.time, "end_time": s.end_time,
                "step": s.status.step, "dt": s.status.dt, "steps_per_second": s.status.steps_per_second,
                "stage": s.status.stage_name, "particles": s.particle_count, "device": s.device,
                "rain_mm_h": s.forcing.rainfall.intensity * MM_PER_HOUR,
                "rain_factor": s.forcing.rainfall.factor if s.forcing.rainfall.HasField("factor") else None,
                "ponding_p_max": s.forcing.ponding.p_max,
                "parent": self.parent, "fork_step": self.fork_step}

    def history(self, points=600):
        """Probe series (every k-th sample, the last always), events and the hyetograph."""
        n = len(self.sample_times)
        stride = max(1, math.ceil(n / points))
        picked = list(range(0, n, stride))
        if n and picked[-1] != n - 1:
            picked.append(n - 1)
        rain = list(self.rain)
        if rain and self.simulation is not None:  # the step function reaches the present
            rain.append((max(self.simulation.status.time, rain[-1][0]), rain[-1][1]))
        return {"probe_names": self.probe_names, "times": [self.sample_times[k] for k in picked],
                "values": [self.sample_values[k] for k in picked], "events": self.events[-300:],
                "rain": rain}


class Hub:
    """Polls one server for every browser; `snapshot()` is what they read, `wait(version)` blocks
    until there is something newer (the browsers' long poll)."""

    def __init__(self, client):
        self.client = client
        self.lock = threading.Condition()
        self.version = 0
        self.reachable = None       # None until the first poll
        self.error = ""
        self.since = time.time()    # of the current reachable / unreachable spell
        self.views = {}             # name -> SimulationView
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="hub", daemon=True)

    def start(self):
        self._thread.start()

    def stop(self):
        self._stop.set()
        self._thread.join()

    def changed(self):
        """Called with the lock held: wakes the browsers' long polls."""
        self.version += 1
        self.lock.notify_all()

    def wait(self, version, timeout):
        with self.lock:
            self.lock.wait_for(lambda: self.version != version or self._stop.is_set(), timeout)
            return self.version

    def state_of(self, name):
        with self.lock:
            view = self.views.get(name)
            return view.simulation.state if view and view.simulation else None

    def step_of(self, name):
        with self.lock:
            view = self.views.get(name)
            return view.simulation.status.step if view and view.simulation else None

    def _run(self):
        while not self._stop.is_set():
            started = time.monotonic()
            try:
                self._poll()
            except grpc.RpcError as e:
                self._unreachable(f"{e.code().name}: {e.details()}")
            self._stop.wait(max(0.0, POLL_SECONDS - (time.monotonic() - started)))

    def _unreachable(self, why):
        with self.lock:
            if self.reachable is not False:
                self.reachable, self.since = False, time.time()
            self.error = why
            self.changed()

    def _poll(self):
        simulations = self.client.list()
        with self.lock:
            back = self.reachable is not True
            if back:  # first contact, or the server is back: read every history afresh
                self.views, self.reachable, self.since, self.error = {}, True, time.time(), ""
            known = {name: (view.last_event_time(), view.sample_times[-1] if view.sample_times else -math.inf)
                     for name, view in self.views.items()}
        updates = []
        for s in simulations:
            event_since, sample_since = known.get(s.name, (-math.inf, -math.inf))
            sim = self.client.simulation(s.name)
            try:
                events = sim.events(since_time=event_since)
                probes = self.client.call("ListProbes", pb.ListProbesRequest(name=s.name, since_time=sample_since))
            except grpc.RpcError as e:
                if e.code() == grpc.StatusCode.NOT_FOUND:  # deleted between the list and now
                    continue
                raise
            updates.append((s, events, probes))
        with self.lock:
            listed = {s.name for s, _, _ in updates}
            for name in list(self.views):
                if name not in listed:
                    del self.views[name]
            for s, events, probes in updates:
                view = self.views.setdefault(s.name, SimulationView(s.name))
                view.simulation = s
                view.add_events(events)
                view.add_samples(probes.probe_names, probes.samples)
                view.note_rain(s)
            self.changed()

    def snapshot(self, selected=None):
        """The JSON the page shows: the server's reachability, every simulation's summary, and the
        history of `selected`'s family (the root it was forked from, and every branch of it)."""
        with self.lock:
            sims = [v.summary() for v in sorted(self.views.values(), key=lambda v: v.name) if v.simulation]
            family = self._family(selected) if selected in self.views else []
            return {"version": self.version, "reachable": self.reachable, "error": self.error,
                    "since": self.since, "simulations": sims,
                    "family": {name: self.views[name].history() for name in family}}

    def _family(self, name):
        root = name
        seen = {root}
        while self.views[root].parent in self.views and self.views[root].parent not in seen:
            root = self.views[root].parent
            seen.add(root)
        members, changed = {root}, True
        while changed:  # every simulation whose parent is a member
            changed = False
            for other, view in self.views.items():
                if other not in members and view.parent in members:
                    members.add(other)
                    changed = True
        return sorted(members)

