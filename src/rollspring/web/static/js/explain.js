// The page explains the paper (issue 26, point 3): the system's description by the picker, and
// three short "Why?" panels — X̂ (its weights, why it stays put), why the centre of mass moves,
// and percussion points — each with the numbers of the system shown, opened by links from the
// strip's note and the plots' heading. The percussion panel has a "snap the spring here" button
// for every spring end on a rolling body: it sets that end's attachment to {height: (1 + γ)R}.
// The math is plain Unicode: the server converts only its own derivation to MathML.
//
// The pure helpers (gammaOf, percussionHeight) are shared with scene.js, which marks each
// body's percussion point.

import { sig } from "./format.js";

/** γ in I = γ m R² of the built-in shapes (docs/physics.md §1; rollspring.model.schema). */
const GAMMAS = { hoop: 1, cylinder: 0.5, sphere: 0.4, shell: 2 / 3 };

/** The body's inertia factor γ (0 for a slider, which does not rotate). */
export function gammaOf(body) {
  if (body.shape === "slider") return 0;
  if (body.shape === "custom") return Number(body.inertia_factor);
  return GAMMAS[body.shape] ?? 0;
}

/** The percussion height (1 + γ)R above the body's track (m), or null for a slider. */
export function percussionHeight(body) {
  return body.shape === "slider" ? null : (1 + gammaOf(body)) * body.radius;
}

/** Every spring end on a rolling body: {spring, end, body, height (its percussion height),
 * snapped (its attachment is already there)}. */
export function springEndsOnBodies(system) {
  const bodies = new Map(system.bodies.map((b) => [b.id, b]));
  const ends = [];
  system.springs.forEach((spring, s) => {
    spring.ends.forEach((id, j) => {
      const body = bodies.get(id);
      if (!body || body.shape === "slider") return;
      const height = percussionHeight(body);
      const at = spring.at ? spring.at[j] : null;
      const snapped = Boolean(at && at.height != null && Math.abs(at.height - height) <= 1e-12 * Math.max(1, height));
      ends.push({ spring: s, end: j, body, height, snapped });
    });
  });
  return ends;
}

/** Track heights that make every spring between two bodies horizontal once its ends are at the
 * bodies' percussion points (the paper's Fig. 3): {id: track_height}, only for the bodies that
 * move. The first body of each group joined by springs keeps its track; a group whose springs
 * cannot all be level (a loop) is left as it is. */
export function levelTracks(system) {
  const bodies = new Map(system.bodies.filter((b) => b.shape !== "slider").map((b) => [b.id, b]));
  const links = system.springs.filter((s) => s.ends.every((id) => bodies.has(id)));
  const top = new Map(); // id → the height of its percussion point above the floor
  const tracks = {};
  for (const start of bodies.values()) {
    if (top.has(start.id)) continue;
    const group = new Map([[start.id, (start.track_height || 0) + percussionHeight(start)]]);
    const queue = [start.id];
    let ok = true;
    while (queue.length) {
      const id = queue.shift();
      for (const s of links) {
        if (!s.ends.includes(id)) continue;
        const other = s.ends[0] === id ? s.ends[1] : s.ends[0];
        if (!group.has(other)) {
          group.set(other, group.get(id));
          queue.push(other);
        } else if (group.get(other) !== group.get(id)) ok = false;
      }
    }
    for (const [id, y] of group) {
      top.set(id, y);
      const b = bodies.get(id);
      const track = y - percussionHeight(b);
      if (ok && Math.abs(track - (b.track_height || 0)) > 1e-12) tracks[id] = track;
    }
  }
  return tracks;
}

function el(tag, props = {}, ...children) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(props)) {
    if (k === "dataset") Object.assign(node.dataset, v);
    else if (k in node) node[k] = v;
    else node.setAttribute(k, v);
  }
  node.append(...children);
  return node;
}

/** Wire the "Why?" links: a link opens its panel and brings it into view (the page's URL
 * fragment holds the shared state, so the link does not change it). `onSnap(ends, tracks)` is
 * called with [{spring, end, height}] (and {id: track_height} for the levelling button) when a
 * snap button is pressed. */
export class Explainer {
  constructor(root, onSnap) {
    this.root = root;
    this.onSnap = onSnap;
    document.addEventListener("click", (e) => {
      const link = e.target.closest && e.target.closest("a[data-why]");
      if (!link) return;
      e.preventDefault();
      this.open(link.dataset.why);
    });
  }

  /** Open the panel `id` (or bring the element it names into view) and focus it. */
  open(id) {
    const target = document.getElementById(id) || document.querySelector(`[data-plot="${id}"]`);
    if (!target) return;
    if (target.tagName === "DETAILS") target.open = true;
    target.scrollIntoView({ block: "start" });
    const focus = target.tagName === "DETAILS" ? target.querySelector("summary") : target;
    if (focus) focus.focus({ preventScroll: true });
  }

  /** The description of `system` in `slot`. */
  describe(slot, system) {
    const text = (system && system.description) || "";
    slot.textContent = text;
    slot.hidden = !text;
  }

  /** The panels' numbers for `system` and its analysis `analysis` (or null). */
  update(system, analysis) {
    this.xhat(system, analysis);
    this.cm(system);
    this.percussion(system);
  }

  xhat(system, analysis) {
    const box = this.root.querySelector("#why-xhat .numbers");
    const sp = analysis && analysis.stationary_point;
    const ids = new Set(system.bodies.map((b) => b.id));
    const weights = sp && sp.weights && Object.keys(sp.weights).every((id) => ids.has(id)) ? sp.weights : null;
    if (!weights) {
      box.replaceChildren(el("p", {}, "This system has no X̂: a spring to a wall (or a force) "
        + "pushes the whole system, so no combination of the positions stays put."));
      return;
    }
    const rows = system.bodies.filter((b) => weights[b.id] != null).map((b) => {
      const inertia = (1 + gammaOf(b)) * b.mass; // I′/R² = (1 + γ) m
      return el("li", { dataset: { whyBody: b.id, weight: String(weights[b.id]) } },
        `${b.id} (${b.shape}): I′/R² = (1 + ${sig(gammaOf(b), 3)}) · ${sig(b.mass, 4)} kg = ${sig(inertia, 4)} kg, `
        + `so w = ${sig(weights[b.id], 4)}`);
    });
    const formula = Object.entries(weights).map(([id, w]) => `${sig(w, 4)}·x_${id}`).join(" + ");
    box.replaceChildren(el("p", {}, "For the system shown:"), el("ul", {}, ...rows),
      el("p", { className: "formula" }, `X̂ = ${formula}`
        + (sp.is_centre_of_mass ? " — here the same as the centre of mass."
          : " — not the centre of mass, whose weights are the masses.")));
  }

  cm(system) {
    const box = this.root.querySelector("#why-cm .numbers");
    const rolling = system.bodies.filter((b) => b.shape !== "slider");
    const total = system.bodies.reduce((m, b) => m + b.mass, 0);
    box.replaceChildren(el("p", {}, `For the system shown: Σm = ${sig(total, 4)} kg, so a_CM = Σf / ${sig(total, 4)} kg; `
      + (rolling.length ? `the frictions are those on ${rolling.map((b) => b.id).join(", ")}.`
        : "no body rolls, so there is no friction.")));
  }

  percussion(system) {
    const box = this.root.querySelector("#why-percussion .numbers");
    const rolling = system.bodies.filter((b) => b.shape !== "slider");
    const items = rolling.map((b) => el("li", { dataset: { whyBody: b.id, height: String(percussionHeight(b)) } },
      `${b.id} (${b.shape}, γ = ${sig(gammaOf(b), 3)}, R = ${sig(b.radius, 4)} m): `
      + `(1 + γ)R = ${sig(percussionHeight(b), 4)} m above its track`));
    const ends = springEndsOnBodies(system);
    const buttons = ends.map((e) => {
      const button = el("button", { type: "button", className: "snap", dataset: { spring: String(e.spring), end: String(e.end) } },
        `Snap spring ${e.spring + 1}'s end on ${e.body.id} here (h = ${sig(e.height, 4)} m)`);
      button.addEventListener("click", () => this.onSnap([{ spring: e.spring, end: e.end, height: e.height }]));
      const note = e.snapped ? " ✓ attached at its percussion point" : "";
      return el("li", {}, button, note);
    });
    const parts = [el("p", {}, "For the system shown (the mark P on each body):"),
      el("ul", {}, ...items)];
    if (ends.length) {
      const all = el("button", { type: "button", className: "snap-all" }, "Snap every spring end here");
      const every = ends.map((e) => ({ spring: e.spring, end: e.end, height: e.height }));
      all.addEventListener("click", () => this.onSnap(every));
      parts.push(el("ul", { className: "snaps" }, ...buttons), el("p", {}, all));
      if (Object.keys(levelTracks(system)).length) {
        const level = el("button", { type: "button", className: "snap-level" },
          "Snap every spring end here and raise the tracks so the springs are level (the paper's Fig. 3)");
        level.addEventListener("click", () => this.onSnap(every, levelTracks(system)));
        parts.push(el("p", { className: "note" }, "On one floor the springs then tilt: the frictions "
          + "still vanish to first order in the swing, but not to second. Level springs (each "
          + "body on a track at its own height) remove that too:"), el("p", {}, level));
      }
    } else {
      parts.push(el("p", {}, "No spring ends on a rolling body here."));
    }
    box.replaceChildren(...parts);
  }
}
