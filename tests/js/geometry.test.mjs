import { test } from "node:test";
import assert from "node:assert/strict";
import { attachmentFromPoint, attachmentPolar, bodyPoint, makeView, snapDrag, springEnds, zigzag, worldBounds }
  from "../../src/rollspring/outputs/js/geometry.js";

const close = (a, b, tol = 1e-12) => assert.ok(Math.abs(a - b) <= tol, `${a} vs ${b}`);
const hoop = { id: "hoop", shape: "hoop", mass: 1, radius: 0.1, x: 0 };

test("attachment forms: centre, height on the vertical, radius and angle clockwise from up", () => {
  assert.deepEqual(attachmentPolar(hoop, {}), { r: 0, alpha: 0 });
  close(attachmentPolar(hoop, { height: 0.15 }).r, 0.05);
  assert.equal(attachmentPolar(hoop, { height: 0.15 }).alpha, 0);
  close(attachmentPolar(hoop, { height: 0.05 }).r, 0.05);
  close(attachmentPolar(hoop, { height: 0.05 }).alpha, Math.PI);
  close(attachmentPolar(hoop, { radius: 0.1, angle: 90 }).alpha, Math.PI / 2);
});

test("a point fixed in a rolling body follows (M1): clockwise rotation moves the top to the right", () => {
  const top = attachmentPolar(hoop, { radius: 0.1, angle: 0 });
  const p = bodyPoint(hoop, 0.3, Math.PI / 2, top);
  close(p.x, 0.4);
  close(p.y, 0.1);
});

test("attachmentFromPoint inverts the polar form at rest, rounded, within the body", () => {
  assert.deepEqual(attachmentFromPoint(hoop, { x: 0.05, y: 0.1 }), { radius: 0.05, angle: 90 });
  assert.deepEqual(attachmentFromPoint(hoop, { x: 0, y: 0.3 }), { radius: 0.1, angle: 0 });
  assert.deepEqual(attachmentFromPoint(hoop, { x: -0.05, y: 0.1 }), { radius: 0.05, angle: 270 });
  assert.deepEqual(attachmentFromPoint(hoop, { x: 0.001, y: 0.1 }), {});
});

test("spring ends: anchors where they are, body ends at their attachment", () => {
  const system = { bodies: [hoop], anchors: [{ id: "wall", x: -0.5, y: 0.1 }],
    springs: [{ ends: ["wall", "hoop"], stiffness: 100, at: [{}, { radius: 0.1, angle: 270 }] }] };
  const [a, b] = springEnds(system, system.springs[0], () => ({ x: 0, phi: 0 }));
  assert.deepEqual(a, { x: -0.5, y: 0.1 });
  close(b.x, -0.1);
  close(b.y, 0.1);
});

test("zigzag: leads at both ends, teeth alternate at a fixed width and stretch with the length", () => {
  const short = zigzag({ x: 0, y: 0 }, { x: 100, y: 0 }, { coils: 4, width: 5, lead: 10 });
  const long = zigzag({ x: 0, y: 0 }, { x: 200, y: 0 }, { coils: 4, width: 5, lead: 10 });
  assert.equal(short.length, 2 + 8 + 2);
  assert.deepEqual(short[0], { x: 0, y: 0 });
  assert.deepEqual(short.at(-1), { x: 100, y: 0 });
  assert.deepEqual(short.slice(2, -2).map((p) => p.y), [5, -5, 5, -5, 5, -5, 5, -5]);
  const pitch = (pts) => pts[3].x - pts[2].x;
  close(pitch(long) / pitch(short), 180 / 80);
  assert.deepEqual(zigzag({ x: 0, y: 0 }, { x: 15, y: 0 }, { lead: 10 }), [{ x: 0, y: 0 }, { x: 15, y: 0 }]);
});

test("zigzag at the joints (the report's player): 2·coils − 1 teeth between equal pieces", () => {
  const pts = zigzag({ x: 0, y: 0 }, { x: 100, y: 0 }, { coils: 4, width: 5, lead: 10, placement: "joints" });
  assert.equal(pts.length, 2 + 7 + 2);
  assert.deepEqual(pts.slice(2, -2).map((p) => p.y), [5, -5, 5, -5, 5, -5, 5]);
  assert.deepEqual(pts.slice(2, -2).map((p) => p.x), [20, 30, 40, 50, 60, 70, 80]);
  assert.deepEqual(pts[1], { x: 10, y: 0 });
  assert.deepEqual(pts.at(-2), { x: 90, y: 0 });
  const middles = zigzag({ x: 0, y: 0 }, { x: 100, y: 0 }, { coils: 4, width: 5, lead: 10 });
  assert.deepEqual(middles.slice(2, -2).map((p) => p.x), [15, 25, 35, 45, 55, 65, 75, 85]);
});

test("the view keeps equal scales and round-trips world ↔ canvas", () => {
  const view = makeView({ xmin: -1, xmax: 1, ymin: 0, ymax: 0.5 }, 400, 200);
  close(view.pxPerM, 200);
  const q = view.toCanvas({ x: 0.25, y: 0.1 });
  const p = view.toWorld(q);
  close(p.x, 0.25);
  close(p.y, 0.1);
  assert.ok(view.toCanvas({ x: 0, y: 0.4 }).y < view.toCanvas({ x: 0, y: 0 }).y, "y up on the canvas");
});

test("world bounds hold every body over its path and every anchor", () => {
  const w = worldBounds({ bodies: [hoop], anchors: [{ id: "w", x: -1, y: 0.1 }] }, { hoop: [0, 2] });
  assert.ok(w.xmin < -1 && w.xmax > 2.1 && w.ymin < 0 && w.ymax > 0.2);
});

test("a drag snaps to the 1 mm grid", () => {
  close(snapDrag(20.4, 1000), 0.02);
  close(snapDrag(-3.6, 1000), -0.004);
  close(snapDrag(10, 500), 0.02);
});
