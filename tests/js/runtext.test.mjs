import { test } from "node:test";
import assert from "node:assert/strict";
import { canonical, fileStem, maxRatio, peakFriction, rollingText }
  from "../../src/rollspring/web/static/js/runtext.js";

const hoop = { id: "hoop", shape: "hoop" };
const cylinder = { id: "cylinder", shape: "cylinder" };
const m1 = { id: "m1", shape: "slider" };
const m2 = { id: "m2", shape: "slider" };

test("sliders slide, they do not roll: no -Infinity (issue 26)", () => {
  assert.equal(maxRatio({ max_friction_ratio: {} }), null);
  assert.equal(rollingText([m1, m2], maxRatio({ max_friction_ratio: {} })),
    "the bodies are sliders: they slide without friction, none rolls");
  assert.equal(rollingText([hoop, m2], 0.25),
    "every rolling body rolls without slipping, max |f|/(μs N) = 0.250; "
    + "m2 slides without friction (a slider does not roll)");
  assert.equal(rollingText([hoop, cylinder], 0.0512),
    "every body rolls without slipping, max |f|/(μs N) = 0.0512");
});

test("the largest friction ratio skips bodies without one", () => {
  assert.equal(maxRatio({ max_friction_ratio: { hoop: 0.2, cylinder: null, m: 0.5 } }), 0.5);
  assert.equal(maxRatio({ max_friction_ratio: 0.3 }), 0.3);
  assert.equal(maxRatio({ max_friction_ratio: null }), null);
});

test("each body's peak |friction| over a run, nulls skipped", () => {
  const run = { bodies: { hoop: { friction: [0, -0.875, 0.5, null] }, m1: { friction: [0, 0] } } };
  assert.equal(peakFriction(run, [hoop, m1]), "hoop 0.8750, m1 0 N");
});

test("the same system in any key order is the same; a changed value is not", () => {
  const a = { bodies: [{ id: "a", mass: 1, x: 0 }], gravity: 9.81 };
  const b = { gravity: 9.81, bodies: [{ x: 0, mass: 1.0, id: "a" }] };
  assert.equal(canonical(a), canonical(b));
  assert.notEqual(canonical(a), canonical({ ...b, gravity: 9.8 }));
  assert.notEqual(canonical(a), canonical({ ...a, bodies: [{ id: "a", mass: 2, x: 0 }] }));
});

test("downloads carry the preset's name, or the system's, and -edited once changed", () => {
  assert.equal(fileStem("hoop-cylinder", "Hoop and cylinder", false), "hoop-cylinder");
  assert.equal(fileStem("hoop-cylinder", "Hoop and cylinder", true), "hoop-cylinder-edited");
  assert.equal(fileStem("", "My Two Hoops!", false), "my-two-hoops");
  assert.equal(fileStem("", "My Two Hoops!", true), "my-two-hoops-edited");
  assert.equal(fileStem("", "", true), "system-edited");
  assert.equal(fileStem("", "★", false), "system");
});
