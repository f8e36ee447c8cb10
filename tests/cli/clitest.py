"""Shared helpers for the process-level tests of the `cascade` executable (tests/cli/test_*.py).

tests/CMakeLists.txt runs each test_*.py as
    /usr/bin/python3 tests/cli/test_NAME.py --cascade PATH --source-dir REPO --work-dir DIR
and the scripts are unittest programs. Run one by hand the same way, e.g.
    /usr/bin/python3 tests/cli/test_lifecycle.py --cascade build/release/bin/cascade \
        --source-dir . --work-dir /tmp/cli_lifecycle
"""

import argparse
import os
import pathlib
import shutil
import subprocess
import sys
import unittest

CASCADE = None     # pathlib.Path of the executable
SOURCE_DIR = None  # the repository root
WORK_DIR = None    # a scratch folder of this test script, emptied at the start


def main():
    global CASCADE, SOURCE_DIR, WORK_DIR
    parser = argparse.ArgumentParser()
    parser.add_argument("--cascade", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    args, rest = parser.parse_known_args()
    CASCADE = pathlib.Path(args.cascade).resolve()
    SOURCE_DIR = pathlib.Path(args.source_dir).resolve()
    WORK_DIR = pathlib.Path(args.work_dir).resolve()
    if not CASCADE.is_file():
        sys.exit(f"no cascade executable at {CASCADE}")
    if WORK_DIR.exists():
        shutil.rmtree(WORK_DIR)
    WORK_DIR.mkdir(parents=True)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)


def case(name):
    """A case file of the repository: case("hydrostatic_tank_2d") → cases/hydrostatic_tank_2d.yaml."""
    return SOURCE_DIR / "cases" / f"{name}.yaml"


def run(*args, timeout=60):
    """Runs `cascade ARGS...` to the end; returns the CompletedProcess (text stdout and stderr)."""
    return subprocess.run([str(CASCADE), *map(str, args)], capture_output=True, text=True, timeout=timeout,
                          cwd=WORK_DIR)


def mpirun_launch(processes):
    """The command line that starts a program as PROCESSES processes under mpirun (issue 17), more
    processes than cores with --oversubscribe, and its environment."""
    launcher = shutil.which("mpirun")
    if launcher is None:
        raise AssertionError("mpirun is missing: install openmpi-bin (scripts/install-deps.sh)")
    # Copies between processes through Open MPI's buffers, not the kernel's cross-memory attach,
    # which containers may forbid (tests/CMakeLists.txt).
    env = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
    return [launcher, "--oversubscribe", "--allow-run-as-root", "-np", str(processes)], env


def mpirun(processes, *args, timeout=300):
    """`mpirun -np PROCESSES cascade ARGS`."""
    launch, env = mpirun_launch(processes)
    return subprocess.run([*launch, str(CASCADE), *map(str, args)], capture_output=True, text=True, timeout=timeout,
                          cwd=WORK_DIR, env=env)


def out_dir(name):
    """A fresh, not yet existing output folder under the work dir."""
    d = WORK_DIR / name
    if d.exists():
        shutil.rmtree(d)
    return d


def read_probes(path):
    """probes.csv → (header list, rows as lists of floats)."""
    lines = pathlib.Path(path).read_text().splitlines()
    header = lines[0].split(",")
    rows = [[float(v) for v in line.split(",")] for line in lines[1:] if line]
    return header, rows


def import_h5py():
    try:
        import h5py  # noqa: F401  (Debian's python3-h5py, with /usr/bin/python3)
        return h5py
    except ImportError:
        raise AssertionError(f"h5py is missing from {sys.executable}: install python3-h5py (Debian)")


def record_validation(test, case, reference, metric, measured, reference_value, tolerance=0.0, relative=False,
                      bound="within", tolerance_source=""):
    """States a validation figure for docs/validation.md (the Python twin of
    tests/validation/validation_table.h: one JSON line in <build>/validation/cli.SCRIPT.Class.method.jsonl,
    rendered by scripts/render_validation.py) and returns whether it holds; the caller asserts it.
    bound: "within" (|measured - reference| <= tolerance, a fraction of |reference| when relative),
    "at_most" or "at_least" (one-sided limits)."""
    import datetime
    import json
    import math
    if bound == "at_most":
        passed = measured <= reference_value
    elif bound == "at_least":
        passed = measured >= reference_value
    else:
        allowed = tolerance * abs(reference_value) if relative else tolerance
        passed = abs(measured - reference_value) <= allowed
    passed = bool(passed and math.isfinite(measured))
    name = "cli." + pathlib.Path(sys.argv[0]).stem.removeprefix("test_") + "." + ".".join(test.id().split(".")[-2:])
    figure = {"test": name, "case": case, "reference": reference, "metric": metric,
              "measured": measured if math.isfinite(measured) else None, "reference_value": reference_value,
              "tolerance": tolerance, "relative": relative, "bound": bound, "tolerance_source": tolerance_source,
              "pass": passed, "known_failure": name.endswith("KnownFailure"),
              "measured_at": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")}
    folder = CASCADE.parent.parent / "validation"
    folder.mkdir(exist_ok=True)
    path = folder / f"{name}.jsonl"
    mode = "a" if name in _recorded_tests else "w"  # a test's figures of an earlier run are replaced
    _recorded_tests.add(name)
    with open(path, mode, encoding="utf-8") as f:
        f.write(json.dumps(figure, ensure_ascii=False) + "\n")
    print(f"validation: {case}: {metric} = {measured} against {reference_value} ({reference})")
    return passed


_recorded_tests = set()


def fixture(name):
    """A test case file: fixture("rain_column") → tests/cli/fixtures/rain_column.yaml."""
    return SOURCE_DIR / "tests" / "cli" / "fixtures" / f"{name}.yaml"


def use_python_client():
    """Makes the Python client (clients/python) and its generated stubs (<build>/python) importable."""
    for path in (CASCADE.parent.parent / "python", SOURCE_DIR / "clients" / "python"):
        if str(path) not in sys.path:
            sys.path.insert(0, str(path))


OPERATOR_TOKEN, VIEWER_TOKEN = "operator-token-0123456789", "viewer-token-0123456789"


def token_file():
    """A cascade-server --tokens file under the work dir: alice the operator, bob the viewer."""
    path = WORK_DIR / "tokens.txt"
    path.write_text(f"# name role token\nalice operator {OPERATOR_TOKEN}\nbob viewer {VIEWER_TOKEN}\n")
    return path


class Server:
    """A cascade-server process on a free port (`with Server(...) as server:`); leaving the block
    sends SIGTERM and checks that it exits 0. `server.address` is 127.0.0.1:PORT (also when it
    listens on another host, e.g. `listen="0.0.0.0:0"`). `env`: variables added to the server's
    environment. `server.warnings`: the lines it printed before the one that says where it listens."""

    def __init__(self, name, *args, env=None, listen="127.0.0.1:0", processes=None):
        self.env = {**os.environ, **(env or {})}
        self.processes = processes
        self.data_dir = WORK_DIR / name
        self.args = [str(CASCADE.parent / "cascade-server"), "--listen", listen, "--data-dir",
                     str(self.data_dir), "--threads", "1", *map(str, args)]
        if processes:  # split over processes (issue 17)
            launch, launch_env = mpirun_launch(processes)
            self.args = [*launch, *self.args]
            self.env = {**launch_env, **(env or {})}
        self.process = None
        self.address = None

    def __enter__(self):
        self.process = subprocess.Popen(self.args, stderr=subprocess.PIPE, text=True, env=self.env)
        self.warnings = []
        self.notes = []  # what else it printed before that line (a split server says so)
        line = self.process.stderr.readline()
        while line and "listening on " not in line:
            (self.warnings if "WARNING" in line else self.notes).append(line)
            line = self.process.stderr.readline()
        if "listening on " not in line:
            self.process.kill()
            raise AssertionError(f"cascade-server did not start: {line}{self.process.stderr.read()}")
        port = line.split("listening on ")[1].split(",")[0].rsplit(":", 1)[1]
        self.address = f"127.0.0.1:{port}"
        return self

    def stop(self):
        """SIGTERM; returns (exit code, the rest of stderr)."""
        self.process.terminate()
        rest = self.process.communicate(timeout=30)[1]
        return self.process.returncode, rest

    def stopped_cleanly(self, code, rest):
        """Whether the server ended as SIGTERM should end it. Open MPI's mpirun exits 1 after it has
        passed a SIGTERM on, even when every process exits 0: under mpirun, process 0's last line."""
        return "cascade-server: stopped" in rest if self.processes else code == 0

    def __exit__(self, *exc):
        if self.process.poll() is None:
            code, rest = self.stop()
            if exc[0] is None and not self.stopped_cleanly(code, rest):
                raise AssertionError(f"cascade-server exited {code}: {rest}")

    def cli(self, *args, token=None):
        """`cascade SUBCOMMAND ... --server ADDRESS` (the subcommand first)."""
        extra = ["--token", token] if token else []
        return run(*args, "--server", self.address, *extra)


def query_frame(server, name, out_name, fields):
    """`cascade query NAME FIELDS --out WORK_DIR/OUT_NAME.h5` on `server`: (every dataset of the
    frame by name, as numpy arrays; the frame's step)."""
    h5py = import_h5py()
    out = WORK_DIR / f"{out_name}.h5"
    p = server.cli("query", name, *fields, "--out", out)
    assert p.returncode == 0, p.stderr
    with h5py.File(out) as f:
        frame = f["frames"]["000000"]
        return {k: frame[k][()] for k in frame.keys()}, int(frame.attrs["step"])


def png_pixels(data):
    """An 8-bit RGB PNG (as render/png_encoder.cpp writes it) → (width, height, rows of bytes)."""
    import struct
    import zlib
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 2), "not 8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, previous = zlib.decompress(idat), 3 * width, [], bytearray(3 * width)
    for y in range(height):
        line = raw[y * (stride + 1):(y + 1) * (stride + 1)]
        kind, row = line[0], bytearray(line[1:])
        for x in range(stride):
            a = row[x - 3] if x >= 3 else 0
            b, c = previous[x], previous[x - 3] if x >= 3 else 0
            if kind == 1:
                row[x] = (row[x] + a) & 255
            elif kind == 2:
                row[x] = (row[x] + b) & 255
            elif kind == 3:
                row[x] = (row[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[x] = (row[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(row))
        previous = row
    return width, height, rows
