#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""Issue 23 item 1: a virtual brick that joins brickEmu's own IR hub, driven as NQC 4 drives a brick over TCP.

    BRICKEMU_DIR=/path/to/brickemu python3 tools/emu/irserver_probe.py [--rcxsim build/host/rcxsim]
        [--firmware build/h8300/drivers/openrcx.srec] [--skip-firmware]

Starts brickEmu's `ir-server` on a free loopback port (BRICKEMU_IR_PORT, mend 4 of emulator.md; with
BRICKEMU_IR_FOREGROUND=1 it stays in the foreground and is stopped by its pid, else it ends when its last client
leaves), then `rcxsim --rom --tcp-join 127.0.0.1:PORT`: a brick with only the ROM. The client is the project's
stand-in for NQC 4's TCP link (tests/net/net_lib.py: no tower echo expected, the reply searched after the hub's echo,
4 tries, 0.5 s per reply). It downloads the firmware as `nqc -firmware` does (10, 15, 65, 75, 45 blocks of 200
bytes, A5, 15), waiting for each reply until nothing has come for 0.5 s (0.3 s after a block, NQC's wait); then, on
a brick with its firmware, a program as `nqc -d` does (net_lib's own download), starts it and polls its result.
--hub rcxsim runs the same against `rcxsim --tcp` instead, for comparison. Each step prints PASS/FAIL, its time
and how many packets it took (a step that needed retries took more packets than commands).
"""
import argparse
import os
import socket
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
NET_TESTS = os.path.join(REPO, "tests", "net")
VERSION_REPLY = bytes.fromhex("0003000100030208")
KEY = [0x01, 0x03, 0x05, 0x07, 0x0B]
UNLOCK = [0xA5, 0x4C, 0x45, 0x47, 0x4F, 0xAE]     # "LEGO" and AE: start the firmware
BLOCK = 200
BLOCK_WAIT = 0.3                                  # NQC waits this long after a download block


def srec_image(path):
    """(entry, bytes from the lowest address) of an S-record file."""
    mem, entry = {}, 0x8000
    for line in open(path):
        line = line.strip()
        if len(line) < 4 or line[0] != "S" or line[1] not in "123789":
            continue
        raw = bytes.fromhex(line[2:])
        alen = {"1": 2, "2": 3, "3": 4, "7": 4, "8": 3, "9": 2}[line[1]]
        addr = int.from_bytes(raw[1:1 + alen], "big")
        if line[1] in "789":
            entry = addr
        else:
            for i, b in enumerate(raw[1 + alen:-1]):
                mem[addr + i] = b
    lo, hi = min(mem), max(mem)
    return entry, bytes(mem.get(a, 0) for a in range(lo, hi + 1))


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class Step:
    def __init__(self):
        self.ok = True

    def report(self, name, ok, t0, sent, detail=""):
        packets, commands = sent
        self.ok &= bool(ok)
        print("%-4s  %-44s %6.2f s  %3d packets for %3d commands%s" % (
            "PASS" if ok else "FAIL", name, time.time() - t0, packets, commands, ("  " + detail) if detail else ""),
            flush=True)


def command_idle(net_lib, client, payload, reply_len, idle):
    """A direct command as net_lib's Client sends it (bit 3 toggled on a repeated opcode, pending input drained, the
    same bytes up to 4 times), but a try ends only when nothing has come for `idle` seconds: NQC 4.1 flashes a brick
    through rcxsim --tcp, whose echo comes at air speed, and fails through ir-server, whose echo comes at once
    (issue 23), so its wait for a download block's reply runs from the last byte heard, not from the send."""
    payload = bytearray(payload)
    if payload[0] == client.last_op:
        payload[0] ^= 0x08
    client.last_op = payload[0]
    packet, want = net_lib.frame(payload), payload[0] ^ 0xFF
    for _ in range(client.TRIES):
        client.drain()
        client.write(packet)
        got, last = bytearray(), time.monotonic()
        while time.monotonic() - last < idle:
            chunk = client.read(0.02)
            if chunk:
                got += chunk
                last = time.monotonic()
                reply = net_lib.find_packet(bytes(got), want)
                if reply is not None and len(reply) == reply_len:
                    return reply
    return None


def stop_proc(proc, name):
    """Stops one of our processes by its own pid and prints what it said on its standard error."""
    proc.terminate()
    try:
        err = proc.communicate(timeout=5)[1].decode(errors="replace").strip()
    except subprocess.TimeoutExpired:
        proc.kill()
        err = ""
    if err:
        print("      %s said: %s" % (name, err.replace("\n", " | ")), flush=True)


class Room:
    """A hub on a free loopback port, a brick in it (rcxsim, --rom or with its firmware) and our client.

    hub "ir-server": brickEmu's ir-server and `rcxsim --tcp-join`; hub "rcxsim": `rcxsim --tcp` itself, for comparison.
    """

    def __init__(self, args, net_lib, rom):
        self.procs = []
        self.client = None
        self.sent = [0, 0]                          # packets written, commands given (retries: more packets)
        port = free_port()
        if args.hub == "ir-server":
            env = dict(os.environ, BRICKEMU_IR_PORT=str(port), BRICKEMU_IR_FOREGROUND="1")
            self._start("ir-server", [args.irserver], env, cwd=os.path.dirname(args.irserver))
        else:
            self._start("rcxsim", [args.rcxsim] + (["--rom"] if rom else []) + ["--tcp", "127.0.0.1:%d" % port])
        # The client connects first and stays: ir-server ends when its last client leaves.
        end = time.time() + 5
        while self.client is None:
            try:
                self.client = net_lib.Client(port)
            except OSError:
                if time.time() > end:
                    raise SystemExit("the hub did not listen on port %d" % port)
                time.sleep(0.05)
        write, command = self.client.write, self.client.command

        def counting_write(data):
            self.sent[0] += 1
            write(data)

        def counting_command(payload, reply_len):
            self.sent[1] += 1
            return command(payload, reply_len)
        self.client.write, self.client.command = counting_write, counting_command
        if args.hub == "ir-server":
            self._start("rcxsim", [args.rcxsim] + (["--rom"] if rom else []) + ["--tcp-join", "127.0.0.1:%d" % port])
        time.sleep(1.0)

    def _start(self, name, argv, env=None, cwd=None):
        """cwd: brickEmu's build writes a gmon.out (it is built with -pg) where it runs."""
        self.procs.append((name, subprocess.Popen(argv, env=env, cwd=cwd, stdout=subprocess.DEVNULL,
                                                  stderr=subprocess.PIPE)))

    def close(self):
        if self.client:
            self.client.close()
        for name, proc in reversed(self.procs):
            if proc.poll() is None:
                stop_proc(proc, name)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcxsim", default=os.path.join(REPO, "build", "host", "rcxsim"))
    ap.add_argument("--firmware", default=os.path.join(REPO, "build", "h8300", "drivers", "openrcx.srec"))
    ap.add_argument("--skip-firmware", action="store_true", help="only the program steps (rcxsim with its firmware)")
    ap.add_argument("--hub", choices=("ir-server", "rcxsim"), default="ir-server",
                    help="the hub: brickEmu's ir-server (default), or rcxsim --tcp for comparison")
    a = ap.parse_args()
    a.irserver = os.path.join(os.environ.get("BRICKEMU_DIR", ""), "ir-server")
    need = [(a.rcxsim, "rcxsim (make host)")] + ([(a.irserver, "BRICKEMU_DIR/ir-server")] if a.hub == "ir-server"
                                                 else [])
    for f, what in need:
        if not os.access(f, os.X_OK):
            sys.exit("%s not found: %s" % (what, f))
    os.environ["RCXSIM"] = a.rcxsim                  # net_lib's helpers want it
    sys.dont_write_bytecode = True                   # no __pycache__ in the source tree
    sys.path.insert(0, NET_TESTS)
    import net_lib                                   # noqa: E402

    st = Step()
    room = None
    try:
        room = Room(a, net_lib, rom=not a.skip_firmware)
        client, sent = room.client, room.sent

        def cmd(payload, reply_len, wait=0.5):
            sent[1] += 1
            return command_idle(net_lib, client, payload, reply_len, wait)

        t0, sent[:] = time.time(), [0, 0]
        r = None
        while r is None and time.time() - t0 < 5:
            r = cmd([0x10], 1)
        st.report("ping through " + a.hub, r is not None, t0, sent)

        if not a.skip_firmware:
            entry, image = srec_image(a.firmware)
            ck = sum(image[:0x4C00]) & 0xFFFF
            t0, sent[:] = time.time(), [0, 0]
            steps = [cmd([0x10], 1), cmd([0x15] + KEY, 9), cmd([0x65] + KEY, 1),
                     cmd([0x75, entry & 0xFF, entry >> 8, ck & 0xFF, ck >> 8, 0], 2)]
            blocks = [image[i:i + BLOCK] for i in range(0, len(image), BLOCK)]
            bad = None
            for n, blk in enumerate(blocks, 1):
                seq = 0 if n == len(blocks) else n
                r = cmd([0x45, seq & 0xFF, seq >> 8, len(blk) & 0xFF, len(blk) >> 8] + list(blk) + [sum(blk) & 0xFF],
                        2, BLOCK_WAIT)
                if r is None or r[1] != 0:
                    bad = "block %d of %d: %r" % (n, len(blocks), r)
                    break
            ok = all(s is not None for s in steps) and bad is None
            if ok:
                ok = cmd(UNLOCK, 26, 1.0) is not None
                bad = None if ok else "no reply to A5 (unlock)"
            v = cmd([0x15] + KEY, 9) if ok else None
            ok = ok and v is not None and v[1:] == VERSION_REPLY
            st.report("firmware download as nqc -firmware (%d blocks)" % len(blocks), ok, t0, sent,
                      bad or ("version %s" % (v[1:].hex(" ") if v else None)))
            if not ok:
                # The program steps on a brick that has its firmware already: a new room, rcxsim without --rom.
                room.close()
                room = Room(a, net_lib, rom=False)
                client, sent = room.client, room.sent
            time.sleep(0.5)

        t0, sent[:] = time.time(), [0, 0]
        rcx = net_lib.compile_rcx("count.nqc", os.path.join(os.environ.get("TMPDIR", "/tmp"),
                                                            "irserver_probe.%d.rcx" % os.getpid()))
        client.TIMEOUT = net_lib.Client.TIMEOUT      # net_lib's own wait (0.5 s) for every packet of a download
        try:
            client.download(rcx)
            ok, why = True, ""
        except SystemExit:                           # net_lib's check() exits; its message is on stderr
            ok, why = False, "see the message above"
        os.unlink(rcx)
        st.report("program download as nqc -d (count.nqc)", ok, t0, sent, why)
        t0, sent[:] = time.time(), [0, 0]
        started = cmd([0x71, 0], 1) is not None
        end = time.time() + 10
        val = None
        while started and time.time() < end and val != 42:
            r = cmd([0x12, 0, 0], 3)
            val = None if r is None else r[1] | r[2] << 8
            time.sleep(0.1)
        st.report("start it and poll variable 0 = 42", started and val == 42, t0, sent, "value %s" % val)
    finally:
        if room:
            room.close()
    return 0 if st.ok else 1


if __name__ == "__main__":
    sys.exit(main())
