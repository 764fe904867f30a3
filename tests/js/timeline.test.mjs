import { test } from "node:test";
import assert from "node:assert/strict";
import { advance, clockText, outputInterval, sampleIndex, stepForward, valueAt }
  from "../../src/rollspring/web/static/js/timeline.js";
import { roundTo, sig, signedMetres } from "../../src/rollspring/web/static/js/format.js";

const times = Array.from({ length: 601 }, (_, i) => (10 * i) / 600);

test("Step advances by exactly one output interval and stops at the end", () => {
  const dt = outputInterval(times);
  assert.equal(dt, 10 / 600);
  assert.equal(stepForward(0, dt, 10), dt);
  assert.equal(stepForward(9.99, dt, 10), 10);
});

test("playback advances with wall time × speed and reports the end", () => {
  assert.deepEqual(advance(1, 500, 0.5, 10), { t: 1.25, ended: false });
  assert.deepEqual(advance(9.9, 1000, 2, 10), { t: 10, ended: true });
});

test("samples: index of the last sample at or before t; linear interpolation between", () => {
  assert.equal(sampleIndex(times, 0), 0);
  assert.equal(sampleIndex(times, 10), 600);
  assert.equal(sampleIndex(times, 0.02), 1);
  assert.equal(sampleIndex(times, -1), 0);
  const values = times.map((t) => 2 * t);
  assert.ok(Math.abs(valueAt(times, values, 0.025) - 0.05) < 1e-12);
  assert.equal(valueAt(times, values, 20), 20);
  assert.equal(valueAt([0, 1], [null, 1], 0.5), null);
});

test("clock and number formats", () => {
  assert.equal(clockText(1 / 60), "t = 0.0167 s");
  assert.equal(sig(0.02), "0.02000");
  assert.equal(sig(10.801234497, 6), "10.8012");
  assert.equal(sig("inf"), "∞");
  assert.equal(sig(null), "—");
  assert.equal(signedMetres(0.02), "+0.02000 m");
  assert.equal(signedMetres(-0.009), "−0.009000 m");
  assert.equal(signedMetres(0), "0 m");
  assert.equal(roundTo(0.49 + 0.02, 1e-6), 0.51);
});
