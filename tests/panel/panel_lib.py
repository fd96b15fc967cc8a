# SPDX-License-Identifier: MPL-2.0
"""Shared by the panel tests: rcxsim with --panel on a free loopback port, and small HTTP helpers (stdlib only).

Every wait is bounded, and the simulator is stopped (by its own pid) however a test ends.
"""
import ctypes
import http.client
import json
import shutil
import signal
import os
import subprocess
import sys
import tempfile
import time

RCXSIM = os.environ["RCXSIM"]
NQC = os.environ.get("NQC", "nqc")
HERE = os.path.dirname(os.path.abspath(__file__))


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)


def _die_with_parent():
    """In the child: should the test itself be killed (CTest's timeout), the simulator goes too."""
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def wait_for(what, probe, seconds=10.0, every=0.05):
    """Calls probe() until it returns something true; fails after `seconds`."""
    end = time.monotonic() + seconds
    last = None
    while time.monotonic() < end:
        last = probe()
        if last:
            return last
        time.sleep(every)
    fail("timed out waiting for %s (last: %r)" % (what, last))


class Sim:
    """rcxsim --panel 0 (any free port) with the given options; the port is read from what it prints."""

    def __init__(self, *args):
        self.work = tempfile.mkdtemp(prefix="panel.", dir=os.environ.get("PANEL_TMP"))
        self.err_path = os.path.join(self.work, "sim.err")
        self.trace = os.path.join(self.work, "trace.jsonl")
        self.err = open(self.err_path, "w")
        self.proc = subprocess.Popen([RCXSIM, "--panel", "0", "--trace", self.trace] + list(args),
                                     stdout=subprocess.DEVNULL, stderr=self.err, preexec_fn=_die_with_parent)
        self.port = wait_for("the panel's address", self._port)
        self.host = "127.0.0.1"

    def _port(self):
        if self.proc.poll() is not None:
            fail("rcxsim exited early: " + open(self.err_path).read())
        for line in open(self.err_path):
            if "panel at http://127.0.0.1:" in line:
                return int(line.rsplit(":", 1)[1].strip().rstrip("/"))
        return None

    def path(self, name):
        return os.path.join(self.work, name)

    def alive(self):
        return self.proc.poll() is None

    def request(self, method, url, body=None, headers=None, timeout=10):
        c = http.client.HTTPConnection(self.host, self.port, timeout=timeout)
        try:
            c.request(method, url, body=body, headers=headers or {})
            r = c.getresponse()
            return r.status, r.read().decode("utf-8", "replace"), dict(r.getheaders())
        finally:
            c.close()

    def state(self):
        status, body, headers = self.request("GET", "/state")
        check(status == 200, "GET /state: %d %s" % (status, body))
        check(headers.get("Content-Type") == "application/json", "GET /state: content type")
        return json.loads(body)

    def post(self, url, expect=204):
        status, body, _ = self.request("POST", url)
        check(status == expect, "POST %s: got %d %r, expected %d" % (url, status, body, expect))
        return body

    def stop(self):
        """SIGTERM, as Ctrl-C would; returns how many seconds rcxsim took to end."""
        start = time.monotonic()
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
                fail("rcxsim did not stop on SIGTERM within 10 s")
        self.err.close()
        return time.monotonic() - start

    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if not self.err.closed:
            self.err.close()
        if kind is not None:
            sys.stderr.write("--- rcxsim's messages:\n" + open(self.err_path).read())
        shutil.rmtree(self.work, ignore_errors=True)


def nqc_compile(source, out):
    subprocess.run([NQC, "-TRCX2", "-O" + out, os.path.join(HERE, source)], check=True, timeout=60)
    return out
