// SPDX-License-Identifier: MPL-2.0
// The virtual RCX panel: draws every brick from the snapshots rcxsim streams on /events, and sends the user's
// inputs back by POST. The LCD is drawn from the 9-byte segment image alone: each element of brick.svg with
// data-seg="k.n" is lit when bit n of byte k is set.
"use strict";

const TOUCH_PRESSED_RAW = 60;   // a pressed touch sensor pulls the input low...
const TOUCH_RELEASED_RAW = 1023; // ...a released one leaves it at the pull-up
const NOTE_NAMES = ["C", "C♯", "D", "D♯", "E", "F", "F♯", "G", "G♯", "A", "A♯", "B"];
const DIRECTIONS = { fwd: "forward", rev: "reverse", brake: "brake", float: "float" };
const SENSOR_MODES_IN_TENTHS = { celsius: "°C", fahrenheit: "°F" };

let brickSvg = "";
const cards = [];
let audio = null; // AudioContext once the user switches the tones on
let sending = Promise.resolve(); // inputs leave one at a time: a release never overtakes its press

// One input to the simulator, after those already sent.
function post(path, params) {
    const url = path + "?" + new URLSearchParams(params);
    sending = sending
        .then(() => fetch(url, { method: "POST" }))
        .then(r => { if (!r.ok) return r.text().then(t => console.warn(path, r.status, t)); })
        .catch(e => console.warn(path, e));
    return sending;
}

// A slider sends only its newest value while an earlier one is on its way.
function latestOnly(send) {
    let busy = false, pending = null;
    const pump = () => {
        if (pending === null) { busy = false; return; }
        const v = pending;
        pending = null;
        busy = true;
        send(v).then(pump);
    };
    return v => { pending = v; if (!busy) pump(); };
}

// Something held down while pressed: by pointer (captured, so a release outside still counts) or by keyboard.
function holdable(el, send) {
    let held = false;
    const press = e => {
        if (held || (e.button !== undefined && e.button !== 0)) return;
        held = true;
        el.classList.add("held");
        if (e.pointerId !== undefined && el.setPointerCapture) el.setPointerCapture(e.pointerId);
        e.preventDefault();
        send(true);
    };
    const release = () => {
        if (!held) return;
        held = false;
        el.classList.remove("held");
        send(false);
    };
    el.addEventListener("pointerdown", press);
    el.addEventListener("pointerup", release);
    el.addEventListener("pointercancel", release);
    el.addEventListener("lostpointercapture", release);
    el.addEventListener("keydown", e => { if ((e.key === " " || e.key === "Enter") && !e.repeat) press(e); });
    el.addEventListener("keyup", e => { if (e.key === " " || e.key === "Enter") release(); });
    el.addEventListener("blur", release);
    return () => held;
}

function noteName(hz) {
    const n = Math.round(12 * Math.log2(hz / 440) + 69);
    const cents = Math.round(1200 * Math.log2(hz / (440 * Math.pow(2, (n - 69) / 12))));
    const off = Math.abs(cents) >= 5 ? ` ${cents > 0 ? "+" : ""}${cents}¢` : ""; // closer is in tune to the ear
    return NOTE_NAMES[((n % 12) + 12) % 12] + (Math.floor(n / 12) - 1) + off;
}

function fromTemplate(id) {
    return document.getElementById(id).content.firstElementChild.cloneNode(true);
}

function buildCard(i) {
    const node = fromTemplate("brick-template");
    const card = { node, i, buttons: {}, outputs: {}, inputs: [], last: null };
    node.dataset.brick = i;
    node.querySelector(".index").textContent = i;
    const face = node.querySelector(".face");
    face.innerHTML = brickSvg;
    card.segs = Array.from(face.querySelectorAll("[data-seg]"), el => {
        const [k, n] = el.dataset.seg.split(".").map(Number);
        return { el, k, n };
    });
    face.querySelectorAll("[data-button]").forEach(el => {
        const name = el.dataset.button;
        card.buttons[name] = { el, held: holdable(el, down =>
            post("/button", { brick: i, button: name, action: down ? "down" : "up" })) };
    });
    for (const name of ["A", "B", "C"]) {
        const row = fromTemplate("output-row");
        row.querySelector("th").textContent = name;
        node.querySelector(".outputs tbody").appendChild(row);
        card.outputs[name] = { row, rotor: face.querySelector(`[data-rotor="${name}"]`) };
    }
    for (let n = 1; n <= 3; n++) {
        const row = fromTemplate("input-row");
        row.querySelector("th").textContent = n;
        const raw = row.querySelector(".raw");
        const sendRaw = latestOnly(v => post("/sensor", { brick: i, input: n, raw: v }));
        let dragging = false;
        raw.addEventListener("pointerdown", () => { dragging = true; });
        raw.addEventListener("pointerup", () => { dragging = false; });
        raw.addEventListener("input", () => sendRaw(raw.value));
        const touch = row.querySelector(".touch");
        holdable(touch, down =>
            post("/sensor", { brick: i, input: n, raw: down ? TOUCH_PRESSED_RAW : TOUCH_RELEASED_RAW }));
        node.querySelector(".inputs tbody").appendChild(row);
        card.inputs.push({ row, raw, busy: () => dragging || document.activeElement === raw });
    }
    const battery = node.querySelector(".battery");
    const sendBattery = latestOnly(v => post("/battery", { brick: i, mv: v }));
    battery.addEventListener("input", () => sendBattery(battery.value));
    card.battery = battery;
    card.irLeds = { in: face.querySelector('[data-ir="in"]'), out: face.querySelector('[data-ir="out"]') };
    document.getElementById("bricks").appendChild(node);
    return card;
}

function text(card, selector, value) {
    card.node.querySelector(selector).textContent = value;
}

function blink(el) {
    el.classList.add("blink");
    clearTimeout(el.blinkTimer);
    el.blinkTimer = setTimeout(() => el.classList.remove("blink"), 150);
}

function renderBrick(card, b) {
    text(card, ".power", b.power === "on" ? "" : `(${b.power === "rom" ? "ROM, no firmware" : b.power})`);
    const image = b.lcd.match(/../g).map(h => parseInt(h, 16));
    for (const s of card.segs) s.el.classList.toggle("on", (image[s.k] >> s.n & 1) === 1);
    text(card, ".lcd-hex", b.lcd);
    text(card, ".lcd-num", `${b.num || "nothing"}${b.prog ? `, program ${b.prog}` : ""}`);

    for (const name of ["A", "B", "C"]) {
        const m = b.motors[name], o = card.outputs[name];
        o.row.className = m.dir;
        o.row.querySelector(".dir").textContent = DIRECTIONS[m.dir];
        o.row.querySelector(".level").textContent = `power ${m.level}`;
        const turning = m.dir === "fwd" || m.dir === "rev";
        o.row.querySelector(".bar").textContent = turning ? "■".repeat(m.level + 1) + "□".repeat(7 - m.level) : "";
        o.rotor.setAttribute("class", `rotor ${m.dir}`);
        o.rotor.style.animationDuration = `${(2.4 / (m.level + 1)).toFixed(2)}s`;
    }

    const tone = card.node.querySelector(".tone");
    tone.textContent = b.sound ? `${b.sound} Hz, ${noteName(b.sound)}` : "silent";
    tone.classList.toggle("playing", b.sound > 0);
    playTone(card, b.sound);

    b.sensors.forEach((s, n) => {
        const input = card.inputs[n];
        if (!input.busy()) input.raw.value = s.raw;
        input.row.querySelector(".raw-value").textContent = s.raw;
        input.row.querySelector(".touch").classList.toggle("held", s.raw === TOUCH_PRESSED_RAW);
        const unit = SENSOR_MODES_IN_TENTHS[s.mode];
        const value = unit && s.value !== 0x7FFF ? `${(s.value / 10).toFixed(1)} ${unit}` : s.value;
        input.row.querySelector(".seen").textContent = (s.type === "none" ? "no type" : s.type) +
            `, ${s.mode}${s.slope ? ` slope ${s.slope}` : ""}: ${value}${s.power ? ", powered" : ""}`;
    });

    for (const [name, btn] of Object.entries(card.buttons))
        btn.el.classList.toggle("held", btn.held() || b.buttons[name]);

    if (document.activeElement !== card.battery) card.battery.value = b.battery;
    text(card, ".battery-value", `${(b.battery / 1000).toFixed(2)} V`);
    text(card, ".slot", b.slot || "none");
    text(card, ".tasks", b.tasks.length ? `task${b.tasks.length > 1 ? "s" : ""} ${b.tasks.join(", ")}` : "none");
    text(card, ".ir-in", b.ir.in);
    text(card, ".ir-out", b.ir.out);
    text(card, ".ir-range", b.ir.range);
    if (card.last && card.last.ir.in !== b.ir.in) blink(card.irLeds.in);
    if (card.last && card.last.ir.out !== b.ir.out) blink(card.irLeds.out);
    card.last = b;
}

function render(state) {
    while (cards.length < state.bricks.length) cards.push(buildCard(cards.length));
    document.getElementById("bricks").classList.toggle("many", cards.length > 1);
    state.bricks.forEach((b, i) => renderBrick(cards[i], b));
    document.getElementById("clock").textContent = `simulated ${(state.t / 1000).toFixed(1)} s`;
}

// The real tones through the browser's audio, once the user asks for them (browsers need a click first).
function playTone(card, hz) {
    if (!audio) return;
    if (!card.osc) {
        card.osc = audio.createOscillator();
        card.gain = audio.createGain();
        card.osc.type = "square";
        card.gain.gain.value = 0;
        card.osc.connect(card.gain).connect(audio.destination);
        card.osc.start();
    }
    if (hz) card.osc.frequency.setValueAtTime(hz, audio.currentTime);
    card.gain.gain.setTargetAtTime(hz ? 0.05 : 0, audio.currentTime, 0.005);
}

document.getElementById("audio").addEventListener("change", e => {
    if (e.target.checked) {
        audio = audio || new AudioContext();
        audio.resume();
        for (const c of cards) if (c.last) playTone(c, c.last.sound);
    } else if (audio) {
        audio.suspend();
    }
});

function setLink(up) {
    const el = document.getElementById("link");
    el.textContent = up ? "live" : "not connected to rcxsim";
    el.className = `link ${up ? "up" : "down"}`;
}

async function start() {
    brickSvg = await (await fetch("brick.svg")).text();
    render(await (await fetch("state")).json());
    const events = new EventSource("events");
    events.onopen = () => setLink(true);
    events.onerror = () => setLink(false);
    events.onmessage = e => { setLink(true); render(JSON.parse(e.data)); };
}

start().catch(e => { setLink(false); console.error(e); });
