# SPDX-License-Identifier: MPL-2.0
"""Shared by the TCP link tests: rcxsim as the IR hub on a free loopback port, and a client that talks to it the way
NQC 4's TCP link (-Stcp) does (stdlib only).

NQC 4's link, as its sources show: a plain TCP stream, no framing; it does not expect the tower's echo (the link
counts as a USB tower), but ir-server echoes every client's bytes back to it, so the reply is found by searching
for the header 55 FF 00 followed by the complement of the command's opcode; pending input is drained before each
command; a command that gets no reply is sent again, identical, up to 4 times; an opcode equal to the previous
one is sent with bit 3 flipped. Every wait here is bounded, and rcxsim is stopped (by its own pid) however a test
ends.
"""
import os
import select
import socket
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
# The panel tests' helpers: messages, bounded waits, the simulator dying with the test.
sys.path.insert(0, os.path.join(HERE, "..", "panel"))
from panel_lib import NQC, RCXSIM, Sim, _die_with_parent, check, fail, wait_for  # noqa: E402,F401


def frame(payload):
    """The standard IR packet: 55 FF 00, each byte and its complement, the sum and its complement."""
    out = bytearray(b"\x55\xff\x00")
    for b in payload:
        out += bytes([b, b ^ 0xFF])
    s = sum(payload) & 0xFF
    return bytes(out + bytes([s, s ^ 0xFF]))


def find_packet(data, first):
    """The payload of the first well-formed packet in data whose first byte, ignoring bit 3, is `first`; or None."""
    i = data.find(b"\x55\xff\x00")
    while i >= 0:
        j = i + 3
        payload = bytearray()
        while j + 1 < len(data) and data[j] ^ data[j + 1] == 0xFF:
            payload.append(data[j])
            j += 2
        # The last pair is the checksum: try every length, shortest first.
        for n in range(1, len(payload)):
            if (payload[0] & 0xF7) == (first & 0xF7) and sum(payload[:n]) & 0xFF == payload[n]:
                return bytes(payload[:n])
        i = data.find(b"\x55\xff\x00", i + 1)
    return None


def compile_rcx(source, out):
    subprocess.run([NQC, "-TRCX2", "-O" + out, os.path.join(HERE, source)], check=True, timeout=60)
    return out


class Hub(Sim):
    """rcxsim --tcp 127.0.0.1:0 (a port the system picks) with the given options; the port is read from what it
    prints. Or, with tcp=("--tcp-join", ...), an rcxsim that joins a hub. Stopped as the panel tests' Sim."""

    def __init__(self, *args, tcp=("--tcp", "127.0.0.1:0")):
        self.work = tempfile.mkdtemp(prefix="net.", dir=os.environ.get("NET_TMP"))
        self.err_path = os.path.join(self.work, "sim.err")
        self.trace = os.path.join(self.work, "trace.jsonl")
        self.err = open(self.err_path, "w")
        self.proc = subprocess.Popen([RCXSIM] + list(tcp) + ["--trace", self.trace] + list(args),
                                     stdout=subprocess.DEVNULL, stderr=self.err, preexec_fn=_die_with_parent)
        self.port = wait_for("the hub's address", self._port) if tcp[0] == "--tcp" else None

    def _port(self):
        if self.proc.poll() is not None:
            fail("rcxsim exited early: " + open(self.err_path).read())
        for line in open(self.err_path):
            if line.startswith("rcxsim: IR hub at 127.0.0.1:"):
                return int(line.split(":")[2].split()[0])
        return None

    def messages(self):
        return open(self.err_path).read()

    def client(self):
        return Client(self.port)


class Client:
    """One TCP client of the hub, speaking as NQC 4's link does."""

    TRIES = 4
    TIMEOUT = 0.5

    def __init__(self, port):
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=5)
        self.sock.setblocking(False)
        self.heard = bytearray()    # everything this client has read
        self.last_op = None

    def close(self):
        self.sock.close()

    def read(self, seconds):
        """Reads for up to `seconds`; returns what came."""
        got = bytearray()
        end = time.monotonic() + seconds
        while True:
            left = end - time.monotonic()
            if left <= 0:
                break
            r, _, _ = select.select([self.sock], [], [], left)
            if not r:
                break
            try:
                data = self.sock.recv(4096)
            except (BlockingIOError, InterruptedError):
                continue
            if not data:
                raise ConnectionError("the hub closed the connection")
            got += data
        self.heard += got
        return bytes(got)

    def drain(self):
        self.read(0.01)

    def write(self, data):
        self.sock.setblocking(True)
        try:
            self.sock.sendall(data)
        finally:
            self.sock.setblocking(False)

    def command(self, payload, reply_len):
        """Sends a direct command and returns the reply's payload (reply opcode first), or None after 4 tries."""
        payload = bytearray(payload)
        if payload[0] == self.last_op:
            payload[0] ^= 0x08
        self.last_op = payload[0]
        packet = frame(payload)
        want = payload[0] ^ 0xFF
        for _ in range(self.TRIES):
            self.drain()
            self.write(packet)
            if reply_len == 0:
                return b""
            got = bytearray()
            end = time.monotonic() + self.TIMEOUT
            while time.monotonic() < end:
                got += self.read(min(0.05, max(0.0, end - time.monotonic())))
                reply = find_packet(bytes(got), want)
                if reply is not None and len(reply) == reply_len:
                    return reply
        return None

    def ping(self):
        r = self.command([0x10], 1)
        return r is not None and r[0] & 0xF7 == 0xE7

    def poll(self, source, index):
        r = self.command([0x12, source, index], 3)
        check(r is not None, "no reply to poll %d %d" % (source, index))
        v = r[1] | r[2] << 8
        return v - 65536 if v >= 32768 else v

    def download(self, rcx_path):
        """A program download as nqc -d sends it (host-tools.md §2): ping, stop, delete tasks and subs, each sub and
        task as a begin and blocks of at most 20 bytes numbered 1, 2, ... and 0 for the last, then the sound."""
        data = open(rcx_path, "rb").read()
        check(data[:4] == b"RCXI", "%s: not an nqc image" % rcx_path)
        nchunks = struct.unpack_from("<H", data, 6)[0]
        chunks, at = [], 12
        for _ in range(nchunks):
            kind, number, length = struct.unpack_from("<BBH", data, at)
            chunks.append((kind, number, data[at + 4:at + 4 + length]))
            at += 4 + ((length + 3) & ~3)
        check(self.ping(), "download: no reply to the ping")
        for op in (0x50, 0x40, 0x70):
            check(self.command([op], 1) is not None, "download: no reply to %02x" % op)
        for kind, number, code in sorted(chunks, key=lambda c: -c[0]):  # subs first
            begin = [0x35 if kind == 1 else 0x25, 0, number, 0, len(code) & 0xFF, len(code) >> 8]
            r = self.command(begin, 2)
            check(r is not None and r[1] == 0, "download: begin of %s %d: %r" % (kind, number, r))
            blocks = [code[i:i + 20] for i in range(0, len(code), 20)]
            for n, block in enumerate(blocks, 1):
                seq = 0 if n == len(blocks) else n
                r = self.command([0x45, seq & 0xFF, seq >> 8, len(block), 0] + list(block) + [sum(block) & 0xFF], 2)
                check(r is not None and r[1] == 0, "download: block %d of %s %d: %r" % (n, kind, number, r))
        check(self.command([0x51, 0x05], 1) is not None, "download: no reply to the sound")


class StandInHub:
    """ir_hub.py, the stand-in for brickEmu's ir-server (relay to all, echo to the sender, no pacing), on a free
    loopback port or the given one; stop() kills it (by its own pid), as ir-server ends when its last client
    leaves."""

    def __init__(self, port=0):
        self.proc = subprocess.Popen([sys.executable, os.path.join(HERE, "ir_hub.py"), str(port)],
                                     stdout=subprocess.PIPE, preexec_fn=_die_with_parent)
        line = self.proc.stdout.readline().decode()
        check(line.startswith("port "), "the stand-in hub did not start: %r" % line)
        self.port = int(line.split()[1])

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        self.proc.stdout.close()

    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        self.stop()


class PtyTower:
    """A serial tower that is a client of a TCP hub: a pseudo-terminal at `path` for Debian's nqc 3.1 (which has
    no TCP link), whose bytes a thread copies to the hub and the hub's (its echo included, as a serial tower hears
    itself) back, as they come."""

    def __init__(self, port, path):
        import pty
        import threading
        import tty
        self.master, self.slave = pty.openpty()
        tty.setraw(self.slave)
        self.path = path
        os.symlink(os.ttyname(self.slave), path)
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=5)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.stopping = False
        self.sent = bytearray()     # everything the host tool wrote
        self.thread = threading.Thread(target=self._copy, daemon=True)
        self.thread.start()

    def _copy(self):
        while not self.stopping:
            r, _, _ = select.select([self.master, self.sock], [], [], 0.1)
            try:
                if self.master in r:
                    data = os.read(self.master, 4096)
                    self.sent += data
                    self.sock.sendall(data)
                if self.sock in r:
                    data = self.sock.recv(4096)
                    if not data:
                        return
                    os.write(self.master, data)
            except OSError:
                return

    def resent(self):
        """How many packets the host tool sent again right after sending them (a retry: nqc flips bit 3 of an
        opcode equal to the previous one, so only a retry repeats a packet)."""
        starts = [i for i in range(len(self.sent)) if self.sent[i:i + 3] == b"\x55\xff\x00"]
        packets = [bytes(self.sent[a:b]) for a, b in zip(starts, starts[1:] + [len(self.sent)])]
        return sum(1 for a, b in zip(packets, packets[1:]) if a == b)

    def close(self):
        self.stopping = True
        self.thread.join(timeout=2)
        self.sock.close()
        os.unlink(self.path)
        os.close(self.master)
        os.close(self.slave)

    def __enter__(self):
        return self

    def __exit__(self, kind, value, tb):
        self.close()
