# SPDX-License-Identifier: MPL-2.0
"""rcxsim --panel over HTTP: GET /state, inputs by POST and what they do to a running program, the event stream,
and every kind of bad request (each refused with a 4xx and a one-line reason, the simulator unharmed)."""
import json
import os
import re
import shutil
import socket
import tempfile

from panel_lib import Sim, check, fail, nqc_compile, wait_for


def brick0(sim):
    return sim.state()["bricks"][0]


def refused(sim, method, url, status, body=None, headers=None):
    got, text, _ = sim.request(method, url, body=body, headers=headers)
    check(got == status, "%s %s: got %d %r, expected %d" % (method, url, got, text, status))
    check(text.endswith("\n") and text.count("\n") == 1 and len(text) > 1,
          "%s %s: the reason is not one line: %r" % (method, url, text))


def raw_exchange(sim, data, timeout=5):
    """Bytes straight onto a connection; returns what came back (the status line first, if any)."""
    s = socket.create_connection((sim.host, sim.port), timeout=timeout)
    try:
        s.sendall(data)
        try:
            s.shutdown(socket.SHUT_WR)
        except OSError:  # the server answered a refused request and closed first: its answer is still to be read
            pass
        out = b""
        while True:
            try:
                chunk = s.recv(4096)
            except (ConnectionResetError, socket.timeout):
                break
            if not chunk:
                break
            out += chunk
        return out
    finally:
        s.close()


def open_stream(sim, path="/events"):
    s = socket.create_connection((sim.host, sim.port), timeout=5)
    s.sendall(b"GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/event-stream\r\n\r\n" % path.encode())
    return s


def next_event(sock, buf):
    """The next `data:` event of a chunked event stream, as JSON; buf carries what was read ahead."""
    while True:
        i = buf[0].find(b"data: ")
        if i >= 0:
            j = buf[0].find(b"\n\n", i)
            if j >= 0:
                event = buf[0][i + 6:j]
                buf[0] = buf[0][j + 2:]
                return json.loads(event)
        chunk = sock.recv(65536)
        if not chunk:
            fail("event stream closed")
        # Strip the chunked framing: events never contain "\r\n", the chunk headers always do.
        buf[0] += b"".join(part for part in chunk.split(b"\r\n") if not _is_chunk_size(part))


def _is_chunk_size(part):
    try:
        int(part, 16)
        return True
    except ValueError:
        return part.startswith(b"HTTP/") or b": " in part and not part.startswith(b"data:") and b"{" not in part


def test_state_and_inputs(sim):
    # The power-on beep-beep (160 ms on, 60 off, twice) has a silence in it: wait past its 440 ms, then for quiet.
    wait_for("the power-on sound to end",
             lambda: (lambda st: st["t"] >= 600 and st["bricks"][0]["sound"] == 0)(sim.state()))
    check(sim.state()["world"] is False, "no world without --world")
    b = brick0(sim)
    for key in ("motors", "lcd", "num", "prog", "sound", "sensors", "buttons", "battery", "slot", "tasks", "ir"):
        check(key in b, "state lacks %s" % key)
    check(b["power"] == "on", "power")
    check(sorted(b["motors"]) == ["A", "B", "C"], "motors A-C")
    # Braked at power-on, as firm0328 leaves its outputs (reference-firmware.md).
    check(b["motors"]["A"]["dir"] == "brake", "A brakes at power-on: %r" % b["motors"]["A"])
    check(len(b["lcd"]) == 18 and int(b["lcd"], 16) >= 0, "lcd is 9 bytes hex: %r" % b["lcd"])
    check(b["prog"] == "1" and b["slot"] == 1, "program 1 selected and shown")
    check([s["input"] for s in b["sensors"]] == [1, 2, 3], "three inputs")
    check(b["sensors"][0]["raw"] == 1023, "inputs read the pull-up")
    check(b["buttons"] == {"onoff": False, "run": False, "view": False, "prgm": False}, "no button held")
    check(b["battery"] == 9000 and b["tasks"] == [] and b["sound"] == 0, "battery, tasks, sound: %r" % b)

    # Run starts the preloaded program: its first instruction makes input 1 a touch sensor.
    sim.post("/button?button=run&action=down")
    check(brick0(sim)["buttons"]["run"], "Run held")
    sim.post("/button?brick=0&button=run&action=up")
    check(not brick0(sim)["buttons"]["run"], "Run released")
    b = wait_for("the program to run", lambda: (lambda b: b if b["tasks"] == [0] else None)(brick0(sim)))
    wait_for("input 1 to be a touch sensor", lambda: brick0(sim)["sensors"][0]["type"] == "touch")
    s1 = brick0(sim)["sensors"][0]
    check(s1["mode"] == "bool" and s1["value"] == 0, "touch sensor, released: %r" % s1)

    # Pressing the touch sensor: the program sees 1 and turns output A on.
    sim.post("/sensor?input=1&raw=60")
    s1 = brick0(sim)["sensors"][0]
    check(s1["raw"] == 60, "raw value taken: %r" % s1)
    wait_for("the program to see the press", lambda: brick0(sim)["sensors"][0]["value"] == 1)
    wait_for("output A on", lambda: brick0(sim)["motors"]["A"] == {"dir": "fwd", "level": 7})
    sim.post("/sensor?input=1&raw=1023")
    wait_for("output A off (brake)", lambda: brick0(sim)["motors"]["A"]["dir"] == "brake")

    sim.post("/battery?mv=7000")
    check(brick0(sim)["battery"] == 7000, "battery taken")
    sim.post("/battery?brick=0&mv=9000")
    check(sim.request("HEAD", "/state")[0] == 200, "HEAD /state")


def test_pages(sim):
    for url, kind in (("/", "text/html"), ("/index.html", "text/html"), ("/panel.js", "text/javascript"),
                      ("/panel.css", "text/css"), ("/brick.svg", "image/svg+xml")):
        status, body, headers = sim.request("GET", url)
        check(status == 200 and headers["Content-Type"].startswith(kind) and len(body) > 100, "GET %s" % url)
    status, body, _ = sim.request("GET", "/brick.svg")
    segs = set(re.findall(r'data-seg="([0-8]\.[0-7])"', body))
    # rcx-hardware.md §3.6: all 72 bits of the 9 bytes are segments except 5.2 and 8.2
    check(segs == {"%d.%d" % (k, n) for k in range(9) for n in range(8)} - {"5.2", "8.2"},
          "brick.svg draws every LCD segment: %s" % sorted(segs))


def test_refusals(sim):
    refused(sim, "GET", "/nothing", 404)
    refused(sim, "GET", "/../etc/passwd", 404)
    refused(sim, "GET", "/panel", 404)
    refused(sim, "GET", "/button?button=run&action=down", 405)
    refused(sim, "POST", "/state", 405)
    refused(sim, "PUT", "/", 405)
    refused(sim, "DELETE", "/sensor?input=1&raw=3", 405)
    refused(sim, "POST", "/button", 400)
    refused(sim, "POST", "/button?button=fire&action=down", 400)
    refused(sim, "POST", "/button?button=run&action=hold", 400)
    refused(sim, "POST", "/button?button=run", 400)
    refused(sim, "POST", "/button?button=RUN&action=down", 400)
    refused(sim, "POST", "/sensor?input=4&raw=1", 400)
    refused(sim, "POST", "/sensor?input=0&raw=1", 400)
    refused(sim, "POST", "/sensor?input=1&raw=1024", 400)
    refused(sim, "POST", "/sensor?input=1&raw=-1", 400)
    refused(sim, "POST", "/sensor?input=1&raw=0x10", 400)
    refused(sim, "POST", "/sensor?input=1&raw=", 400)
    refused(sim, "POST", "/sensor?input=1&raw", 400)
    refused(sim, "POST", "/sensor?input=1&raw=99999999999999999999999", 400)
    refused(sim, "POST", "/battery?mv=65536", 400)
    refused(sim, "POST", "/battery", 400)
    refused(sim, "POST", "/battery?mv=7000&volts=7", 400)
    refused(sim, "POST", "/battery?mv=7000&mv=8000", 400)
    refused(sim, "POST", "/battery?brick=1&mv=7000", 400)
    refused(sim, "POST", "/battery?brick=-1&mv=7000", 400)
    refused(sim, "POST", "/battery?brick=x&mv=7000", 400)
    refused(sim, "POST", "/battery?mv=7000", 413, body=b"mv=7000",
            headers={"Content-Type": "application/x-www-form-urlencoded"})
    refused(sim, "POST", "/battery?mv=7000", 413, body=b"x" * 200000)
    refused(sim, "POST", "/battery?mv=7000", 403, headers={"Origin": "http://evil.example"})
    check(brick0(sim)["battery"] == 9000, "no refused request changed the battery")

    # Not HTTP at all, a request line without a version, headers without end, an oversized URL and header:
    # whatever libmicrohttpd answers, it is a 4xx (or nothing), and the simulator lives on.
    for data in (b"GARBAGE\r\n\r\n", b"GET /state\r\n\r\n", b"\x00\xff\x16\x03\x01" * 50,
                 b"GET /state HTTP/1.1\r\nHost: x\r\nBroken header line\r\n\r\n",
                 b"GET /" + b"a" * 100000 + b" HTTP/1.1\r\nHost: x\r\n\r\n",
                 b"GET /state HTTP/1.1\r\nHost: x\r\nX-Big: " + b"b" * 100000 + b"\r\n\r\n",
                 b"POST /sensor?input=1&raw=5 HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n",
                 b"POST /sensor?input=1&raw=5 HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n"):
        reply = raw_exchange(sim, data)
        status = reply.split(b" ", 2)[1] if reply.startswith(b"HTTP/1.") else b""
        check(reply == b"" or status.startswith(b"4"), "%r...: answered %r" % (data[:30], reply[:80]))
        check(sim.alive(), "rcxsim died on %r..." % data[:30])
    check(brick0(sim)["sensors"][0]["raw"] == 1023, "no malformed request reached input 1")


def test_streams(sim):
    """Many pages at once: each stream gets the snapshot, and a change reaches all of them."""
    streams = [open_stream(sim) for _ in range(24)]
    bufs = [[b""] for _ in streams]
    for s, buf in zip(streams, bufs):
        check(len(next_event(s, buf)["bricks"]) == 1, "first event: one brick")
    sim.post("/sensor?input=2&raw=500")
    for s, buf in zip(streams, bufs):
        wait_for("the change on every stream", lambda: next_event(s, buf)["bricks"][0]["sensors"][1]["raw"] == 500,
                 seconds=5, every=0)
    check(brick0(sim)["sensors"][1]["raw"] == 500, "GET /state with streams open")
    for s in streams:
        s.close()


def test_bricks():
    with Sim("--bricks", "2") as sim:
        state = sim.state()
        check(len(state["bricks"]) == 2 and state["bricks"][1]["brick"] == 1, "two bricks")
        sim.post("/sensor?brick=1&input=3&raw=17")
        state = sim.state()
        check(state["bricks"][1]["sensors"][2]["raw"] == 17 and state["bricks"][0]["sensors"][2]["raw"] == 1023,
              "input reached brick 1 only")
        refused(sim, "POST", "/sensor?brick=2&input=3&raw=17", 400)
        check(sim.stop() < 3, "stopped")


def main():
    scratch = tempfile.mkdtemp(prefix="panel.", dir=os.environ.get("PANEL_TMP"))
    rcx = nqc_compile("touch.nqc", os.path.join(scratch, "touch.rcx"))
    with Sim("--load", rcx) as sim:
        test_pages(sim)
        test_refusals(sim)
        test_state_and_inputs(sim)
        stream = open_stream(sim)  # left open: stopping must not wait for it
        next_event(stream, [b""])
        test_streams(sim)
        took = sim.stop()
        check(took < 3, "rcxsim took %.1f s to stop with a page open" % took)
        check(sim.proc.returncode == 0, "rcxsim exit status %d" % sim.proc.returncode)
        stream.close()
    shutil.rmtree(scratch)
    test_bricks()
    print("panel API: ok")


if __name__ == "__main__":
    main()
