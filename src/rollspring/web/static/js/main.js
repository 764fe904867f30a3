// rollspring's interactive page: wires the editor, the canvas, the plots and the panels to the
// API (docs/web-api.md). Every committed change sends one POST /api/simulate (+ /api/analyze)
// at once, and changes while dragging are debounced;
// the whole trajectory comes back and is animated here with requestAnimationFrame.
//
// For benchmarks and tests the page exposes `window.rollspringPage`:
//   frameTimes()  → the recent requestAnimationFrame timestamps (ms) while playing (last 240);
//   lastUpdate()  → {changed, drawn}: performance.now() of the last parameter change (slider
//                   release, field commit, drag release, key on a body) and of the first canvas
//                   frame drawn with the motion computed for it (null before any change);
//   ready()       → a Promise resolved once the first motion is drawn;
//   system()      → a copy of the system being edited (the JSON form);
//   time()        → the clock (s); dt() → the Step interval (s): one output interval;
//   settled()     → true when no change waits to be computed or drawn (for tests);
//   drawn()       → what the last frame drew (CSS px): the strip's CM and X̂ positions and its
//                   magnification, each force arrow's signed length, the arrows' px per N,
//                   each body's percussion mark ({id: {x, y}}), the px per m, and the
//                   ids of the bodies glowing for a slip (flashed) or held at rest by rolling
//                   resistance (held);
//   plotData(key) → a plot's series labels, line styles and data as plotted;
//   plotWindow(key) → the time window [t0, t1] a plot shows (a drag zooms every plot);
//   lesson()      → the guided lesson's step shown, {step, key, count}, or null;
//   playing()     → whether the animation plays;
//   labBusy()     → whether the lab is reading a file or fitting.
// Initial displacements are shown relative to where each body was when the system was loaded
// (the preset, file or link): that is also where Home puts a body back.

import { ApiError, getJson, latest, postBlob, postJson } from "./api.js";
import { Editor, parseField } from "./editor.js";
import { Explainer } from "./explain.js";
import { roundTo, sig, signedMetres } from "./format.js";
import { attachmentFromPoint, springEnds, worldBounds } from "./geometry.js";
import { Handles } from "./handles.js";
import { LabPanel } from "./lab.js";
import { LessonPanel, STEPS } from "./lesson.js";
import { renderDerivation, renderEnergyBars, renderModes } from "./panels.js";
import { watchScrollBoxes } from "./scrollbox.js";
import { Plots } from "./plots.js";
import { canonical, fileStem, maxRatio, peakFriction, rollingText } from "./runtext.js";
import { Scene } from "./scene.js";
import { energyBars, FORCE_COLOURS, neededMu } from "./series.js";
import { wireShortcuts } from "./shortcuts.js";
import { advance, clockText, DURATION_DEFAULT, outputInterval, outputsFor, parseDuration, sampleIndex, SPEEDS,
  stepBackward, stepForward, valueAt } from "./timeline.js";
import { decodeState, encodeState } from "./urlstate.js";

const DEBOUNCE_MS = 90;
const FORCE_VALUES_MS = 100; // while playing, the force values' text is rewritten this often
// The force arrows' scales at zoom ×1 (px per N), one per kind, fixed while the page is open
// (the arrow-scale control multiplies them): the default system's frictions (≤ 0.5 N) are
// ~30 px, its weights ~40 px, its spring's pull ~30 px.
const FORCE_SCALES = { spring: 30, friction: 60, normal: 4 };
const ZOOMS = [0.25, 0.5, 1, 2, 4, 8];
const FORCE_NAMES = { friction: "friction f", normal: "normal force N", spring: "spring force" };
/** The smallest tap target on a touch or narrow screen (CSS px; WCAG 2.5.5), as in page.css. */
const TAP = 44;
const touch = window.matchMedia("(max-width: 960px), (pointer: coarse)");
/** A screen wide enough for the editor's column beside the animation (page.css). */
const wide = window.matchMedia("(min-width: 961px)");

const $ = (selector) => document.querySelector(selector);

const state = {
  preset: "",
  system: null, // the system being edited (JSON form)
  loaded: {}, // body id → x when the system was loaded (Home)
  show: { spring: false, friction: true, normal: false, markers: true, linear: false, dots: false,
    values: false, absolute: false, percussion: true },
  onSlip: "stop",
  speed: 1,
  start: null, // {mode, amplitude}: start along a mode instead of the system's x, v
  t: 0,
  window: null, // the world window the canvas shows
  duration: DURATION_DEFAULT, // the run length (s)
  lesson: null, // the guided lesson's step shown (its index), or null
  strip: null, // the strip's magnification, fixed by a lesson step, or null: chosen to fit
};
const DEFAULT_SHOW = { ...state.show }; // the view options Reset all restores

let run = null; // the last good /api/simulate answer
let lesson = null; // the strip's series of `run` (see lessonOf)
let needed = null; // body id → max |f|/N needed up to each sample of `run`
const forceScale = { ...FORCE_SCALES }; // px per N now (the arrow-scale control)
let arrowZoom = 1;
const labelled = new Set(); // bodies hovered or focused: their forces get value labels
let hovered = null;
let presets = []; // /api/presets
let origin = ""; // the system as loaded (canonical JSON): "(edited)" once it differs
let loadedSystem = null; // the system as loaded (Reset all goes back to it, or to its preset)
let goodStart = null; // the mode start of the last motion computed (a refused one reverts to it)
let lastMode = null; // the mode "Play mode" last asked for (a new amplitude replays it)
let autoplay = false; // play the next motion as soon as it is in ("Play mode" pressed)
let analysis = null; // the last good /api/analyze answer
let playing = false;
let dragging = false;
let alerted = false;
let lastFrame = null;
const frames = [];
let pendingChange = null;
let lastUpdate = null;
let drawnRun = null;
let beforeLesson = null; // the page's state when the lesson began (Leave goes back to it)
let forceValuesAt = -Infinity; // when the force values were last written while playing (ms)
let resolveReady;
const readyPromise = new Promise((resolve) => (resolveReady = resolve));

const simulate = latest("/api/simulate");
const analyze = latest("/api/analyze");
const derive = latest("/api/derive");
const scene = new Scene($("#scene"), $("#strip"));
const plots = new Plots($("#plots"), (t) => seek(t), $("#reset-zoom"));
const editor = new Editor($("#editor"), (kind) => edited(kind));
const explainer = new Explainer(document, snap);
const lab = new LabPanel($("#lab"), {
  system: () => structuredClone(state.system),
  drawn: (data) => showData(data),
  fitted: (system, data) => showFitted(system, data),
});
const lessonPanel = new LessonPanel($("#lesson"), { go: goStep, leave: leaveLesson });
const handles = new Handles($("#handles"), {
  x: (id) => body(id).x,
  home: (id) => state.loaded[id] ?? body(id).x,
  pxPerM: () => scene.view.pxPerM,
  moveBody,
  dotAt,
  moveDot,
});

function body(id) {
  return state.system.bodies.find((b) => b.id === id);
}

// ---------------------------------------------------------------- loading and recomputing

function loadSystem(system, preset = "", { compute = true } = {}) {
  state.system = structuredClone(system);
  loadedSystem = structuredClone(system);
  origin = canonical(system);
  state.preset = preset;
  state.loaded = Object.fromEntries(system.bodies.map((b) => [b.id, b.x]));
  state.start = null;
  state.t = 0;
  state.window = worldBounds(state.system);
  scene.setWindow(state.window);
  $("#preset").value = preset;
  editor.load(state.system);
  lab.syncChoices(state.system);
  run = null;
  goodStart = null;
  showPicker();
  explainer.describe($("#preset-description"), state.system);
  explainer.update(state.system, null);
  if (compute) recomputeNow();
}

/** Changed since it was loaded (a preset: since the preset's own system). */
function isEdited() {
  const preset = presets.find((p) => p.name === state.preset);
  return canonical(state.system) !== (preset ? canonical(preset.system) : origin);
}

/** The picker names the preset, or "(edited) <preset>" once the system differs from it
 * ("(edited)" first: a long title is cut at the picker's width). */
function showPicker() {
  const picker = $("#preset");
  if (!picker.options.length) return;
  const preset = presets.find((p) => p.name === state.preset);
  const edited = isEdited();
  picker.options[0].textContent = preset
    ? `(edited) ${preset.title} (${preset.name})`
    : `${edited ? "(edited) " : ""}${state.system.name || "your system"}`;
  picker.options[0].hidden = Boolean(preset) && !edited; // offered only when it is the one shown
  picker.value = preset && !edited ? preset.name : "";
}

let timer = null;
let inFlight = 0;
function recompute() {
  clearTimeout(timer);
  timer = setTimeout(recomputeNow, DEBOUNCE_MS);
}

let errorShown = false;

async function recomputeNow() {
  clearTimeout(timer);
  timer = null;
  const system = structuredClone(state.system);
  const request = { system, duration: state.duration, outputs: outputsFor(state.duration), on_slip: state.onSlip,
    linear: state.show.linear };
  if (state.start) request.start = state.start;
  setStatus("Computing…");
  inFlight += 1;
  try {
    // both requests at once; the motion is drawn as soon as it is in, the modes when they are
    const pending = analyze({ system });
    pending.catch(() => {}); // its error, if any, is the simulation's too: shown once, below
    const sim = await simulate(request);
    if (!sim) return; // superseded by a newer change
    editor.clearErrors();
    $("#system-error").hidden = true;
    errorShown = false;
    goodStart = request.start || null;
    if (request.start) clearStartError();
    applyMotion(sim, system);
    const lin = await pending;
    if (!lin || run !== sim) return;
    applyAnalysis(lin);
  } catch (error) {
    if (error instanceof ApiError && /^start(\.|$)/.test(error.path) && request.start) {
      startRefused(error); // the mode start asked for: shown at its box, the last one kept
    } else {
      showError(error);
    }
  } finally {
    inFlight -= 1;
  }
}

/** A mode start the server refused (an amplitude out of range): its message next to the
 * amplitude box, and the start of the motion on screen kept, so later edits still compute. */
function startRefused(error) {
  errorShown = true;
  autoplay = false;
  state.start = goodStart;
  const slot = $("#amplitude-error");
  slot.textContent = error.message;
  slot.hidden = false;
  $("#amplitude").setAttribute("aria-invalid", "true");
  renderInitial();
  setStatus("Not computed: the mode's amplitude is not valid (see the message next to it); "
    + "the motion shown is the last one computed.");
}

function clearStartError() {
  $("#amplitude-error").hidden = true;
  $("#amplitude-error").textContent = "";
  $("#amplitude").removeAttribute("aria-invalid");
}

function showError(error) {
  errorShown = true;
  if (error instanceof ApiError) {
    editor.clearErrors();
    if (!editor.showError(error.path, error.message)) {
      $("#system-error").textContent = error.message;
      $("#system-error").hidden = false;
    }
    setStatus("Not computed: the system is not valid (see the message next to the field).");
  } else {
    setStatus(`Not computed: ${error.message}`);
  }
}

/** A new motion: the animation, the plots, the clock (the modes follow in applyAnalysis). */
function applyMotion(sim, system) {
  run = sim;
  run.system = system;
  alerted = false;
  restSaid = -Infinity;
  $("#alert").textContent = "";
  const end = run.t[run.t.length - 1];
  state.t = Math.min(state.t, end);
  // a body leaving the window: show the whole motion
  const bounds = worldBounds(system, Object.fromEntries(Object.entries(run.bodies).map(([id, b]) => [id, b.x])));
  if (bounds.xmin < state.window.xmin || bounds.xmax > state.window.xmax) {
    state.window = { ...state.window, xmin: Math.min(bounds.xmin, state.window.xmin),
      xmax: Math.max(bounds.xmax, state.window.xmax) };
    scene.setWindow(state.window);
  }
  const slider = $("#time");
  slider.max = String(end);
  slider.step = end > 0 ? String(outputInterval(run.t)) : "any";
  $("#dt").textContent = end > 0 ? `${sig(outputInterval(run.t), 4)} s`
    : "— (the motion ends at t = 0: nothing to step through)";
  $("#friction-peak").textContent = peakFriction(run, system.bodies);
  lesson = lessonOf(run);
  needed = Object.fromEntries(Object.entries(run.bodies).map(([id, b]) => [id, neededMu(b.friction, b.normal)]));
  buildGauges(system);
  plots.setRun(run, system, plotView());
  renderInitial();
  describeRun();
  renderDissipation();
  if (autoplay && !playing && end > 0) play();
  autoplay = false;
  draw();
  saveUrl();
  if ($("#derivation").open) loadDerivation();
  if ($("#toml-panel").open && !tomlEdited) loadToml();
}

/** The linear analysis of the system now shown: the modal table, X̂, the displacements. */
function applyAnalysis(lin) {
  analysis = lin;
  plots.update("positions", run, run.system, plotView());
  renderModes($("#modes tbody"), analysis, playMode);
  renderAnalysisNote();
  renderInitial();
  explainer.update(state.system, analysis);
}

function describeRun() {
  const s = run.summary;
  const event = firstEvent();
  const end = run.t[run.t.length - 1];
  if (event && end === 0) {
    setStatus(`Not run: ${event.body} ${event.kind === "slip"
      ? "slips at once, at t = 0 (the friction it needs at the start is more than μs N); tick "
        + "“continue after a slip” to run on with kinetic friction"
      : "lifts off at once, at t = 0 (its normal force is not positive)"}.`);
  } else if (event) {
    setStatus(`Computed ${sig(end, 4)} s. ${event.kind === "slip" ? "Slips" : "Lifts off"}: `
      + `${event.body} at t = ${event.time.toFixed(4)} s — play to see it.`);
  } else {
    const rest = (s.events || []).find((e) => e.kind === "rest");
    setStatus(`Computed ${sig(end, 4)} s (${s.status}); `
      + `${rollingText(run.system.bodies, maxRatio(s))}.`
      + (rest ? ` Comes to rest: ${rest.body} at t = ${rest.time.toFixed(4)} s (rolling resistance).` : ""));
  }
}

/** What rolling resistance (M22) did: each body's coming to rest ("rest") and starting again
 * ("release"), in time order. */
function restEvents() {
  return (run.summary.events || []).filter((e) => e.kind === "rest" || e.kind === "release")
    .sort((a, b) => a.time - b.time);
}

/** The energy the run dissipated (the summary's energy_dissipated, by damping, kinetic friction
 * and rolling resistance) and the rest/release events, beside the energy bars' "lost". */
function renderDissipation() {
  const note = $("#energy-note");
  const s = run.summary;
  const total = Number(s.energy_dissipated) || 0;
  const by = s.dissipated_by || {};
  const events = restEvents();
  note.dataset.dissipated = String(total);
  note.dataset.rollingResistance = String(by.rolling_resistance ?? 0);
  note.dataset.events = JSON.stringify(events);
  if (total <= 0 && !events.length) {
    note.hidden = true;
    note.textContent = "";
    return;
  }
  const names = { rolling_resistance: "rolling resistance", damping: "spring damping",
    kinetic_friction: "kinetic friction" };
  const parts = Object.entries(names).filter(([key]) => Number(by[key]) > 0)
    .map(([key, name]) => `${name} ${sig(by[key], 4)} J`);
  const lines = [`Energy dissipated over the run: ${sig(total, 4)} J`
    + (parts.length ? ` (${parts.join(", ")})` : "") + "; the total energy falls by it."];
  if (events.length) {
    lines.push(events.map((e) => `${e.body} ${e.kind === "rest" ? "comes to rest (held by rolling resistance)"
      : "starts to roll again"} at t = ${e.time.toFixed(4)} s`).join("; ") + ".");
  }
  note.textContent = lines.join(" ");
  note.hidden = false;
}

/** The first slip or lift-off: {kind, time, body} or null. */
function firstEvent() {
  const { first_slip: slip, first_liftoff: lift } = run.summary;
  const events = [];
  if (slip) events.push({ kind: "slip", ...slip });
  if (lift) events.push({ kind: "lift-off", ...lift });
  events.sort((a, b) => a.time - b.time);
  return events[0] || null;
}

function renderAnalysisNote() {
  const osc = analysis.modes.filter((m) => m.kind === "oscillating");
  const sp = analysis.stationary_point;
  const parts = [osc.length ? `Ω = ${sig(osc[0].omega, 6)} rad/s (lowest mode)` : "no oscillating mode"];
  if (sp && sp.weights) {
    parts.push(`X̂ = ${Object.entries(sp.weights).map(([id, w]) => `${sig(w, 4)}·x_${id}`).join(" + ")}`
      + `${sp.is_centre_of_mass ? " (the centre of mass)" : " (not the centre of mass)"}`);
  }
  if (analysis.warnings && analysis.warnings.length) parts.push(`⚠ ${analysis.warnings.join(" ⚠ ")}`);
  $("#analysis-note").textContent = parts.join(" · ");
}

// ---------------------------------------------------------------- the initial state

function renderInitial() {
  const list = $("#initial");
  const eq = analysis ? analysis.equilibrium.x || {} : {};
  const items = state.system.bodies.map((b) => {
    const li = document.createElement("li");
    const out = document.createElement("output");
    out.id = `disp-${b.id}`;
    out.className = "displacement";
    const d = roundTo(b.x - (state.loaded[b.id] ?? b.x), 1e-9);
    out.dataset.m = String(d);
    out.textContent = signedMetres(d);
    const fromEq = eq[b.id] != null ? `; from equilibrium ${signedMetres(roundTo(b.x - eq[b.id], 1e-9))}` : "";
    li.append(`${b.id}: x₀ = ${sig(b.x, 5)} m, moved `, out, ` from where it was loaded${fromEq}`);
    return li;
  });
  if (state.start) {
    const li = document.createElement("li");
    li.textContent = `Starting at rest along mode ${state.start.mode + 1}, largest centre `
      + `displacement ${state.start.amplitude} m (drag a body to start from the positions above).`;
    items.push(li);
  }
  list.replaceChildren(...items);
}

function moveBody(id, x, phase) {
  pause();
  state.t = 0;
  state.start = null;
  body(id).x = x;
  editor.refreshField(`bodies.${state.system.bodies.indexOf(body(id))}.x`);
  dragging = phase === "move";
  renderInitial();
  draw();
  if (phase === "end") edited("commit");
}

/** The attachment dot under canvas point q, when dragging them is switched on (at t = 0). */
function dotAt(q) {
  if (!state.show.dots || playing || state.t !== 0 || !state.system) return null;
  const dots = attachmentDotsNow();
  return dots.find((d) => Math.hypot(d.p.x - q.x, d.p.y - q.y) <= 7) || null;
}

function attachmentDotsNow() {
  const dots = [];
  state.system.springs.forEach((spring, s) => {
    const ends = springEnds(state.system, spring, (id) => ({ x: body(id).x, phi: 0 }));
    spring.ends.forEach((id, j) => {
      const b = body(id);
      if (b && b.shape !== "slider") dots.push({ spring: s, end: j, body: b, p: scene.view.toCanvas(ends[j]) });
    });
  });
  return dots;
}

function moveDot(dot, q, phase) {
  const spring = state.system.springs[dot.spring];
  spring.at ??= [{}, {}];
  spring.at[dot.end] = attachmentFromPoint(dot.body, scene.view.toWorld(q));
  dragging = phase === "move";
  draw();
  if (phase === "end") {
    editor.render();
    edited("commit");
  }
}

/** "Snap the spring here": each of `ends` ([{spring, end, height}]) attached at that height
 * on its body's centre vertical (its percussion point), and the bodies of `tracks` ({id:
 * track_height}) moved to those tracks; then computed again. */
function snap(ends, tracks = {}) {
  pause();
  for (const [id, h] of Object.entries(tracks)) body(id).track_height = h;
  if (Object.keys(tracks).length) {
    state.window = worldBounds(state.system);
    scene.setWindow(state.window);
  }
  for (const { spring, end, height } of ends) {
    const s = state.system.springs[spring];
    s.at ??= [{}, {}];
    s.at[end] = { height };
  }
  editor.render();
  edited("commit");
}

// ---------------------------------------------------------------- edits

// A committed change (a slider released, a field entered, a drag ended) is computed at once;
// the stream of "input" events while a slider or a body is being dragged is debounced.
function edited(kind) {
  showPicker();
  lab.syncChoices(state.system);
  explainer.update(state.system, analysis);
  renderInitial();
  draw();
  if (kind === "commit") {
    pendingChange = performance.now();
    recomputeNow();
  } else {
    recompute();
  }
}

function playMode(index) {
  // the box's text as typed: the server says what is wrong with it, next to the box
  state.start = { mode: index, amplitude: parseField($("#amplitude").value) };
  lastMode = index;
  autoplay = true;
  state.t = 0;
  pendingChange = performance.now();
  pause();
  recomputeNow();
}

// ---------------------------------------------------------------- the clock and drawing

function dt() {
  return run ? outputInterval(run.t) : 1 / 60;
}

function play() {
  if (!run) return;
  if (state.t >= run.t[run.t.length - 1]) {
    state.t = 0;
    alerted = false;
  }
  playing = true;
  lastFrame = null;
  $("#play").textContent = "Pause";
  $("#play").setAttribute("aria-label", "Pause");
  requestAnimationFrame(tick);
}

function pause() {
  if (!playing) return;
  playing = false;
  $("#play").textContent = "Play";
  $("#play").setAttribute("aria-label", "Play");
  draw(); // the force values, shown while paused
  saveUrl();
}

function tick(now) {
  if (!playing) return;
  frames.push(now);
  if (frames.length > 240) frames.shift();
  if (lastFrame !== null) {
    const next = advance(state.t, now - lastFrame, state.speed, run.t[run.t.length - 1]);
    state.t = next.t;
    if (next.ended) pause();
  }
  lastFrame = now;
  draw();
  if (playing) requestAnimationFrame(tick);
}

function seek(t) {
  pause();
  state.t = Math.max(0, Math.min(t, run ? run.t[run.t.length - 1] : 0));
  if (run && state.t < (firstEvent()?.time ?? Infinity)) alerted = false;
  draw();
  saveUrl();
}

function step() {
  if (!run) return;
  seek(stepForward(state.t, dt(), run.t[run.t.length - 1]));
}

function stepBack() {
  if (!run) return;
  seek(stepBackward(run.t, state.t));
}

/** Pose of every body at the clock: from the trajectory, or while a body is being dragged or
 * its new motion is on its way, at rest where the system places it. */
function frameNow() {
  const preview = !run || dragging || (state.t === 0 && pendingChange !== null && drawnRun === run && !state.start);
  const t = state.t;
  const system = preview ? state.system : run.system;
  if (preview) {
    const pose = (id) => ({ x: body(id).x, phi: 0 });
    const tensions = system.springs.map((s) => restTension(system, s, pose));
    return { system, pose, tensions, contact: () => null, cm: null, xhat: null, t, ghosts: null,
      flash: new Set(), show: state.show, forceScale, labelled, lesson: null, preview: true };
  }
  const times = run.t;
  const pose = (id) => ({ x: valueAt(times, run.bodies[id].x, t), phi: valueAt(times, run.bodies[id].phi, t) });
  const i = sampleIndex(times, t);
  const flash = new Set();
  const event = firstEvent();
  if (event && t >= event.time - 1e-9) flash.add(event.body);
  for (const [id, b] of Object.entries(run.bodies)) if (b.slipping[i]) flash.add(id);
  // bodies held at rest by rolling resistance (their last rest/release event a rest)
  const held = new Set();
  for (const e of restEvents()) {
    if (e.time > t + 1e-9) break;
    if (e.kind === "rest") held.add(e.body);
    else held.delete(e.body);
  }
  return {
    system, pose, t, flash, held, show: state.show,
    tensions: run.springs.map((s) => valueAt(times, s.tension, t)),
    contact: (id) => ({ f: valueAt(times, run.bodies[id].friction, t), N: valueAt(times, run.bodies[id].normal, t) }),
    cm: valueAt(times, run.cm_x, t),
    xhat: run.stationary_x ? valueAt(times, run.stationary_x, t) : null,
    ghosts: state.show.linear && run.linear
      ? Object.fromEntries(Object.entries(run.linear).map(([id, xs]) => [id, valueAt(times, xs, t)])) : null,
    forceScale, labelled, lesson, stripMagnification: state.strip,
    preview: false,
  };
}

function restTension(system, spring, pose) {
  if (spring.rest_length == null) return 0;
  const [a, b] = springEnds(system, spring, pose);
  return spring.stiffness * (Math.hypot(b.x - a.x, b.y - a.y) - spring.rest_length);
}

let lastPose = null;
function draw() {
  if (!state.system) return;
  const frame = frameNow();
  lastPose = frame.pose;
  scene.draw(frame);
  $("#clock").textContent = clockText(state.t);
  $("#clock").dataset.t = String(state.t);
  $("#time").value = String(state.t);
  placeHandles(frame);
  if (!frame.preview) {
    plots.setTime(state.t);
    const i = sampleIndex(run.t, state.t);
    renderEnergyBars($("#energy-bars"), energyBars(run, i));
    renderGauges(i);
    // the force values as text: at every frame while paused; while playing, ten times a second
    // (a number that changes at 60 Hz cannot be read, and the text costs a layout)
    const now = performance.now();
    if (!playing || now - forceValuesAt >= FORCE_VALUES_MS) {
      forceValuesAt = now;
      renderForceValues(frame);
    }
    announceEvent();
    if (drawnRun !== run) {
      drawnRun = run;
      if (pendingChange !== null) {
        lastUpdate = { changed: pendingChange, drawn: performance.now() };
        pendingChange = null;
      }
      resolveReady();
    }
  }
}

function announceEvent() {
  announceRest();
  const event = firstEvent();
  if (!event || alerted || state.t < event.time - 1e-9) return;
  alerted = true;
  const what = event.kind === "slip"
    ? "starts to slip: the friction it needs reaches μs N"
    : "lifts off: its normal force reaches zero";
  $("#alert").textContent = `${event.body} ${what}, at t = ${event.time.toFixed(4)} s.`;
  if (state.onSlip === "stop" || event.kind !== "slip") pause();
}

/** A body coming to rest (or starting again) under rolling resistance, said as the clock
 * passes it, like a slip (the animation plays on). */
let restSaid = -Infinity;
function announceRest() {
  if (!run) return;
  const passed = restEvents().filter((e) => e.time <= state.t + 1e-9);
  if (!passed.length) {
    restSaid = -Infinity;
    return;
  }
  const last = passed[passed.length - 1];
  if (last.time === restSaid) return;
  restSaid = last.time;
  $("#alert").textContent = `${last.body} ${last.kind === "rest"
    ? "comes to rest: rolling resistance holds it" : "starts to roll again"}, at t = ${last.time.toFixed(4)} s.`;
}

function placeHandles(frame) {
  handles.sync(frame.system.bodies.map((b) => {
    const { x } = frame.pose(b.id);
    const c = scene.view.toCanvas({ x, y: (b.track_height || 0) + b.radius });
    const size = Math.max(28, 2 * b.radius * scene.view.pxPerM);
    // on a touch or narrow screen the target is at least TAP px, around a ring of the body's size
    const box = touch.matches ? Math.max(TAP, size) : size;
    const home = state.loaded[b.id] ?? b.x;
    const d = roundTo(body(b.id) ? body(b.id).x - home : 0, 1e-9);
    return { id: b.id, left: c.x - box / 2, top: c.y - box / 2, size: box, ring: size, now: d,
      min: roundTo(state.window.xmin - home, 1e-3), max: roundTo(state.window.xmax - home, 1e-3),
      text: `${signedMetres(d)} from where it was loaded` };
  }));
}

function setStatus(text) {
  $("#status").textContent = text;
}

// ---------------------------------------------------------------- the lesson and the forces

/** What the plots show: positions from the equilibrium of the analysis now shown (when it is
 * of these bodies), or absolute. */
function plotView() {
  const eq = analysis && analysis.equilibrium && analysis.equilibrium.found ? analysis.equilibrium.x : null;
  const sp = analysis ? analysis.stationary_point : null;
  return { absolute: state.show.absolute, equilibrium: eq, weights: sp && sp.weights ? sp.weights : null,
    measured: lab.data };
}

// ---------------------------------------------------------------- the lab

/** A run long enough to cover the measured table (within the page's 1 to 60 s). */
function coverData(data) {
  const t = data.t.filter((v) => v != null);
  const end = t.length ? t[t.length - 1] : 0;
  const wanted = Math.min(60, Math.max(1, Math.ceil(end * 100 - 1e-9) / 100));
  if (wanted > state.duration + 1e-12) {
    state.duration = wanted;
    $("#duration").value = String(wanted);
    return true;
  }
  return false;
}

/** The measured table drawn over the positions (null: none). */
function showData(data) {
  if (data && coverData(data)) {
    recomputeNow();
    return;
  }
  if (run) plots.update("positions", run, run.system, plotView());
}

/** The fitted system in the editor, the plots showing its motion over the data. */
function showFitted(system, data) {
  coverData(data);
  loadSystem(system, "");
}

/** The strip's series: the CM and X̂ with the middle of each one's range, and the larger
 * half-range (m), which sets the magnification. */
function lessonOf(sim) {
  const mid = (values) => {
    let lo = Infinity;
    let hi = -Infinity;
    for (const v of values) {
      if (v == null) continue;
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
    return lo <= hi ? { mid: (lo + hi) / 2, half: (hi - lo) / 2 } : { mid: 0, half: 0 };
  };
  const cm = mid(sim.cm_x);
  const xhat = sim.stationary_x ? mid(sim.stationary_x) : null;
  return { times: sim.t, cm: sim.cm_x, xhat: sim.stationary_x, cmMid: cm.mid,
    xhatMid: xhat ? xhat.mid : 0, halfRange: Math.max(cm.half, xhat ? xhat.half : 0) };
}

let gaugeIds = "";
/** One "needed μ" gauge per rolling body: max |f|/N needed so far against its μs. */
function buildGauges(system) {
  const rolling = system.bodies.filter((b) => b.shape !== "slider");
  const ids = rolling.map((b) => `${b.id}:${b.mu_static}`).join("|");
  if (ids === gaugeIds) return;
  gaugeIds = ids;
  $(".mu-box").hidden = rolling.length === 0;
  $("#mu-gauges").replaceChildren(...rolling.map((b) => {
    const row = document.createElement("div");
    row.className = "gauge";
    row.dataset.gauge = b.id;
    const name = document.createElement("span");
    name.className = "name";
    name.textContent = b.id;
    const track = document.createElement("div");
    track.className = "track";
    track.setAttribute("aria-hidden", "true");
    const fill = document.createElement("div");
    fill.className = "fill";
    const limit = document.createElement("div");
    limit.className = "limit";
    track.append(fill, limit);
    const value = document.createElement("output");
    value.className = "value";
    row.append(name, track, value);
    Object.assign(row, { mu: Number(b.mu_static), fill, limit, value, lastNow: NaN, lastTotal: NaN });
    return row;
  }));
}

function renderGauges(i) {
  // only what changed is written (the running max changes seldom): no work in most frames
  for (const row of $("#mu-gauges").children) {
    const series = needed[row.dataset.gauge];
    if (!series) continue;
    const now = series[i];
    const total = series[series.length - 1];
    if (row.lastNow === now && row.lastTotal === total) continue;
    row.lastNow = now;
    row.lastTotal = total;
    const mu = row.mu;
    const finite = Number.isFinite(mu);
    const top = Math.max(finite ? mu : 0, total, 1e-12) * 1.15;
    row.fill.style.width = `${Math.min(100, (now / top) * 100).toFixed(2)}%`;
    row.limit.hidden = !finite;
    if (finite) row.limit.style.left = `${Math.min(100, (mu / top) * 100).toFixed(2)}%`;
    row.dataset.over = String(finite && now > mu);
    row.value.textContent = `needs μ ≥ ${sig(now, 3)} of μs = ${finite ? sig(mu, 3) : "∞"}`;
  }
}

function renderForceValues(frame) {
  const parts = [];
  for (const b of frame.system.bodies) {
    const c = frame.contact(b.id);
    if (!c) continue;
    const f = b.shape === "slider" ? "" : `f = ${c.f < 0 ? "−" : "+"}${sig(Math.abs(c.f), 3)} N, `;
    parts.push(`${b.id}: ${f}N = ${sig(c.N, 4)} N`);
  }
  frame.tensions.forEach((t, s) => parts.push(`spring ${s + 1}: T = ${t < 0 ? "−" : "+"}${sig(Math.abs(t), 3)} N`));
  $("#force-values").textContent = parts.length ? `At ${clockText(frame.t)}: ${parts.join("; ")}.` : "";
}

function renderForceKey() {
  for (const kind of Object.keys(FORCE_SCALES)) {
    const item = $(`#force-key [data-force="${kind}"]`);
    item.querySelector(".swatch").style.background = FORCE_COLOURS[kind];
    item.querySelector(".scale").textContent = `${FORCE_NAMES[kind]}: 1 N = ${sig(forceScale[kind], 3)} px`;
  }
}

function setArrowZoom(z) {
  arrowZoom = z;
  $("#arrow-scale").value = String(z);
  for (const kind of Object.keys(FORCE_SCALES)) forceScale[kind] = FORCE_SCALES[kind] * arrowZoom;
  renderForceKey();
  draw();
}

function wireForceKey() {
  const zoom = $("#arrow-scale");
  zoom.replaceChildren(...ZOOMS.map((z) => new Option(`×${z}`, String(z))));
  zoom.value = String(arrowZoom);
  zoom.addEventListener("change", () => setArrowZoom(Number(zoom.value)));
  renderForceKey();
  // value labels for the body under the pointer or with the keyboard focus
  const layer = $("#handles");
  const relabel = () => {
    labelled.clear();
    if (hovered) labelled.add(hovered);
    const focused = document.activeElement && document.activeElement.closest && document.activeElement.closest("#handles [data-body]");
    if (focused) labelled.add(focused.dataset.body);
    if (!playing) draw();
  };
  layer.addEventListener("pointermove", (e) => {
    if (!state.system) return;
    const box = layer.getBoundingClientRect();
    const x = scene.view.toWorld({ x: e.clientX - box.left, y: e.clientY - box.top }).x;
    const frame = lastPose;
    let best = null;
    let bestD = Infinity;
    for (const b of state.system.bodies) {
      const d = Math.abs((frame ? frame(b.id).x : b.x) - x) - b.radius;
      if (d < bestD) {
        bestD = d;
        best = b.id;
      }
    }
    const id = bestD * scene.view.pxPerM < 24 ? best : null;
    if (id !== hovered) {
      hovered = id;
      relabel();
    }
  });
  layer.addEventListener("pointerleave", () => {
    if (hovered !== null) {
      hovered = null;
      relabel();
    }
  });
  layer.addEventListener("focusin", relabel);
  layer.addEventListener("focusout", () => setTimeout(relabel));
}

// ---------------------------------------------------------------- the URL (share)

let urlTimer = null;
/** The fragment the page itself last wrote or opened. A different one in the address bar is a
 * link the user pasted, whose hashchange is still queued: a state encoded before it must not
 * overwrite it (the page would then open its own old state instead of the link). */
let ownHash = location.hash;
let urlWrites = 0; // writes of the page's state begun: only the newest one lands
let pastes = 0; // links opened from the address bar (hashchange)

/** Whether a write of the page's state begun as ``write`` (``urlWrites`` then) after ``seen``
 * pastes may land: no newer write begun, no link pasted since, none waiting for its hashchange. */
function mayWrite(write, seen) {
  return write === urlWrites && seen === pastes && location.hash === ownHash;
}

function saveUrl() {
  clearTimeout(urlTimer);
  urlTimer = setTimeout(async () => {
    const write = ++urlWrites;
    const seen = pastes;
    const fragment = await encodeState(shareable());
    if (!mayWrite(write, seen)) return; // a newer state, or a pasted link, wins
    history.replaceState(null, "", `#${fragment}`);
    ownHash = location.hash;
  }, 150);
}

function shareable() {
  return { preset: state.preset, system: state.system, loaded: state.loaded, show: state.show,
    onSlip: state.onSlip, speed: state.speed, start: state.start, t: state.t, window: state.window,
    duration: state.duration, lesson: state.lesson, strip: state.strip };
}

/** What a link holds: the whole state (the page as shared, in the lesson's step if it was on),
 * or only {lesson: k}: that step, as the lesson sets it up. */
function openSaved(saved) {
  if (saved.system) {
    restore(saved);
  } else if (Number.isInteger(saved.lesson) && STEPS[saved.lesson]) {
    goStep(saved.lesson, { focus: "title" });
  }
}

function restore(saved) {
  loadSystem(saved.system, saved.preset || "", { compute: false });
  Object.assign(state, { loaded: saved.loaded, show: { ...state.show, ...saved.show }, onSlip: saved.onSlip,
    speed: saved.speed, start: saved.start, t: saved.t, window: saved.window,
    duration: parseDuration(saved.duration ?? DURATION_DEFAULT).value ?? DURATION_DEFAULT,
    strip: Number.isFinite(saved.strip) && saved.strip > 0 ? saved.strip : null });
  scene.setWindow(state.window);
  syncViewControls();
  showPicker();
  const k = Number.isInteger(saved.lesson) && STEPS[saved.lesson] ? saved.lesson : null;
  if (k !== null) {
    showStep(k);
    plots.showOnly(STEPS[k].plots, STEPS[k].lines);
  } else if (state.lesson !== null) {
    closeLesson();
  }
  recomputeNow();
}

// ---------------------------------------------------------------- the guided lesson

function reducedMotion() {
  return window.matchMedia("(prefers-reduced-motion: reduce)").matches;
}

/** The lesson's panel beside the animation: at the top of the editor's column on a wide
 * screen, right under the animation (which stays in view on a phone) on a narrow one. */
function placeLesson() {
  const panel = $("#lesson");
  if (wide.matches) $(".sidebar").prepend(panel);
  else $(".scene-row").after(panel);
}

/** Begin the lesson at its first step (the page as it is now kept for Leave). */
function enterLesson() {
  if (state.lesson === null) beforeLesson = structuredClone(shareable());
  goStep(0, { focus: "title" });
}

/** Step k of the lesson: its system and view, computed; `focus`: "title" moves the keyboard
 * focus to the step's heading, "keep" leaves it (on Back, Next or a step's number) unless the
 * control it was on is disabled now. */
function goStep(k, { focus = "title" } = {}) {
  const step = STEPS[k];
  const preset = step && presets.find((p) => p.name === step.preset);
  if (!preset) return;
  pause();
  Object.assign(state, { show: { ...DEFAULT_SHOW, ...step.show }, onSlip: "stop", speed: 1,
    duration: DURATION_DEFAULT, strip: step.magnification });
  setArrowZoom(1);
  syncViewControls();
  clearStartError();
  $("#amplitude").value = String(step.start ? step.start.amplitude : 0.01);
  lastMode = step.start ? step.start.mode : null;
  plots.resetZoom();
  plots.showAllLines();
  plots.showOnly(step.plots, step.lines);
  pendingChange = performance.now();
  loadSystem(preset.system, preset.name, { compute: false });
  state.start = step.start ? { ...step.start } : null;
  state.t = step.t;
  autoplay = step.play && !reducedMotion();
  renderInitial();
  showStep(k);
  const title = $("#lesson-step-title");
  if (focus === "title" || (document.activeElement && document.activeElement.disabled)) {
    title.focus({ preventScroll: true });
  }
  // the step's title in view: beside the animation (a wide screen), or right under it, which
  // stays at the top of a phone's screen (page.css's scroll-padding)
  title.scrollIntoView({ block: wide.matches ? "nearest" : "start" });
  recomputeNow();
}

function showStep(k) {
  state.lesson = k;
  document.body.classList.add("in-lesson");
  lessonPanel.show(k, "#");
  encodeState({ lesson: k }).then((fragment) => {
    if (state.lesson === k) $("#lesson-link").href = `${location.pathname}#${fragment}`;
  });
}

function closeLesson() {
  state.lesson = null;
  state.strip = null;
  lessonPanel.hide();
  document.body.classList.remove("in-lesson");
  plots.showOnly(null);
}

/** The lesson closed, the page kept as it is (another system was chosen or applied). */
function quitLesson() {
  if (state.lesson === null) return;
  closeLesson();
  beforeLesson = null;
  plots.showAllLines();
}

/** Leave the lesson: the page as it was when the lesson began (opened from a link to a step:
 * the step's system stays, with the page's own view). */
function leaveLesson() {
  pause();
  closeLesson();
  plots.showAllLines();
  const saved = beforeLesson;
  beforeLesson = null;
  if (saved) {
    restore({ ...saved, lesson: null });
  } else {
    state.show = { ...DEFAULT_SHOW };
    syncViewControls();
    draw();
    saveUrl();
  }
  $("#lesson-start").focus();
}

// ---------------------------------------------------------------- the panels

let tomlEdited = false;
async function loadToml() {
  try {
    const forms = await postJson("/api/system", { system: state.system });
    $("#toml").value = forms.toml;
    tomlEdited = false;
  } catch (error) {
    showError(error);
  }
}

async function applyToml(text) {
  const slot = $("#toml-error");
  try {
    const forms = await postJson("/api/system", { toml: text });
    slot.hidden = true;
    $("#toml").removeAttribute("aria-invalid");
    tomlEdited = false;
    pendingChange = performance.now();
    quitLesson();
    loadSystem(forms.system, "");
    $("#toml").value = forms.toml;
  } catch (error) {
    slot.textContent = error.message;
    slot.hidden = false;
    $("#toml").setAttribute("aria-invalid", "true");
  }
}

async function loadDerivation() {
  const box = $("#derivation-body");
  box.textContent = "Deriving… (this can take a few seconds)";
  box.setAttribute("aria-busy", "true");
  try {
    const d = await derive({ system: state.system });
    if (d) {
      renderDerivation(box, d);
      watchScrollBoxes(box);
    }
  } catch (error) {
    box.textContent = `Could not derive: ${error.message}`;
  }
  box.removeAttribute("aria-busy");
}

function download(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function downloadStem() {
  return fileStem(state.preset, state.system.name, isEdited());
}

async function downloadFrom(path, payload, name) {
  try {
    download(await postBlob(path, payload), name);
  } catch (error) {
    setStatus(`Download failed: ${error.message}`);
  }
}

// ---------------------------------------------------------------- controls

function syncViewControls() {
  for (const key of Object.keys(state.show)) $(`#show-${key}`).checked = state.show[key];
  $("#continue-slip").checked = state.onSlip === "continue";
  $("#speed").value = String(state.speed);
  $("#duration").value = String(state.duration);
  showDurationError(null);
}

function showDurationError(message) {
  $("#duration-error").textContent = message || "";
  $("#duration-error").hidden = !message;
  if (message) $("#duration").setAttribute("aria-invalid", "true");
  else $("#duration").removeAttribute("aria-invalid");
}

/** Back to the system as loaded (its preset's own system when it came from one), the default
 * view options, arrow scale, speed and run length, at t = 0, paused. */
function resetAll() {
  if (state.lesson !== null) {
    goStep(state.lesson, { focus: "keep" }); // in the lesson: the step as it was set up
    return;
  }
  pause();
  const preset = presets.find((p) => p.name === state.preset);
  Object.assign(state, { show: { ...DEFAULT_SHOW }, onSlip: "stop", speed: 1, duration: DURATION_DEFAULT });
  setArrowZoom(1);
  $("#amplitude").value = "0.01";
  clearStartError();
  lastMode = null;
  autoplay = false;
  syncViewControls();
  plots.resetZoom();
  plots.showAllLines();
  pendingChange = performance.now();
  loadSystem(preset ? preset.system : loadedSystem, state.preset);
}

function wireControls() {
  const picker = $("#preset");
  picker.replaceChildren(new Option("(edited system)", ""),
    ...presets.map((p) => new Option(`${p.title} (${p.name})`, p.name)));
  picker.addEventListener("change", () => {
    const p = presets.find((q) => q.name === picker.value);
    if (p) {
      pause();
      quitLesson(); // another system: the lesson's words no longer describe it
      pendingChange = performance.now();
      loadSystem(p.system, p.name);
    }
  });
  $("#amplitude").addEventListener("change", () => {
    // a new amplitude replays the mode asked for last (and clears its error once valid)
    if (lastMode !== null && (state.start || !$("#amplitude-error").hidden)) playMode(lastMode);
  });
  $("#play").addEventListener("click", () => (playing ? pause() : play()));
  $("#step").addEventListener("click", step);
  $("#step-back").addEventListener("click", stepBack);
  $("#reset-all").addEventListener("click", resetAll);
  $("#lesson-start").addEventListener("click", enterLesson);
  $("#lesson-link").addEventListener("click", (e) => {
    // the step afresh, as the link opens it (the link itself is for copying)
    e.preventDefault();
    if (state.lesson !== null) goStep(state.lesson, { focus: "title" });
  });
  placeLesson();
  wide.addEventListener("change", placeLesson);
  // a link pasted into this tab changes only the fragment: open what it holds
  window.addEventListener("hashchange", async () => {
    clearTimeout(urlTimer); // the old state's pending write would replace the link
    pastes += 1;
    ownHash = location.hash;
    const saved = await decodeState(ownHash);
    if (saved) openSaved(saved);
    else saveUrl(); // a damaged link: the page's own state back in the address bar
  });
  $("#duration").addEventListener("change", () => {
    const parsed = parseDuration($("#duration").value);
    showDurationError(parsed.error);
    if (parsed.error) return;
    state.duration = parsed.value;
    pendingChange = performance.now();
    recomputeNow();
  });
  wireShortcuts({ playPause: () => (playing ? pause() : play()), step, stepBack, restart: () => seek(0),
    lessonNext: () => state.lesson !== null && state.lesson < STEPS.length - 1 && goStep(state.lesson + 1, { focus: "keep" }),
    lessonBack: () => state.lesson !== null && state.lesson > 0 && goStep(state.lesson - 1, { focus: "keep" }) },
    $("#shortcuts"), $("#keys-help"));
  $("#restart").addEventListener("click", () => seek(0));
  $("#time").addEventListener("input", () => seek(Number($("#time").value)));
  const speed = $("#speed");
  speed.replaceChildren(...SPEEDS.map((s) => new Option(`${s}×`, String(s))));
  speed.addEventListener("change", () => {
    state.speed = Number(speed.value);
    saveUrl();
  });
  for (const key of Object.keys(state.show)) {
    $(`#show-${key}`).addEventListener("change", (e) => {
      state.show[key] = e.target.checked;
      if (key === "linear") recomputeNow();
      else if (key === "absolute" && run) plots.update("positions", run, run.system, plotView());
      else draw();
      saveUrl();
    });
  }
  wireForceKey();
  $("#continue-slip").addEventListener("change", (e) => {
    state.onSlip = e.target.checked ? "continue" : "stop";
    pendingChange = performance.now();
    recomputeNow();
  });
  $("#share").addEventListener("click", async () => {
    clearTimeout(urlTimer);
    const write = ++urlWrites;
    const seen = pastes;
    const url = `${location.origin}${location.pathname}#${await encodeState(shareable())}`;
    if (mayWrite(write, seen)) {
      history.replaceState(null, "", url);
      ownHash = location.hash;
    }
    $("#share-url").value = url;
    $("#share-url").hidden = false;
    $("#share-url").select();
    try {
      await navigator.clipboard.writeText(url);
      setStatus("Link copied: it opens this system, initial state, view and time.");
    } catch {
      setStatus("Link ready: copy it from the field next to the Share button.");
    }
  });
  $("#toml-panel").addEventListener("toggle", () => $("#toml-panel").open && loadToml());
  $("#toml").addEventListener("input", () => (tomlEdited = true));
  $("#apply-toml").addEventListener("click", () => applyToml($("#toml").value));
  $("#import").addEventListener("change", async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    const text = await file.text();
    $("#toml").value = text;
    applyToml(text);
    e.target.value = "";
  });
  $("#download-toml").addEventListener("click", async () => {
    if (!tomlEdited) await loadToml();
    download(new Blob([$("#toml").value], { type: "application/toml" }), `${downloadStem()}.toml`);
  });
  $("#download-csv").addEventListener("click", () => downloadFrom("/api/simulate.csv",
    { system: state.system, duration: state.duration, outputs: outputsFor(state.duration), on_slip: state.onSlip,
      ...(state.start ? { start: state.start } : {}) }, `${downloadStem()}-trajectory.csv`));
  $("#download-report").addEventListener("click", () => downloadFrom("/api/report",
    { system: state.system }, `${downloadStem()}-report.html`));
  $("#derivation").addEventListener("toggle", () => $("#derivation").open && loadDerivation());
  syncViewControls();
  watchScrollBoxes($(".modes-section"));
  new ResizeObserver(() => {
    if (scene.resize()) draw();
  }).observe($("#scene"));
}

window.rollspringPage = {
  frameTimes: () => [...frames],
  lastUpdate: () => (lastUpdate ? { ...lastUpdate } : null),
  ready: () => readyPromise,
  system: () => structuredClone(state.system),
  time: () => state.t,
  dt,
  settled: () => timer === null && inFlight === 0 && lab.busy === 0 && (pendingChange === null || errorShown),
  drawn: () => structuredClone({ ...scene.drawn, forceScale }),
  plotData: (key) => plots.plotted(key),
  plotWindow: (key) => plots.window(key),
  labBusy: () => lab.busy > 0,
  lesson: () => (state.lesson === null ? null
    : { step: state.lesson, key: STEPS[state.lesson].key, count: STEPS.length }),
  playing: () => playing,
};

async function main() {
  presets = await getJson("/api/presets");
  wireControls();
  ownHash = location.hash; // a link pasted while the page was loading is the one opened
  const saved = await decodeState(ownHash);
  if (saved) {
    openSaved(saved);
    return;
  }
  let start = null;
  try {
    start = await getJson("/api/start");
  } catch {
    // an older server without /api/start: the default preset
  }
  const preset = presets.find((p) => p.name === (start && start.preset)) || presets.find((p) => p.name === "hoop-cylinder") || presets[0];
  if (start && !start.preset) loadSystem(start.system, "");
  else loadSystem(preset.system, preset.name);
}

main().catch((error) => setStatus(`The page could not start: ${error.message}`));
