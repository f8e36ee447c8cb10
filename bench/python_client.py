"""What the Python benchmarks of the server share: the build folder's generated stubs and
clients/python on sys.path, so that `import cascade_client` finds both."""

import pathlib
import sys


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
