// Pure playback arithmetic (no DOM): where the clock is, what a Step does, and values between
// output samples. Times in seconds, samples on the server's output grid t[0..n-1].

export const SPEEDS = [0.1, 0.25, 0.5, 1, 1.5, 2];

/** The output interval of a trajectory: the fixed dt a Step advances the clock by. */
export function outputInterval(times) {
  return times.length > 1 ? (times[times.length - 1] - times[0]) / (times.length - 1) : 0;
}

/** The clock after one Step: exactly t + dt, not past the end. */
export function stepForward(t, dt, end) {
  return Math.min(t + dt, end);
}

/** The clock after `elapsedMs` of wall time at `speed`; {t, ended} (ended: reached `end`). */
export function advance(t, elapsedMs, speed, end) {
  const next = t + (elapsedMs / 1000) * speed;
  return next >= end ? { t: end, ended: true } : { t: next, ended: false };
}

/** Index i of the last sample with times[i] <= t (0 before the start, n-1 after the end). */
export function sampleIndex(times, t) {
  let lo = 0;
  let hi = times.length - 1;
  if (t >= times[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (times[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

/** values(t) by linear interpolation between samples (nulls stay null). */
export function valueAt(times, values, t) {
  const i = sampleIndex(times, t);
  if (i >= times.length - 1) return values[times.length - 1];
  const a = values[i];
  const b = values[i + 1];
  if (a == null || b == null) return a;
  const s = (t - times[i]) / (times[i + 1] - times[i]);
  return a + (b - a) * Math.max(0, Math.min(1, s));
}

/** The clock as shown: "t = 1.2333 s" (4 decimals). */
export function clockText(t) {
  return `t = ${t.toFixed(4)} s`;
}

/** The clock after one Step back: the last output time before t (0 at the start). */
export function stepBackward(times, t) {
  const tol = 1e-9 * Math.max(1, Math.abs(t));
  let i = sampleIndex(times, t);
  while (i > 0 && times[i] >= t - tol) i -= 1;
  return Math.max(0, Math.min(times[i], t));
}

// The run length (the simulated duration, s). The server takes up to 600 s; the page keeps to
// DURATION_MAX so that its trajectory (an output every 1/60 s) stays small and quick to draw.
export const DURATION_DEFAULT = 10;
export const DURATION_MIN = 1;
export const DURATION_MAX = 60;
export const OUTPUTS_PER_SECOND = 60;

/** The run length typed in its box: {value} (s) or {error} (a sentence for next to the box). */
export function parseDuration(text) {
  const s = String(text ?? "").trim().replace(/\s*s$/, "");
  const value = /^[+]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i.test(s) ? Number(s) : NaN;
  if (!Number.isFinite(value)) {
    return { error: `The run length must be a number of seconds, from ${DURATION_MIN} to ${DURATION_MAX}.` };
  }
  if (value < DURATION_MIN || value > DURATION_MAX) {
    return { error: `The run length must be from ${DURATION_MIN} s to ${DURATION_MAX} s (not ${s}).` };
  }
  return { value };
}

/** The output times asked for a run of `duration` s: one every 1/60 s (601 for 10 s). */
export function outputsFor(duration) {
  return Math.round(OUTPUTS_PER_SECOND * duration) + 1;
}
