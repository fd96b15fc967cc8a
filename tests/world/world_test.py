#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""The world end to end (issue 22): NQC programs written for the project, compiled by the real nqc, run on robots
in scenes by rcxsim --world --fast, judged from the poses in the trace. `world_test.py NAME` runs one test; CTest
sets RCXSIM, NQC, WORLD_DIR (this folder), SCENES (the shipped scenes) and WORK (a scratch folder).

Figures of the model the limits below come from (docs/world.md): the Roverbot preset's wheels are 43.2 mm across,
geared 3:1 down from 71427 motors that turn 360 rpm without load, so a wheel's top speed is
v0 = 360 / 3 / 60 * pi * 43.2 = 271 mm/s."""
import atexit
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

RCXSIM = os.environ["RCXSIM"]
NQC = os.environ.get("NQC", "nqc")
HERE = os.environ.get("WORLD_DIR", os.path.dirname(os.path.abspath(__file__)))
SCENES = os.environ["SCENES"]
WORK = tempfile.mkdtemp(prefix="world.", dir=os.environ.get("WORK"))
atexit.register(shutil.rmtree, WORK, True)
V0 = 360 / 3 / 60 * math.pi * 43.2  # mm/s


def fail(why):
    print("FAIL: " + why, file=sys.stderr)
    sys.exit(1)


def compile_nqc(name):
    out = os.path.join(WORK, name + ".rcx")
    subprocess.run([NQC, "-TRCX2", "-O" + out, os.path.join(HERE, name + ".nqc")], check=True, timeout=60)
    return out


def script(lines):
    path = os.path.join(WORK, "script%d" % len(os.listdir(WORK)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def press_run(bricks=1):
    """Each brick's Run button pressed at 0 ms and let go at 50 ms: the preloaded program starts."""
    return ["0 @%d button run down" % b for b in range(bricks)] + ["50 @%d button run up" % b for b in range(bricks)]


def run(args, trace_name="trace.jsonl"):
    trace = os.path.join(WORK, trace_name)
    p = subprocess.run([RCXSIM, "--fast", "--trace", trace] + args, capture_output=True, text=True, timeout=120)
    if p.returncode != 0:
        fail("rcxsim %s: status %d: %s" % (" ".join(args), p.returncode, p.stderr))
    with open(trace) as f:
        return [json.loads(line) for line in f]


def poses(lines, robot=0):
    return [(l["t"], l["x"], l["y"], l["h"]) for l in lines if l.get("robot") == robot]


def oval_distance(x, y):
    """Distance from the middle of the test pad's line (floorgen.c: half circles of 300 mm round (400, 500) and
    (1000, 500) joined by straights)."""
    cx = min(max(x, 400), 1000)
    return abs(math.hypot(x - cx, y - 500) - 300)


def test_linefollow():
    """Two laps of the oval with one light sensor, within a time derived from the model, the same trace twice.
    The sensor keeps to the line's outer edge: 2 * 600 + 2 * pi * 310 = 3148 mm a lap. The follower drives one
    wheel at a time, so the chassis moves at v0 / 2 = 136 mm/s: two laps take 6296 / 136 = 46.4 s. Allowed: that
    and 15 % (the turns from one wheel to the other, the start), 53.4 s. A follower that loses the line or a model
    that drives slower fails; the robot's centre must stay within 90 mm of the line (the sensor is 60 mm ahead of
    the axle, the line 10 mm from its edge, and 20 mm for the zigzag)."""
    rcx = compile_nqc("linefollow")
    limit_ms = int(2 * (2 * 600 + 2 * math.pi * 310) / (V0 / 2) * 1.15 * 1000)
    args = ["--world", "testpad", "--load", rcx, "--script", script(press_run()), "--duration", str(limit_ms)]
    lines = run(args)
    again = run(args, "again.jsonl")
    if lines != again:
        fail("two runs of the same scene, program and script gave different traces")
    turned, last, laps_at = 0.0, None, None
    for t, x, y, _ in poses(lines):
        a = math.atan2(y - 500, x - 700)
        if last is not None:
            turned += (a - last + math.pi) % (2 * math.pi) - math.pi
        last = a
        if oval_distance(x, y) > 90:
            fail("off the line at %d ms: (%.0f, %.0f), %.0f mm from it" % (t, x, y, oval_distance(x, y)))
        if laps_at is None and turned >= 4 * math.pi:
            laps_at = t
    if laps_at is None:
        fail("%.2f laps in %d ms, 2 wanted" % (turned / 2 / math.pi, limit_ms))
    print("two laps in %d ms (limit %d ms)" % (laps_at, limit_ms))


def inside_box(px, py, cx, cy, w, h, heading, inset):
    a = math.radians(heading)
    dx, dy = px - cx, py - cy
    u, v = dx * math.cos(a) + dy * math.sin(a), -dx * math.sin(a) + dy * math.cos(a)
    return abs(u) < w / 2 - inset and abs(v) < h / 2 - inset


def corners(x, y, h, l=160, w=120):
    a = math.radians(h)
    return [(x + u * math.cos(a) - v * math.sin(a), y + u * math.sin(a) + v * math.cos(a))
            for u in (-l / 2, l / 2) for v in (-w / 2, w / 2)]


def test_bumper():
    """Five simulated minutes of a bumper car in the arena: no corner of the chassis ever inside a wall or a fixed
    obstacle (3 mm allowed for Chipmunk's contact slop), and never stuck: within every 10 s the places it has been
    span at least 100 mm or it turns at least 90 degrees. (Each bump backs it off for 0.7 s at 271 mm/s, 190 mm
    when nothing is behind it, and turns it for 0.5-1.5 s at up to 2 * 271 / 112 rad/s, 277 degrees/s: a robot
    that can move does far more in 10 s, even in a crowded corner; one wedged with its tyres slipping does nothing.)
    """
    with open(os.path.join(SCENES, "arena.json")) as f:
        scene = json.load(f)
    rcx = compile_nqc("bumper")
    lines = run(["--world", "arena", "--load", rcx, "--script", script(press_run()), "--duration", "300000"])
    p = poses(lines)
    if p[-1][0] < 300000:
        fail("the trace ends at %d ms" % p[-1][0])
    fixed = [o for o in scene["obstacles"] if not o.get("movable")]
    inner = 20  # half the walls' 40 mm
    bumps = sum(1 for l in lines if l.get("motor") == "A" and l.get("dir") == "rev")
    for t, x, y, h in p:
        for cx, cy in corners(x, y, h):
            if not (inner - 3 <= cx <= 1500 - inner + 3 and inner - 3 <= cy <= 1200 - inner + 3):
                fail("through a wall at %d ms: corner (%.0f, %.0f)" % (t, cx, cy))
            for o in fixed:
                if inside_box(cx, cy, o["x"], o["y"], o["w"], o["h"], o.get("heading", 0), 3):
                    fail("inside an obstacle at %d ms: corner (%.0f, %.0f)" % (t, cx, cy))
    for i, (t, x, y, _) in enumerate(p):
        if t + 10000 > 300000:
            break
        window = [q for q in p[i:] if q[0] <= t + 10000]
        xs, ys, hs = [q[1] for q in window], [q[2] for q in window], [q[3] for q in window]
        span = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
        turned = sum(abs((b - a + 180) % 360 - 180) for a, b in zip(hs, hs[1:]))
        if span < 100 and turned < 90:
            fail("stuck from %d ms round (%.0f, %.0f): in 10 s its places span %.0f mm, it turned %.0f degrees"
                 % (t, x, y, span, turned))
    if bumps < 10:
        fail("only %d bumps in 5 minutes: the bumpers do not work" % bumps)
    print("5 minutes, %d bumps, never through a wall or an obstacle, never stuck" % bumps)


def test_odometry():
    """Drive until the rotation sensor on the left axle reads 160 (16 counts a turn: 10 turns), then brake. The
    scene puts the robot elsewhere; the script places it at (150, 300) heading east. Ten turns of a 43.2 mm wheel
    are 10 * pi * 43.2 = 1357.2 mm: where the program braked and where the robot came to rest must both be within
    2 % of that (the brake stops it in v0^2 / 2a = 6 mm at the tyres' grip, a = 0.8 * 0.8 * g)."""
    rcx = compile_nqc("odometry")
    lines = run(["--world", os.path.join(HERE, "odometry.json"), "--load", rcx, "--duration", "10000",
                 "--script", script(["0 place robot 0 150 300 0"] + press_run())])
    p = poses(lines)
    placed = [l for l in lines if l.get("placed")]
    if not placed or (placed[0]["x"], placed[0]["y"]) != (150.0, 300.0):
        fail("the script did not place the robot at (150, 300)")
    brake = [l["t"] for l in lines if l.get("motor") == "A" and l.get("dir") == "brake" and l["t"] > 50]
    if not brake:
        fail("the program never braked")
    at_brake = [q for q in p if q[0] >= brake[0]]  # the pose line after the brake line: the same instant
    want = 10 * math.pi * 43.2
    for what, q in (("braking", at_brake[0]), ("at rest", p[-1])):
        d = math.hypot(q[1] - 150, q[2] - 300)
        if abs(d - want) > 0.02 * want:
            fail("%s: %.1f mm from the start, %.1f mm wanted (2 %%)" % (what, d, want))
        print("%s after %.1f mm (%.2f %% from %.1f)" % (what, d, 100 * (d - want) / want, want))
    if abs(p[-1][2] - 300) > 5:
        fail("it did not drive straight: y %.1f at rest" % p[-1][2])


def test_two_robots():
    """Two bricks in one IR room: the scout drives north onto the oval's bottom straight and, seeing the line,
    stops and sends message 1; the waiter, driving east inside the oval, stops when the message arrives. The
    scout's sensor, 60 mm ahead, starts 70 mm before the line's edge: about 0.3 s at 271 mm/s. The message is
    a 9-byte packet at 2400 baud (about 40 ms) and the waiter's loop polls it within milliseconds: it must stop
    within 300 ms of the scout's IR bytes, long before it reaches the oval's far side (950 mm, 3.5 s away)."""
    scout, waiter = compile_nqc("scout"), compile_nqc("waiter")
    lines = run(["--world", "two_robots", "--load", "0@" + scout, "--load", "1@" + waiter, "--duration", "6000",
                 "--script", script(press_run(2))])
    sent = [l["t"] for l in lines if l.get("brick") == 0 and "ir" in l and l["t"] > 50]
    if not sent:
        fail("the scout never sent its message")
    stops = [l["t"] for l in lines if l.get("brick") == 1 and l.get("motor") == "A" and l.get("dir") == "brake"
             and l["t"] > 100]
    if not stops or not sent[0] <= stops[0] <= sent[0] + 300:
        fail("the waiter did not stop within 300 ms of the message at %d ms (stops: %s)" % (sent[0], stops[:3]))
    s, w = poses(lines, 0)[-1], poses(lines, 1)[-1]
    if oval_distance(s[1] + 60 * math.cos(math.radians(s[3])), s[2] + 60 * math.sin(math.radians(s[3]))) > 25:
        fail("the scout's sensor stopped away from the line: robot at (%.0f, %.0f)" % (s[1], s[2]))
    moving = [q for q in poses(lines, 1) if q[0] >= stops[0]][0]
    if moving[1] < 400 or w[1] > moving[1] + 20 or w[1] > 800:
        fail("the waiter did not drive and then stop: at %.0f mm when told, %.0f mm at the end" % (moving[1], w[1]))
    print("message at %d ms, waiter braked at %d ms at x = %.0f, rests at %.0f" % (sent[0], stops[0], moving[1], w[1]))


def test_download():
    """The README's demo as a user runs it: rcxsim --world testpad with a tower on a pseudo-terminal, the real nqc
    downloads the line follower and starts it (-d ... -run), and the robot leaves its start (500, 190) along the
    line. At --speed 10, the 100 mm it must cover take about 0.75 s of simulated time at v0 / 2."""
    tty, trace = os.path.join(WORK, "rcx"), os.path.join(WORK, "download.jsonl")
    sim = subprocess.Popen([RCXSIM, "--world", "testpad", "--tty", tty, "--speed", "10", "--trace", trace],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        for _ in range(200):
            if os.path.exists(tty) or sim.poll() is not None:
                break
            time.sleep(0.05)
        if not os.path.exists(tty):
            fail("rcxsim made no tower")
        subprocess.run([NQC, "-S" + tty, "-TRCX2", "-d", os.path.join(HERE, "linefollow.nqc"), "-run"], check=True,
                       timeout=60, capture_output=True)
        for _ in range(300):
            with open(trace) as f:
                lines = [json.loads(l) for l in f if l.endswith("\n")]
            moved = [q for q in poses(lines) if q[1] > 600 and abs(q[2] - 190) < 40]
            if moved:
                print("downloaded by nqc, started, the robot at (%.0f, %.0f) at %d ms" % (moved[0][1], moved[0][2],
                                                                                         moved[0][0]))
                return
            time.sleep(0.1)
        fail("the robot did not follow the line after nqc -d -run")
    finally:
        sim.terminate()
        sim.wait(timeout=30)


BAD = {
    # file: what its one line must say
    "missing_image.json": "floor image",
    "wrong_size.json": "\"w\" must be a number from 100",
    "unknown_key.json": "unknown key \"colour\"",
    "outside.json": "outside the",
    "not_json.json": "not valid JSON (line 3)",
    "no_robots.json": "\"robots\" must be a list",
    "robot_file.json": "robot_bad.json: its keys: unknown key \"x\"",  # a robot file's keys: no pose
}


def test_bad_scenes():
    """Each broken scene is refused before anything runs: exit status 2, one line on the standard error naming the
    file and the problem, nothing on the standard output."""
    for name, says in sorted(BAD.items()):
        if name == "robot_bad.json":
            continue
        path = os.path.join(HERE, "bad", name)
        p = subprocess.run([RCXSIM, "--world", path, "--fast", "--duration", "10"], capture_output=True, text=True,
                           timeout=30)
        err = p.stderr.splitlines()
        if p.returncode != 2 or len(err) != 1 or path not in err[0] or says not in err[0] or p.stdout:
            fail("%s: status %d, standard error %r, standard output %r; wanted 2 and one line naming it and saying %r"
                 % (name, p.returncode, p.stderr, p.stdout, says))
        print(err[0])


if __name__ == "__main__":
    globals()["test_" + sys.argv[1]]()
