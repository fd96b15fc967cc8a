# SPDX-License-Identifier: MPL-2.0
"""rcxsim --panel --world over HTTP (issue 22): the scene, the poses, the floor picture, the scene list and the
world's event stream; a place, a scene switch and a floor picture applied by the simulation; every kind of bad
request refused with a 4xx and a one-line reason, the simulator unharmed. Without --world, every /world path is 404."""
import json
import struct
import zlib

from panel_lib import Sim, check, wait_for
from test_api import next_event, open_stream, raw_exchange, refused

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"  # PNG specification, 5.2


def png(width, height, rgb):
    """A PNG file of one colour (PNG specification: IHDR, one IDAT of filtered scanlines, IEND)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\x00" + bytes(rgb) * width for _ in range(height))
    return (PNG_SIGNATURE + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def get_json(sim, url):
    status, body, headers = sim.request("GET", url)
    check(status == 200, "GET %s: %d %r" % (url, status, body))
    check(headers.get("Content-Type") == "application/json", "GET %s: content type %r" % (url, headers))
    return json.loads(body)


def trace_poses(sim, robot):
    """The poses of a robot that rcxsim wrote into its trace, oldest first."""
    out = []
    for line in open(sim.trace):
        try:
            d = json.loads(line)
        except ValueError:
            continue
        if d.get("robot") == robot and "x" in d:
            out.append(d)
    return out


def without_world():
    with Sim() as sim:
        for method, url in (("GET", "/world"), ("GET", "/world/pose"), ("GET", "/world/floor.png"),
                            ("GET", "/world/scenes"), ("GET", "/world/events"),
                            ("POST", "/world/place?robot=0&x=1&y=1&h=0"), ("POST", "/world/scene?name=arena")):
            refused(sim, method, url, 404)
        refused(sim, "POST", "/world/floor", 404, body=png(4, 4, (0, 0, 0)))
        check(sim.state()["bricks"][0]["power"] == "on", "still running")
        check(sim.stop() < 3, "rcxsim stopped")


def reads(sim):
    check(sim.state()["world"] is True, "GET /state tells the page there is a world")
    scene = get_json(sim, "/world")
    check(scene["floor"]["w"] == 1500 and scene["floor"]["h"] == 1200, "the arena's floor: %r" % scene["floor"])
    check(len(scene["walls"]) == 4 and len(scene["obstacles"]) == 4 and len(scene["robots"]) == 1, "arena: %r" % scene)
    check([o["movable"] for o in scene["obstacles"]] == [False, False, True, True], "movable: %r" % scene["obstacles"])
    pose = get_json(sim, "/world/pose")
    r0 = pose["robots"][0]
    check(abs(r0["x"] - 300) < 1 and abs(r0["y"] - 300) < 1 and abs(r0["h"] - 30) < 1, "robot 0 placed: %r" % r0)
    check(len(r0["inputs"]) == 3 and len(pose["obstacles"]) == 4, "pose: %r" % pose)
    status, body, headers = sim.request("GET", "/world/floor.png")
    check(status == 200 and headers["Content-Type"] == "image/png", "GET /world/floor.png: %d %r" % (status, headers))
    scenes = get_json(sim, "/world/scenes")
    check({"arena", "maze", "testpad", "two_robots"} <= set(scenes["scenes"]), "scenes: %r" % scenes)
    check(scenes["current"] == "arena", "current scene: %r" % scenes)

    # The stream: the scene first, as a "scene" event, then poses as plain events.
    s = open_stream(sim, "/world/events")
    buf = [b""]
    try:
        first = next_event(s, buf)
        check(first == scene, "the stream starts with the scene: %r" % first)
        second = next_event(s, buf)
        check(set(second) == {"t", "robots", "obstacles"}, "then the poses: %r" % second)
    finally:
        s.close()
    s = open_stream(sim, "/world/events")
    try:
        got = [b""]

        def more():
            got[0] += s.recv(65536)
            return got[0] if b"data: " in got[0] else None
        raw = wait_for("the first event", more)
        check(b"event: scene\ndata: {" in raw, "the scene comes as an event named scene: %r" % raw[:200])
    finally:
        s.close()


def writes(sim):
    sim.post("/world/place?robot=0&x=800.5&y=600&h=-90")
    r0 = get_json(sim, "/world/pose")["robots"][0]
    check(abs(r0["x"] - 800.5) < 2 and abs(r0["y"] - 600) < 2 and abs(r0["h"] % 360 - 270) < 2, "placed: %r" % r0)
    wait_for("the place in the trace", lambda: any(abs(p["x"] - 800.5) < 2 and abs(p["y"] - 600) < 2
                                                   for p in trace_poses(sim, 0)))
    sim.post("/world/place?obstacle=3&x=1000&y=150&h=45")
    o3 = get_json(sim, "/world/pose")["obstacles"][3]
    check(abs(o3["x"] - 1000) < 2 and abs(o3["y"] - 150) < 2, "obstacle 3 placed: %r" % o3)

    version = get_json(sim, "/world")["floor"]["version"]
    picture = png(150, 120, (200, 220, 240))
    status, body, _ = sim.request("POST", "/world/floor", body=picture, headers={"Content-Type": "image/png"})
    check(status == 204, "POST /world/floor: %d %r" % (status, body))
    check(get_json(sim, "/world")["floor"]["version"] > version, "the floor's version went up")

    sim.post("/world/scene?name=maze")
    check(get_json(sim, "/world/scenes")["current"] == "maze", "maze is current")
    check(get_json(sim, "/world")["scene"] != "arena", "another scene")
    sim.post("/world/scene?name=arena")


def refusals(sim):
    refused(sim, "GET", "/world/nothing", 404)
    refused(sim, "GET", "/world/place?robot=0&x=1&y=1&h=0", 405)
    refused(sim, "POST", "/world", 405)
    refused(sim, "POST", "/world/events", 405)
    refused(sim, "POST", "/world/place?robot=1&x=100&y=100&h=0", 400)          # one robot in the arena
    refused(sim, "POST", "/world/place?obstacle=0&x=100&y=100&h=0", 400)       # fixed to the floor
    refused(sim, "POST", "/world/place?obstacle=4&x=100&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&obstacle=2&x=100&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?x=100&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&x=1500.5&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&y=-1&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&x=nan&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&y=100", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&y=100&h=north", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&y=100&h=0&speed=3", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&x=200&y=100&h=0", 400)
    refused(sim, "POST", "/world/place?robot=0&x=100&y=100&h=0", 403, headers={"Origin": "http://evil.example"})
    refused(sim, "POST", "/world/scene", 400)
    refused(sim, "POST", "/world/scene?name=../arena", 400)
    refused(sim, "POST", "/world/scene?name=arena.json", 400)
    refused(sim, "POST", "/world/scene?name=nowhere", 404)
    refused(sim, "POST", "/world/scene?name=two_robots", 409)                  # two robots, one brick
    refused(sim, "POST", "/world/floor", 400)
    refused(sim, "POST", "/world/floor", 400, body=b"GIF89a" + b"\0" * 100)
    refused(sim, "POST", "/world/floor", 422, body=PNG_SIGNATURE + b"\0" * 100)  # a PNG's start, then nothing
    refused(sim, "POST", "/world/floor?x=1", 400, body=png(4, 4, (0, 0, 0)))
    # Too large: said in the headers (refused before the body is read), or found while the chunks come.
    head = b"POST /world/floor HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: %d\r\n\r\n" % (8 * 1024 * 1024 + 1)
    check(raw_exchange(sim, head).startswith(b"HTTP/1.1 413 "), "a declared 8 MiB + 1 refused")
    chunk = b"\0" * 65536
    chunked = (b"POST /world/floor HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\n" +
               (b"10000\r\n" + chunk + b"\r\n") * 129 + b"0\r\n\r\n")
    answer = raw_exchange(sim, chunked, timeout=20)
    check(answer.startswith(b"HTTP/1.1 413 ") and answer.endswith(b"at most 8 MiB\n"), "chunks past 8 MiB: %r" % answer)
    refused(sim, "POST", "/world/place?robot=0&x=1&y=1&h=0", 413, body=b"x" * 100)
    check(get_json(sim, "/world/scenes")["current"] == "arena", "still the arena")
    check(sim.state()["bricks"][0]["power"] == "on", "the simulator is unharmed")


def main():
    without_world()
    with Sim("--world", "arena") as sim:
        reads(sim)
        writes(sim)
        refusals(sim)
        check(sim.stop() < 3, "rcxsim stopped")
    print("panel world API: ok")


if __name__ == "__main__":
    main()
