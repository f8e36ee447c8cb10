#!/usr/bin/env python3
"""Renders docs/validation.md from the figures the validation tests wrote.

Each validation test records its figures through tests/validation/validation_table.h (C++) or
tests/cli/clitest.py's record_validation (Python) as JSON lines in BUILD/validation/<test>.jsonl:
what was measured, against which reference, the tolerance and where it comes from, pass or fail.
scripts/test.sh runs this script after CTest, so the table is the one the last run measured; a
test that did not run keeps the row of its last run, with that run's date.

usage: render_validation.py [--figures build/release/validation] [--output docs/validation.md]
"""

import argparse
import json
import pathlib
import sys

HEADER = """# Validation

Every figure below was measured and asserted by a test of the suite; the tests write them and
`scripts/render_validation.py` renders this page (`bash scripts/test.sh` does both; the known
failures run with `ctest --test-dir build/release -R KnownFailure`, then
`/usr/bin/python3 scripts/render_validation.py`). Documentation that quotes a validation figure
quotes it from here. Do not edit by hand.

Result: **pass**, **FAIL** (the test fails: a defect), or **known failure** (a claim the model does
not meet yet, in a test named `...KnownFailure` that `scripts/test.sh` leaves out; README,
"Known failures", says why). A known-failure test may hold passing figures beside the failing one.
Tolerance: ± a fraction of the reference (%) or ± an absolute amount in the metric's unit; ≤ and ≥
are one-sided limits.

"""


def number(v):
    if v is None:
        return "—"
    if v == 0:
        return "0"
    a = abs(v)
    if 1e-3 <= a < 1e5:
        text = f"{v:.4g}"
    else:
        text = f"{v:.3e}"
    return text


def reference_cell(f):
    if f["bound"] == "at_most":
        return "≤ " + number(f["reference_value"])
    if f["bound"] == "at_least":
        return "≥ " + number(f["reference_value"])
    return number(f["reference_value"])


def tolerance_cell(f):
    if f["bound"] != "within":
        return "limit"
    if f["relative"]:
        return f"±{100 * f['tolerance']:.3g}%"
    return "±" + number(f["tolerance"])


def deviation_cell(f):
    m, r = f["measured"], f["reference_value"]
    if f["bound"] != "within" or m is None or r is None or r == 0:
        return ""
    return f" ({100 * (m - r) / abs(r):+.1f}%)"


def result_cell(f):
    if f["known_failure"]:
        return "known failure" if not f["pass"] else "pass (in a known-failure test)"
    return "pass" if f["pass"] else "**FAIL**"


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = pathlib.Path(__file__).resolve().parent.parent
    parser.add_argument("--figures", default=root / "build" / "release" / "validation", type=pathlib.Path)
    parser.add_argument("--output", default=root / "docs" / "validation.md", type=pathlib.Path)
    args = parser.parse_args()

    figures = []
    for path in sorted(args.figures.glob("*.jsonl")):
        for number_of_line, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if not line.strip():
                continue
            try:
                figures.append(json.loads(line))
            except json.JSONDecodeError as e:
                sys.exit(f"render_validation: {path}:{number_of_line}: {e}")
    if not figures:
        sys.exit(f"render_validation: no figures in {args.figures} (run the validation tests first)")

    cases = {}
    for f in figures:
        cases.setdefault(f["case"], []).append(f)

    counts = {"pass": 0, "fail": 0, "known": 0}
    for f in figures:
        if f["known_failure"] and not f["pass"]:
            counts["known"] += 1
        elif f["pass"]:
            counts["pass"] += 1
        else:
            counts["fail"] += 1
    dates = sorted(f["measured_at"] for f in figures)

    out = [HEADER]
    out.append(f"{len(figures)} figures from {len({f['test'] for f in figures})} tests, measured "
               f"{dates[0][:10]} to {dates[-1][:10]}: {counts['pass']} pass, {counts['fail']} fail, "
               f"{counts['known']} known failure{'' if counts['known'] == 1 else 's'}.\n")
    for case in sorted(cases):
        rows = cases[case]
        out.append(f"\n## {case}\n")
        out.append("| metric | reference | reference value | tolerance | tolerance from | measured | result | test |")
        out.append("|---|---|---|---|---|---|---|---|")
        for f in rows:
            out.append("| " + " | ".join(cell(c) for c in [
                f["metric"], f["reference"], reference_cell(f), tolerance_cell(f), f["tolerance_source"],
                number(f["measured"]) + deviation_cell(f), result_cell(f),
                f"`{f['test']}` ({f['measured_at'][:10]})"]) + " |")
    args.output.write_text("\n".join(out) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
