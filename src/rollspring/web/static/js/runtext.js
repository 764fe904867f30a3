// What the page says about a run and a system, as text (pure: no DOM): how the bodies moved,
// each body's peak friction, the name downloads carry, and whether a system was edited.

import { sig } from "./format.js";

/** The largest |f|/(μs N) of a run's summary (an object per body, or one number), or null
 * when no body has one (a system of sliders: they have no friction). */
export function maxRatio(summary) {
  const m = summary.max_friction_ratio;
  const values = m && typeof m === "object" ? Object.values(m) : [m];
  const finite = values.filter((v) => typeof v === "number" && Number.isFinite(v));
  return finite.length ? Math.max(...finite) : null;
}

/** What the bodies did over a run without slip: the rolling ones roll (with the largest
 * friction ratio), the sliders slide without friction (they do not roll). */
export function rollingText(bodies, ratio) {
  const sliders = bodies.filter((b) => b.shape === "slider").map((b) => b.id);
  const rolling = bodies.length - sliders.length;
  const parts = [];
  if (rolling) {
    parts.push(`${sliders.length ? "every rolling body" : "every body"} rolls without slipping`
      + (ratio == null ? "" : `, max |f|/(μs N) = ${sig(ratio, 3)}`));
  }
  if (sliders.length) {
    parts.push(rolling
      ? `${sliders.join(", ")} slide${sliders.length > 1 ? "" : "s"} without friction (a slider does not roll)`
      : "the bodies are sliders: they slide without friction, none rolls");
  }
  return parts.join("; ");
}

/** Each body's largest |friction| over a run ("hoop 0.8750, cylinder 0.5833 N"). */
export function peakFriction(run, bodies) {
  const parts = bodies.map((b) => {
    const values = (run.bodies[b.id]?.friction || []).filter((v) => v != null);
    return `${b.id} ${sig(values.reduce((m, v) => Math.max(m, Math.abs(v)), 0), 4)}`;
  });
  return `${parts.join(", ")} N`;
}

/** JSON with sorted keys: two systems are the same when these are. */
export function canonical(value) {
  return JSON.stringify(value, (_, v) => (v && typeof v === "object" && !Array.isArray(v)
    ? Object.fromEntries(Object.keys(v).sort().map((k) => [k, v[k]])) : v));
}

/** The stem of a download's name: the preset's name, else the system's name made a file
 * name, else "system"; "-edited" once the system differs from what was loaded. */
export function fileStem(preset, systemName, edited) {
  const name = preset || (systemName || "").toLowerCase().replace(/[^a-z0-9]+/g, "-")
    .replace(/^-+|-+$/g, "") || "system";
  return edited ? `${name}-edited` : name;
}
