// The report's animation player (src/rollspring/outputs/report/assets/player.js): its pure parts
// (interpolation, spring ends and zigzags drawn with the shared geometry.js, markers, the view)
// and, on a small stand-in for the DOM, what startPlayer draws and how its controls act.
import { test } from "node:test";
import assert from "node:assert/strict";
import { endPoint, fmt, marker, sample, springPoints, startPlayer, viewWindow }
  from "../../src/rollspring/outputs/report/assets/player.js";

const close = (a, b, tol = 1e-12) => assert.ok(Math.abs(a - b) <= tol, `${a} vs ${b}`);

/** Frame data as animation_data makes it: a hoop and a cylinder joined centre to centre, the
 * hoop also tied to a wall by a spring on its rim. */
function frames() {
  return {
    t: [0, 0.5, 1],
    x: [[0, 0.3], [0.01, 0.29], [0.02, 0.28]],
    phi: [[0, 0], [-0.1, 0.1], [-0.2, 0.2]],
    f: [[0.1, -0.1], [0.05, -0.05], [0, 0]],
    N: [[9.8, 9.8], [9.8, 9.8], [9.8, 9.8]],
    ratio: [[0.2, 0.2], [1.5, 0.1], [0, 0]],
    cm: [0.15, 0.15, 0.15],
    xhat: [0.14, 0.14, 0.14],
    bodies: [
      { id: "hoop", shape: "hoop", R: 0.1, track: 0, x_ref: 0, phi_ref: 0, mu: 0.5,
        marks: [[0.1, Math.PI / 2]] },
      { id: "cyl", shape: "cylinder", R: 0.1, track: 0, x_ref: 0.3, phi_ref: 0, mu: 0.5,
        marks: [] },
    ],
    springs: [
      { ends: [{ body: 0, r: 0, alpha: 0 }, { body: 1, r: 0, alpha: 0 }] },
      { ends: [{ anchor: [-0.4, 0.1] }, { body: 0, r: 0.1, alpha: 3 * Math.PI / 2 }] },
    ],
    anchors: [{ id: "wall", x: -0.4, y: 0.1 }],
    R_max: 0.1, floor: 0, cm_ref: 0.15, xhat_ref: 0.14, f_scale: 1.5, magnify: 2,
    magnify_options: [1, 2, 5],
    colors: { floor: "#7f7f7f", edge: "#1f3b57", hoop: "#1f3b57", cylinder: "#a6c8e0",
      custom: "#e8d3a9", slider: "#bdbdbd", mark: "#e0007f", spring: "#333333",
      friction: "#e66101", applied: "#a50026", cm: "#000000", xhat: "#7b3294", wall: "#7f7f7f" },
  };
}

test("sample interpolates linearly between stored frames and names the nearer one", () => {
  const D = frames();
  const s = sample(D, 0.25);
  close(s.x[0], 0.005);
  close(s.phi[1], 0.05);
  close(s.f[0], 0.075);
  assert.equal(s.index, 1);  // halfway rounds to the later frame
  assert.equal(sample(D, 0.2).index, 0);
  close(sample(D, 5).x[1], 0.28);  // clamped to the last frame
  assert.equal(sample({ ...D, xhat: null }, 0).xhat, null);
});

test("spring ends: anchors where they are, body points by geometry.js (M1)", () => {
  const D = frames();
  assert.deepEqual(endPoint(D, D.springs[1].ends[0], [0, 0.3], [0, 0]), { x: -0.4, y: 0.1 });
  const rim = endPoint(D, D.springs[1].ends[1], [0, 0.3], [Math.PI / 2, 0]);
  close(rim.x, 0);  // the left rim point turned a quarter clockwise is at the top
  close(rim.y, 0.2);
});

/** The zigzag the player drew before it used geometry.js (its own copy, kept in a Python string
 * in outputs/report/_assets.py). */
function formerZigzag(p, q, rMax) {
  const dx = q[0] - p[0], dy = q[1] - p[1], L = Math.sqrt(dx * dx + dy * dy);
  const ux = dx / L, uy = dy / L, nx = -uy, ny = ux, coils = 14, lead = 0.12 * L;
  const amp = Math.min(0.25 * rMax, 0.06 * L), pts = [p];
  pts.push([p[0] + ux * lead, p[1] + uy * lead]);
  for (let k = 1; k < 2 * coils; k++) {
    const s = lead + (L - 2 * lead) * k / (2 * coils), side = (k % 2 ? 1 : -1) * amp;
    pts.push([p[0] + ux * s + nx * side, p[1] + uy * s + ny * side]);
  }
  pts.push([q[0] - ux * lead, q[1] - uy * lead]); pts.push(q);
  return pts;
}

test("springs: the shared zigzag draws the player's springs as before (14 coils at the joints)", () => {
  for (const [p, q] of [[[0, 0.1], [0.3, 0.1]], [[-0.4, 0.1], [-0.1, 0.13]], [[0, 0], [0, 2]]]) {
    const drawn = springPoints({ x: p[0], y: p[1] }, { x: q[0], y: q[1] }, 0.1)
      .split(" ").map((pair) => pair.split(",").map(Number));
    const before = formerZigzag(p, q, 0.1);
    assert.equal(drawn.length, before.length);
    assert.equal(drawn.length, 2 + 27 + 2);
    drawn.forEach((pt, k) => {
      close(pt[0], before[k][0]);
      close(pt[1], -before[k][1]);  // SVG y is down
    });
  }
});

test("markers: a triangle for the CM, a diamond for X-hat, in SVG coordinates", () => {
  assert.equal(marker(1, 2, 0.5, "triangle"), "M1,-2.5 L0.5,-1.65 L1.5,-1.65 Z");
  assert.equal(marker(1, 2, 0.5, "diamond"), "M1,-2.5 L1.5,-2 L1,-1.5 L0.5,-2 Z");
  assert.equal(fmt(-1e-14, 3), "0.000");
  assert.equal(fmt(0.12345, 3), "0.123");
});

test("the view holds every magnified frame, the anchors and the floor band, at the aspect", () => {
  const D = frames();
  const v = viewWindow(D, 2, 3);
  close(v.width / v.height, 3);
  close(v.xmax - v.xmin, v.width);
  assert.ok(v.xmin < -0.4 && v.xmax > 0.3 + 2 * (0.28 - 0.3) + 0.1);
  assert.ok(v.ymin < -0.8 * D.R_max && v.ymax > 0.2);
  const wide = viewWindow(D, 50, 3);
  assert.ok(wide.xmax > 1 && wide.width > v.width);  // the hoop drawn 50 times further out
});

// -- a stand-in for the browser: elements with attributes, children, text and listeners ----------

class Element {
  constructor(name) {
    this.name = name;
    this.attributes = {};
    this.children = [];
    this.listeners = {};
    this.textContent = "";
    this.clientWidth = 900;
    this.clientHeight = 300;
  }
  setAttribute(k, v) { this.attributes[k] = String(v); }
  getAttribute(k) { return this.attributes[k]; }
  appendChild(e) { this.children.push(e); return e; }
  removeChild(e) { this.children.splice(this.children.indexOf(e), 1); return e; }
  get firstChild() { return this.children[0] || null; }
  addEventListener(type, f) { (this.listeners[type] ||= []).push(f); }
  fire(type) { (this.listeners[type] || []).forEach((f) => f({ type })); }
  querySelectorAll(name) { return this.children.filter((c) => c.name === name); }
  all(name) {
    return this.children.flatMap((c) => [...(c.name === name ? [c] : []), ...c.all(name)]);
  }
}

function page(D) {
  const byId = {};
  const add = (id, name) => (byId[id] = new Element(name));
  add("animation-data", "script").textContent = JSON.stringify(D);
  add("scene", "svg");
  add("play", "button");
  add("speed", "select").value = "1";
  add("frame", "input").value = "0";
  add("magnify", "select").value = String(D.magnify);
  add("clock", "span");
  for (const body of D.bodies) {
    const row = add(`readout-${body.id}`, "tr");
    for (let k = 0; k < 5; k++) row.appendChild(new Element("td"));
  }
  const doc = {
    getElementById: (id) => byId[id] || null,
    createElementNS: (_ns, name) => new Element(name),
  };
  const win = { frames: [], listeners: {}, requestAnimationFrame(f) { this.frames.push(f); },
    addEventListener(type, f) { this.listeners[type] = f; } };
  return { byId, doc, win };
}

test("startPlayer draws the first frame: view box, bodies, zigzag springs, markers, readout", () => {
  const D = frames();
  const { byId, doc, win } = page(D);
  startPlayer(doc, win);
  const svg = byId.scene;
  const [w, h] = svg.getAttribute("viewBox").split(" ").slice(2).map(Number);
  close(w / h, 3);
  assert.deepEqual(svg.children.map((g) => g.getAttribute("class")),
    ["static", "springs", "bodies", "marks"]);
  const groups = svg.all("g").filter((g) => g.getAttribute("class") === "body");
  assert.deepEqual(groups.map((g) => g.getAttribute("data-id")), ["hoop", "cyl"]);
  assert.equal(groups[0].getAttribute("transform"), "translate(0,-0.1) rotate(0)");
  const springs = svg.all("polyline");
  assert.equal(springs.length, 2);
  assert.equal(springs[0].getAttribute("points"),
    springPoints({ x: 0, y: 0.1 }, { x: 0.3, y: 0.1 }, D.R_max));
  const marks = svg.children[3].all("path");
  assert.equal(marks.length, 2 + 2);  // two friction arrows, the CM and X-hat
  assert.equal(byId.clock.textContent, "t = 0.000 s");
  assert.equal(byId["readout-hoop"].children[2].textContent, "0.1000");
  assert.equal(byId["readout-hoop"].children[4].textContent, fmt(0.1 / 9.8, 4));
  assert.equal(byId.frame.max, "2");
});

test("the controls: the slider pauses and jumps, Play runs on animation frames, magnify refits", () => {
  const D = frames();
  const { byId, doc, win } = page(D);
  startPlayer(doc, win);
  byId.frame.value = "2";
  byId.frame.fire("input");
  assert.equal(byId.clock.textContent, "t = 1.000 s");
  assert.equal(byId.play.textContent, "Play");
  byId.play.fire("click");
  assert.equal(byId.play.textContent, "Pause");
  assert.equal(byId.play.getAttribute("aria-pressed"), "true");
  win.frames.shift()(1000);
  win.frames.shift()(1250);  // a quarter second later, past the end: it wraps to the start
  assert.equal(byId.clock.textContent, "t = 0.250 s");
  byId.play.fire("click");
  assert.equal(byId.play.textContent, "Play");
  const before = byId.scene.getAttribute("viewBox");
  byId.magnify.value = "50";
  byId.magnify.fire("change");
  assert.notEqual(byId.scene.getAttribute("viewBox"), before);
  assert.equal(byId.scene.children[0].all("line").length, 1);  // the static layer redrawn once
});

test("a page without frame data gets no player", () => {
  const doc = { getElementById: () => null };
  assert.equal(startPlayer(doc, {}), undefined);
});
