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

test("Step back goes to the previous output time, never below 0", async () => {
  const { stepBackward } = await import("../../src/rollspring/web/static/js/timeline.js");
  const dt = outputInterval(times);
  assert.equal(stepBackward(times, times[3]), times[2]);
  assert.equal(stepBackward(times, times[3] + dt / 3), times[3]);
  assert.equal(stepBackward(times, times[1]), 0);
  assert.equal(stepBackward(times, 0), 0);
  assert.equal(stepBackward(times, 10), times[599]);
});

test("the run length is a number of seconds within the page's bounds", async () => {
  const { parseDuration, outputsFor, DURATION_MAX } = await import("../../src/rollspring/web/static/js/timeline.js");
  assert.deepEqual(parseDuration("4"), { value: 4 });
  assert.deepEqual(parseDuration(" 2.5 s"), { value: 2.5 });
  assert.match(parseDuration("abc").error, /number of seconds/);
  assert.match(parseDuration("").error, /number of seconds/);
  assert.match(parseDuration("-3").error, /number of seconds/);
  assert.match(parseDuration("0.5").error, /from 1 s to 60 s/);
  assert.match(parseDuration(String(DURATION_MAX + 1)).error, /not 61/);
  assert.equal(outputsFor(10), 601);
  assert.equal(outputsFor(2.5), 151);
  assert.ok(outputsFor(DURATION_MAX) <= 20000); // the server's MAX_OUTPUTS
});
