"""What-if ensembles: branches of one running simulation, side by side (docs/api.md, ForkSimulation).

    from cascade_client import Client
    from cascade_client.ensemble import ensemble
    sim = Client(address).simulation("simulations/storm")
    result = ensemble(sim, rain_factors=[1, 1.5, 2], until=3 * 3600)
    print(result.table())          # each branch's events: ponding, onset, impact, wave at each gauge
    result.plot("ensemble.png")    # the gauges (or other probes) of every branch

Each branch is a fork of the simulation at one step (a running parent pauses for the forks and
goes on after them), with the case's rain times a factor (rainfall.factor) or a hyetograph of its
own: a list of (time s, intensity m/s) on the case's clock, each row from the first step boundary at
or after its time. The branches run on the server at once, sharing its cores, to a time, or each
a few seconds past its own failure: stop_after=("landslide_onset", 3.0). `cascade ensemble`
is the same from the command line.
"""

import math
import threading

from cascade_client import State


class Branch:
    def __init__(self, label, factor=None, hyetograph=()):
        self.label = label
        self.factor = factor
        self.hyetograph = sorted(hyetograph)
        self.simulation = None  # the fork (cascade_client.Simulation)
        self.error = None       # a grpc.RpcError that ended its run


def _intensity_at(rows, time):
    at = 0.0  # before the first row: no rain
    for t, intensity in rows:
        if t <= time:
            at = intensity
    return at


def _run(branch, end, stop_after):
    """To `end`, each later hyetograph row applied where a scheduled change would apply it: run
    to its time, then change the rain, so that nothing depends on when a request arrives. With
    stop_after, each run ends early after the branch's event, and the branch goes no further."""
    sim = branch.simulation
    try:
        now = sim.get()
        for t, intensity in branch.hyetograph:
            if t <= now.status.time:
                continue
            if t >= end:
                break
            now = sim.run_until(t, stop_after)
            if now.state != State.PAUSED or now.status.time < t:
                return
            sim.set_rainfall(intensity)
        if end > now.status.time:
            sim.run_until(end, stop_after)
    except Exception as error:  # reported in the table; the other branches go on
        branch.error = error


class Ensemble:
    def __init__(self, parent_name, fork_time, fork_step, branches):
        self.parent_name = parent_name
        self.fork_time = fork_time
        self.fork_step = fork_step
        self.branches = branches
        self.rows = [self._outcome(b) for b in branches]
        self.gauges = sorted({g for row in self.rows for g in row["gauges"]})

    @staticmethod
    def _outcome(branch):
        sim = branch.simulation
        final = sim.get()
        row = {"branch": branch.label, "simulation": sim.name, "state": State.Name(final.state),
               "time": final.status.time, "ponding_started": math.nan, "landslide_onset": math.nan, "water_impact": math.nan,
               "overtopping": math.nan, "gauges": {}, "error": str(branch.error or "")}
        names, times, _, values = sim.probes()
        for event in sim.events():
            if event.kind in ("ponding_started", "landslide_onset", "water_impact", "overtopping") \
                    and math.isnan(row[event.kind]):
                row[event.kind] = event.time
            if event.kind == "wave_at_gauge":
                probe = event.message.split(":")[0]
                rise = math.nan
                if probe in names and len(times):
                    column = values[:, names.index(probe)]
                    rise = float(column.max() - column[0])  # over the still water, the first sample
                row["gauges"][probe] = (event.time, rise)
        row["probes"] = (names, times, values)
        return row

    def table(self):
        """The branches' events as text: times in s (the onset also in h), rises in m."""
        header = ["branch", "simulation", "state", "time_s", "ponding_s", "onset_s", "onset_h", "impact_s",
                  "overtopping_s"]
        for g in self.gauges:
            header += [f"{g}_arrival_s", f"{g}_rise_m"]
        lines = [header]
        for row in self.rows:
            cells = [row["branch"], row["simulation"], row["state"], row["time"], row["ponding_started"],
                     row["landslide_onset"],
                     row["landslide_onset"] / 3600, row["water_impact"], row["overtopping"]]
            for g in self.gauges:
                cells += list(row["gauges"].get(g, (math.nan, math.nan)))
            lines.append(["-" if isinstance(c, float) and math.isnan(c) else
                          (f"{c:.6g}" if isinstance(c, float) else str(c)) for c in cells])
        widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
        return "\n".join("  ".join(c.ljust(w) for c, w in zip(line, widths)).rstrip() for line in lines)

    def plot(self, path, probes=None):
        """One panel per probe (default: the gauges where a wave arrived in some branch, else every
        probe), a line per branch from the fork on, the landslide's onset marked; a PNG at `path`."""
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        names = self.rows[0]["probes"][0] if self.rows else []
        probes = list(probes or self.gauges or names)
        fig, axes = plt.subplots(len(probes), 1, figsize=(8, 2.6 * max(1, len(probes))), squeeze=False)
        for ax, probe in zip(axes[:, 0], probes):
            for row in self.rows:
                names, times, values = row["probes"]
                if probe not in names:
                    continue
                after = times >= self.fork_time
                line, = ax.plot(times[after], values[after, names.index(probe)], label=row["branch"])
                if not math.isnan(row["landslide_onset"]):
                    ax.axvline(row["landslide_onset"], color=line.get_color(), linestyle=":", linewidth=1)
            ax.set_ylabel(probe)
            ax.legend(fontsize=8)
        axes[-1, 0].set_xlabel("time (s); dotted: landslide onset")
        fig.suptitle(f"{self.parent_name}: branches from t = {self.fork_time:.6g} s (step {self.fork_step})")
        fig.tight_layout()
        fig.savefig(path, dpi=100)
        plt.close(fig)


def ensemble(simulation, rain_factors=(), hyetographs=None, until=None, stop_after=None):
    """Forks one branch per rain factor and per hyetograph ({label: [(time s, intensity m/s)]}),
    runs them side by side to `until` (default the case's end), each ending early `seconds`
    after its own first cascade event `kind` with stop_after=(kind, seconds), and returns an
    Ensemble."""
    branches = [Branch(f"rain x{f:g}", factor=f) for f in rain_factors]
    branches += [Branch(label, hyetograph=rows) for label, rows in (hyetographs or {}).items()]
    if not branches:
        raise ValueError("an ensemble needs rain factors or hyetographs")
    parent = simulation.get()
    was_running = parent.state == State.RUNNING
    if was_running:
        parent = simulation.pause()  # every branch from the same step
    try:
        for b in branches:
            if b.factor is not None:
                fork = simulation.fork(rainfall__factor=b.factor)
            else:
                fork = simulation.fork(rainfall__intensity=_intensity_at(b.hyetograph, parent.status.time))
            b.simulation = simulation.client.simulation(fork.name)
    finally:
        if was_running:
            simulation.resume()
    end = parent.end_time if until is None else until
    threads = [threading.Thread(target=_run, args=(b, end, stop_after)) for b in branches]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return Ensemble(parent.name, parent.status.time, parent.status.step, branches)
