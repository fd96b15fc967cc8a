#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""Issue 23 item 1: a virtual brick that joins brickEmu's own IR hub, driven as NQC 4 drives a brick over TCP.

    BRICKEMU_DIR=/path/to/brickemu python3 tools/emu/irserver_probe.py [--rcxsim build/host/rcxsim]
        [--firmware build/h8300/drivers/openrcx.srec] [--skip-firmware]

Starts brickEmu's `ir-server` on a free loopback port (BRICKEMU_IR_PORT, mend 4 of emulator.md; with
BRICKEMU_IR_FOREGROUND=1 it stays in the foreground and is stopped by its pid, else it ends when its last client
leaves), then `rcxsim --rom --tcp-join 127.0.0.1:PORT`: a brick with only the ROM. The client is the project's
stand-in for NQC 4's TCP link (tests/net/net_lib.py: no tower echo expected, the reply searched after the hub's echo,
4 tries, 0.5 s per reply) with NQC's 0.3 s wait for a download block's reply. It downloads the firmware as
`nqc -firmware` does (10, 15, 65, 75, 45 blocks of 200 bytes, A5, 15), then a program as `nqc -d` does, starts it
and polls its result. Each step prints PASS/FAIL, its time and how many packets it took (a step that needed
retries took more packets than commands).
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
BLOCK_WAIT = 0.3                                  # NQC waits this long for a download block's reply


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


def stop_sim(sim):
    """Stops an rcxsim (by its own pid) and prints what it said."""
    sim.terminate()
    try:
        err = sim.communicate(timeout=5)[1].decode(errors="replace").strip()
    except subprocess.TimeoutExpired:
        sim.kill()
        err = ""
    if err:
        print("      rcxsim said: " + err.replace("\n", " | "), flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rcxsim", default=os.path.join(REPO, "build", "host", "rcxsim"))
    ap.add_argument("--firmware", default=os.path.join(REPO, "build", "h8300", "drivers", "openrcx.srec"))
    ap.add_argument("--skip-firmware", action="store_true", help="start rcxsim with its firmware, not --rom")
    a = ap.parse_args()
    irserver = os.path.join(os.environ.get("BRICKEMU_DIR", ""), "ir-server")
    for f, what in ((irserver, "BRICKEMU_DIR/ir-server"), (a.rcxsim, "rcxsim (make host)")):
        if not os.access(f, os.X_OK):
            sys.exit("%s not found: %s" % (what, f))
    os.environ["RCXSIM"] = a.rcxsim                  # net_lib's helpers want it
    sys.path.insert(0, NET_TESTS)
    import net_lib                                   # noqa: E402

    port = free_port()
    hub = subprocess.Popen([irserver], env=dict(os.environ, BRICKEMU_IR_PORT=str(port), BRICKEMU_IR_FOREGROUND="1"),
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    sim = None
    client = None
    st = Step()
    try:
        # The first client must stay: ir-server ends when its last client leaves.
        end = time.time() + 5
        while client is None:
            try:
                client = net_lib.Client(port)
            except OSError:
                if time.time() > end:
                    sys.exit("ir-server did not listen on port %d" % port)
                time.sleep(0.05)
        sent = [0, 0]                                # packets written, commands given (retries: more packets)
        write, command = client.write, client.command

        def counting_write(data):
            sent[0] += 1
            write(data)

        def counting_command(payload, reply_len):
            sent[1] += 1
            return command(payload, reply_len)
        client.write, client.command = counting_write, counting_command
        def start_sim(*opts):
            p = subprocess.Popen([a.rcxsim] + list(opts) + ["--tcp-join", "127.0.0.1:%d" % port],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
            time.sleep(1.0)
            return p
        sim = start_sim(*([] if a.skip_firmware else ["--rom"]))

        def cmd(payload, reply_len, wait=0.5):
            client.TIMEOUT = wait
            return client.command(payload, reply_len)

        t0, sent[:] = time.time(), [0, 0]
        r = None
        while r is None and time.time() - t0 < 5:
            r = cmd([0x10], 1)
        st.report("ping through ir-server", r is not None, t0, sent)

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
                # The program steps on a brick that has its firmware already: a new rcxsim without --rom.
                stop_sim(sim)
                sim = start_sim()
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
        if client:
            client.close()
        if sim:
            stop_sim(sim)
        if hub.poll() is None:
            hub.terminate()
            hub.wait(5)
    return 0 if st.ok else 1


if __name__ == "__main__":
    sys.exit(main())
