"""The README's main job, as a client of a running cascade-server: rain on a slope, the landslide,
the wave at the far bank, steered live.

    PYTHONPATH=build/release/python:clients/python /usr/bin/python3 scripts/cascade_demo.py \
        --server 127.0.0.1:50051 --case cases/cascade_demo_2d.yaml --out out/cascade_demo_2d

Creates the simulation, starts it, raises the rainfall intensity when the simulated time passes
--raise-at (a live UpdateForcing while it runs), and saves PNG snapshots rendered on the server at
the start, at the change and at each cascade event (ponding, landslide onset, water impact, wave at
the far gauge, overtopping). It stops --after seconds of simulated time after the last of the
events the case names (or at the case's end time), then plots the probes (pore pressure, soil
speed and slide front, wave elevation) against time and writes summary.json: the events with their
times, the rainfall change and the run's particle-steps per second.
"""

import argparse
import json
import pathlib
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


def save_snapshots(sim, folder, label, log):
    for name, options in SNAPSHOTS.items():
        image = sim.snapshot(metadata=True, width=1280, height=560, **options)
        path = folder / f"{label}_{name}.png"
        path.write_bytes(image.png)
        log(f"  snapshot {path.name} at t = {image.time:.2f} s (step {image.step})")


def expected_events(case_text):
    """The event kinds the case's `events` block asks for: the run stops --after seconds after the
    last of them."""
    import yaml
    events = (yaml.safe_load(case_text) or {}).get("events") or {}
    return {kind for kind, value in events.items() if value}


def run(args):
    out = pathlib.Path(args.out)
    snapshots = out / "snapshots"
    snapshots.mkdir(parents=True, exist_ok=True)
    started_wall = time.monotonic()

    def log(message):
        print(f"[{time.monotonic() - started_wall:6.1f} s] {message}", flush=True)

    wanted = expected_events(pathlib.Path(args.case).read_text())
    with Client(args.server) as client:
        sim = client.create(args.case, overrides=args.set)
        info = sim.get()
        base_rain = info.forcing.rainfall.intensity
        log(f"created {sim.name}: {info.particle_count} particles, end time {info.end_time:g} s, "
            f"rainfall {base_rain:g} m/s")
        counts_start = phase_counts(sim)
        save_snapshots(sim, snapshots, "00_start", log)
        sim.start()

        change = None
        seen = []  # the cascade events so far, in order
        stop_at = info.end_time
        for update in sim.watch(interval=0.5, events=True):
            if isinstance(update, pb.Event):
                if update.kind not in CASCADE_EVENTS:
                    continue
                seen.append(update)
                log(f"event {update.kind} at t = {update.time:.2f} s: {update.message}")
                save_snapshots(sim, snapshots, f"{len(seen):02d}_{update.kind}", log)
                if wanted <= {e.kind for e in seen}:
                    stop_at = min(stop_at, update.time + args.after)
                continue
            status = update
            if change is None and status.time >= args.raise_at:
                change = sim.set_rainfall(base_rain * args.raise_factor)
                log(f"rainfall raised {base_rain:g} -> {base_rain * args.raise_factor:g} m/s, "
                    f"effective at step {change.effective_step} (t = {change.effective_time:.2f} s)")
                save_snapshots(sim, snapshots, "00_rain_raised", log)
            if status.time >= stop_at:
                sim.pause()
                log(f"stopping at t = {status.time:.2f} s")
                break
        final = sim.get()
        if final.state == State.FAILED:
            raise SystemExit(f"the simulation failed: {final.failure_reason}")
        save_snapshots(sim, snapshots, "99_end", log)
        counts_end = phase_counts(sim)
        names, times, _, values = sim.probes()
        events = [e for e in sim.events() if e.kind in CASCADE_EVENTS]
        sim.delete()

    wall = time.monotonic() - started_wall
    write_probes(out / "probes.csv", names, times, values)
    plot(out, names, times, values, events, change)
    summary = {
        "case": args.case,
        "simulated_time_s": final.status.time,
        "steps": final.status.step,
        "wall_seconds": wall,
        "particles": final.particle_count,
        # Each particle's mass is ρ_w0 dp^d, fixed: a phase's mass is its particle count.
        "phase_particles": {"start": counts_start, "end": counts_end},
        "particle_steps_per_second": final.particle_count * final.status.step / wall,
        "rainfall_change": None if change is None else {
            "from_m_per_s": base_rain, "to_m_per_s": base_rain * args.raise_factor,
            "time_s": change.effective_time, "step": change.effective_step},
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


def plot(out, names, times, values, events, change):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    def column(name):
        return values[:, names.index(name)]

    def mark(ax):
        if change is not None:
            ax.axvline(change.effective_time, color="k", linestyle="--", linewidth=0.8, label="rain raised")
        for e in events:
            ax.axvline(e.time, color="grey", linestyle=":", linewidth=0.8)
            ax.annotate(e.kind, (e.time, 1.0), xycoords=("data", "axes fraction"), rotation=90,
                        va="top", ha="right", fontsize=7, color="grey")

    figures = {
        "pore_pressure.png": ("pore pressure (kPa)", [n for n in names if n.startswith("pore_pressure")], 1e-3),
        "soil_speed.png": ("largest soil speed (m/s)", [n for n in names if n == "max_soil_speed"], 1.0),
        "wave_elevation.png": ("wave elevation above the still level (m)", [n for n in names if n.startswith("gauge")], 1.0),
    }
    for file, (label, columns, scale) in figures.items():
        fig, ax = plt.subplots(figsize=(8, 4))
        for name in columns:
            y = column(name)
            if file == "wave_elevation.png":
                y = y - y[0]
            ax.plot(times, y * scale, label=name)
        mark(ax)
        ax.set_xlabel("time (s)")
        ax.set_ylabel(label)
        ax.legend(loc="upper left", fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(out / file, dpi=120)
        plt.close(fig)


def print_summary(summary, out):
    print(f"\nCascade demo: {summary['simulated_time_s']:.1f} s simulated in {summary['wall_seconds']:.0f} s "
          f"of wall time ({summary['steps']} steps, {summary['particles']} particles, "
          f"{summary['particle_steps_per_second']:.3g} particle-steps/s)")
    lines = [(e["time_s"], f"{e['kind']}: {e['message']}") for e in summary["events"]]
    change = summary["rainfall_change"]
    if change:
        lines.append((change["time_s"], f"rainfall raised {change['from_m_per_s']:g} -> "
                                        f"{change['to_m_per_s']:g} m/s (step {change['step']})"))
    for t, line in sorted(lines):
        print(f"  t = {t:7.2f} s  {line}")
    counts = summary["phase_particles"]
    kept = "kept" if counts["start"] == counts["end"] else "NOT kept"
    print(f"  mass of each phase {kept}: water {counts['start']['water']} -> {counts['end']['water']}, "
          f"soil {counts['start']['soil']} -> {counts['end']['soil']} particles")
    print(f"Outputs in {out}/: snapshots/*.png, pore_pressure.png, soil_speed.png, wave_elevation.png, "
          f"probes.csv, summary.json")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--server", default="127.0.0.1:50051")
    parser.add_argument("--case", default="cases/cascade_demo_2d.yaml")
    parser.add_argument("--out", default="out/cascade_demo_2d")
    parser.add_argument("--set", action="append", default=[], help="a case override, as cascade run --set")
    parser.add_argument("--raise-at", type=float, default=5.0, help="simulated time (s) of the rainfall change")
    parser.add_argument("--raise-factor", type=float, default=2.0, help="the rainfall intensity's factor")
    parser.add_argument("--after", type=float, default=3.0,
                        help="simulated seconds to run on after the last event")
    run(parser.parse_args())


if __name__ == "__main__":
    main()
