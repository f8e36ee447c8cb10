"""cascade-server over TLS with a certificate generated at test time (openssl): TLS clients (the
CLI with --tls-ca, Python with root certificates) are served, plaintext ones fail; a non-loopback
listen address needs TLS and a token file, or --insecure, which warns."""

import subprocess
import unittest

import clitest


def make_certificates():
    """A self-signed CA and a server certificate for 127.0.0.1 and localhost that it signs, under
    the work dir: returns (ca.pem, server.pem, server.key)."""
    d = clitest.WORK_DIR / "certificates"
    d.mkdir(exist_ok=True)
    ec = ["-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes"]

    def openssl(*args):
        subprocess.run(["openssl", *map(str, args)], check=True, capture_output=True, timeout=30)

    openssl("req", "-x509", *ec, "-keyout", d / "ca.key", "-out", d / "ca.pem", "-days", "1",
            "-subj", "/CN=Cascade test CA", "-addext", "basicConstraints=critical,CA:TRUE",
            "-addext", "keyUsage=critical,keyCertSign,cRLSign")
    openssl("req", *ec, "-keyout", d / "server.key", "-out", d / "server.csr", "-subj", "/CN=localhost")
    (d / "server.ext").write_text("subjectAltName=IP:127.0.0.1,DNS:localhost\nextendedKeyUsage=serverAuth\n")
    openssl("x509", "-req", "-in", d / "server.csr", "-CA", d / "ca.pem", "-CAkey", d / "ca.key",
            "-CAcreateserial", "-days", "1", "-extfile", d / "server.ext", "-out", d / "server.pem")
    return d / "ca.pem", d / "server.pem", d / "server.key"


class Tls(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.ca, cert, key = make_certificates()
        cls.tls = ("--tls-cert", cert, "--tls-key", key, "--tokens", clitest.token_file())
        clitest.use_python_client()

    def test_tls_clients_are_served_and_plaintext_ones_fail(self):
        import grpc
        import cascade_client
        with clitest.Server("tls", *self.tls) as server:
            p = server.cli("create", clitest.fixture("rain_column"), "--id", "t", "--tls-ca", self.ca,
                           token=clitest.OPERATOR_TOKEN)
            self.assertEqual(p.returncode, 0, p.stderr)
            p = server.cli("step", "t", "2", "--tls-ca", self.ca, "--json", token=clitest.OPERATOR_TOKEN)
            self.assertEqual(p.returncode, 0, p.stderr)
            with cascade_client.Client(server.address, token=clitest.VIEWER_TOKEN,
                                       root_certificates=self.ca.read_bytes()) as client:
                self.assertEqual(client.simulation("t").get().status.step, 2)

            p = server.cli("get", "t", token=clitest.VIEWER_TOKEN)
            self.assertEqual(p.returncode, 1)
            self.assertIn("UNAVAILABLE", p.stderr)
            with cascade_client.Client(server.address, token=clitest.VIEWER_TOKEN) as plaintext:
                with self.assertRaises(grpc.RpcError) as raised:
                    plaintext.call("GetSimulation", cascade_client.pb.GetSimulationRequest(name="simulations/t"),
                                   timeout=10)
                self.assertEqual(raised.exception.code(), grpc.StatusCode.UNAVAILABLE)
            # A TLS client still gets the token check.
            p = server.cli("get", "t", "--tls-ca", self.ca)
            self.assertIn("UNAUTHENTICATED", p.stderr)

    def test_non_loopback_address_with_tls_and_tokens(self):
        with clitest.Server("tls_any", *self.tls, listen="0.0.0.0:0") as server:
            self.assertEqual(server.warnings, [])
            p = server.cli("list", "--tls-ca", self.ca, token=clitest.VIEWER_TOKEN)
            self.assertEqual(p.returncode, 0, p.stderr)


class ListenAddress(unittest.TestCase):
    def start(self, *args):
        return subprocess.run([str(clitest.CASCADE.parent / "cascade-server"), "--listen", "0.0.0.0:0", "--data-dir",
                               str(clitest.WORK_DIR / "open"), *map(str, args)], capture_output=True, text=True,
                              timeout=30)

    def test_non_loopback_without_tls_or_tokens_is_refused(self):
        for args in [(), ("--tokens", clitest.token_file()), ("--tls-cert", "server.pem", "--tls-key", "server.key")]:
            p = self.start(*args)
            self.assertEqual(p.returncode, 2, args)
            self.assertIn("not a loopback address: it needs --tls-cert, --tls-key and --tokens", p.stderr)

    def test_insecure_warns_and_serves_plaintext(self):
        with clitest.Server("insecure", "--insecure", listen="0.0.0.0:0") as server:
            self.assertEqual(len(server.warnings), 1)
            self.assertIn("WARNING: --insecure: 0.0.0.0:0 is reachable from other machines without TLS",
                          server.warnings[0])
            self.assertEqual(server.cli("list").returncode, 0)


if __name__ == "__main__":
    clitest.main()
