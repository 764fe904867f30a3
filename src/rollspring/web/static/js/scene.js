// The animation canvas: tracks, walls, rolling bodies with spokes and a mark, zigzag springs,
// force arrows to scale, the CM and X̂ on the floor, ghost bodies of the linear solution, a
// clock. `Scene.draw(frame)` paints one instant; what the instant is comes from main.js.

import { makeView, springEnds, zigzag } from "./geometry.js";
import { bodyColour } from "./series.js";
import { clockText } from "./timeline.js";

const INK = "#1d2430";
const FORCE_COLOURS = { spring: "#8a4fbf", friction: "#c2502b", normal: "#2e8b57" };

/** The canvas and its view of the world window; handles the device pixel ratio. */
export class Scene {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext("2d");
    this.window = { xmin: -0.5, xmax: 0.5, ymin: -0.1, ymax: 0.3 };
    this.resize();
  }

  /** Fit the canvas to its CSS box; returns true when its size changed. */
  resize() {
    const box = this.canvas.getBoundingClientRect();
    const width = Math.max(1, Math.round(box.width));
    const height = Math.max(1, Math.round(box.height));
    const ratio = window.devicePixelRatio || 1;
    const changed = width !== this.width || height !== this.height;
    this.width = width;
    this.height = height;
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(height * ratio);
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    this.setWindow(this.window);
    return changed;
  }

  /** Show the world window `w` ({xmin, xmax, ymin, ymax}, metres). */
  setWindow(w) {
    this.window = w;
    this.view = makeView(w, this.width, this.height);
    this.canvas.dataset.pxPerM = String(this.view.pxPerM);
  }

  /** Paint one instant. `frame`: {system, pose(id) → {x, phi}, tensions[], contact(id) →
   * {f, N}, cm, xhat (or null), t, ghosts {id: x} or null, flash Set of ids, show {spring,
   * friction, normal, markers}, forceScale (px per N)}. */
  draw(frame) {
    const { ctx, view } = this;
    ctx.clearRect(0, 0, this.width, this.height);
    drawTracks(ctx, view, frame.system, this.width);
    drawWalls(ctx, view, frame.system);
    if (frame.ghosts) drawGhosts(ctx, view, frame);
    frame.system.springs.forEach((spring, s) => drawSpring(ctx, view, frame, spring, s));
    frame.system.bodies.forEach((body, i) => drawBody(ctx, view, frame, body, i));
    if (frame.show.markers) drawMarkers(ctx, view, frame);
    drawForces(ctx, view, frame);
    ctx.fillStyle = INK;
    ctx.font = "600 15px system-ui, sans-serif";
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    ctx.fillText(clockText(frame.t), 10, 8);
  }
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

function drawBody(ctx, view, frame, body, i) {
  const { x, phi } = frame.pose(body.id);
  const c = view.toCanvas({ x, y: (body.track_height || 0) + body.radius });
  const r = body.radius * view.pxPerM;
  const colour = bodyColour(i);
  ctx.save();
  if (frame.flash.has(body.id)) {
    ctx.shadowColor = "#ff1a1a";
    ctx.shadowBlur = 18;
  }
  if (body.shape === "slider") {
    ctx.fillStyle = tint(colour);
    ctx.strokeStyle = colour;
    ctx.lineWidth = 2;
    ctx.fillRect(c.x - r, c.y - r, 2 * r, 2 * r);
    ctx.strokeRect(c.x - r, c.y - r, 2 * r, 2 * r);
    ctx.restore();
    label(ctx, body.id, c.x, c.y - r - 4);
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
  label(ctx, body.id, c.x, c.y - r - 6);
}

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
  const marks = [{ x: frame.cm, text: "CM", colour: "#555" }];
  if (frame.xhat != null) marks.push({ x: frame.xhat, text: "X̂", colour: "#000" });
  marks.forEach((m, k) => {
    if (m.x == null) return;
    const px = view.toCanvas({ x: m.x, y: 0 }).x;
    ctx.fillStyle = m.colour;
    ctx.beginPath();
    ctx.moveTo(px, y + 2);
    ctx.lineTo(px - 6, y + 12);
    ctx.lineTo(px + 6, y + 12);
    ctx.closePath();
    ctx.fill();
    ctx.font = "12px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.textBaseline = "top";
    ctx.fillStyle = "#fff";
    ctx.fillRect(px - 11, y + 13 + k * 13, 22, 13);
    ctx.fillStyle = m.colour;
    ctx.fillText(m.text, px, y + 13 + k * 13);
  });
}

function drawForces(ctx, view, frame) {
  const k = frame.forceScale;
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
        arrow(ctx, p, { x: sign * t * dx / l * k, y: -sign * t * dy / l * k }, FORCE_COLOURS.spring);
      });
    });
  }
  for (const body of frame.system.bodies) {
    const { x } = frame.pose(body.id);
    const contact = frame.contact(body.id);
    if (!contact) continue;
    const p = view.toCanvas({ x, y: body.track_height || 0 });
    if (frame.show.friction && body.shape !== "slider") {
      arrow(ctx, p, { x: contact.f * k, y: 0 }, FORCE_COLOURS.friction);
    }
    if (frame.show.normal) arrow(ctx, p, { x: 0, y: -contact.N * k }, FORCE_COLOURS.normal);
  }
}

/** Largest force a frame can show (N), for the arrow scale. */
export function largestForce(run, show) {
  let max = 0;
  const take = (values) => {
    for (const v of values) if (v != null) max = Math.max(max, Math.abs(v));
  };
  if (show.spring) run.springs.forEach((s) => take(s.tension));
  for (const b of Object.values(run.bodies)) {
    if (show.friction) take(b.friction);
    if (show.normal) take(b.normal);
  }
  return max;
}


function arrow(ctx, p, d, colour) {
  const length = Math.hypot(d.x, d.y);
  if (length < 1) return;
  const ux = d.x / length;
  const uy = d.y / length;
  const head = Math.min(9, length * 0.6);
  const tip = { x: p.x + d.x, y: p.y + d.y };
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

function label(ctx, text, x, y) {
  ctx.font = "12px system-ui, sans-serif";
  ctx.textAlign = "center";
  ctx.textBaseline = "bottom";
  ctx.fillStyle = INK;
  ctx.fillText(text, x, y);
}

function tint(hex) {
  return `${hex}33`;
}
