"""The README's main job, as a client of a running cascade-server: a storm on a slope, its failure,
the slide into the channel and the wave at the far bank, steered live.

    PYTHONPATH=build/release/python:clients/python /usr/bin/python3 scripts/cascade_demo.py \
        --server 127.0.0.1:50051 --case cases/cascade_storm_2d.yaml --out out/cascade_storm_2d

Creates the simulation and starts it: the case's stages run on the server (geostatic start, the
implicit rain stage over hours, the dynamic stage from the failure on). When the simulated storm
passes --raise-at, the operator raises the rain to --raise-to (a live UpdateForcing: the forecast
got worse; it replaces the case's rain series from then on). Saves PNG snapshots rendered on the
server at the start, at the change, at each stage change and at each cascade event (ponding,
landslide onset, water impact, wave at the far gauge, overtopping). Stops --after seconds of
simulated time after the last of the events the case names (or at its end time), then plots the
storm (rain in mm/h and pore pressures against hours) and the slide (soil speed and wave elevation
against seconds after the failure), and writes summary.json: the time of failure in hours after the
storm began, the rain that fell until then, the events, the rain change, the stage water balance.

Durations and intensities take units as in case files: --raise-at "3 h", --raise-to "90 mm/h"
(a bare number is SI: s, m/s).
"""

import argparse
import json
import pathlib
import re
import time

from cascade_client import Client, State, pb

# The snapshots of each key moment: the soil's pore pressure with water and bedrock in their phase
# colours (the rain's work), and the speed of soil and water (the slide and the wave); side view,
# fixed colour ranges so that frames compare.
SNAPSHOTS = {
    "pore_pressure": dict(field="pore_pressure", phase="all", min=-8e3, max=8e3, colour_map="cool_warm"),
    "speed": dict(field="velocity", min=0.0, max=4.0),
}
# The events of a case's `events` block (server/scenario/cascade_events.h).
CASCADE_EVENTS = ("ponding_started", "landslide_onset", "water_impact", "wave_at_gauge", "overtopping")

# The units a case file takes for durations and rain intensities (docs/cases.md, "Units"), in SI.
TIME_UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0, "d": 86400.0, "day": 86400.0}
RATE_UNITS = {"m/s": 1.0, "mm/h": 1e-3 / 3600.0, "mm/min": 1e-3 / 60.0, "mm/d": 1e-3 / 86400.0,
              "mm/day": 1e-3 / 86400.0}
MM_PER_HOUR = 3.6e6  # m/s -> mm/h


def quantity(text, units):
    """A number with an optional unit of `units` ("3 h", "90 mm/h", "1e-5"), in SI."""
    match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([A-Za-z/]*)\s*", str(text))
    if not match:
        raise ValueError(f"not a number with a unit: {text!r}")
    number, unit = float(match.group(1)), match.group(2)
    if not unit:
        return number
    if unit not in units:
        raise ValueError(f"unknown unit {unit!r} in {text!r}; one of {', '.join(units)}")
    return number * units[unit]


def storm_series(case):
    """The case's rain as (time s, intensity m/s) steps: its `rainfall` series or its constant
    `rainfall_intensity`."""
    hydraulics = case.get("hydraulics") or {}
    if hydraulics.get("rainfall"):
        return [(quantity(p["time"], TIME_UNITS), quantity(p["intensity"], RATE_UNITS)) for p in hydraulics["rainfall"]]
    return [(0.0, quantity(hydraulics.get("rainfall_intensity", 0), RATE_UNITS))]


def rain_at(series, change, t):
    """Intensity (m/s) at time t: the series, or the operator's change from its effective time."""
    if change is not None and t >= change["time_s"]:
        return change["to_m_per_s"]
    value = series[0][1]
    for start, intensity in series:
        if t >= start:
            value = intensity
    return value


def rain_fallen(series, change, until):
    """Depth of rain (m) from t = 0 to `until`, per unit horizontal area."""
    times = sorted({0.0, until} | {t for t, _ in series if 0 < t < until} |
                   ({change["time_s"]} if change is not None and 0 < change["time_s"] < until else set()))
    return sum(rain_at(series, change, a) * (b - a) for a, b in zip(times, times[1:]))


def save_snapshots(sim, folder, label, log):
    for name, options in SNAPSHOTS.items():
        image = sim.snapshot(metadata=True, width=1280, height=560, **options)
        path = folder / f"{label}_{name}.png"
        path.write_bytes(image.png)
        log(f"  snapshot {path.name} at t = {image.time:.2f} s (step {image.step})")


def clock(t, failure):
    """A time as the storm's hours, or as seconds after the failure once it has come."""
    if failure is not None and t >= failure:
        return f"failure + {t - failure:.2f} s"
    return f"{t / 3600:.2f} h"


def water_balance(message):
    """The figures of a stage change's water balance (server/solver/staged_engine.cpp), if any."""
    found = re.search(r"water balance \(m\^\d\): (.*)$", message)
    if not found:
        return None
    return {name.strip().replace(" ", "_"): float(value)
            for name, value in re.findall(r"([a-z ]+?) ([-+0-9.e]+)(?:,|$)", found.group(1))}


def run(args):
    import yaml
    out = pathlib.Path(args.out)
    snapshots = out / "snapshots"
    snapshots.mkdir(parents=True, exist_ok=True)
    started_wall = time.monotonic()

    def log(message):
        print(f"[{time.monotonic() - started_wall:6.1f} s] {message}", flush=True)

    case = yaml.safe_load(pathlib.Path(args.case).read_text()) or {}
    wanted = {kind for kind, value in (case.get("events") or {}).items() if value}
    stages = [stage.get("name", "") for stage in case.get("stages") or []]
    series = storm_series(case)
    raise_at = quantity(args.raise_at, TIME_UNITS)
    raise_to = quantity(args.raise_to, RATE_UNITS)
    with Client(args.server) as client:
        sim = client.create(args.case, overrides=args.set)
        info = sim.get()
        log(f"created {sim.name}: {info.particle_count} particles, end time {info.end_time / 3600:g} h, "
            f"stages {' -> '.join(stages) or '(one)'}; rain {info.forcing.rainfall.intensity * MM_PER_HOUR:g} mm/h")
        counts_start = phase_counts(sim)
        save_snapshots(sim, snapshots, "00_start", log)
        sim.start()

        change = None
        failure = None      # the time of the hand-over to the last (dynamic) stage
        seen = []           # the cascade events so far, in order
        stage_changes = []
        stop_at = info.end_time
        for update in sim.watch(interval=0.5, events=True):
            if isinstance(update, pb.Event):
                if update.kind == "stage_changed":
                    stage_changes.append(update)
                    log(f"stage change at {clock(update.time, failure)}: {update.message}")
                    if stages and update.message.startswith(f"{stages[-2] if len(stages) > 1 else ''} -> {stages[-1]}"):
                        failure = update.time
                        log(f"the slope fails {failure / 3600:.2f} h after the storm began")
                    save_snapshots(sim, snapshots, f"{len(seen) + len(stage_changes):02d}_stage_{len(stage_changes)}", log)
                    continue
                if update.kind not in CASCADE_EVENTS:
                    continue
                seen.append(update)
                log(f"event {update.kind} at {clock(update.time, failure)}: {update.message}")
                save_snapshots(sim, snapshots, f"{len(seen) + len(stage_changes):02d}_{update.kind}", log)
                if wanted <= {e.kind for e in seen}:
                    stop_at = min(stop_at, update.time + args.after)
                continue
            status = update
            if change is None and status.time >= raise_at:
                before = rain_at(series, None, status.time)
                reply = sim.set_rainfall(raise_to)
                change = {"from_m_per_s": before, "to_m_per_s": raise_to, "time_s": reply.effective_time,
                          "step": reply.effective_step}
                log(f"the operator raises the rain {before * MM_PER_HOUR:g} -> {raise_to * MM_PER_HOUR:g} mm/h, "
                    f"effective at step {reply.effective_step} ({clock(reply.effective_time, failure)})")
                save_snapshots(sim, snapshots, "00_rain_raised", log)
            if status.time >= stop_at:
                sim.pause()
                log(f"stopping at {clock(status.time, failure)}")
                break
        final = sim.get()
        if final.state == State.FAILED:
            raise SystemExit(f"the simulation failed: {final.failure_reason}")
        save_snapshots(sim, snapshots, "99_end", log)
        counts_end = phase_counts(sim)
        names, times, _, values = sim.probes()
        # The cascade, the stage changes and any particle that left the domain.
        events = [e for e in sim.events() if e.kind in CASCADE_EVENTS + ("stage_changed", "particles_lost")]
        sim.delete()

    wall = time.monotonic() - started_wall
    write_probes(out / "probes.csv", names, times, values)
    plot(out, names, times, values, series, change, failure, events)
    balances = [b for b in (water_balance(e.message) for e in events if e.kind == "stage_changed") if b]
    summary = {
        "case": args.case,
        "simulated_time_s": final.status.time,
        "steps": final.status.step,
        "wall_seconds": wall,
        "particles": final.particle_count,
        # Each particle's mass is ρ_w0 dp^d, fixed: a phase's mass is its particle count.
        "phase_particles": {"start": counts_start, "end": counts_end},
        "particle_steps_per_second": final.particle_count * final.status.step / wall,
        "time_of_failure_h": None if failure is None else failure / 3600,
        "rain_until_failure_mm": None if failure is None else 1e3 * rain_fallen(series, change, failure),
        "rain_stage_water_balance": balances[-1] if balances else None,
        "rainfall_change": change,
        "events": [{"kind": e.kind, "time_s": e.time, "step": e.step, "message": e.message} for e in events],
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print_summary(summary, out)
    if counts_start != counts_end:
        raise SystemExit(f"particles were lost: {counts_start} at the start, {counts_end} at the end")
    missing = wanted - {e.kind for e in events}
    if missing:
        raise SystemExit(f"events that did not happen by t = {final.status.time:.1f} s: {', '.join(sorted(missing))}")


def phase_counts(sim):
    phases = list(sim.query("pressure")["phase"])
    return {"water": phases.count(0), "soil": phases.count(1)}


def write_probes(path, names, times, values):
    with open(path, "w") as f:
        f.write("time," + ",".join(names) + "\n")
        for t, row in zip(times, values):
            f.write(f"{t!r}," + ",".join(repr(float(v)) for v in row) + "\n")


def plot(out, names, times, values, series, change, failure, events):
    """storm.png: rain (mm/h) and pore pressures (kPa) against the storm's hours, to the failure;
    soil_speed.png and wave_elevation.png: the slide against seconds after the failure."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    def column(name):
        return values[:, names.index(name)]

    end_of_storm = failure if failure is not None else (times[-1] if len(times) else 0.0)
    hours = np.linspace(0.0, end_of_storm, 2000)
    fig, (rain_ax, pore_ax) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    rain_ax.fill_between(hours / 3600, [rain_at(series, change, t) * MM_PER_HOUR for t in hours], step="post",
                         color="tab:blue", alpha=0.4, label="rain as applied")
    rain_ax.step([t / 3600 for t, _ in series], [i * MM_PER_HOUR for _, i in series], where="post", color="k",
                 linewidth=0.8, linestyle=":", label="the case's storm")
    rain_ax.set_ylabel("rain (mm/h)")
    rain_rows = times <= end_of_storm
    for name in (n for n in names if n.startswith("pore_pressure")):
        pore_ax.plot(times[rain_rows] / 3600, column(name)[rain_rows] * 1e-3, label=name)
    pore_ax.set_ylabel("pore pressure (kPa)")
    pore_ax.set_xlabel("time since the storm began (h)")
    for ax in (rain_ax, pore_ax):
        if change is not None:
            ax.axvline(change["time_s"] / 3600, color="k", linestyle="--", linewidth=0.8, label="rain raised")
        if failure is not None:
            ax.axvline(failure / 3600, color="tab:red", linewidth=1.0, label="failure")
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out / "storm.png", dpi=120)
    plt.close(fig)

    start = failure if failure is not None else 0.0
    slide_rows = times >= start
    after = times[slide_rows] - start
    figures = {
        "soil_speed.png": ("largest soil speed (m/s)", [n for n in names if n == "max_soil_speed"]),
        "wave_elevation.png": ("wave elevation above the still level (m)", [n for n in names if n.startswith("gauge")]),
    }
    for file, (label, columns) in figures.items():
        fig, ax = plt.subplots(figsize=(8, 4))
        for name in columns:
            y = column(name)[slide_rows]
            if file == "wave_elevation.png" and len(y):
                y = y - y[0]
            ax.plot(after, y, label=name)
        for e in events:
            if e.kind in CASCADE_EVENTS and e.time >= start:
                ax.axvline(e.time - start, color="grey", linestyle=":", linewidth=0.8)
                ax.annotate(e.kind, (e.time - start, 1.0), xycoords=("data", "axes fraction"), rotation=90,
                            va="top", ha="right", fontsize=7, color="grey")
        ax.set_xlabel("time after the failure (s)" if failure is not None else "time (s)")
        ax.set_ylabel(label)
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(out / file, dpi=120)
        plt.close(fig)


def print_summary(summary, out):
    print(f"\nCascade demo: {summary['simulated_time_s'] / 3600:.2f} h simulated in {summary['wall_seconds']:.0f} s "
          f"of wall time ({summary['steps']} steps, {summary['particles']} particles)")
    failure = None if summary["time_of_failure_h"] is None else summary["time_of_failure_h"] * 3600
    lines = [(e["time_s"], f"{e['kind']}: {e['message']}") for e in summary["events"]]
    change = summary["rainfall_change"]
    if change:
        lines.append((change["time_s"], f"rain raised by the operator {change['from_m_per_s'] * MM_PER_HOUR:g} -> "
                                        f"{change['to_m_per_s'] * MM_PER_HOUR:g} mm/h (step {change['step']})"))
    for t, line in sorted(lines, key=lambda x: x[0]):
        print(f"  {clock(t, failure):>18}  {line}")
    if failure is not None:
        print(f"  time of failure: {summary['time_of_failure_h']:.2f} h after the storm began, "
              f"{summary['rain_until_failure_mm']:.0f} mm of rain by then")
    balance = summary["rain_stage_water_balance"]
    if balance:
        print(f"  rain stage water balance: rain {balance['rain']:.4g}, storage change {balance['storage_change']:.4g}, "
              f"error {balance['error']:.2g} (m^2 of section)")
    counts = summary["phase_particles"]
    kept = "kept" if counts["start"] == counts["end"] else "NOT kept"
    print(f"  mass of each phase {kept}: water {counts['start']['water']} -> {counts['end']['water']}, "
          f"soil {counts['start']['soil']} -> {counts['end']['soil']} particles")
    print(f"Outputs in {out}/: snapshots/*.png, storm.png, soil_speed.png, wave_elevation.png, probes.csv, summary.json")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--server", default="127.0.0.1:50051")
    parser.add_argument("--case", default="cases/cascade_storm_2d.yaml")
    parser.add_argument("--out", default="out/cascade_storm_2d")
    parser.add_argument("--set", action="append", default=[], help="a case override, as cascade run --set")
    parser.add_argument("--raise-at", default="2 h", help="simulated time of the rain change (default 2 h)")
    parser.add_argument("--raise-to", default="90 mm/h", help="the raised rain intensity (default 90 mm/h)")
    parser.add_argument("--after", type=float, default=3.0,
                        help="simulated seconds to run on after the last event")
    run(parser.parse_args())


if __name__ == "__main__":
    main()
