// SPDX-License-Identifier: MPL-2.0
// The world view (rcxsim --world): the floor picture, walls, obstacles and each robot with its sensors and trail,
// drawn on a canvas at the browser's frame rate. rcxsim streams the scene ("scene" events) and the poses (about 50 a
// second) on /world/events; the page draws each frame at a simulated time a little behind the newest pose and
// interpolates between the two poses around it, so the robots glide instead of jumping. A robot or a movable
// obstacle is dragged with the pointer (and turned with the wheel): POST /world/place. Without --world (GET /state
// says "world": false) nothing of this appears. Uses post() and latestOnly() of panel.js.
"use strict";

const ROBOT_COLOURS = ["#e8590c", "#1c7ed6", "#2f9e44", "#ae3ec9", "#f08c00", "#0c8599", "#c2255c", "#5c940d"];
const BODY_COLOUR = "#f5c518";       // the RCX's yellow
const TOUCH_PRESSED_BELOW = 512;    // a pressed touch sensor pulls its input towards 0, a released one to 1023
const PLAYBACK_DELAY_MS = 60;       // wall time the drawing stays behind the newest pose: three pose gaps
const TRAIL_STEP_MM = 3;            // a trail takes a point once the robot moved this far...
const TRAIL_JUMP_MM = 150;          // ...and breaks where it moved further in one pose (dragged, or a new scene)...
const DRIVE_MM_PER_MS = 1;          // ...than it could drive in the simulated time between (a Roverbot: 0.3)
const WHEEL_TURN_DEG = 15;

const world = {
    scene: null,          // GET /world
    floor: null,          // the floor picture, an Image once loaded
    floorLoads: 0,
    samples: [],          // recent poses: {at: wall ms of arrival, t: simulated ms, robots, obstacles}
    rate: 1,              // simulated ms per wall ms, measured over the samples
    playT: null,          // the simulated time being drawn
    drawn: null,          // what the last frame drew: {t, robots: [{i, x, y, h, inputs}], obstacles: [...]}
    frames: 0,
    frameTimes: [],       // wall ms of the frames of the last second
    drawMs: 0,            // the last frame's drawing time...
    drawTotal: 0,         // ...all frames' together...
    drawMax: 0,           // ...and the longest
    drag: null,           // {kind: "robot"|"obstacle", i, dx, dy, x, y, h, until}
    held: {},             // poses the pointer holds, by "robot 0": shown until rcxsim's poses agree
    scale: 1,             // canvas CSS px per mm
};
window.worldView = world; // the browser test reads what the page drew from here

const canvas = () => document.getElementById("world-canvas");

function worldStatus(text, bad) {
    const el = document.getElementById("world-status");
    el.textContent = text;
    el.classList.toggle("bad", !!bad);
}

// A request whose answer is shown in the status line: the server's one-line reason when it refuses.
async function worldRequest(url, options, done) {
    try {
        const r = await fetch(url, Object.assign({ method: "POST" }, options));
        if (r.ok) worldStatus(done, false);
        else worldStatus((await r.text()).trim() || `refused (${r.status})`, true);
    } catch (e) {
        worldStatus(`not sent: ${e}`, true);
    }
}

// ---- the scene ----

function fitCanvas() {
    const c = canvas(), s = world.scene;
    if (!s) return;
    const room = Math.max(320, Math.min(820, document.documentElement.clientWidth - 48));
    const wide = Math.min(room, 640 * s.floor.w / s.floor.h); // a tall floor (a maze) must not need scrolling
    world.scale = wide / s.floor.w;
    const dpr = window.devicePixelRatio || 1;
    c.style.width = `${Math.round(s.floor.w * world.scale)}px`;
    c.style.height = `${Math.round(s.floor.h * world.scale)}px`;
    c.width = Math.round(s.floor.w * world.scale * dpr);
    c.height = Math.round(s.floor.h * world.scale * dpr);
    paintBackground();
}

// What does not move, drawn once into a canvas of its own that each frame copies: the floor picture, the walls,
// and the trails, which addTrailPoints() draws on as the poses come. A new picture or size starts it again.
function paintBackground() {
    const c = canvas(), s = world.scene, k = world.scale * (window.devicePixelRatio || 1);
    const layer = world.background = document.createElement("canvas");
    layer.width = c.width;
    layer.height = c.height;
    const g = layer.getContext("2d");
    g.fillStyle = "#ffffff";
    g.fillRect(0, 0, c.width, c.height);
    if (world.floor) g.drawImage(world.floor, 0, 0, c.width, c.height); // the picture's top row is the far side
    g.setTransform(k, 0, 0, -k, 0, c.height); // millimetres, y up
    g.strokeStyle = "#495057";
    g.lineCap = "square";
    for (const w of s.walls) {
        g.lineWidth = w.t || 10;
        g.beginPath();
        g.moveTo(w.x1, w.y1);
        g.lineTo(w.x2, w.y2);
        g.stroke();
    }
    world.trails = [];
}

function setScene(scene) {
    const renamed = !world.scene || world.scene.scene !== scene.scene;
    world.scene = scene;
    world.held = {};
    const img = new Image();
    img.onload = () => { if (world.scene === scene) { world.floor = img; paintBackground(); } };
    img.onerror = () => { if (world.scene === scene) { world.floor = null; paintBackground(); } };
    img.src = `world/floor.png?load=${++world.floorLoads}`;
    if (renamed) {
        world.samples = [];
        world.playT = null;
    }
    fitCanvas();
    document.getElementById("world-name").textContent = scene.scene;
    listScenes();
}

async function listScenes() {
    const r = await fetch("world/scenes");
    if (!r.ok) return;
    const list = await r.json(), select = document.getElementById("scene");
    const options = list.scenes.map(name => new Option(name, name, false, name === list.current));
    if (!list.scenes.includes(list.current)) // started from a file of its own: named as the scene names itself
        options.unshift(new Option(world.scene.scene, "", true, true));
    select.replaceChildren(...options);
    if (options[0].value === "") options[0].disabled = true;
}

// ---- the poses ----

function addSample(pose) {
    const at = performance.now(), s = world.samples;
    if (s.length && pose.t < s[s.length - 1].t) s.length = 0; // a new scene starts its clock again
    s.push({ at, t: pose.t, robots: pose.robots, obstacles: pose.obstacles });
    while (s.length > 2 && s[s.length - 1].at - s[0].at > 1000) s.shift();
    if (s.length > 1 && s[s.length - 1].at > s[0].at)
        world.rate = Math.max(0, (s[s.length - 1].t - s[0].t) / (s[s.length - 1].at - s[0].at));
    addTrailPoints(pose.robots, s.length > 1 ? pose.t - s[s.length - 2].t : 0);
}

// A move of d mm in dt simulated ms is a jump (a drag, another scene), not a drive.
function jumped(d, dt) {
    return d > TRAIL_JUMP_MM + DRIVE_MM_PER_MS * dt;
}

function addTrailPoints(robots, dt) {
    const layer = world.background;
    if (!layer) return;
    const g = layer.getContext("2d"), k = world.scale * (window.devicePixelRatio || 1), H = world.scene.floor.h;
    g.setTransform(1, 0, 0, 1, 0, 0);
    for (const r of robots) {
        if (world.held[`robot ${r.i}`]) { // carried by the pointer: no trail, it starts again where it is put down
            world.trails[r.i] = null;
            continue;
        }
        const last = world.trails[r.i];
        const d = last ? Math.hypot(r.x - last.x, r.y - last.y) : Infinity;
        if (d < TRAIL_STEP_MM) continue;
        if (!jumped(d, dt)) {
            g.strokeStyle = ROBOT_COLOURS[r.i % ROBOT_COLOURS.length];
            g.globalAlpha = 0.75;
            g.lineWidth = Math.max(1.5, 4 * k);
            g.lineCap = "round";
            g.beginPath();
            g.moveTo(last.x * k, (H - last.y) * k);
            g.lineTo(r.x * k, (H - r.y) * k);
            g.stroke();
        }
        world.trails[r.i] = { x: r.x, y: r.y };
    }
}

function lerpAngle(a, b, f) {
    const d = ((b - a) % 360 + 540) % 360 - 180;
    return a + d * f;
}

function lerpThings(a, b, f, dt) {
    return b.map(q => {
        const p = a.find(o => o.i === q.i);
        if (!p || jumped(Math.hypot(q.x - p.x, q.y - p.y), dt)) return q; // no glide over a jump
        return Object.assign({}, q, { x: p.x + (q.x - p.x) * f, y: p.y + (q.y - p.y) * f, h: lerpAngle(p.h, q.h, f) });
    });
}

// The poses at the simulated time drawn now: playT follows the newest pose PLAYBACK_DELAY_MS behind, at the
// simulation's own rate, pulled gently towards where it should be so that late or early poses do not jerk it.
function posesNow(now, dt) {
    const s = world.samples;
    if (!s.length) return null;
    const last = s[s.length - 1];
    const ideal = last.t + (now - last.at - PLAYBACK_DELAY_MS) * world.rate;
    if (world.playT === null || Math.abs(world.playT - ideal) > 1000 * Math.max(1, world.rate))
        world.playT = ideal;
    else
        world.playT += dt * world.rate + (ideal - world.playT) * 0.1;
    world.playT = Math.min(world.playT, last.t);
    let k = s.length - 1;
    while (k > 0 && s[k - 1].t > world.playT) k--;
    if (k === 0 || s[k].t <= world.playT) {
        const at = s[k];
        return { t: at.t, robots: at.robots, obstacles: at.obstacles };
    }
    const a = s[k - 1], b = s[k], f = (world.playT - a.t) / (b.t - a.t);
    return { t: world.playT, robots: lerpThings(a.robots, b.robots, f, b.t - a.t),
             obstacles: lerpThings(a.obstacles, b.obstacles, f, b.t - a.t) };
}

// What the pointer holds wins over what the stream says, until the stream agrees (or a second has passed).
function withHeld(things, kind, now) {
    return things.map(o => {
        const key = `${kind} ${o.i}`, h = world.held[key];
        if (!h) return o;
        const agrees = Math.hypot(o.x - h.x, o.y - h.y) < 2 && Math.abs(lerpAngle(o.h, h.h, 1) - o.h) < 2;
        if (!world.drag && (agrees || now > h.until)) {
            delete world.held[key];
            return o;
        }
        return Object.assign({}, o, { x: h.x, y: h.y, h: h.h });
    });
}

// ---- drawing ----

function sensorFill(sensor, raw) {
    if (sensor.kind === "touch") return raw < TOUCH_PRESSED_BELOW ? "#e03131" : "#f1f3f5";
    if (sensor.kind === "light") { // the brightness the sensor reads, as the firmware's percent scale gives it
        const percent = raw < 391 ? 100 : Math.max(0, Math.floor((1023 - raw) * 25 / 156));
        const v = Math.round(255 * percent / 100);
        return `rgb(${v},${v},${v})`;
    }
    return "#74c0fc"; // rotation: on the axle
}

// Whether the brick powers an input (a light sensor's LED is lit only then), from its card's last snapshot.
function powered(brick, input) {
    const card = typeof cards !== "undefined" ? cards[brick] : null;
    return !!(card && card.last && card.last.sensors[input - 1].power);
}

function drawRobot(g, spec, pose) {
    g.save();
    g.translate(pose.x, pose.y);
    g.rotate(pose.h * Math.PI / 180);
    const l = spec.l, w = spec.w, wheel = spec.wheel_d || 40, track = spec.track || w;
    g.fillStyle = "#343a40"; // the wheels, outside the chassis when the track is wider
    for (const side of [-1, 1]) g.fillRect(-wheel / 2, side * track / 2 - 7, wheel, 14);
    g.fillStyle = BODY_COLOUR;
    g.strokeStyle = "#5c4700";
    g.lineWidth = 3;
    g.fillRect(-l / 2, -w / 2, l, w);
    g.strokeRect(-l / 2, -w / 2, l, w);
    g.fillStyle = ROBOT_COLOURS[spec.i % ROBOT_COLOURS.length]; // the front, in the robot's colour
    g.beginPath();
    g.moveTo(l / 2 - 4, 0);
    g.lineTo(l / 2 - 30, w / 4);
    g.lineTo(l / 2 - 30, -w / 4);
    g.closePath();
    g.fill();
    for (const s of spec.sensors || []) {
        g.beginPath();
        g.arc(s.x, s.y, s.kind === "light" ? 10 : 8, 0, 2 * Math.PI);
        g.fillStyle = sensorFill(s, pose.inputs ? pose.inputs[s.input - 1] : 1023);
        g.fill();
        g.lineWidth = 2.5;
        g.strokeStyle = s.kind === "light" && powered(spec.brick, s.input) ? "#f03e3e" : "#212529"; // its red LED
        g.stroke();
    }
    g.restore();
}

function drawObstacle(g, spec, pose) {
    g.save();
    g.translate(pose.x, pose.y);
    g.rotate((pose.h || 0) * Math.PI / 180);
    g.fillStyle = spec.color || "#868e96";
    g.strokeStyle = spec.movable ? "#212529" : "#495057";
    g.lineWidth = spec.movable ? 2 : 4;
    g.beginPath();
    if (spec.shape === "circle") g.arc(0, 0, spec.r, 0, 2 * Math.PI);
    else g.rect(-spec.w / 2, -spec.h / 2, spec.w, spec.h);
    g.fill();
    g.stroke();
    g.restore();
}

function draw(poses) {
    const c = canvas(), g = c.getContext("2d"), s = world.scene;
    const dpr = window.devicePixelRatio || 1, k = world.scale * dpr;
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.drawImage(world.background, 0, 0);
    g.setTransform(k, 0, 0, -k, 0, c.height); // from here on millimetres, y up, angles counter-clockwise
    if (!poses) return;
    const obstacles = new Map(s.obstacles.map(o => [o.i, o])), robots = new Map(s.robots.map(r => [r.i, r]));
    for (const o of poses.obstacles) if (obstacles.has(o.i)) drawObstacle(g, obstacles.get(o.i), o);
    for (const r of poses.robots) if (robots.has(r.i)) drawRobot(g, robots.get(r.i), r);
    g.setTransform(dpr, 0, 0, dpr, 0, 0); // the robots' numbers upright, in CSS pixels
    g.font = "bold 12px system-ui, sans-serif";
    g.textAlign = "center";
    g.textBaseline = "middle";
    for (const r of poses.robots) {
        const p = toCanvas(r.x, r.y);
        g.fillStyle = "#212529";
        g.fillText(String(r.i), p.x, p.y);
    }
}

function frame(now) {
    requestAnimationFrame(frame);
    const dt = world.lastFrame === undefined ? 0 : now - world.lastFrame;
    world.lastFrame = now;
    if (!world.scene) return;
    const t0 = performance.now();
    let poses = posesNow(now, dt);
    if (poses)
        poses = Object.assign({}, poses, { robots: withHeld(poses.robots, "robot", now),
                                           obstacles: withHeld(poses.obstacles, "obstacle", now) });
    draw(poses);
    world.drawn = poses;
    world.drawMs = performance.now() - t0;
    world.drawTotal += world.drawMs;
    world.drawMax = Math.max(world.drawMax, world.drawMs);
    world.frames++;
    world.frameTimes.push(now);
    while (world.frameTimes.length && world.frameTimes[0] < now - 1000) world.frameTimes.shift();
    if (world.frames % 30 === 0)
        document.getElementById("world-fps").textContent = `${world.frameTimes.length} frames/s`;
}

// ---- the pointer ----

function toCanvas(x, y) { // mm -> CSS pixels from the canvas's top-left corner
    return { x: x * world.scale, y: (world.scene.floor.h - y) * world.scale };
}
world.toCanvas = toCanvas;

function toFloor(e) {
    const r = canvas().getBoundingClientRect();
    return { x: (e.clientX - r.left) / world.scale, y: world.scene.floor.h - (e.clientY - r.top) / world.scale };
}

function inside(p, pose, halfL, halfW) { // p in the rectangle of a pose, in its own frame
    const a = -(pose.h || 0) * Math.PI / 180, dx = p.x - pose.x, dy = p.y - pose.y;
    const u = dx * Math.cos(a) - dy * Math.sin(a), v = dx * Math.sin(a) + dy * Math.cos(a);
    return Math.abs(u) <= halfL && Math.abs(v) <= halfW;
}

// The robot or movable obstacle under a point, robots first (they are drawn on top).
function thingAt(p) {
    const poses = world.drawn, s = world.scene;
    if (!poses) return null;
    for (const r of poses.robots.slice().reverse()) {
        const spec = s.robots.find(q => q.i === r.i);
        if (spec && inside(p, r, spec.l / 2 + 10, Math.max(spec.w, spec.track || 0) / 2 + 10))
            return { kind: "robot", i: r.i, pose: r };
    }
    for (const o of poses.obstacles.slice().reverse()) {
        const spec = s.obstacles.find(q => q.i === o.i);
        if (!spec || !spec.movable) continue;
        const hit = spec.shape === "circle" ? Math.hypot(p.x - o.x, p.y - o.y) <= spec.r + 5
                                            : inside(p, o, spec.w / 2 + 5, spec.h / 2 + 5);
        if (hit) return { kind: "obstacle", i: o.i, pose: o };
    }
    return null;
}

const sendPlace = latestOnly(q => post("/world/place", q));

function place(kind, i, x, y, h) {
    const f = world.scene.floor;
    x = Math.min(Math.max(x, 0), f.w);
    y = Math.min(Math.max(y, 0), f.h);
    h = ((h % 360) + 360) % 360;
    world.held[`${kind} ${i}`] = { x, y, h, until: performance.now() + 1000 };
    sendPlace({ [kind]: i, x: x.toFixed(1), y: y.toFixed(1), h: h.toFixed(1) });
}

function pointerEvents(c) {
    c.addEventListener("pointerdown", e => {
        if (e.button !== 0 || !world.scene) return;
        const p = toFloor(e), hit = thingAt(p);
        if (!hit) return;
        world.drag = { kind: hit.kind, i: hit.i, dx: p.x - hit.pose.x, dy: p.y - hit.pose.y, h: hit.pose.h || 0 };
        c.setPointerCapture(e.pointerId);
        c.classList.add("dragging");
        e.preventDefault();
    });
    c.addEventListener("pointermove", e => {
        if (!world.scene) return;
        const p = toFloor(e), d = world.drag;
        if (!d) {
            c.style.cursor = thingAt(p) ? "grab" : "";
            return;
        }
        place(d.kind, d.i, p.x - d.dx, p.y - d.dy, d.h);
    });
    const end = e => {
        const d = world.drag;
        if (!d) return;
        world.drag = null;
        c.classList.remove("dragging");
        if (e.type === "pointerup") {
            const p = toFloor(e);
            place(d.kind, d.i, p.x - d.dx, p.y - d.dy, d.h);
        }
    };
    c.addEventListener("pointerup", end);
    c.addEventListener("pointercancel", end);
    c.addEventListener("wheel", e => { // turns what is under the pointer
        if (!world.scene) return;
        const hit = thingAt(toFloor(e));
        if (!hit) return;
        e.preventDefault();
        const h = (hit.pose.h || 0) + (e.deltaY < 0 ? WHEEL_TURN_DEG : -WHEEL_TURN_DEG);
        if (world.drag) world.drag.h = h;
        place(hit.kind, hit.i, hit.pose.x, hit.pose.y, h);
    }, { passive: false });
}

// ---- start ----

async function worldStart() {
    if (!(await (await fetch("state")).json()).world) return; // rcxsim runs without --world: the page stays as it was
    const r = await fetch("world");
    if (!r.ok) return;
    document.getElementById("world").hidden = false;
    setScene(await r.json());
    pointerEvents(canvas());
    document.getElementById("scene").addEventListener("change", e =>
        worldRequest(`world/scene?name=${encodeURIComponent(e.target.value)}`, {}, `scene ${e.target.value}`));
    document.getElementById("floor-file").addEventListener("change", e => {
        const file = e.target.files[0];
        if (file) worldRequest("world/floor", { body: file, headers: { "Content-Type": "image/png" } },
                               `floor picture ${file.name}`);
        e.target.value = "";
    });
    window.addEventListener("resize", () => { fitCanvas(); });
    const events = new EventSource("world/events");
    events.addEventListener("scene", e => setScene(JSON.parse(e.data)));
    events.onmessage = e => addSample(JSON.parse(e.data));
    requestAnimationFrame(frame);
}

worldStart().catch(e => console.error("world view:", e));
