import { test } from "node:test";
import assert from "node:assert/strict";
import { energyBars, energySeries, forceSeries, magnification, neededMu, newtonSeries, positionSeries, ratioSeries }
  from "../../src/rollspring/web/static/js/series.js";
import { fieldPath } from "../../src/rollspring/web/static/js/api.js";
import { getPath, parseField, setPath } from "../../src/rollspring/web/static/js/editor.js";

const run = {
  t: [0, 1, 2],
  bodies: {
    hoop: { x: [0, 0.1, 0.2], friction: [0.5, 0, -0.5], normal: [9.81, 9.81, 9.81], friction_ratio: [0.05, 0, 0.05] },
    cylinder: { x: [0.5, 0.4, 0.3], friction: [-0.3, 0, 0.3], normal: [9.81, 9.81, 9.81], friction_ratio: [0.03, 0, 0.03] },
  },
  cm_x: [0.25, 0.25, 0.25], stationary_x: [0.2, 0.2, 0.2],
  energy: { kinetic: [0, 0.004, 0], potential: [0.005, 0.001, 0.004], total: [0.005, 0.005, 0.004] },
  linear: { hoop: [0, 0.1, 0.19], cylinder: [0.5, 0.4, 0.31] },
};
const system = { bodies: [{ id: "hoop", mu_static: 1 }, { id: "cylinder", mu_static: "inf" }] };

test("positions: absolute x of each centre, the CM, X̂ (both bold) and the dashed linear solution", () => {
  const { data, series, unit } = positionSeries(run, system, { absolute: true });
  assert.equal(unit, "x (m)");
  assert.deepEqual(series.map((s) => s.label), ["hoop x", "cylinder x", "CM", "X̂", "hoop linear", "cylinder linear"]);
  assert.equal(data.length, series.length + 1);
  assert.deepEqual(data[0], run.t);
  assert.deepEqual(data[1], run.bodies.hoop.x);
  assert.ok(series.at(-1).dash);
  assert.ok(series[2].width >= 3 && series[3].width >= 3);
  const plain = positionSeries({ ...run, stationary_x: null, linear: null }, system, { absolute: true });
  assert.deepEqual(plain.series.map((s) => s.label), ["hoop x", "cylinder x", "CM"]);
});

test("positions: by default displacements (mm) from the equilibrium, the CM's and X̂'s from theirs", () => {
  const massive = { bodies: [{ id: "hoop", mass: 1 }, { id: "cylinder", mass: 3 }] };
  const view = { equilibrium: { hoop: 0.1, cylinder: 0.4 }, weights: { hoop: 0.5, cylinder: 0.5 } };
  const { data, series, unit, reference } = positionSeries(run, massive, view);
  assert.equal(reference, "equilibrium");
  assert.equal(unit, "x − x_eq (mm)");
  assert.deepEqual(series.slice(0, 4).map((s) => s.label), ["hoop", "cylinder", "CM", "X̂"]);
  const close = (a, b) => a.forEach((v, i) => assert.ok(Math.abs(v - b[i]) < 1e-9, `${v} ≠ ${b[i]}`));
  close(data[1], [-100, 0, 100]);
  close(data[2], [100, 0, -100]);
  close(data[3], [(0.25 - 0.325) * 1000, (0.25 - 0.325) * 1000, (0.25 - 0.325) * 1000]); // CM_eq = (0.1 + 3·0.4)/4
  close(data[4], [-50, -50, -50]); // X̂_eq = 0.25
  // no equilibrium (none found, or not yet analysed): from t = 0
  const fromStart = positionSeries(run, massive, {});
  assert.equal(fromStart.reference, "t = 0");
  close(fromStart.data[1], [0, 100, 200]);
});

test("Newton's second law for the whole system: Σf beside (Σm)·a_CM, null where a body slips", () => {
  const newton = newtonSeries({ t: [0, 1, 2], friction_x: [0.2, 0, -0.2], cm_a: [0.1, null, -0.1],
    total_mass: 2, other_external_x: [0, null, 0] });
  assert.deepEqual(newton.series.map((s) => s.label), ["Σf (frictions)", "(Σm)·a_CM"]);
  assert.deepEqual(newton.data, [[0, 1, 2], [0.2, 0, -0.2], [0.2, null, -0.2]]);
  const walled = newtonSeries({ t: [0, 1], friction_x: [0.2, 0.1], cm_a: [0.2, 0.1], total_mass: 2,
    other_external_x: [0.2, 0.1] });
  assert.deepEqual(walled.series.map((s) => s.label), ["Σf (frictions)", "Σf + walls and forces", "(Σm)·a_CM"]);
  assert.deepEqual(walled.data[2], [0.4, 0.2]);
});

test("needed μ: the running max of |f|/N; magnification: 1, 2, 5 × 10^k within the room", () => {
  assert.deepEqual(Array.from(neededMu([0.1, -0.5, 0.2, null, 3], [1, 10, 1, 1, 0])), [0.1, 0.1, 0.2, 0.2, 0.2]);
  assert.equal(magnification(0.7, 150), 200);
  assert.equal(magnification(0.7, 100), 100);
  assert.equal(magnification(100, 10), 1);
  assert.equal(magnification(0, 100), 1000);
});

test("forces: f and N per body, the ±μs N band only where μs is finite", () => {
  const { data, series } = forceSeries(run, system);
  assert.deepEqual(series.map((s) => s.label),
    ["hoop f", "hoop N", "hoop +μs N", "hoop −μs N", "cylinder f", "cylinder N"]);
  assert.deepEqual(data[3], [9.81, 9.81, 9.81]);
  assert.deepEqual(data[4], [-9.81, -9.81, -9.81]);
});

test("friction ratio with the slip line at 1; energies", () => {
  const ratio = ratioSeries(run);
  assert.deepEqual(ratio.data.at(-1), [1, 1, 1]);
  assert.deepEqual(energySeries(run).series.map((s) => s.label), ["kinetic", "potential", "total"]);
  const split = { ...run, energy: { ...run.energy, translational: [0, 0.003, 0], rotational: [0, 0.001, 0] } };
  assert.deepEqual(energySeries(split).series.map((s) => s.label),
    ["kinetic", "translational", "rotational", "potential", "total"]);
});

test("energy bars: lost = initial total − current total; rounding noise shows as 0", () => {
  const bars = energyBars(run, 2);
  assert.equal(bars.kinetic, 0);
  assert.equal(bars.potential, 0.004);
  assert.ok(Math.abs(bars.lost - 0.001) < 1e-15);
  assert.equal(bars.scale, 0.005);
  const noisy = { ...run, energy: { ...run.energy, total: [0.005, 0.005 + 1e-18, 0.005] } };
  assert.equal(energyBars(noisy, 1).lost, 0);
  // the integrator's energy error (here 4e-9 of the total, within rtol 1e-8) is not a loss
  const drift = { ...run, energy: { ...run.energy, total: [0.005, 0.005 + 2e-11, 0.005] } };
  assert.equal(energyBars(drift, 1).lost, 0);
  // a real loss (stick-slip, damping) is shown
  const damped = { ...run, energy: { ...run.energy, total: [0.005, 0.00499, 0.005] } };
  assert.ok(Math.abs(energyBars(damped, 1).lost - 1e-5) < 1e-15);
});

test("a 422's loc names the field the page shows the message next to", () => {
  assert.equal(fieldPath(["body", "system", "bodies", 0, "mass"]), "bodies.0.mass");
  assert.equal(fieldPath(["body", "toml"]), "toml");
  assert.equal(fieldPath([]), "");
});

test("fields: dotted paths into the system; numbers, inf, empty optional values", () => {
  const s = { bodies: [{ mass: 1 }] };
  assert.equal(getPath(s, "bodies.0.mass"), 1);
  setPath(s, "springs", []);
  setPath(s, "bodies.0.mu_kinetic", 0.3);
  assert.equal(s.bodies[0].mu_kinetic, 0.3);
  setPath(s, "bodies.0.mu_kinetic", undefined);
  assert.ok(!("mu_kinetic" in s.bodies[0]));
  assert.equal(parseField(" -1 "), -1);
  assert.equal(parseField("inf", { allowInf: true }), "inf");
  assert.equal(parseField("", { optional: true }), undefined);
  assert.equal(parseField("abc"), "abc");
});
