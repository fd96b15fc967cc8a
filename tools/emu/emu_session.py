#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""Shared by the hand-check scripts: an emulated RCX with an image booted, the real nqc as its host, PASS/FAIL lines.

The emulated RCX is a local build of brickEmu with the mends of emulator.md (mend 4, a private IR port, and mend 8,
the counters and the S<hz> sound lines, are required). It is driven by the project's shared emulator tools
(rcxemu.py: the IR hub, a pseudo-terminal for nqc/firmdl3, the GUI socket, a GDB client), which are looked up in
$RCXEMU_TOOLS, else in the `shared/tools/emulator` folder next to the checkout. BRICKEMU_DIR names the build.
"""
import os
import re
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_IMAGE = os.path.join(REPO, "build", "h8300", "drivers", "openrcx.srec")
DEFAULT_LGO = os.path.join(REPO, "build", "h8300", "drivers", "openrcx.lgo")


def _find_tools():
    """The folder holding rcxemu.py: $RCXEMU_TOOLS, or shared/tools/emulator beside the checkout (main is
    /work/main, worktrees /work/wt/NAME: one or two levels up)."""
    cands = [os.environ.get("RCXEMU_TOOLS", "")]
    cands += [os.path.join(REPO, *[".."] * up, "shared", "tools", "emulator") for up in (1, 2)]
    for c in cands:
        if c and os.path.isfile(os.path.join(c, "rcxemu.py")):
            return os.path.abspath(c)
    sys.exit("rcxemu.py not found: set RCXEMU_TOOLS to the folder of the shared emulator tools")


def _check_build():
    d = os.environ.get("BRICKEMU_DIR")
    if not d or not os.path.isfile(os.path.join(d, "emu")) or not os.path.isfile(os.path.join(d, "rom.coff")):
        sys.exit("BRICKEMU_DIR must name a mended brickEmu build (the folder with emu and rom.coff)")


_check_build()
sys.path.insert(0, _find_tools())
import rcxemu  # noqa: E402

rcxemu.log = lambda *a: None            # the hub's connect lines would interleave with the report


# Input n's A/D channel (rcx-hardware.md: input 1 = AN2, input 2 = AN1, input 3 = AN0, battery = AN3).
AD_CHANNEL = {1: 2, 2: 1, 3: 0}
BATTERY_RAW = 320                       # about 9 V


class Report:
    """PASS/FAIL/SKIP lines as the checks go, and a summary."""

    def __init__(self):
        self.rows = []

    def check(self, name, ok, detail=""):
        self.rows.append((name, "PASS" if ok else "FAIL", detail))
        print("%-4s  %s%s" % ("PASS" if ok else "FAIL", name, ("  (" + detail + ")") if detail else ""), flush=True)
        return ok

    def skip(self, name, why):
        self.rows.append((name, "SKIP", why))
        print("SKIP  %s  (%s)" % (name, why), flush=True)

    def summary(self):
        n = {k: sum(1 for r in self.rows if r[1] == k) for k in ("PASS", "FAIL", "SKIP")}
        print("%d PASS, %d FAIL, %d SKIP" % (n["PASS"], n["FAIL"], n["SKIP"]), flush=True)
        return 1 if n["FAIL"] else 0


def wait_until(pred, seconds, every=0.05):
    """pred()'s first true value within `seconds`, else None."""
    end = time.time() + seconds
    while True:
        v = pred()
        if v or time.time() >= end:
            return v or None
        time.sleep(every)


class Brick:
    """One emulated RCX behind its own IR hub and pseudo-terminal; logs (emu.log, ir.log) in rundir."""

    def __init__(self, rundir=None, speed=1):
        self.rundir = os.path.abspath(rundir or tempfile.mkdtemp(prefix="rcxemu."))
        os.makedirs(self.rundir, exist_ok=True)
        self.irlog = os.path.join(self.rundir, "ir.log")
        self.hub = rcxemu.IRHub(port=0, logfile=self.irlog)
        self.hub.start()
        self.bridge = rcxemu.PtyBridge(self.hub, link=os.path.join(self.rundir, "tty"))
        self.tty = self.bridge.link
        self.emu = rcxemu.Emu(ir_port=self.hub.port, logname=os.path.join(self.rundir, "emu.log"), speed=speed)
        self.emu.sync()
        for n in AD_CHANNEL:
            self.raw(n, 1023)               # nothing plugged in
        self.emu.sensor(3, BATTERY_RAW)

    def close(self):
        self.emu.close()

    # -- the brick's side ----------------------------------------------------------------------------------------
    def raw(self, inp, value):
        """Input 1-3's A/D value (0-1023) as the sensor would give it."""
        self.emu.sensor(AD_CHANNEL[inp], value)

    def lcd(self):
        return self.emu.lcd_text()

    def digits(self):
        """The four digits and the minus sign as shown, e.g. ' 0000'."""
        m = re.match(r"\[(.*)\] prog=(.)", self.lcd())
        return m.group(1) if m else ""

    def program_digit(self):
        m = re.match(r"\[.*\] prog=(.)", self.lcd())
        return m.group(1) if m else ""

    def lcd_on(self):
        return self.emu.lcd_on

    def press(self, button, hold=0.15):
        """button: 'R' Run, 'O' On-Off, 'P' Prgm, 'V' View."""
        self.emu.press(button, hold)

    def counters(self):
        return self.emu.counters()

    def boot(self, image=DEFAULT_IMAGE):
        """Power the ROM on, load the image straight into memory (no IR) and wait for its display."""
        if not self.emu.power_on():
            return False
        self.emu.load_firmware(image)
        return wait_until(lambda: "0000" in self.digits(), 10) is not None

    # -- the host's side: the real nqc on the pseudo-terminal ---------------------------------------------------
    def nqc(self, *args, timeout=60):
        """(return code, output, seconds) of `nqc -S<tty> args...`."""
        t = time.time()
        try:
            r = subprocess.run(["nqc", "-S" + self.tty] + list(args), capture_output=True, text=True,
                               timeout=timeout, cwd=self.rundir)
            rc, out = r.returncode, (r.stdout + r.stderr)
        except subprocess.TimeoutExpired:
            rc, out = -1, "timed out after %d s" % timeout
        return rc, out.strip(), time.time() - t

    def raw_cmd(self, hexbytes, timeout=30):
        """nqc -raw: the reply's data bytes, or None without a reply."""
        rc, out, _ = self.nqc("-raw", hexbytes, timeout=timeout)
        if rc != 0:
            return None
        return bytes(int(h, 16) for h in re.findall(r"\b[0-9a-fA-F]{2}\b", out))

    def ping(self):
        """(answered, seconds nqc took, reply latency in ms from the IR log or None)."""
        mark = os.path.getsize(self.irlog)
        rc, _, secs = self.nqc("-raw", "10", timeout=30)
        return rc == 0, secs, self.reply_latency_ms(mark)

    def poll(self, source, index):
        """A value through Poll (0x12), signed; None without a reply."""
        r = self.raw_cmd("12%02x%02x" % (source, index))
        if r is None or len(r) != 2:
            return None
        v = r[0] | r[1] << 8
        return v - 65536 if v >= 32768 else v

    def var(self, n):
        return self.poll(0, n)

    def download(self, name, source, run=True, timeout=120):
        """Compiles `source` with the real nqc (-TRCX2) and downloads it (and starts it): (ok, output)."""
        path = os.path.join(self.rundir, name + ".nqc")
        with open(path, "w") as f:
            f.write(source)
        args = ["-TRCX2", "-d", path] + (["-run"] if run else [])
        rc, out, _ = self.nqc(*args, timeout=timeout)
        return rc == 0, out

    def reply_latencies_ms(self, mark=0):
        """Time from the end of each host packet after `mark` (IR log offset) that got an answer to the brick's first
        byte after it, minus the packet's time on the air (the emulator takes bytes in at 2400 baud, 11 bits each)."""
        with open(self.irlog) as f:
            f.seek(mark)
            rows = [line.split(None, 2) for line in f if line.strip()]
        lats = []
        for i, (t, who, data) in enumerate(rows):
            if who != "host":
                continue
            nxt = [float(r[0]) for r in rows[i + 1:] if r[1].startswith("emu")]
            if nxt:
                lats.append((nxt[0] - float(t) - len(bytes.fromhex(data)) * 11 / 2400.0) * 1000)
        return lats

    def reply_latency_ms(self, mark=0):
        """The last host packet's (reply_latencies_ms), or None."""
        lats = self.reply_latencies_ms(mark)
        return lats[-1] if lats else None
