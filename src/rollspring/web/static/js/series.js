// Trajectory (the /api/simulate answer) → uPlot data and series (pure: no DOM, no uPlot).
// Each function returns {data: [t, ...columns], series: [{label, stroke, dash?}, ...]}, the
// series list without uPlot's leading x entry.

export const PALETTE = ["#1f6fb2", "#c2502b", "#2e8b57", "#8a4fbf", "#b8860b", "#d6336c"];

export function bodyColour(index) {
  return PALETTE[index % PALETTE.length];
}

/** Centre positions of every body, the CM and X̂ (when the system has one), and, when the run
 * carries it, each centre's linear modal solution as a dashed line. */
export function positionSeries(run) {
  const data = [run.t];
  const series = [];
  Object.keys(run.bodies).forEach((id, i) => {
    data.push(run.bodies[id].x);
    series.push({ label: `${id} x`, stroke: bodyColour(i) });
  });
  data.push(run.cm_x);
  series.push({ label: "CM", stroke: "#555", dash: [2, 3] });
  if (run.stationary_x) {
    data.push(run.stationary_x);
    series.push({ label: "X̂", stroke: "#000", dash: [8, 4] });
  }
  if (run.linear) {
    Object.keys(run.bodies).forEach((id, i) => {
      if (!run.linear[id]) return;
      data.push(run.linear[id]);
      series.push({ label: `${id} linear`, stroke: bodyColour(i), dash: [6, 4], width: 1 });
    });
  }
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

/** Kinetic, potential and total energy. */
export function energySeries(run) {
  return {
    data: [run.t, run.energy.kinetic, run.energy.potential, run.energy.total],
    series: [
      { label: "kinetic", stroke: "#1f6fb2" },
      { label: "potential", stroke: "#2e8b57" },
      { label: "total", stroke: "#000" },
    ],
  };
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
