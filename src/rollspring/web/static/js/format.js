// Number formatting for the page (pure).

/** x to `digits` significant digits, trailing zeros kept ("0.02000"); "0" for zero, "∞" for inf,
 * "—" for null or NaN. */
export function sig(x, digits = 4) {
  if (x === "inf" || x === Infinity) return "∞";
  if (x == null || Number.isNaN(x)) return "—";
  if (x === 0) return "0";
  const a = Math.abs(x);
  if (a >= 1e6 || a < 1e-4) return x.toExponential(digits - 1);
  return x.toPrecision(digits);
}

/** A signed displacement in metres: "+0.02000 m", "−0.001000 m", "0 m". */
export function signedMetres(x, digits = 4) {
  if (x === 0) return "0 m";
  return `${x > 0 ? "+" : "−"}${sig(Math.abs(x), digits)} m`;
}

/** x rounded to a multiple of `unit` without binary noise (0.49 + 0.02 → 0.51). */
export function roundTo(x, unit) {
  const decimals = Math.max(0, Math.ceil(-Math.log10(unit)));
  return Number((Math.round(x / unit) * unit).toFixed(decimals));
}
