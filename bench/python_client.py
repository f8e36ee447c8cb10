"""What the Python benchmarks of the server share: the build folder's generated stubs and
clients/python on sys.path, so that `import cascade_client` finds both."""

import contextlib
import pathlib
import subprocess
import sys
import tempfile
import threading


def use_client(build):
    """Puts <build>/python and clients/python first on sys.path; returns the build folder resolved."""
    build = pathlib.Path(build).resolve()
    sys.path[:0] = [str(build / "python"), str(pathlib.Path(__file__).resolve().parent.parent / "clients" / "python")]
    return build


def add_running_case_arguments(parser):
    """--build, --case (default the small rain column of the CLI tests) and --set, with an end time
    far beyond any measurement so that the simulation keeps stepping."""
    parser.add_argument("--build", default="build/release")
    parser.add_argument("--case", default="tests/cli/fixtures/rain_column.yaml")
    parser.add_argument("--set", action="append", default=["end_time=1e7"],
                        help="case overrides, as cascade run --set")


@contextlib.contextmanager
def server(build, threads):
    """A cascade-server of the build on a free loopback port with a scratch data folder; yields
    (its Popen, its address) and terminates it at the end. Its stderr is drained, so that it never
    blocks on it."""
    with tempfile.TemporaryDirectory() as data:
        process = subprocess.Popen([str(build / "bin" / "cascade-server"), "--listen", "127.0.0.1:0", "--data-dir", data,
                                    "--threads", str(threads)], stderr=subprocess.PIPE, text=True)
        address = process.stderr.readline().split("listening on ")[1].split(",")[0]
        threading.Thread(target=process.stderr.read, daemon=True).start()
        try:
            yield process, address
        finally:
            process.terminate()
            process.wait(timeout=60)
