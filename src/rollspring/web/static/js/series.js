// Trajectory (the /api/simulate answer) → uPlot data and series (pure: no DOM, no uPlot).
// Each function returns {data: [t, ...columns], series: [{label, stroke, dash?}, ...]}, the
// series list without uPlot's leading x entry.

export const PALETTE = ["#1f6fb2", "#c2502b", "#2e8b57", "#8a4fbf", "#b8860b", "#d6336c"];

export function bodyColour(index) {
  return PALETTE[index % PALETTE.length];
}

/** The colours of the centre of mass and of X̂, in the plots and on the canvas. */
export const CM_COLOUR = "#111";
export const XHAT_COLOUR = "#008c95";
/** The colour of each kind of force arrow (and of the force key). */
export const FORCE_COLOURS = { spring: "#8a4fbf", friction: "#c2502b", normal: "#2e8b57" };

/** Centre positions of every body, the CM and X̂ (when the system has one, both drawn boldly),
 * and, when the run carries it, each centre's linear modal solution as a dashed line.
 * `view.absolute`: x (m); otherwise (the default) the displacement (mm) from the equilibrium
 * `view.equilibrium` ({id: x}, with the CM's and X̂'s equilibria from the bodies' masses in
 * `system` and X̂'s weights `view.weights`), or from t = 0 without one. Returns also `unit`
 * and `reference` ("equilibrium", "t = 0" or "absolute"). */
export function positionSeries(run, system = null, view = {}) {
  const ids = Object.keys(run.bodies);
  const eq = view.equilibrium;
  const reference = view.absolute ? "absolute" : eq && ids.every((id) => eq[id] != null) ? "equilibrium" : "t = 0";
  const scale = reference === "absolute" ? 1 : 1000;
  const origin = (values, zero) => (reference === "absolute" ? values
    : values.map((v) => (v == null ? null : (v - zero) * scale)));
  const zeroOf = (id) => (reference === "equilibrium" ? eq[id] : run.bodies[id].x[0]);
  const data = [run.t];
  const series = [];
  const suffix = reference === "absolute" ? " x" : "";
  ids.forEach((id, i) => {
    data.push(origin(run.bodies[id].x, zeroOf(id)));
    series.push({ label: `${id}${suffix}`, stroke: bodyColour(i) });
  });
  let cmZero = run.cm_x[0];
  let xhatZero = run.stationary_x ? run.stationary_x[0] : 0;
  if (reference === "equilibrium") {
    const mass = new Map((system ? system.bodies : []).map((b) => [b.id, Number(b.mass)]));
    const total = ids.reduce((sum, id) => sum + (mass.get(id) || 0), 0);
    if (total > 0) cmZero = ids.reduce((sum, id) => sum + mass.get(id) * eq[id], 0) / total;
    if (view.weights) xhatZero = ids.reduce((sum, id) => sum + (view.weights[id] || 0) * eq[id], 0);
  }
  data.push(origin(run.cm_x, cmZero));
  series.push({ label: "CM", stroke: CM_COLOUR, width: 3.5 });
  if (run.stationary_x) {
    data.push(origin(run.stationary_x, xhatZero));
    series.push({ label: "X̂", stroke: XHAT_COLOUR, width: 3.5, dash: [10, 5] });
  }
  if (run.linear) {
    ids.forEach((id, i) => {
      if (!run.linear[id]) return;
      data.push(origin(run.linear[id], zeroOf(id)));
      series.push({ label: `${id} linear`, stroke: bodyColour(i), dash: [6, 4], width: 1 });
    });
  }
  const unit = reference === "absolute" ? "x (m)"
    : reference === "equilibrium" ? "x − x_eq (mm)" : "x − x(0) (mm)";
  const measured = view.measured;
  if (measured && ids.some((id) => measured.bodies[id])) {
    const columns = [];
    const labels = [];
    ids.forEach((id, i) => {
      if (!measured.bodies[id]) return;
      columns.push(origin(measured.bodies[id].x, zeroOf(id)));
      labels.push({ label: `${id} data`, stroke: bodyColour(i), markers: true });
    });
    const merged = withMeasured(data, measured.t, columns);
    return { data: merged, series: [...series.map((s) => ({ ...s, spanGaps: true })), ...labels], unit, reference };
  }
  return { data, series, unit, reference };
}

/** The columns `data` (over data[0], the model's times) and `columns` (over `times`, a measured
 * table's) on one time axis, the union of both in order: each column null at the other's
 * times. */
export function withMeasured(data, times, columns) {
  const model = data[0];
  const t = [];
  const fromModel = [];
  const fromData = [];
  let i = 0;
  let j = 0;
  while (i < model.length || j < times.length) {
    const a = i < model.length ? model[i] : Infinity;
    const b = j < times.length ? times[j] : Infinity;
    if (a === b) {
      t.push(a);
      fromModel.push(i++);
      fromData.push(j++);
    } else if (a < b) {
      t.push(a);
      fromModel.push(i++);
      fromData.push(-1);
    } else {
      t.push(b);
      fromModel.push(-1);
      fromData.push(j++);
    }
  }
  const pick = (column, index) => index.map((k) => (k < 0 ? null : column[k] ?? null));
  return [t, ...data.slice(1).map((column) => pick(column, fromModel)),
    ...columns.map((column) => pick(column, fromData))];
}

/** Newton's second law for the whole system: Σf (the frictions: the only horizontal external
 * forces of bodies joined to each other alone) beside (Σm)·a_CM, with a_CM from the exact
 * equations of motion (the server's `cm_a`; null where a body slips); with walls or external
 * forces, also Σf plus those. */
export function newtonSeries(run) {
  const data = [run.t, run.friction_x];
  const series = [{ label: "Σf (frictions)", stroke: FORCE_COLOURS.friction, width: 4 }];
  const other = run.other_external_x || [];
  if (other.some((v) => v != null && Math.abs(v) > 0)) {
    data.push(run.friction_x.map((f, i) => (other[i] == null ? null : f + other[i])));
    series.push({ label: "Σf + walls and forces", stroke: "#8a4fbf", width: 2.5 });
  }
  data.push(run.cm_a.map((a) => (a == null ? null : run.total_mass * a)));
  series.push({ label: "(Σm)·a_CM", stroke: CM_COLOUR, width: 1.8, dash: [6, 5] });
  return { data, series };
}

/** Friction f and normal force N of every body, with the ±μs N band (finite μs only). */
export function forceSeries(run, system) {
  const data = [run.t];
  const series = [];
  const mu = new Map(system.bodies.map((b) => [b.id, b.mu_static]));
  Object.keys(run.bodies).forEach((id, i) => {
    const b = run.bodies[id];
    data.push(b.friction);
    series.push({ label: `${id} f`, stroke: bodyColour(i) });
    data.push(b.normal);
    series.push({ label: `${id} N`, stroke: bodyColour(i), dash: [1, 3] });
    const m = Number(mu.get(id));
    if (Number.isFinite(m) && m > 0) {
      data.push(b.normal.map((n) => (n == null ? null : m * n)));
      series.push({ label: `${id} +μs N`, stroke: bodyColour(i), dash: [8, 4], width: 1 });
      data.push(b.normal.map((n) => (n == null ? null : -m * n)));
      series.push({ label: `${id} −μs N`, stroke: bodyColour(i), dash: [8, 4], width: 1 });
    }
  });
  return { data, series };
}

/** |f|/(μs N) of every body (slip where it reaches 1). */
export function ratioSeries(run) {
  const data = [run.t];
  const series = [];
  Object.keys(run.bodies).forEach((id, i) => {
    data.push(run.bodies[id].friction_ratio);
    series.push({ label: `${id} |f|/(μs N)`, stroke: bodyColour(i) });
  });
  data.push(run.t.map(() => 1));
  series.push({ label: "slip", stroke: "#b00020", dash: [4, 4], width: 1 });
  return { data, series };
}

/** Kinetic energy (with its translational and rotational parts, when the run has them),
 * potential and total energy. */
export function energySeries(run) {
  const e = run.energy;
  const data = [run.t, e.kinetic];
  const series = [{ label: "kinetic", stroke: "#1f6fb2", width: 2 }];
  if (e.translational && e.rotational) {
    data.push(e.translational, e.rotational);
    series.push({ label: "translational", stroke: "#1f6fb2", dash: [6, 4], width: 1.4 },
      { label: "rotational", stroke: "#b8860b", dash: [2, 3], width: 1.6 });
  }
  data.push(e.potential, e.total);
  series.push({ label: "potential", stroke: "#2e8b57" }, { label: "total", stroke: "#000" });
  return { data, series };
}

/** max |f|/N needed up to each sample (the friction coefficient the rolling has needed so far;
 * 0 for a body with N ≤ 0 at no sample), over `friction` and `normal`: a Float64Array. */
export function neededMu(friction, normal) {
  const out = new Float64Array(friction.length);
  let max = 0;
  for (let i = 0; i < friction.length; i++) {
    const f = friction[i];
    const n = normal[i];
    if (f != null && n != null && n > 0) max = Math.max(max, Math.abs(f) / n);
    out[i] = max;
  }
  return out;
}

/** The magnification (1, 2, 5 × a power of ten, at most `cap`) that shows a swing of
 * `halfRangePx` px (at the animation's scale) as at most `roomPx` px. */
export function magnification(halfRangePx, roomPx, cap = 1000) {
  let best = 1;
  for (let k = 0; k <= 4; k++) {
    for (const m of [1, 2, 5]) {
      const mag = m * 10 ** k;
      if (mag <= cap && mag * halfRangePx <= roomPx) best = Math.max(best, mag);
    }
  }
  return best;
}

/** The energy bars at sample i: kinetic, potential and lost (initial total − current total;
 * below 1e-6 of the total it is the integrator's error, far below what a bar or a 3-digit
 * label can show, and shown as 0), each with the bars' common scale. */
export function energyBars(run, i) {
  const e = run.energy;
  const scale = Math.max(...e.total.filter((v) => v != null), 1e-12);
  const lost = e.total[0] - e.total[i];
  return {
    kinetic: e.kinetic[i],
    potential: e.potential[i],
    lost: Math.abs(lost) < 1e-6 * scale ? 0 : lost,
    scale,
  };
}
