// The animation canvas: tracks, walls, rolling bodies with spokes and a mark, zigzag springs,
// force arrows to fixed scales (px per N, one per kind of force) with value labels, the CM and
// X̂ on the floor, ghost bodies of the linear solution, a clock; and under it the lesson strip:
// the CM and X̂ magnified, each with a fading trail. Body labels are laid out so that they never
// overlap (raised a row, or shortened, when neighbours are close). `Scene.draw(frame)` paints one instant;
// what the instant is comes from main.js. What was drawn last (pixel positions and arrow
// lengths) is kept in `scene.drawn`, for tests.

import { makeView, springEnds, zigzag } from "./geometry.js";
import { percussionHeight } from "./explain.js";
import { sig } from "./format.js";
import { bodyColour, CM_COLOUR, FORCE_COLOURS, magnification, XHAT_COLOUR } from "./series.js";
import { clockText, sampleIndex, valueAt } from "./timeline.js";

const INK = "#1d2430";
/** The longest arrow drawn, as a share of the canvas width (a longer one is cut, marked so). */
const ARROW_MAX = 0.45;
/** The trail of the strip's markers: how far back (s) and in how many fading steps. */
const TRAIL_S = 0.6;
const TRAIL_STEPS = 6;

/** The canvas and its view of the world window; handles the device pixel ratio. */
/** Size ``owner.canvas`` to its CSS box at the device's pixel ratio (drawing in CSS px): sets
 * ``owner.width``, ``owner.height`` and the context's transform; true when the size changed. */
function fitCanvas(owner) {
  const box = owner.canvas.getBoundingClientRect();
  const width = Math.max(1, Math.round(box.width));
  const height = Math.max(1, Math.round(box.height));
  const ratio = window.devicePixelRatio || 1;
  const changed = width !== owner.width || height !== owner.height;
  owner.width = width;
  owner.height = height;
  owner.canvas.width = Math.round(width * ratio);
  owner.canvas.height = Math.round(height * ratio);
  owner.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  return changed;
}

export class Scene {
  /** `canvas`: the animation; `stripCanvas` (optional): the magnified CM and X̂ strip. */
  constructor(canvas, stripCanvas = null) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.strip = stripCanvas ? new Strip(stripCanvas) : null;
    this.window = { xmin: -0.5, xmax: 0.5, ymin: -0.1, ymax: 0.3 };
    // what the last frame drew (CSS px), rewritten in place by every draw
    this.drawn = { friction: {}, normal: {}, spring: [], labels: [], bodyLabels: [],
      percussion: {}, pxPerM: 0, strip: this.strip ? this.strip.drawn : null };
    this.wantedLabels = []; // the body labels of the frame being drawn, before their layout
    this.resize();
  }

  /** Fit the canvas to its CSS box; returns true when its size changed. */
  resize() {
    const changed = fitCanvas(this);
    this.setWindow(this.window);
    const stripChanged = this.strip ? this.strip.resize() : false;
    return changed || stripChanged;
  }

  /** Show the world window `w` ({xmin, xmax, ymin, ymax}, metres). */
  setWindow(w) {
    this.window = w;
    this.view = makeView(w, this.width, this.height);
    this.canvas.dataset.pxPerM = String(this.view.pxPerM);
  }

  /** Paint one instant. `frame`: {system, pose(id) → {x, phi}, tensions[], contact(id) →
   * {f, N}, cm, xhat (or null), t, ghosts {id: x} or null, flash Set of ids (slipping or at
   * the run's first slip: a red glow), held Set of ids or absent (at rest under rolling
   * resistance: a grey glow), show {spring,
   * friction, normal, markers, values}, forceScale {spring, friction, normal} (px per N),
   * labelled (a Set of body ids whose forces get value labels), lesson (see Strip.draw) or
   * null}. */
  draw(frame) {
    const { ctx, view } = this;
    ctx.clearRect(0, 0, this.width, this.height);
    drawTracks(ctx, view, frame.system, this.width);
    drawWalls(ctx, view, frame.system);
    if (frame.ghosts) drawGhosts(ctx, view, frame);
    frame.system.springs.forEach((spring, s) => drawSpring(ctx, view, frame, spring, s));
    const wanted = this.wantedLabels;
    wanted.length = 0;
    frame.system.bodies.forEach((body, i) => drawBody(ctx, view, frame, body, i, wanted));
    drawPercussion(ctx, view, frame, this.drawn.percussion);
    this.drawn.pxPerM = view.pxPerM;
    this.drawn.held = frame.held ? [...frame.held] : [];
    this.drawn.flashed = [...frame.flash];
    if (frame.show.markers) drawMarkers(ctx, view, frame);
    drawForces(ctx, view, frame, this.drawn, this.width * ARROW_MAX);
    ctx.fillStyle = INK;
    ctx.font = CLOCK_FONT;
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    const clock = clockText(frame.t);
    ctx.fillText(clock, 10, 8);
    const clockBox = { x: 10, y: 8, w: textWidth(ctx, CLOCK_FONT, clock), h: 18 };
    drawBodyLabels(ctx, wanted, this.drawn.bodyLabels, this.width, clockBox);
    if (this.strip) this.strip.draw(frame, view.pxPerM);
  }
}

/** The lesson strip: the CM and X̂ each on its own row, about the middle of its range, at one
 * magnification (1, 2, 5 × 10^k, the largest that keeps both inside the strip) of the
 * animation's scale, each with a trail of the last TRAIL_S s that fades and falls with age
 * (the CM's a wave, X̂'s a straight line: it stays put). */
class Strip {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    // the markers' x, the rows' y, the trails' length (s) and fall (px): the trail point of a
    // time t − a is drawn a/trail·fall px below its row
    this.drawn = { cm: null, xhat: null, magnification: 1, pxPerM: 0, cmY: 0, xhatY: 0,
      trail: TRAIL_S, fall: 0 };
    this.labelled = 0; // ± the magnification the title and label describe (− without X̂)
    this.title = "";
    this.rows = [
      { key: "cm", name: "CM", values: null, mid: 0, colour: CM_COLOUR, y: 0 },
      { key: "xhat", name: "X̂", values: null, mid: 0, colour: XHAT_COLOUR, y: 0 },
    ];
  }

  resize() {
    return fitCanvas(this);
  }

  /** `frame.lesson`: {times, cm, xhat (or null), cmMid, xhatMid, halfRange (m)} of the run. */
  draw(frame, pxPerM) {
    const { ctx, width, height } = this;
    const lesson = frame.lesson;
    ctx.clearRect(0, 0, width, height);
    if (!lesson) {
      this.drawn.cm = null;
      this.drawn.xhat = null;
      return;
    }
    // fixed by a lesson step (so that steps compare), or the largest that fits
    const mag = frame.stripMagnification || magnification(lesson.halfRange * pxPerM, 0.3 * width);
    const k = pxPerM * mag; // px per metre in the strip
    const cx = width / 2;
    // two bands under the title, each with its marker on top and its trail falling below
    const band = (height - 22) / 2;
    const fall = band - 12;
    const [cmRow, xhatRow] = this.rows;
    cmRow.values = lesson.cm;
    cmRow.mid = lesson.cmMid;
    cmRow.y = 28;
    xhatRow.values = lesson.xhat;
    xhatRow.mid = lesson.xhatMid;
    xhatRow.y = 28 + band;
    this.drawn.cmY = cmRow.y;
    this.drawn.xhatY = xhatRow.y;
    this.drawn.fall = fall;
    ctx.font = "600 12px system-ui, sans-serif";
    ctx.textBaseline = "top";
    ctx.textAlign = "left";
    ctx.fillStyle = INK;
    if (this.labelled !== (lesson.xhat ? mag : -mag)) { // the words change with these only
      this.labelled = lesson.xhat ? mag : -mag;
      this.title = `${lesson.xhat ? "CM and X̂" : "CM"} magnified ×${mag}`;
      this.canvas.setAttribute("aria-label", `The centre of mass${lesson.xhat ? " and the stationary "
        + "point X̂" : ""}, magnified ×${mag}, each about the middle of its range.`);
      this.canvas.dataset.magnification = String(mag);
    }
    ctx.fillText(this.title, 6, 3);
    scaleBar(ctx, width, k);
    const times = lesson.times;
    const i = sampleIndex(times, frame.t);
    for (const row of this.rows) {
      if (!row.values) continue;
      ctx.strokeStyle = "#c9d0da";
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(30, row.y);
      ctx.lineTo(width - 6, row.y);
      ctx.moveTo(cx, row.y - 5);
      ctx.lineTo(cx, row.y + 5);
      ctx.stroke();
      // the trail: samples back to TRAIL_S s ago, in TRAIL_STEPS paths of fading alpha
      const dtSample = times.length > 1 ? times[1] - times[0] : 1;
      const back = Math.min(i, Math.max(1, Math.round(TRAIL_S / dtSample)));
      const per = Math.max(1, Math.ceil(back / TRAIL_STEPS));
      ctx.strokeStyle = row.colour;
      ctx.lineWidth = 2.5;
      for (let step = 0, j = i; step < TRAIL_STEPS && j > i - back; step++) {
        ctx.globalAlpha = 0.75 * (1 - step / TRAIL_STEPS);
        ctx.beginPath();
        const stop = Math.max(i - back, j - per);
        for (let m = j; m >= stop; m--) {
          const v = row.values[m];
          if (v == null) continue;
          const px = cx + (v - row.mid) * k;
          const py = row.y + ((frame.t - times[m]) / TRAIL_S) * fall;
          if (m === j) ctx.moveTo(px, py);
          else ctx.lineTo(px, py);
        }
        ctx.stroke();
        j = stop;
      }
      ctx.globalAlpha = 1;
      const now = valueAt(times, row.values, frame.t);
      const px = now == null ? null : cx + (now - row.mid) * k;
      this.drawn[row.key] = px;
      ctx.font = "600 13px system-ui, sans-serif";
      ctx.textBaseline = "middle";
      ctx.textAlign = "left";
      ctx.fillStyle = row.colour;
      ctx.fillText(row.name, 6, row.y);
      if (px != null) {
        ctx.beginPath();
        ctx.arc(px, row.y, 6.5, 0, 2 * Math.PI);
        ctx.fill();
        ctx.strokeStyle = "#fff";
        ctx.lineWidth = 1.5;
        ctx.stroke();
      }
    }
    if (!lesson.xhat) this.drawn.xhat = null;
    this.drawn.magnification = mag;
    this.drawn.pxPerM = k;
  }
}

/** A scale bar at the strip's top right: a round length (1, 2 or 5 × 10^k m) 30–120 px long. */
function scaleBar(ctx, width, k) {
  let length = 10;
  for (let e = -7; e <= 1 && length === 10; e++) {
    for (const m of [1, 2, 5]) {
      if (m * 10 ** e * k >= 30) {
        length = m * 10 ** e;
        break;
      }
    }
  }
  const px = length * k;
  const x1 = width - 8;
  const x0 = x1 - px;
  ctx.strokeStyle = INK;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.moveTo(x0, 10);
  ctx.lineTo(x1, 10);
  ctx.moveTo(x0, 6);
  ctx.lineTo(x0, 14);
  ctx.moveTo(x1, 6);
  ctx.lineTo(x1, 14);
  ctx.stroke();
  ctx.font = "11px system-ui, sans-serif";
  ctx.textAlign = "right";
  ctx.textBaseline = "top";
  ctx.fillStyle = INK;
  if (length !== barLength) {
    barLength = length;
    barText = lengthText(length);
  }
  ctx.fillText(barText, x0 - 4, 4);
}

let barLength = 0;
let barText = "";

function lengthText(m) {
  if (m >= 1) return `${sig(m, 1)} m`;
  if (m >= 1e-3) return `${Number((m * 1e3).toPrecision(1))} mm`;
  return `${Number((m * 1e6).toPrecision(1))} µm`;
}

function drawTracks(ctx, view, system, width) {
  const heights = [...new Set(system.bodies.map((b) => b.track_height || 0))];
  const floor = Math.min(...heights);
  for (const h of heights) {
    const y = view.toCanvas({ x: 0, y: h }).y;
    ctx.strokeStyle = INK;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(0, y);
    ctx.lineTo(width, y);
    ctx.stroke();
    if (h === floor) hatch(ctx, 0, y, width, 12);
  }
}

function hatch(ctx, x, y, w, h) {
  ctx.save();
  ctx.beginPath();
  ctx.rect(x, y, w, h);
  ctx.clip();
  ctx.strokeStyle = "#8b93a1";
  ctx.lineWidth = 1;
  ctx.beginPath();
  for (let i = x - h; i < x + w; i += 8) {
    ctx.moveTo(i, y + h);
    ctx.lineTo(i + h, y);
  }
  ctx.stroke();
  ctx.restore();
}

function drawWalls(ctx, view, system) {
  const floor = Math.min(...system.bodies.map((b) => b.track_height || 0));
  for (const anchor of system.anchors || []) {
    // the wall stands on the side away from what its springs pull towards
    const spring = system.springs.find((s) => s.ends.includes(anchor.id));
    const other = spring && system.bodies.find((b) => spring.ends.includes(b.id));
    const side = other && other.x < anchor.x ? 0 : -12;
    const p = view.toCanvas(anchor);
    const bottom = view.toCanvas({ x: 0, y: floor }).y;
    const top = Math.min(p.y - 24, bottom - 24);
    ctx.fillStyle = "#dfe3ea";
    ctx.fillRect(p.x + side, top, 12, bottom - top);
    hatch(ctx, p.x + side, top, 12, bottom - top);
    ctx.strokeStyle = INK;
    ctx.lineWidth = 1.5;
    ctx.strokeRect(p.x + side, top, 12, bottom - top);
    dot(ctx, p, 3.5, INK);
  }
}

function drawSpring(ctx, view, frame, spring, s) {
  const [a, b] = springEnds(frame.system, spring, frame.pose).map(view.toCanvas);
  const tension = frame.tensions[s] || 0;
  ctx.strokeStyle = tension > 1e-9 ? "#a33b2b" : tension < -1e-9 ? "#2b5ea3" : "#555";
  ctx.lineWidth = 1.8;
  ctx.lineJoin = "round";
  ctx.beginPath();
  zigzag(a, b, { coils: 9, width: 7, lead: 10 }).forEach((p, i) =>
    (i ? ctx.lineTo(p.x, p.y) : ctx.moveTo(p.x, p.y)));
  ctx.stroke();
  for (const p of [a, b]) dot(ctx, p, frame.show.dots ? 6 : 4, "#fff", INK);
}

function drawBody(ctx, view, frame, body, i, labels) {
  const { x, phi } = frame.pose(body.id);
  const c = view.toCanvas({ x, y: (body.track_height || 0) + body.radius });
  const r = body.radius * view.pxPerM;
  const colour = bodyColour(i);
  ctx.save();
  if (frame.flash.has(body.id)) {
    ctx.shadowColor = "#ff1a1a";
    ctx.shadowBlur = 18;
  } else if (frame.held && frame.held.has(body.id)) {
    // held at rest by rolling resistance: a grey glow, as a slip's red one
    ctx.shadowColor = "#4a5568";
    ctx.shadowBlur = 14;
  }
  if (body.shape === "slider") {
    ctx.fillStyle = tint(colour);
    ctx.strokeStyle = colour;
    ctx.lineWidth = 2;
    ctx.fillRect(c.x - r, c.y - r, 2 * r, 2 * r);
    ctx.strokeRect(c.x - r, c.y - r, 2 * r, 2 * r);
    ctx.restore();
    labels.push({ id: body.id, x: c.x, y: c.y - r - 4 });
    return;
  }
  const ring = body.shape === "hoop" || body.shape === "shell";
  ctx.beginPath();
  ctx.arc(c.x, c.y, r, 0, 2 * Math.PI);
  if (body.shape === "sphere") {
    const g = ctx.createRadialGradient(c.x - r / 3, c.y - r / 3, r / 8, c.x, c.y, r);
    g.addColorStop(0, "#fff");
    g.addColorStop(1, tint(colour));
    ctx.fillStyle = g;
  } else {
    ctx.fillStyle = ring ? "rgba(255,255,255,0.6)" : tint(colour);
  }
  ctx.fill();
  ctx.strokeStyle = colour;
  ctx.lineWidth = body.shape === "hoop" ? 5 : 2.5;
  ctx.stroke();
  ctx.restore();
  // spokes every 60°, turned by phi (clockwise on screen as in the world)
  ctx.strokeStyle = colour;
  ctx.lineWidth = 1.2;
  ctx.beginPath();
  for (let k = 0; k < 6; k++) {
    const a = phi + (k * Math.PI) / 3;
    ctx.moveTo(c.x, c.y);
    ctx.lineTo(c.x + r * Math.sin(a), c.y - r * Math.cos(a));
  }
  ctx.stroke();
  // the mark: the body's top point in its initial placement
  dot(ctx, { x: c.x + 0.78 * r * Math.sin(phi), y: c.y - 0.78 * r * Math.cos(phi) },
    Math.max(3, r * 0.12), INK);
  dot(ctx, c, 2.5, INK);
  labels.push({ id: body.id, x: c.x, y: c.y - r - 6 });
}

/** Each rolling body's percussion point P, at (1 + γ)R above its contact point on the vertical
 * through its centre (with `show.percussion`); their canvas positions go into `drawn` ({id:
 * {x, y}}, emptied otherwise). The mark is a fixed height that moves along with the body but
 * does not turn with it: the percussion property belongs to the line of action of a horizontal
 * pull at that height above the contact, whichever material point is there — a mark turning
 * with the body would leave that height as soon as it rolls and teach the wrong thing (that
 * one point of the body is special); a spring attached there at rest stays near it for small
 * swings, which is why friction vanishes to first order. */
function drawPercussion(ctx, view, frame, drawn) {
  for (const id of Object.keys(drawn)) delete drawn[id];
  if (!frame.show.percussion) return;
  for (const body of frame.system.bodies) {
    const h = percussionHeight(body);
    if (h == null) continue;
    const { x } = frame.pose(body.id);
    const p = view.toCanvas({ x, y: (body.track_height || 0) + h });
    drawn[body.id] = { x: p.x, y: p.y };
    ctx.save();
    ctx.strokeStyle = PERCUSSION_COLOUR;
    ctx.fillStyle = "#fff";
    ctx.lineWidth = 2;
    ctx.beginPath(); // a small open diamond with a tick on each side
    ctx.moveTo(p.x, p.y - 6);
    ctx.lineTo(p.x + 6, p.y);
    ctx.lineTo(p.x, p.y + 6);
    ctx.lineTo(p.x - 6, p.y);
    ctx.closePath();
    ctx.fill();
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(p.x - 12, p.y);
    ctx.lineTo(p.x - 7, p.y);
    ctx.moveTo(p.x + 7, p.y);
    ctx.lineTo(p.x + 12, p.y);
    ctx.stroke();
    ctx.font = "600 11px system-ui, sans-serif";
    ctx.textAlign = "left";
    ctx.textBaseline = "middle";
    ctx.fillStyle = PERCUSSION_COLOUR;
    ctx.fillText("P", p.x + 14, p.y);
    ctx.restore();
  }
}

const PERCUSSION_COLOUR = "#0b7a55";

function drawGhosts(ctx, view, frame) {
  ctx.save();
  ctx.setLineDash([5, 4]);
  frame.system.bodies.forEach((body, i) => {
    const x = frame.ghosts[body.id];
    if (x == null) return;
    const c = view.toCanvas({ x, y: (body.track_height || 0) + body.radius });
    ctx.strokeStyle = bodyColour(i);
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.arc(c.x, c.y, body.radius * view.pxPerM, 0, 2 * Math.PI);
    ctx.stroke();
  });
  ctx.restore();
}

function drawMarkers(ctx, view, frame) {
  const floor = Math.min(...frame.system.bodies.map((b) => b.track_height || 0));
  const y = view.toCanvas({ x: 0, y: floor }).y;
  const marks = [{ x: frame.cm, text: "CM", colour: CM_COLOUR }];
  if (frame.xhat != null) marks.push({ x: frame.xhat, text: "X̂", colour: XHAT_COLOUR });
  marks.forEach((m, k) => {
    if (m.x == null) return;
    const px = view.toCanvas({ x: m.x, y: 0 }).x;
    ctx.fillStyle = m.colour;
    ctx.beginPath();
    ctx.moveTo(px, y + 1);
    ctx.lineTo(px - 8, y + 14);
    ctx.lineTo(px + 8, y + 14);
    ctx.closePath();
    ctx.fill();
    ctx.font = "600 13px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.textBaseline = "top";
    ctx.fillStyle = "#fff";
    ctx.fillRect(px - 12, y + 15 + k * 14, 24, 14);
    ctx.fillStyle = m.colour;
    ctx.fillText(m.text, px, y + 15 + k * 14);
  });
}

/** The force arrows at their kind's fixed scale (px per N); an arrow longer than `maxPx` is
 * cut there and ends in a bar. Records each arrow's drawn (signed) length in `drawn`; labels
 * the values of the bodies in `frame.labelled` (or of every body with `show.values`). */
function drawForces(ctx, view, frame, drawn, maxPx) {
  const k = frame.forceScale;
  const all = frame.show.values;
  drawn.spring.length = 0;
  drawn.labels.length = 0;
  if (frame.show.spring) {
    frame.system.springs.forEach((spring, s) => {
      const ends = springEnds(frame.system, spring, frame.pose);
      const dx = ends[1].x - ends[0].x;
      const dy = ends[1].y - ends[0].y;
      const l = Math.hypot(dx, dy) || 1;
      const t = frame.tensions[s] || 0;
      spring.ends.forEach((id, j) => {
        if (!frame.system.bodies.some((b) => b.id === id)) return;
        // force on end a: +T e, on end b: −T e (docs/physics.md §2)
        const sign = j === 0 ? 1 : -1;
        const p = view.toCanvas(ends[j]);
        const length = arrow(ctx, p, sign * t * dx / l * k.spring, -sign * t * dy / l * k.spring,
          FORCE_COLOURS.spring, maxPx);
        drawn.spring.push(length);
      });
      // the tension once per spring, over its middle (positive: stretched)
      const [a, b] = spring.ends;
      if (all || frame.labelled.has(a) || frame.labelled.has(b)) {
        const m = view.toCanvas({ x: (ends[0].x + ends[1].x) / 2, y: (ends[0].y + ends[1].y) / 2 });
        valueLabel(ctx, drawn, frame.labelled.has(a) || !frame.labelled.has(b) ? a : b, m.x,
          m.y - 16 - (s % 2) * 15, `T = ${signed(t)} N`, FORCE_COLOURS.spring);
      }
    });
  }
  frame.system.bodies.forEach((body, index) => {
    const { x } = frame.pose(body.id);
    const contact = frame.contact(body.id);
    drawn.friction[body.id] = 0;
    drawn.normal[body.id] = 0;
    if (!contact) return;
    const stagger = (index % 2) * 15; // neighbours' labels on two levels
    const p = view.toCanvas({ x, y: body.track_height || 0 });
    const label = all || frame.labelled.has(body.id);
    if (frame.show.friction && body.shape !== "slider") {
      drawn.friction[body.id] = arrow(ctx, p, contact.f * k.friction, 0, FORCE_COLOURS.friction, maxPx);
      if (label) {
        const right = contact.f >= 0;
        valueLabel(ctx, drawn, body.id, p.x + (right ? 1 : -1) * (Math.abs(drawn.friction[body.id]) + 6), p.y + 14 + stagger,
          `f = ${signed(contact.f)} N`, FORCE_COLOURS.friction, right ? "left" : "right");
      }
    }
    if (frame.show.normal) {
      drawn.normal[body.id] = arrow(ctx, p, 0, -contact.N * k.normal, FORCE_COLOURS.normal, maxPx);
      if (label) {
        valueLabel(ctx, drawn, body.id, p.x + 6, p.y - Math.abs(drawn.normal[body.id]) - 2 - stagger,
          `N = ${sig(contact.N, 3)} N`, FORCE_COLOURS.normal, "left");
      }
    }
  });
}

function signed(v) {
  return `${v < 0 ? "−" : "+"}${sig(Math.abs(v), 3)}`;
}

/** A value label (its text also kept in `drawn.labels` as "<body id>: <text>", for tests). */
function valueLabel(ctx, drawn, id, x, y, text, colour, align = "center") {
  drawn.labels.push(`${id}: ${text}`);
  ctx.font = "600 12px system-ui, sans-serif";
  ctx.textAlign = align;
  ctx.textBaseline = "middle";
  const w = ctx.measureText(text).width;
  // kept on the canvas (a body near its edge would cut its label)
  const room = ctx.canvas.width / (window.devicePixelRatio || 1);
  const wanted = align === "left" ? x : align === "right" ? x - w : x - w / 2;
  const left = Math.max(3, Math.min(wanted, room - w - 3));
  ctx.fillStyle = "rgba(255,255,255,0.88)";
  ctx.fillRect(left - 3, y - 8, w + 6, 16);
  ctx.fillStyle = colour;
  ctx.textAlign = "left";
  ctx.fillText(text, left, y);
}

/** An arrow from p by (dx, dy) px, cut at `maxPx` (then it ends in a bar instead of a head);
 * returns its drawn length, signed as dx (or as −dy for a vertical arrow): 0 below 1 px. */
function arrow(ctx, p, dx, dy, colour, maxPx) {
  const full = Math.hypot(dx, dy);
  if (!(full >= 1)) return 0;
  const length = Math.min(full, maxPx);
  const ux = dx / full;
  const uy = dy / full;
  const head = Math.min(9, length * 0.6);
  const tip = { x: p.x + ux * length, y: p.y + uy * length };
  ctx.strokeStyle = colour;
  ctx.fillStyle = colour;
  ctx.lineWidth = 2.5;
  ctx.beginPath();
  ctx.moveTo(p.x, p.y);
  ctx.lineTo(tip.x - ux * head * 0.8, tip.y - uy * head * 0.8);
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(tip.x, tip.y);
  ctx.lineTo(tip.x - ux * head - uy * head * 0.5, tip.y - uy * head + ux * head * 0.5);
  ctx.lineTo(tip.x - ux * head + uy * head * 0.5, tip.y - uy * head - ux * head * 0.5);
  ctx.closePath();
  ctx.fill();
  if (length < full) { // cut: two bars across the shaft
    for (const back of [14, 19]) {
      const c = { x: tip.x - ux * back, y: tip.y - uy * back };
      ctx.beginPath();
      ctx.moveTo(c.x - uy * 7, c.y + ux * 7);
      ctx.lineTo(c.x + uy * 7, c.y - ux * 7);
      ctx.stroke();
    }
  }
  return dx !== 0 ? Math.sign(dx) * length : -Math.sign(dy) * length;
}

function dot(ctx, p, r, fill, stroke) {
  ctx.beginPath();
  ctx.arc(p.x, p.y, r, 0, 2 * Math.PI);
  ctx.fillStyle = fill;
  ctx.fill();
  if (stroke) {
    ctx.strokeStyle = stroke;
    ctx.lineWidth = 1.5;
    ctx.stroke();
  }
}

const CLOCK_FONT = "600 15px system-ui, sans-serif";
const LABEL_FONT = "12px system-ui, sans-serif";
/** A body label's box height (px), the rows it may be raised by, its horizontal margin. */
const LABEL_H = 14;
const LABEL_ROWS = 4;
const LABEL_PAD = 2;

const widths = new Map(); // font + text → measured width (px): measured once
function textWidth(ctx, font, text) {
  const key = `${font}|${text}`;
  let w = widths.get(key);
  if (w === undefined) {
    ctx.font = font;
    w = ctx.measureText(text).width;
    widths.set(key, w);
  }
  return w;
}

/** A shorter label: the id's first letter and its trailing number ("cylinder8" → "c8"), else
 * its first three characters. */
function shortLabel(id) {
  const number = /\d+$/.exec(id);
  return number ? `${id[0]}${number[0]}` : id.slice(0, 3);
}

function overlaps(a, b) {
  return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

/** Lay out and draw the body labels `wanted` ([{id, x, y}]: centred at x, bottom at y) so that
 * no two overlap, nor the clock: from left to right, each on the lowest free row above its body
 * (a raised label gets a leader line down to it), else shortened, else left out. What is drawn
 * goes into `placed` ([{id, text, x, y, w, h, cx}]: the box, CSS px, and the body's centre x). */
function drawBodyLabels(ctx, wanted, placed, width, clockBox) {
  placed.length = 0;
  const order = [...wanted].sort((a, b) => a.x - b.x);
  ctx.font = LABEL_FONT;
  ctx.textAlign = "left";
  ctx.textBaseline = "bottom";
  for (const want of order) {
    let spot = null;
    for (const text of want.id.length > 3 ? [want.id, shortLabel(want.id)] : [want.id]) {
      const w = textWidth(ctx, LABEL_FONT, text) + 2 * LABEL_PAD;
      const x = Math.max(0, Math.min(width - w, want.x - w / 2));
      for (let row = 0; row < LABEL_ROWS && !spot; row++) {
        const box = { id: want.id, text, x, y: want.y - LABEL_H * (row + 1), w, h: LABEL_H, cx: want.x };
        if (box.y < 0) break;
        if (!overlaps(box, clockBox) && !placed.some((p) => overlaps(p, box))) spot = box;
      }
      if (spot) break;
    }
    if (!spot) continue;
    placed.push(spot);
    if (spot.y + spot.h < want.y - 1) { // raised: a leader line down to its body
      ctx.strokeStyle = "#9aa4b2";
      ctx.lineWidth = 1;
      ctx.beginPath();
      ctx.moveTo(want.x, spot.y + spot.h);
      ctx.lineTo(want.x, want.y);
      ctx.stroke();
    }
    ctx.fillStyle = INK;
    ctx.fillText(spot.text, spot.x + LABEL_PAD, spot.y + spot.h - 1);
  }
}

function tint(hex) {
  return `${hex}33`;
}
