#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""What events cost a busy brick (issue 21), measured on the emulated RCX (a mended brickEmu) with the real nqc.

    BRICKEMU_DIR=/path/to/brickemu python3 tools/emu/events_probe.py [--image IMAGE.srec] [--rows a,b,...]
        [--seconds N] [--rundir DIR]

Each row boots a fresh emulated brick, downloads a program compiled with nqc -TRCX2 whose main task configures the
row's sensor and events and then runs `while (true) x++;`, while a second task copies x after Wait(50) and again
after Wait(100) (one second). From those two copies (Poll of variables, nqc -raw 12 00 NN) the row prints x++ per
second, then whether the brick answers a ping (nqc -raw 10) while the program runs, how long nqc took and the reply's
latency after the command (from the IR log). A brick whose second task never finishes prints "-" for x++/s.

The "changing" row sets input 1 to a rotation sensor stepped 1 000 times a second and inputs 2 and 3 to light
sensors with a new random value every millisecond, through the emulator's GUI socket (three A/D values per
millisecond; the rate actually reached is printed), with 16 events over the three inputs; it also reports the
rotation count against the steps fed. Two more rows check, with 16 events on a touch sensor and motor A on, that a
press of Run stops the program (motor A stops) and a press of On-Off switches the brick off (the display goes off).
"""
import argparse
import os
import random
import sys
import threading
import time

sys.dont_write_bytecode = True           # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emu_session import DEFAULT_IMAGE, Brick, wait_until  # noqa: E402

# The ten event types that watch a sensor, as nqc names them; 16 events use them all, the first six twice.
SENSOR_EVENT_TYPES = ["PRESSED", "RELEASED", "PULSE", "EDGE", "FASTCHANGE", "LOW", "NORMAL", "HIGH", "CLICK",
                      "DOUBLECLICK"]
FOUR = ["PRESSED", "RELEASED", "LOW", "HIGH"]
SIXTEEN = [SENSOR_EVENT_TYPES[i % 10] for i in range(16)]

# Rotation phases by raw value (rcx-hardware.md §3.3), 0-1-2-3-0 counting up.
PHASE_RAW = [1000, 860, 400, 640]


def events(specs):
    """SetEvent lines for [(sensor, type), ...], events numbered from 0."""
    return "".join("    SetEvent(%d, %s, EVENT_TYPE_%s);\n" % (i, s, t) for i, (s, t) in enumerate(specs))


def on_input1(types):
    return events([("SENSOR_1", t) for t in types])


def program(setup, motor=False):
    """The measured program: x is variable 0, its copies 1 and 2, the finished flag 3. Motor A (if asked) comes on
    before the events are set up, so that it is on whatever they do to the brick."""
    return """int x;
int a;
int b;
int done;
task main()
{
%s%s    x = 0;
    start counter;
    while (true) x++;
}
task counter()
{
    Wait(50);
    a = x;
    Wait(100);
    b = x;
    done = 1;
}
""" % ("    OnFwd(OUT_A);\n" if motor else "", setup)


CHANGING = ("    SetSensor(SENSOR_1, SENSOR_ROTATION);\n    ClearSensor(SENSOR_1);\n"
            "    SetSensor(SENSOR_2, SENSOR_LIGHT);\n    SetSensor(SENSOR_3, SENSOR_LIGHT);\n"
            + events([("SENSOR_%d" % (1 + i * 3 // 16), SIXTEEN[i]) for i in range(16)]))

ROWS = [
    ("none", "no sensor configured", ""),
    ("light0", "light sensor on input 1, no event", "    SetSensor(SENSOR_1, SENSOR_LIGHT);\n"),
    ("touch4", "touch on input 1, 4 events (pressed, released, low, high)",
     "    SetSensor(SENSOR_1, SENSOR_TOUCH);\n" + on_input1(FOUR)),
    ("light4", "light on input 1, the same 4 events", "    SetSensor(SENSOR_1, SENSOR_LIGHT);\n" + on_input1(FOUR)),
    ("touch16", "touch on input 1, 16 events (all 10 sensor types)",
     "    SetSensor(SENSOR_1, SENSOR_TOUCH);\n" + on_input1(SIXTEEN)),
    ("light16", "light on input 1, 16 events", "    SetSensor(SENSOR_1, SENSOR_LIGHT);\n" + on_input1(SIXTEEN)),
    ("raw16", "light in raw mode on input 1, 16 events",
     "    SetSensor(SENSOR_1, SENSOR_LIGHT);\n    SetSensorMode(SENSOR_1, SENSOR_MODE_RAW);\n" + on_input1(SIXTEEN)),
    ("changing", "16 events on inputs 1-3 changing every ms (rotation 1 000 steps/s, noisy light x2)", CHANGING),
]


class Feeder(threading.Thread):
    """Every millisecond (as near as the host allows): one rotation step on input 1, random light values on inputs
    2 and 3."""

    def __init__(self, brick):
        super().__init__(daemon=True)
        self.b = brick
        self.stop = False
        self.steps = 0
        self.ticks = 0
        self.t0 = self.t1 = time.monotonic()

    def run(self):
        phase = 0
        self.b.raw(1, PHASE_RAW[0])
        nxt = self.t0 = time.monotonic()
        while not self.stop:
            phase = (phase + 1) % 4
            self.b.raw(1, PHASE_RAW[phase])
            self.b.raw(2, random.randint(300, 800))
            self.b.raw(3, random.randint(300, 800))
            self.steps += 1
            self.ticks += 1
            nxt += 0.001
            d = nxt - time.monotonic()
            if d > 0:
                time.sleep(d)
        self.t1 = time.monotonic()

    def rate(self):
        return self.ticks / max(1e-6, (self.t1 if self.stop else time.monotonic()) - self.t0)


def measure(b, seconds):
    """(x++ per second or None, ping answered, nqc seconds, reply latency ms) while the program runs."""
    done = wait_until(lambda: b.var(3) == 1, seconds, every=0.5)
    rate = None
    if done:
        a, c = b.var(1), b.var(2)
        if a is not None and c is not None:
            rate = (c - a) % 65536          # one second's worth; x wraps at 16 bits
    ok, secs, lat = b.ping()
    return rate, ok, secs, lat


def run_row(args, key, label, setup):
    b = Brick(os.path.join(args.rundir, key) if args.rundir else None)
    feeder = None
    try:
        if not b.boot(args.image):
            return "%-10s boot failed" % key
        ok, out = b.download(key, program(setup))
        if not ok:
            return "%-10s download failed: %s" % (key, out[-100:])
        if key == "changing":
            # the rotation sensor needs a valid phase before the program starts counting
            b.raw(1, PHASE_RAW[0])
            time.sleep(0.1)
        c0, t0 = b.counters(), time.time()
        if key == "changing":
            feeder = Feeder(b)
            feeder.start()
        rate, ok, secs, lat = measure(b, args.seconds)
        extra = ""
        if feeder:
            feeder.stop = True
            feeder.join()
            time.sleep(0.2)
            count = b.poll(9, 0)
            extra = "  (A/D updates %.0f/ms reached; rotation %s of %d steps)" % (feeder.rate() / 1000.0 * 3, count,
                                                                                   feeder.steps)
        c1, t1 = b.counters(), time.time()
        # emulated time against real time over the row: below 1.0 the host could not keep up
        pace = "" if not c0 or not c1 else "  [emulator at %.2fx real time]" % ((c1[0] - c0[0]) / 16e6 / (t1 - t0))
        return "%-10s %-8s %-5s %6.2f s  %8s   %s%s%s" % (
            key, "-" if rate is None else str(rate), "yes" if ok else "NO", secs,
            "-" if lat is None or not ok else "%.1f ms" % lat, label, extra, pace)
    finally:
        if feeder:
            feeder.stop = True
        b.close()


def buttons_rows(args):
    """With 16 events on a touch sensor and motor A on: Run stops the program; On-Off switches the brick off."""
    lines = []
    for what in ("run", "onoff"):
        b = Brick(os.path.join(args.rundir, "button-" + what) if args.rundir else None)
        try:
            if not b.boot(args.image):
                lines.append("%-10s boot failed" % what)
                continue
            setup = "    SetSensor(SENSOR_1, SENSOR_TOUCH);\n" + on_input1(SIXTEEN)
            ok, out = b.download("b" + what, program(setup, motor=True))
            if not ok:
                lines.append("%-10s download failed: %s" % (what, out[-100:]))
                continue
            running = wait_until(lambda: b.emu.motors[0][0] in (1, 2) and b.emu.motors[0][1] > 0, 3)
            time.sleep(1.0)
            t = time.time()
            if what == "run":
                b.press("R")
                stopped = wait_until(lambda: b.emu.motors[0][0] in (0, 3) or b.emu.motors[0][1] == 0, 5)
                took = time.time() - t
                # Stopped, the program no longer counts: is the brick reachable again (the events stay set up)?
                ok, _, lat = b.ping()
                lines.append("%-10s %s  Run pressed with 16 events: motor A %s%s; then a ping: %s" % (
                    "run", "PASS" if running and stopped else "FAIL",
                    "stopped after %.2f s" % took if stopped else "still on after 5 s",
                    "" if running else " (motor A never came on)",
                    "answered (%.1f ms)" % lat if ok and lat is not None else "answered" if ok else "no reply"))
            else:
                b.press("O")
                off = wait_until(lambda: b.lcd_on() == 0, 5)
                lines.append("%-10s %s  On-Off pressed with 16 events: %s" % (
                    "onoff", "PASS" if off else "FAIL",
                    "display off after %.2f s" % (time.time() - t) if off else "display still on after 5 s"))
        finally:
            b.close()
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--image", default=DEFAULT_IMAGE, help="image to boot (.srec), default: this checkout's build")
    ap.add_argument("--rows", default=",".join([r[0] for r in ROWS] + ["buttons"]),
                    help="comma-separated rows to run (default all: %(default)s)")
    ap.add_argument("--seconds", type=float, default=8, help="how long to wait for the 1 s task (default 8)")
    ap.add_argument("--rundir", help="folder for the logs, one subfolder per row (default: temporary folders)")
    a = ap.parse_args()
    want = a.rows.split(",")
    print("%-10s %-8s %-5s %8s  %8s   %s" % ("row", "x++/s", "ping", "nqc", "latency", "program"), flush=True)
    for key, label, setup in ROWS:
        if key in want:
            print(run_row(a, key, label, setup), flush=True)
    if "buttons" in want:
        for line in buttons_rows(a):
            print(line, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
