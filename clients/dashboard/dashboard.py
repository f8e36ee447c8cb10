"""The Cascade dashboard: a thin web client of cascade-server's gRPC API (docs/dashboard.md).

    PYTHONPATH=build/release/python:clients/python /usr/bin/python3 clients/dashboard/dashboard.py \
        --server 127.0.0.1:50051 [--tls-ca CA.pem] [--token-file F] [--listen 127.0.0.1:8080]

or `bash scripts/dashboard.sh [options]`, which sets PYTHONPATH. Then open http://127.0.0.1:8080/
and enter a token of the server's token file (none when the server has no token file).

Python's standard library serves the page (http.server, one thread per request) and JSON; the
gRPC client is clients/python/cascade_client. One thread polls the server for every browser
(hub.py), one stream per watched view brings the frames (frames.py), and each user's actions go
to the server with that user's token (actions.py). Chart.js comes from Debian's libjs-chart.js;
nothing is fetched from the network at run time.
"""

import argparse
import ipaddress
import json
import os
import pathlib
import ssl
import sys
import urllib.parse
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))  # cascade_client, beside this folder in the repository

from cascade_client import Client  # noqa: E402
from actions import Access, Refused, act  # noqa: E402
from frames import Frames  # noqa: E402
from hub import Hub  # noqa: E402

CHART_JS = "/usr/share/javascript/chart.js/chart.min.js"  # Debian's libjs-chart.js (3.9)
LONG_POLL_SECONDS = 10.0
STATIC = {"/": ("index.html", "text/html; charset=utf-8"),
          "/dashboard.js": ("dashboard.js", "text/javascript; charset=utf-8"),
          "/dashboard.css": ("dashboard.css", "text/css; charset=utf-8")}
# Reconnect within about 2 s of a restarted server (gRPC's default backoff grows to 2 minutes).
CHANNEL_OPTIONS = (("grpc.initial_reconnect_backoff_ms", 250), ("grpc.min_reconnect_backoff_ms", 250),
                   ("grpc.max_reconnect_backoff_ms", 2000))


class Handler(BaseHTTPRequestHandler):
    server_version = "cascade-dashboard"
    protocol_version = "HTTP/1.1"  # keep-alive: the page's polls reuse one connection

    def log_message(self, format, *args):  # quiet: one line per poll would drown the log
        pass

    @property
    def app(self):
        return self.server.app

    def token(self):
        header = self.headers.get("Authorization", "")
        return header[len("Bearer "):].strip() if header.startswith("Bearer ") else ""

    def reply(self, status, body, content_type="application/json"):
        data = body if isinstance(body, bytes) else json.dumps(body).encode()
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(data)

    def refuse(self, refused):
        self.reply(refused.status, {"error": refused.message, "code": refused.code})

    def do_GET(self):
        url = urllib.parse.urlsplit(self.path)
        query = {k: v[-1] for k, v in urllib.parse.parse_qs(url.query).items()}
        try:
            if url.path in STATIC:
                file, kind = STATIC[url.path]
                return self.reply(200, (HERE / "static" / file).read_bytes(), kind)
            if url.path == "/favicon.ico":
                return self.reply(204, b"", "image/x-icon")
            if url.path == "/chart.js":
                return self.reply(200, self.app.chart_js, "text/javascript; charset=utf-8")
            if url.path == "/api/whoami":
                return self.reply(200, {"role": self.app.access.role(self.token())})
            if url.path == "/api/updates":
                return self.updates(query)
            if url.path == "/api/frame":
                return self.frame(query)
            self.reply(404, {"error": f"path: no {url.path} here", "code": "NOT_FOUND"})
        except Refused as refused:
            self.refuse(refused)

    def do_POST(self):
        try:
            if self.path != "/api/action":
                raise Refused(404, "NOT_FOUND", f"path: no {self.path} here")
            length = int(self.headers.get("Content-Length", 0))
            if length > 10_000:
                raise Refused(413, "INVALID_ARGUMENT", "body: over 10,000 bytes")
            try:
                body = json.loads(self.rfile.read(length) or b"{}")
            except ValueError as e:
                raise Refused(400, "INVALID_ARGUMENT", f"body: not JSON ({e})")
            if not isinstance(body, dict):
                raise Refused(400, "INVALID_ARGUMENT", "body: expected a JSON object")
            self.reply(200, {"result": act(self.app.client, self.token(), body)})
        except Refused as refused:
            self.refuse(refused)

    def updates(self, query):
        """The long poll: waits until the hub holds something newer than `version` (at most
        LONG_POLL_SECONDS), then answers with everything the page shows."""
        role = self.app.access.role(self.token())
        selected = query.get("selected") or None
        view = (selected, query.get("field", "phase"), query.get("camera", "side")) if selected else None
        if view and self.app.hub.state_of(selected) is None:
            view = None  # gone (deleted, or a server restarted without it): the page selects another
        if view:
            self.app.frames.want(*view)
        try:
            version = int(query.get("version", -1))
        except ValueError:
            raise Refused(400, "INVALID_ARGUMENT", f"version: expected an integer, got {query['version']!r}")
        self.app.hub.wait(version, LONG_POLL_SECONDS)
        body = self.app.hub.snapshot(selected)
        body["role"] = role
        body["frame"] = self.app.frames.want(*view).describe() if view and self.app.hub.state_of(selected) else None
        self.reply(200, body)

    def frame(self, query):
        self.app.access.role(self.token())
        if "sim" not in query:
            raise Refused(400, "INVALID_ARGUMENT", "sim: missing")
        feed = self.app.frames.want(query["sim"], query.get("field", "phase"), query.get("camera", "side"))
        png = feed.png
        if png is None:
            raise Refused(404, "NOT_FOUND", feed.error or "frame: none yet")
        self.reply(200, png, "image/png")


class App:
    def __init__(self, args):
        root = pathlib.Path(args.tls_ca).read_bytes() if args.tls_ca else None
        token = pathlib.Path(args.token_file).read_text().strip() if args.token_file else os.environ.get(
            "CASCADE_TOKEN")
        # The hub's reads use the dashboard's own token (a viewer's is enough); a user's actions
        # use the user's (actions.py).
        self.client = Client(args.server, token=token, root_certificates=root, options=CHANNEL_OPTIONS)
        self.hub = Hub(self.client)
        self.frames = Frames(self.hub)
        self.access = Access(self.client)
        self.chart_js = pathlib.Path(args.chart_js).read_bytes()


def loopback(host):
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return host == "localhost"


def main():
    parser = argparse.ArgumentParser(description="The Cascade dashboard (docs/dashboard.md).")
    parser.add_argument("--server", default="127.0.0.1:50051", help="cascade-server's address")
    parser.add_argument("--tls-ca", help="PEM of the CA that signed the server's certificate")
    parser.add_argument("--token-file", help="a file holding the dashboard's own token for its reads "
                        "(a viewer's is enough; default $CASCADE_TOKEN; none for a server without tokens)")
    parser.add_argument("--listen", default="127.0.0.1:8080", help="HOST:PORT of the page (port 0: a free one)")
    parser.add_argument("--tls-cert", help="PEM certificate chain: serve the page over HTTPS")
    parser.add_argument("--tls-key", help="its PEM key")
    parser.add_argument("--insecure", action="store_true",
                        help="allow plain HTTP on a non-loopback address (tokens then cross the network in clear)")
    parser.add_argument("--chart-js", default=CHART_JS, help="Chart.js 3 (UMD build) to serve")
    args = parser.parse_args()

    host, _, port = args.listen.rpartition(":")
    if not host or not port.isdigit():
        parser.error(f"--listen: expected HOST:PORT, got {args.listen!r}")
    if bool(args.tls_cert) != bool(args.tls_key):
        parser.error("--tls-cert and --tls-key go together")
    if not loopback(host) and not args.tls_cert and not args.insecure:
        parser.error(f"--listen {args.listen}: a non-loopback address needs --tls-cert and --tls-key "
                     "(the page carries tokens), or --insecure")
    if not pathlib.Path(args.chart_js).is_file():
        parser.error(f"--chart-js: no {args.chart_js} (install Debian's libjs-chart.js)")

    app = App(args)
    httpd = ThreadingHTTPServer((host, int(port)), Handler)
    httpd.daemon_threads = True
    httpd.app = app
    scheme = "http"
    if args.tls_cert:
        context = ssl.SSLContext(ssl.PROTOCOL_TLS_SERVER)
        context.load_cert_chain(args.tls_cert, args.tls_key)
        httpd.socket = context.wrap_socket(httpd.socket, server_side=True)
        scheme = "https"
    app.hub.start()
    # The line tests and scripts read to find the port (as cascade-server's).
    print(f"cascade-dashboard: serving {scheme}://{host}:{httpd.server_address[1]}/ for {args.server}",
          file=sys.stderr, flush=True)
    try:
        httpd.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
