"""Server-rendered frames for the dashboard: one feed per (simulation, field, camera) that some
browser watches, shared by all of them (docs/dashboard.md).

While the simulation runs a feed holds one StreamSnapshots open (a frame every FRAME_SECONDS of
wall time; the server sends the latest and drops what a slow reader missed, so the solver never
waits). While it does not run, the feed renders the state it stopped in once (RenderSnapshot).
A feed nobody asked for in FEED_IDLE_SECONDS closes its stream and ends.
"""

import threading
import time

import grpc

from actions import Refused
from cascade_client import State

FRAME_SECONDS = 1.0
FEED_IDLE_SECONDS = 10.0
WIDTH, HEIGHT = 640, 360
MAX_FEEDS = 16


class FrameFeed:
    def __init__(self, hub, name, field, camera):
        self.hub, self.name, self.field, self.camera = hub, name, field, camera
        self.png, self.meta, self.error, self.seq = None, None, "", 0
        self.wanted = time.monotonic()
        self.stream = None
        self.thread = threading.Thread(target=self._run, name=f"frames {name} {field}", daemon=True)

    def options(self):
        options = {"width": WIDTH, "height": HEIGHT, "camera": self.camera}
        if self.field != "phase":
            options["field"] = self.field
        return options

    def idle(self):
        return time.monotonic() - self.wanted > FEED_IDLE_SECONDS

    def _run(self):
        sim = self.hub.client.simulation(self.name)
        while not self.idle():
            state, step = self.hub.state_of(self.name), self.hub.step_of(self.name)
            try:
                if state == State.RUNNING:
                    self.stream = sim.snapshots(every_wall_seconds=FRAME_SECONDS, **self.options())
                    for frame in self.stream:
                        self._store(frame)
                elif state is not None and (self.meta is None or self.meta["step"] != step):
                    self._store(sim.snapshot(metadata=True, **self.options()))
            except grpc.RpcError as e:
                if e.code() != grpc.StatusCode.CANCELLED:  # we cancel a stream when the run stops
                    self._fail(f"{e.code().name}: {e.details()}")
                    time.sleep(4 * FRAME_SECONDS)  # a bad field or a server away: not every 0.5 s
            finally:
                self.stream = None
            time.sleep(FRAME_SECONDS)

    def cancel_if_stale(self):
        """Ends the stream of a feed nobody watches, or of a run that stopped (then the feed
        renders the state it stopped in)."""
        stream = self.stream
        if stream is not None and (self.idle() or self.hub.state_of(self.name) != State.RUNNING):
            stream.cancel()

    def _store(self, frame):
        with self.hub.lock:
            self.png, self.error, self.seq = frame.png, "", self.seq + 1
            self.meta = {"seq": self.seq, "step": frame.step, "time": frame.time, "field": frame.field,
                         "units": frame.units, "range": [frame.range_min, frame.range_max],
                         "camera": frame.camera, "received": time.time()}
            self.hub.changed()

    def _fail(self, why):
        with self.hub.lock:
            self.error = why
            self.hub.changed()

    def describe(self):
        meta = dict(self.meta or {})
        meta.update({"seq": self.seq, "error": self.error, "field": self.field, "camera": self.camera})
        return meta


class Frames:
    """The feeds by (simulation, field, camera); a reaper thread cancels stale streams."""

    def __init__(self, hub):
        self.hub = hub
        self.feeds = {}
        self.lock = threading.Lock()
        threading.Thread(target=self._reap, name="frame reaper", daemon=True).start()

    def want(self, name, field, camera):
        """The feed of this view, started if need be; marks it as watched now. Refuses a view of a
        simulation the server does not list, and more than MAX_FEEDS views at once (each is a
        thread here and a stream on the server)."""
        key = (name, field, camera)
        with self.lock:
            feed = self.feeds.get(key)
            if feed is None or not feed.thread.is_alive():
                if self.hub.state_of(name) is None:
                    raise Refused(404, "NOT_FOUND", f"sim: the server lists no {name}")
                if len(self.feeds) >= MAX_FEEDS:
                    raise Refused(429, "RESOURCE_EXHAUSTED", f"frames: {MAX_FEEDS} views are watched already")
                feed = self.feeds[key] = FrameFeed(self.hub, name, field, camera)
                feed.thread.start()
            feed.wanted = time.monotonic()
            return feed

    def _reap(self):
        while True:
            time.sleep(0.5)
            with self.lock:
                feeds = list(self.feeds.items())
            for key, feed in feeds:
                feed.cancel_if_stale()
                if not feed.thread.is_alive():
                    with self.lock:
                        if self.feeds.get(key) is feed:
                            del self.feeds[key]
