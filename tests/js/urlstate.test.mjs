import { test } from "node:test";
import assert from "node:assert/strict";
import { decodeState, encodeState } from "../../src/rollspring/web/static/js/urlstate.js";

const state = {
  preset: "hoop-cylinder",
  system: { bodies: [{ id: "hoop", shape: "hoop", mass: 1, radius: 0.1, x: 0, mu_static: "inf" }],
    springs: [{ ends: ["hoop", "wall"], stiffness: 100, at: [{ radius: 0.05, angle: 90 }, {}] }],
    anchors: [{ id: "wall", x: -0.5, y: 0.1 }], name: "Näme – with ünicode X̂" },
  show: { spring: true, friction: false }, t: 0.05, start: null,
};

test("the state survives the URL fragment unchanged, with or without '#'", async () => {
  const fragment = await encodeState(state);
  assert.match(fragment, /^v1\.[A-Za-z0-9_-]+$/, "URL-safe");
  assert.deepEqual(await decodeState(fragment), state);
  assert.deepEqual(await decodeState(`#${fragment}`), state);
});

test("it is compressed", async () => {
  const big = { ...state, system: { ...state.system, bodies: Array(40).fill(state.system.bodies[0]) } };
  const fragment = await encodeState(big);
  assert.ok(fragment.length < JSON.stringify(big).length / 4);
});

test("no state, a foreign fragment or a damaged one decodes to null", async () => {
  assert.equal(await decodeState(""), null);
  assert.equal(await decodeState("#section-2"), null);
  assert.equal(await decodeState("#v1.not-deflate-data"), null);
});
