import { test } from "node:test";
import assert from "node:assert/strict";
import { fieldPath, pathInMessage } from "../../src/rollspring/web/static/js/api.js";

test("a 422's location is the editor's path", () => {
  assert.equal(fieldPath(["body", "system", "bodies", 0, "mass"]), "bodies.0.mass");
  assert.equal(fieldPath(["body", "start", "amplitude"]), "start.amplitude");
  assert.equal(fieldPath(["body", "system"]), "");
});

test("a message about the whole system names the part it is about (issue 26)", () => {
  assert.equal(pathInMessage("system: springs[0].ends: a spring cannot join 'hoop' to itself"),
    "springs.0.ends");
  assert.equal(pathInMessage("system: springs[0]: its two ends coincide in the initial placement"),
    "springs.0");
  assert.equal(pathInMessage("system: bodies[1].at[0] is odd"), "bodies.1.at.0");
  assert.equal(pathInMessage("system: duplicate id 'hoop'"), "");
  assert.equal(pathInMessage("duration: must be > 0"), "");
  assert.equal(pathInMessage(undefined), "");
});
