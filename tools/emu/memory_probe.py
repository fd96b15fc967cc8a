#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""Host commands on a full memory, on the emulated RCX (issue 21 item 3, docs/timing.md).

Fills the five program slots with nqc (ten tasks each), then re-downloads slot 1 (everything after it moves),
sends raw what nqc -d does not (a task in 200-byte blocks, a download abandoned by the next BeginOfTask, a
DeleteAllTasks meeting the download in progress), clears the memory with `nqc -clear` and downloads and runs a small
program. For each step: whether nqc succeeded,
how long it took, and the longest reply latency of the brick over its packets (from the IR log): a command that
holds the main loop shows there, since the brick answers only once it has executed the command.

Usage: BRICKEMU_DIR=/path/to/brickemu python3 tools/emu/memory_probe.py [--image F.srec] [--rundir DIR] [--statements N]
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emu_session import DEFAULT_IMAGE, Brick, Report, wait_until  # noqa: E402


def big_program(statements, seed):
    """Ten tasks of `statements` assignments each: some 49 x statements bytes of code (nqc 3.1)."""
    tasks = []
    for t in range(10):
        body = "".join("    x%d = %d;\n" % (t, (seed + t * statements + k) % 30000) for k in range(statements))
        tasks.append("task %s()\n{\n%s}\n" % ("main" if t == 0 else "t%d" % t, body))
    return "".join("int x%d;\n" % t for t in range(10)) + "".join(tasks)


def free_memory(b):
    """Memory map words 93 - 92 (firm0328's free memory), or None."""
    r = b.raw_cmd("20", timeout=60)
    if r is None or len(r) != 188:
        return None
    words = [r[2 * i] << 8 | r[2 * i + 1] for i in range(94)]
    return words[93] - words[92]


def step(b, rep, name, *nqc_args, timeout=600):
    mark = os.path.getsize(b.irlog)
    rc, out, secs = b.nqc(*nqc_args, timeout=timeout)
    lat = b.reply_latencies_ms(mark)
    worst = max(lat) if lat else float("nan")
    rep.check(name, rc == 0, "%.1f s, %d replies, longest latency %.1f ms%s"
              % (secs, len(lat), worst, "" if rc == 0 else ": " + out[-200:]))
    return worst


def raw_step(b, rep, name, hexbytes, want=b"\x00"):
    """One raw command answered with `want` after its opcode (a download's status 0 by default); its reply latency
    from the IR log."""
    mark = os.path.getsize(b.irlog)
    r = b.raw_cmd(hexbytes, timeout=60)
    lat = b.reply_latencies_ms(mark)
    worst = max(lat) if lat else float("nan")
    got = "none" if r is None else r.hex() or "(the opcode only)"
    rep.check(name, r == want, "reply %s, latency %.1f ms" % (got, worst))
    return worst


def block(op, seq, data):
    """A download block (ContinueDL, op 45 or toggled 4D): seq(2) len(2) data checksum."""
    return "%02x%02x%02x%02x%02x%s%02x" % (op, seq & 255, seq >> 8, len(data) & 255, len(data) >> 8, data.hex(),
                                         sum(data) & 255)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--image", default=DEFAULT_IMAGE)
    ap.add_argument("--rundir")
    ap.add_argument("--statements", type=int, default=44, help="per task (default 44: some 2 200 bytes a slot)")
    a = ap.parse_args()
    rep = Report()
    b = Brick(a.rundir)
    print("logs in", b.rundir, flush=True)
    try:
        if not rep.check("boot", b.boot(a.image)):
            return 1
        empty = free_memory(b)
        rep.check("memory map on the empty brick", empty is not None, "%s bytes free" % empty)
        for p in range(1, 6):
            path = os.path.join(b.rundir, "big%d.nqc" % p)
            with open(path, "w") as f:
                f.write(big_program(a.statements, p))
            b.nqc("-pgm", str(p))          # (nqc -d FILE -pgm N selects N only after the download)
            step(b, rep, "download slot %d" % p, "-TRCX2", "-d", path)
        full = free_memory(b)
        rep.check("memory full", full is not None and empty is not None and full < empty // 8,
                  "%s bytes free" % full)
        path = os.path.join(b.rundir, "again.nqc")
        with open(path, "w") as f:
            f.write(big_program(a.statements, 1))  # the same size: it must fit again
        b.nqc("-pgm", "1")
        step(b, rep, "re-download slot 1 (the other slots move)", "-TRCX2", "-d", path)
        # What nqc -d does not send: the longest blocks a host may (200 bytes, of one-byte byte codes, each looked at
        # for Swan code), and the two commands that resize twice: a BeginOfTask that abandons a download, and a
        # DeleteAllTasks that meets the download in progress (reference-firmware.md: it stays).
        codes = bytes([0x10, 0x50, 0x80, 0x90, 0x06, 0x16, 0x26, 0x36, 0x56, 0x66] * 20)
        raw_step(b, rep, "BeginOfTask 9 of slot 1, 400 bytes", "250009009001")
        raw_step(b, rep, "its first block, 200 bytes", block(0x45, 1, codes))
        raw_step(b, rep, "its last block, 200 bytes", block(0x4D, 0, codes))
        raw_step(b, rep, "BeginOfTask 3, 240 bytes", "2d000300f000")
        raw_step(b, rep, "one block of it", block(0x45, 1, bytes([0x14, 1, 2, 1, 0] * 4)))
        raw_step(b, rep, "BeginOfTask 5 abandoning it", "250005000f00")
        raw_step(b, rep, "one block of that", block(0x4D, 1, bytes([0x14, 1, 2, 1, 0] * 3)))
        raw_step(b, rep, "DeleteAllTasks meeting the download in progress", "40", b"")
        raw_step(b, rep, "that download's last block (empty): it stayed", block(0x45, 0, b""))
        step(b, rep, "nqc -clear", "-clear")
        now = free_memory(b)
        rep.check("memory empty again", now is not None and empty is not None and empty - now <= 3,
                  "%s bytes free (-clear's SetDatalog 0 keeps the log's own entry, 3 bytes)" % now)
        ok, out = b.download("count", "int n;\ntask main()\n{\n    while (true) n++;\n}\n")
        rep.check("a program downloaded and started after it", ok and wait_until(lambda: (b.var(0) or 0) > 0, 10)
                  is not None, re.sub(r"\s+", " ", out)[-120:])
    finally:
        b.close()
    return rep.summary()


if __name__ == "__main__":
    sys.exit(main())
