// Pure geometry of the drawn scene (no DOM): attachment points, spring zigzags and the
// world-to-canvas view. World: x right, y up, metres; angles clockwise from straight up
// (docs/physics.md (M1)); canvas: x right, y down, CSS pixels. The outputs layer's, shared by the
// report's player (rollspring/outputs/report/assets/player.js), which inlines this module into
// the report page, and the web page, which is served it as /static/js/geometry.js
// (rollspring.web.app): keep it free of imports and of anything but top-level
// `export function` / `export const`.

const DEG = Math.PI / 180;

/** Polar form {r, alpha (rad, clockwise from up)} of an attachment `at` on `body`
 * ({} centre, {height} on the centre vertical, {radius, angle}). */
export function attachmentPolar(body, at) {
  if (!at || (at.height == null && at.radius == null)) return { r: 0, alpha: 0 };
  if (at.height != null) {
    const dy = at.height - body.radius;
    return { r: Math.abs(dy), alpha: dy >= 0 ? 0 : Math.PI };
  }
  return { r: at.radius, alpha: (at.angle || 0) * DEG };
}

/** World position of a point fixed in a body whose centre is at x and turned by phi (M1). */
export function bodyPoint(body, x, phi, polar) {
  const theta = polar.alpha + phi;
  const cy = (body.track_height || 0) + body.radius;
  return { x: x + polar.r * Math.sin(theta), y: cy + polar.r * Math.cos(theta) };
}

/** The attachment {radius, angle} (angle in degrees, clockwise from up, rounded to 1 degree;
 * radius rounded to 1 mm and at most the body's radius) of the world point p for a body at rest
 * at its initial placement; {} when p is within 2 mm of the centre. */
export function attachmentFromPoint(body, p) {
  const cy = (body.track_height || 0) + body.radius;
  const dx = p.x - body.x;
  const dy = p.y - cy;
  const r = Math.min(Math.round(Math.hypot(dx, dy) * 1000) / 1000, body.radius);
  if (r < 0.002) return {};
  let angle = Math.round(Math.atan2(dx, dy) / DEG);
  if (angle < 0) angle += 360;
  return { radius: r, angle };
}

/** The end points of a spring: for each end a body (with its attachment) or an anchor. `pose(id)`
 * gives {x, phi} of a body. */
export function springEnds(system, spring, pose) {
  const bodies = new Map(system.bodies.map((b) => [b.id, b]));
  const anchors = new Map((system.anchors || []).map((a) => [a.id, a]));
  return spring.ends.map((id, j) => {
    const anchor = anchors.get(id);
    if (anchor) return { x: anchor.x, y: anchor.y };
    const body = bodies.get(id);
    const at = spring.at ? spring.at[j] : {};
    const { x, phi } = pose(id);
    return bodyPoint(body, x, phi, attachmentPolar(body, at));
  });
}

/** Points of a zigzag spring from a to b (canvas or world units alike): straight leads of
 * `lead` at both ends and zigzag teeth of half-width `width` between them, so the teeth
 * stretch and squeeze with the length while the width stays. The part between the leads is cut
 * into 2·`coils` equal pieces; `placement` "middles" (the page) puts a tooth at the middle of
 * each piece, "joints" (the report's player) one at each of the 2·`coils` − 1 joints between
 * them; the first tooth is on the left of a → b. Shorter than both leads: a line. One drawing
 * for the page (scene.js) and the report (its player inlines this module). */
export function zigzag(a, b, { coils = 8, width = 6, lead = 8, placement = "middles" } = {}) {
  const dx = b.x - a.x;
  const dy = b.y - a.y;
  const length = Math.hypot(dx, dy);
  if (length <= 2 * lead || length === 0) return [a, b];
  const ux = dx / length;
  const uy = dy / length;
  const nx = -uy;
  const ny = ux;
  const body = length - 2 * lead;
  const points = [a, { x: a.x + ux * lead, y: a.y + uy * lead }];
  const pieces = 2 * coils;
  const joints = placement === "joints";
  for (let i = joints ? 1 : 0; i < pieces; i++) {
    const s = lead + (joints ? body * i / pieces : body * (i + 0.5) / pieces);
    const side = i % 2 === (joints ? 1 : 0) ? width : -width;
    points.push({ x: a.x + ux * s + nx * side, y: a.y + uy * s + ny * side });
  }
  points.push({ x: b.x - ux * lead, y: b.y - uy * lead }, b);
  return points;
}

/** The world window {xmin, xmax, ymin, ymax} that holds the system: every body over its whole
 * trajectory `xs` ({id: [x...]}, optional), every anchor, the floor, with a margin. */
export function worldBounds(system, xs = {}) {
  let xmin = Infinity;
  let xmax = -Infinity;
  let ymin = 0;
  let ymax = 0;
  for (const b of system.bodies) {
    const path = xs[b.id] && xs[b.id].length ? xs[b.id] : [b.x];
    for (const x of [b.x, ...path]) {
      if (x == null) continue;
      xmin = Math.min(xmin, x - b.radius);
      xmax = Math.max(xmax, x + b.radius);
    }
    const h = b.track_height || 0;
    ymin = Math.min(ymin, h);
    ymax = Math.max(ymax, h + 2 * b.radius);
  }
  for (const a of system.anchors || []) {
    xmin = Math.min(xmin, a.x);
    xmax = Math.max(xmax, a.x);
    ymin = Math.min(ymin, a.y);
    ymax = Math.max(ymax, a.y);
  }
  const margin = 0.12 * Math.max(xmax - xmin, ymax - ymin, 0.1);
  return { xmin: xmin - margin, xmax: xmax + margin, ymin: ymin - margin, ymax: ymax + margin };
}

/** The view that shows the world window `w` in a canvas of `width` × `height` CSS px with equal
 * scales, centred: {pxPerM, toCanvas(p), toWorld(q)}. */
export function makeView(w, width, height) {
  const pxPerM = Math.min(width / (w.xmax - w.xmin), height / (w.ymax - w.ymin));
  const cx = (w.xmin + w.xmax) / 2;
  const cy = (w.ymin + w.ymax) / 2;
  const ox = width / 2 - cx * pxPerM;
  const oy = height / 2 + cy * pxPerM;
  return {
    pxPerM,
    toCanvas: (p) => ({ x: ox + p.x * pxPerM, y: oy - p.y * pxPerM }),
    toWorld: (q) => ({ x: (q.x - ox) / pxPerM, y: (oy - q.y) / pxPerM }),
  };
}

/** The displacement (m) of a drag by `dxPx` canvas px, on the drag grid `grid` (default 1 mm). */
export function snapDrag(dxPx, pxPerM, grid = 0.001) {
  return Math.round(dxPx / pxPerM / grid) * grid;
}
