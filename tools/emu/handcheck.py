#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""Hand checks of a firmware image on the emulated RCX (a mended brickEmu), with the real nqc and firmdl3 as hosts.

    BRICKEMU_DIR=/path/to/brickemu python3 tools/emu/handcheck.py [--image IMAGE.srec] [--lgo IMAGE.lgo]
        [--quick] [--skip-sleep] [--skip-firmware] [--skip-brickos] [--rundir DIR]

Boots the image (loaded straight into memory), then: ping, version, battery, a program (motors, a 440 Hz tone, the
display counting), Run, View, Prgm, rotation, light and touch sensors, On-Off to standby and back (also with On-Off
held), sleep after one idle minute (nqc -sleep 1) and waking, `nqc -firmware` over the running image (the real
flashing path through the ROM), brickOS through firmdl3 and back to the image. One PASS/FAIL line per check; exit
status 1 if any failed. --quick skips the three slow ones (sleep: 70 s; firmware: about 140 s each; brickOS).
"""
import argparse
import os
import subprocess
import sys
import time

sys.dont_write_bytecode = True           # no __pycache__ in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emu_session import BATTERY_RAW, DEFAULT_IMAGE, DEFAULT_LGO, Brick, Report, wait_until  # noqa: E402

BRICKOS = "/usr/lib/brickos/brickOS.srec"
VERSION_REPLY = bytes.fromhex("0003000100030208")   # ROM 3.1, firmware 3.2.8: firm0328's numbers (host-tools.md)

# Variable 0 counts every 100 ms and is shown; motors A forward, C reverse; a 440 Hz tone of half a second.
FACE = """
int n;
task main()
{
    n = 0;
    SetUserDisplay(n, 0);
    OnFwd(OUT_A);
    OnRev(OUT_C);
    PlayTone(440, 50);
    while (true) {
        Wait(10);
        n++;
    }
}
"""

# Input 1 rotation, input 2 light (percent), input 3 touch.
SENSORS = """
task main()
{
    SetSensor(SENSOR_1, SENSOR_ROTATION);
    ClearSensor(SENSOR_1);
    SetSensor(SENSOR_2, SENSOR_LIGHT);
    SetSensor(SENSOR_3, SENSOR_TOUCH);
}
"""

# Rotation phases by raw value (rcx-hardware.md §3.3): 0 = 960-1023, 1 = 768-959, 2 = 320-511, 3 = 512-767;
# 0-1-2-3-0 counts up.
PHASE_RAW = [1000, 860, 400, 640]


def light_percent(raw):
    """LEGO's percent conversion (rcx-hardware.md §3.3)."""
    return 100 if raw < 391 else (1023 - raw) * 25 // 156


def turn(b, inp, steps, phase, pause=0.005):
    """Feeds `steps` rotation steps (negative: backwards) from `phase`; returns the phase reached."""
    for _ in range(abs(steps)):
        phase = (phase + (1 if steps > 0 else -1)) % 4
        b.raw(inp, PHASE_RAW[phase])
        time.sleep(pause)
    return phase


def counting(b, var=0, gap=0.6):
    """Whether variable `var` changes over `gap` seconds (None if a poll got no reply)."""
    a = b.var(var)
    time.sleep(gap)
    c = b.var(var)
    return None if a is None or c is None else a != c


def off_and_on(b, r, label):
    """On-Off to standby, then On-Off to wake: display off, no reply while off, display and reply back after."""
    b.press("O")
    off = wait_until(lambda: b.lcd_on() == 0, 5)
    r.check(label + ": On-Off switches off (display off)", off is not None, b.lcd())
    ok, _, _ = b.ping()
    r.check(label + ": no reply while off", not ok)
    t = time.time()
    b.press("O")
    on = wait_until(lambda: b.lcd_on() == 1, 5)
    r.check(label + ": On-Off wakes it (display on)", on is not None, "%.2f s, %s" % (time.time() - t, b.lcd()))
    ok, _, _ = b.ping()
    r.check(label + ": answers a ping after waking", ok)


def check_basics(b, r):
    pings = [b.ping() for _ in range(5)]
    lat = [p[2] for p in pings if p[2] is not None]
    r.check("ping 5 times (nqc -raw 10)", all(p[0] for p in pings),
            "nqc %.2f s each, reply %.1f-%.1f ms after the command" %
            (sum(p[1] for p in pings) / 5, min(lat or [0]), max(lat or [0])))
    v = b.raw_cmd("15010305070b")
    r.check("version (nqc -raw 15010305070b) = 00 03 00 01 00 03 02 08", v == VERSION_REPLY, v and v.hex(" "))
    # Get battery power (30): millivolts, low byte first; raw 320 is 320 x 43988 / 1560 mV (rcx-hardware.md §3.4).
    want = BATTERY_RAW * 43988 // 1560
    mv = wait_until(lambda: (lambda x: x[0] | x[1] << 8 if x and len(x) == 2 and (x[0] or x[1]) else None)(
        b.raw_cmd("30")), 5, every=0.5)
    r.check("battery (nqc -raw 30) about %d mV" % want, mv is not None and abs(mv - want) < 200, str(mv))


def check_program(b, r):
    ok, out = b.download("face", FACE)
    if not r.check("download and run a program with nqc -TRCX2 -d -run", ok, out[-80:]):
        return False
    time.sleep(1.0)
    m = b.emu.motors
    r.check("motors: A and C on in opposite directions, B off",
            m[0][1] > 0 and m[2][1] > 0 and {m[0][0], m[2][0]} == {1, 2} and (m[1][1] == 0 or m[1][0] in (0, 3)),
            str(m))
    # The S<hz> lines (mend 8): how long the speaker stayed at about 440 Hz.
    log = b.emu.sound_log + [(time.time(), 0)]
    at440 = sum(t2 - t1 for (t1, hz), (t2, _) in zip(log, log[1:]) if abs(hz - 440) <= 5)
    r.check("a 440 Hz tone of about 0.5 s", 0.4 <= at440 <= 0.7, "%.2f s at 440 Hz" % at440)
    n = b.var(0)
    time.sleep(0.2)
    r.check("the display shows the program's counter", n is not None and abs(int(b.digits() or "0") - n) <= 3,
            "variable %s, display %r" % (n, b.digits()))
    return True


def check_buttons(b, r):
    r.check("the program is running (variable 0 counts)", counting(b) is True)
    b.press("R")
    time.sleep(0.3)
    r.check("Run stops it", counting(b) is False, b.lcd())
    time.sleep(0.3)                     # the emulator reports outputs as 100 ms averages
    m = b.emu.motors
    r.check("motors stopped after Run", all(m[i][1] == 0 or m[i][0] == 3 for i in range(3)), str(m))
    b.press("R")
    time.sleep(0.3)
    r.check("Run starts it again", counting(b) is True)
    b.press("R")
    time.sleep(0.3)
    before = b.lcd()
    b.press("V")
    time.sleep(0.3)
    first = b.lcd()
    r.check("View changes the display", first != before, "%s -> %s" % (before, first))
    # The view cycle: watch, inputs 1-3, outputs A-C, then round again (7 places).
    seen = [first]
    for _ in range(8):
        b.press("V")
        time.sleep(0.3)
        seen.append(b.lcd())
        if seen[-1] == first:
            break
    r.check("View goes round 7 places and back", len(seen) == 8 and seen[-1] == first,
            "; ".join(x.split(" fig_body")[0] + x.split("fig2")[-1] for x in seen))
    # Presses 0.3 s apart: a release followed by a press within a few ms reads as one press (debounce), as it should.
    b.press("P")
    p = wait_until(lambda: b.program_digit() == "2", 2)
    r.check("Prgm selects program 2", p is not None, b.lcd())
    for _ in range(4):
        time.sleep(0.3)
        b.press("P")
    time.sleep(0.3)
    r.check("four more Prgm presses come back to program 1", b.program_digit() == "1", b.lcd())


def check_sensors(b, r):
    ok, out = b.download("sensors", SENSORS)
    if not r.check("download a sensor program", ok, out[-80:]):
        return
    b.raw(1, PHASE_RAW[0])
    time.sleep(0.3)
    b.nqc("-raw", "71 00")
    time.sleep(0.3)
    ph = turn(b, 1, 48, 0)
    time.sleep(0.2)
    up = b.poll(9, 0)
    ph = turn(b, 1, -32, ph)
    time.sleep(0.2)
    down = b.poll(9, 0)
    r.check("rotation on input 1: 48 steps up, then 32 down", up == 48 and down == 16, "%s, %s" % (up, down))
    for raw in (300, 600, 900):
        b.raw(2, raw)
        time.sleep(0.2)
        v = b.poll(9, 1)
        r.check("light on input 2: raw %d reads %d %%" % (raw, light_percent(raw)), v == light_percent(raw), str(v))
    b.raw(3, 100)
    time.sleep(0.2)
    pressed = b.poll(9, 2)
    b.raw(3, 1023)
    time.sleep(0.2)
    released = b.poll(9, 2)
    r.check("touch on input 3: pressed 1, released 0", (pressed, released) == (1, 0), "%s, %s" % (pressed, released))
    b.raw(2, 1023)


def check_power(b, r, slow):
    off_and_on(b, r, "standby")
    # Switching on with On-Off held: it must come on while held and stay on once released.
    b.press("O")
    wait_until(lambda: b.lcd_on() == 0, 5)
    time.sleep(0.5)
    b.emu.button("O", True)
    on = wait_until(lambda: b.lcd_on() == 1, 3)
    time.sleep(1.5)
    b.emu.button("O", False)
    time.sleep(1.0)
    r.check("On-Off held 2.5 s: comes on while held, stays on after release", on is not None and b.lcd_on() == 1,
            b.lcd())
    ok, _, _ = b.ping()
    r.check("answers a ping after it", ok)
    if not slow:
        r.skip("sleep after 1 min idle (nqc -sleep 1)", "--skip-sleep")
        return
    rc, out, _ = b.nqc("-sleep", "1")
    t = time.time()
    off = wait_until(lambda: b.lcd_on() == 0, 80, every=0.5)
    r.check("nqc -sleep 1: off after one idle minute", off is not None and 55 <= time.time() - t <= 75,
            "rc %d, off after %.0f s" % (rc, time.time() - t))
    b.press("O")
    on = wait_until(lambda: b.lcd_on() == 1, 5)
    ok, _, _ = b.ping()
    r.check("On-Off wakes it, it answers", on is not None and ok, b.lcd())


def download_packets(b, mark):
    """Download blocks (45/4D) and unlocks (A5/AD) the host sent after IR log offset `mark`: more blocks than the
    image has means retries (nqc waits 0.3 s for a block's reply; a stalled host or emulator costs a retry)."""
    blocks = unlocks = 0
    with open(b.irlog) as f:
        f.seek(mark)
        for line in f:
            parts = line.split(None, 2)
            if len(parts) == 3 and parts[1] == "host" and parts[2].startswith("55 ff 00 "):
                op = int(parts[2][9:11], 16) & 0xF7
                blocks += op == 0x45
                unlocks += op == 0xA5
    return blocks, unlocks


def flash(b, r, lgo, label):
    mark = os.path.getsize(b.irlog)
    rc, out, secs = b.nqc("-firmware", lgo, timeout=400)
    blocks, unlocks = download_packets(b, mark)
    r.check(label + ": nqc -firmware", rc == 0, "%.0f s, %d block packets for %d blocks, %d unlock, rc %d%s" % (
        secs, blocks, image_blocks(lgo), unlocks, rc,
        (" " + out.splitlines()[-1]) if rc and out else ""))
    v = b.raw_cmd("15010305070b")
    shows = wait_until(lambda: "0000" in b.digits(), 5)
    r.check(label + ": the new image answers the version and shows 0000", v == VERSION_REPLY and shows is not None,
            "%s, %s" % (v and v.hex(" "), b.lcd()))
    return rc == 0


def image_blocks(srec):
    """How many 200-byte blocks nqc sends for an S-record image (its bytes from the lowest address up)."""
    lo = hi = None
    for line in open(srec):
        if line[:2] in ("S1", "S2", "S3"):
            alen = {"S1": 2, "S2": 3, "S3": 4}[line[:2]]
            raw = bytes.fromhex(line[2:].strip())
            addr = int.from_bytes(raw[1:1 + alen], "big")
            end = addr + len(raw) - 2 - alen
            lo, hi = addr if lo is None else min(lo, addr), end if hi is None else max(hi, end)
    return 0 if lo is None else (hi - lo + 199) // 200


def check_brickos(b, r, lgo):
    t = time.time()
    try:
        p = subprocess.run(["firmdl3", "--tty=" + b.tty, BRICKOS], capture_output=True, text=True, timeout=600)
        rc, out = p.returncode, (p.stdout + p.stderr).strip()
    except subprocess.TimeoutExpired:
        rc, out = -1, "timed out"
    r.check("firmdl3 brickOS.srec over the running image", rc == 0,
            "%.0f s, rc %d %s" % (time.time() - t, rc, out.splitlines()[-1:] if rc else ""))
    if rc != 0:
        return
    time.sleep(2)
    r.check("brickOS runs (its display, no OpenRCX reply to the version)",
            b.raw_cmd("15010305070b") != VERSION_REPLY, b.lcd())
    # Back to the ROM: brickOS's own gesture (Prgm held, On-Off pressed) did nothing on the emulated brick when
    # tried, so take a battery out (the emulator's reset: RAM kept, the ROM starts afresh), as a user would, and
    # switch the ROM on. The ROM answers the version query with firmware 0.0.
    b.emu.reset()
    time.sleep(1.0)
    b.emu.power_on()
    v = b.raw_cmd("15010305070b")
    r.check("battery out: the ROM answers, no firmware (00 03 00 01 00 00 00 00)",
            v == bytes.fromhex("0003000100000000"), v and v.hex(" "))
    flash(b, r, lgo, "back to OpenRCX")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--image", default=DEFAULT_IMAGE, help="image to boot (.srec), default: this checkout's build")
    ap.add_argument("--lgo", default=DEFAULT_LGO, help="image for nqc -firmware (.lgo)")
    ap.add_argument("--rundir", help="folder for the logs (default: a new temporary folder)")
    ap.add_argument("--quick", action="store_true", help="skip the sleep, firmware and brickOS checks")
    ap.add_argument("--skip-sleep", action="store_true")
    ap.add_argument("--skip-firmware", action="store_true")
    ap.add_argument("--skip-brickos", action="store_true")
    a = ap.parse_args()
    r = Report()
    b = Brick(a.rundir)
    print("logs in", b.rundir, flush=True)
    try:
        if not r.check("boot: the image shows 0000, program 1", b.boot(a.image) and b.program_digit() == "1",
                       b.lcd()):
            return r.summary()
        check_basics(b, r)
        if check_program(b, r):
            check_buttons(b, r)
        check_sensors(b, r)
        check_power(b, r, not (a.quick or a.skip_sleep))
        if a.quick or a.skip_firmware:
            r.skip("nqc -firmware over the running image", "--skip-firmware")
        else:
            flash(b, r, a.lgo, "reflash")
        if a.quick or a.skip_brickos:
            r.skip("brickOS and back", "--skip-brickos")
        elif not os.path.exists(BRICKOS):
            r.skip("brickOS and back", BRICKOS + " missing (Debian package brickos)")
        else:
            check_brickos(b, r, a.lgo)
    finally:
        b.close()
    return r.summary()


if __name__ == "__main__":
    sys.exit(main())
