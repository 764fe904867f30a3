import { test } from "node:test";
import assert from "node:assert/strict";
import { positionSeries, withMeasured } from "../../src/rollspring/web/static/js/series.js";
import { freeChoices, withError } from "../../src/rollspring/web/static/js/lab.js";

test("withMeasured puts the model's and the table's columns on the union of their times", () => {
  const merged = withMeasured([[0, 1, 2], [10, 11, 12]], [0.5, 1, 3], [[5, 6, 7]]);
  assert.deepEqual(merged, [
    [0, 0.5, 1, 2, 3],
    [10, null, 11, 12, null],
    [null, 5, 6, null, 7],
  ]);
});

test("positionSeries draws a measured table as markers, in the bodies' own reference", () => {
  const run = { t: [0, 1], bodies: { hoop: { x: [0.1, 0.2] } }, cm_x: [0.1, 0.2], stationary_x: null, linear: null };
  const measured = { t: [0.5], bodies: { hoop: { x: [0.15] }, other: { x: [9] } } };
  const absolute = positionSeries(run, null, { absolute: true, measured });
  assert.deepEqual(absolute.series.map((s) => s.label), ["hoop x", "CM", "hoop data"]);
  assert.equal(absolute.series[2].markers, true);
  assert.equal(absolute.series[0].spanGaps, true);
  assert.deepEqual(absolute.data[0], [0, 0.5, 1]);
  assert.deepEqual(absolute.data[3], [null, 0.15, null]);
  const fromStart = positionSeries(run, null, { measured });
  assert.ok(Math.abs(fromStart.data[3][1] - 50) < 1e-9); // (0.15 − x(0)) in mm
  assert.equal(positionSeries(run, null, {}).series.length, 2); // no table: nothing added
});

test("freeChoices offers each spring's stiffness and damping ticked, masses and C_rr not", () => {
  const system = { bodies: [{ id: "a", shape: "hoop" }, { id: "s", shape: "slider" }],
    springs: [{ ends: ["a", "s"] }] };
  const choices = freeChoices(system);
  assert.deepEqual(choices.filter((c) => c.checked).map((c) => c.path),
    ["springs.0.stiffness", "springs.0.damping"]);
  assert.deepEqual(choices.filter((c) => !c.checked).map((c) => c.path),
    ["bodies.a.mass", "bodies.a.rolling_resistance", "bodies.s.mass"]);
});

test("withError writes the value to the standard error's second significant digit", () => {
  assert.equal(withError(99.99746, 0.22393), "100.00 ± 0.22");
  assert.equal(withError(99.9849, 0.22393), "99.98 ± 0.22");
  assert.equal(withError(0.50054, 0.020527), "0.501 ± 0.021");
  assert.equal(withError(1.5, null), "1.50000");
  assert.equal(withError(null, 1), "—");
});
