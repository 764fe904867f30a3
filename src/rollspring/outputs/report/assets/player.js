// The report's animation player (plain JavaScript, no library). It draws the system as an SVG
// scene from the embedded frame data (`animation-data`, see
// rollspring.outputs.report._motion_sections.animation_data): each body is a group translated
// to its centre and rotated by its angle, each spring a zigzag between its two attachment points
// (drawn by the page's geometry.js: one drawing of springs for the page and the report), the
// friction each body needs an arrow at its contact, and markers for the centre of mass and the
// stationary point X̂. Controls: Play/Pause, a speed selector, a frame slider (dragging it
// pauses) and a magnification of the displacements from equilibrium. Time runs on
// requestAnimationFrame; positions between two stored frames are interpolated linearly.
//
// An ES module for Node's tests (tests/js/player.test.mjs); the report inlines geometry.js and
// this file into one classic script that calls startPlayer(document, window)
// (rollspring.outputs.report._assets), so the page stays one file that fetches nothing.

import { bodyPoint, zigzag } from "../../js/geometry.js";

const NS = "http://www.w3.org/2000/svg";

/** The state at `time` of the frame data `D`: linear interpolation between stored frames;
 * `index` is the nearer stored frame. */
export function sample(D, time) {
  var nFrames = D.t.length, nBodies = D.bodies.length;
  var t0 = D.t[0], t1 = D.t[nFrames - 1];
  var dt = nFrames > 1 ? (t1 - t0) / (nFrames - 1) : 1;
  var u = (time - t0) / dt;
  var i = Math.max(0, Math.min(nFrames - 1, Math.floor(u)));
  var j = Math.min(nFrames - 1, i + 1);
  var a = Math.max(0, Math.min(1, u - i));
  function mix(rows, b) { return rows[i][b] + a * (rows[j][b] - rows[i][b]); }
  var out = { index: a < 0.5 ? i : j, x: [], phi: [], f: [], N: [], ratio: [] };
  for (var b = 0; b < nBodies; b++) {
    out.x.push(mix(D.x, b)); out.phi.push(mix(D.phi, b)); out.f.push(mix(D.f, b));
    out.N.push(mix(D.N, b)); out.ratio.push(mix(D.ratio, b));
  }
  out.cm = D.cm[i] + a * (D.cm[j] - D.cm[i]);
  out.xhat = D.xhat ? D.xhat[i] + a * (D.xhat[j] - D.xhat[i]) : null;
  return out;
}

/** Centre height of body `b` (world, m). */
function centreY(D, b) { return D.bodies[b].track + D.bodies[b].R; }

/** World position {x, y} of a spring end: an anchor, or a point of a body at drawn centres
 * `xs` and angles `phis` (docs/physics.md (M1), geometry.js bodyPoint). */
export function endPoint(D, end, xs, phis) {
  if (end.anchor) { return { x: end.anchor[0], y: end.anchor[1] }; }
  var body = D.bodies[end.body];
  return bodyPoint({ track_height: body.track, radius: body.R }, xs[end.body], phis[end.body],
                   { r: end.r, alpha: end.alpha });
}

/** SVG `points` of a spring from p to q (world, y flipped): geometry.js's zigzag with 14 coils,
 * leads of 12% of the length and teeth min(0.25 R_max, 6% of the length) wide at the joints. */
export function springPoints(p, q, rMax) {
  var length = Math.hypot(q.x - p.x, q.y - p.y);
  var points = zigzag(p, q, { coils: 14, width: Math.min(0.25 * rMax, 0.06 * length),
                              lead: 0.12 * length, placement: "joints" });
  return points.map(function (pt) { return pt.x + "," + (-pt.y); }).join(" ");
}

/** SVG path of a marker at world (x, y): a triangle (the CM) or a diamond (X̂). */
export function marker(x, y, size, kind) {
  var Y = -y;
  if (kind === "triangle") {
    return "M" + x + "," + (Y - size) + " L" + (x - size) + "," + (Y + size * 0.7) +
           " L" + (x + size) + "," + (Y + size * 0.7) + " Z";
  }
  return "M" + x + "," + (Y - size) + " L" + (x + size) + "," + Y + " L" + x + "," + (Y + size) +
         " L" + (x - size) + "," + Y + " Z";
}

/** A readout number: `d` decimals, rounding noise below 5e-13 shown as 0. */
export function fmt(v, d) { return (Math.abs(v) < 5e-13 ? 0 : v).toFixed(d); }

/** The world window {xmin, xmax, ymin, ymax, width, height} (y up) that holds every frame at
 * magnification `magnify`, the anchors and the floor band, widened to the scene's `aspect`
 * (width/height). */
export function viewWindow(D, magnify, aspect) {
  var nFrames = D.t.length, nBodies = D.bodies.length;
  var xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
  function take(x, y) { xmin = Math.min(xmin, x); xmax = Math.max(xmax, x);
                        ymin = Math.min(ymin, y); ymax = Math.max(ymax, y); }
  var stride = Math.max(1, Math.floor(nFrames / 200));
  for (var k = 0; k < nFrames; k += stride) {
    for (var b = 0; b < nBodies; b++) {
      var ref = D.bodies[b].x_ref, x = ref + magnify * (D.x[k][b] - ref), R = D.bodies[b].R;
      take(x - R, D.bodies[b].track); take(x + R, centreY(D, b) + R);
    }
  }
  D.anchors.forEach(function (a) { take(a.x, a.y); });
  var w = xmax - xmin, h = ymax - ymin, pad = 0.08 * Math.max(w, h) + 0.02;
  xmin -= pad; xmax += pad; ymin -= pad + 0.8 * D.R_max; ymax += pad;
  w = xmax - xmin; h = ymax - ymin;
  if (w / h < aspect) { var c = 0.5 * (xmin + xmax); w = h * aspect; xmin = c - w / 2; }
  else { var m = 0.5 * (ymin + ymax); h = w / aspect; ymin = m - h / 2; }
  return { xmin: xmin, xmax: xmin + w, ymin: ymin, ymax: ymin + h, width: w, height: h };
}

/** Start the player of the report page `doc` (its window `win`): draw the first frame and wire
 * the controls. Does nothing on a page without frame data. */
export function startPlayer(doc, win) {
  var node = doc.getElementById("animation-data");
  if (!node) { return; }
  var D = JSON.parse(node.textContent);
  var C = D.colors;  // the figures' palette (rollspring.outputs.figures.COLORS)
  var svg = doc.getElementById("scene");
  var playButton = doc.getElementById("play");
  var speedSelect = doc.getElementById("speed");
  var slider = doc.getElementById("frame");
  var magnifySelect = doc.getElementById("magnify");
  var clock = doc.getElementById("clock");
  var nFrames = D.t.length, nBodies = D.bodies.length;
  var t0 = D.t[0], t1 = D.t[nFrames - 1];
  var state = { time: t0, playing: false, last: null, magnify: D.magnify };

  function el(name, attrs, parent) {
    var e = doc.createElementNS(NS, name);
    for (var k in attrs) { e.setAttribute(k, attrs[k]); }
    if (parent) { parent.appendChild(e); }
    return e;
  }

  // displacements from equilibrium drawn magnified (labelled on the page)
  function drawnX(b, x) { return D.bodies[b].x_ref + state.magnify * (x - D.bodies[b].x_ref); }
  function drawnPhi(b, p) {
    return D.bodies[b].phi_ref + state.magnify * (p - D.bodies[b].phi_ref);
  }

  // -- the view box: every frame fits, at the current magnification -------------------------
  function fitView() {
    var aspect = svg.clientWidth > 0 ? svg.clientWidth / svg.clientHeight : 3;
    var v = viewWindow(D, state.magnify, aspect);
    svg.setAttribute("viewBox", [v.xmin, -v.ymax, v.width, v.height].join(" "));
    state.view = v;
    drawStatic();
  }

  // -- static parts: tracks and anchors ----------------------------------------------------
  var staticLayer = el("g", { "class": "static" }, svg);
  var springLayer = el("g", { "class": "springs" }, svg);
  var bodyLayer = el("g", { "class": "bodies" }, svg);
  var markLayer = el("g", { "class": "marks" }, svg);
  function drawStatic() {
    while (staticLayer.firstChild) { staticLayer.removeChild(staticLayer.firstChild); }
    var v = state.view, seen = {};
    D.bodies.forEach(function (body) {
      if (seen[body.track]) { return; }
      seen[body.track] = true;
      el("rect", { x: v.xmin, y: -body.track, width: v.xmax - v.xmin, height: 0.25 * D.R_max,
                   fill: "#e9edf2" }, staticLayer);
      el("line", { x1: v.xmin, y1: -body.track, x2: v.xmax, y2: -body.track, stroke: C.floor,
                   "stroke-width": 2, "vector-effect": "non-scaling-stroke" }, staticLayer);
    });
    D.anchors.forEach(function (a) {
      var s = 0.12 * D.R_max;
      el("rect", { x: a.x - s / 2, y: -a.y - s / 2, width: s, height: s, fill: C.wall },
         staticLayer);
    });
  }

  // -- bodies ------------------------------------------------------------------------------
  var bodyGroups = D.bodies.map(function (body) {
    var g = el("g", { "class": "body", "data-id": body.id }, bodyLayer);
    var R = body.R;
    if (body.shape === "slider") {
      el("rect", { x: -R, y: -R, width: 2 * R, height: 2 * R, fill: C.slider, stroke: C.edge,
                   "stroke-width": 1.5, "vector-effect": "non-scaling-stroke" }, g);
    } else if (body.shape === "hoop") {
      el("circle", { r: R * 0.97, fill: "none", stroke: C.hoop, "stroke-width": 0.06 * R }, g);
      for (var k = 0; k < 4; k++) {  // spokes, as on a bicycle wheel (the paper's hoop)
        var th = k * Math.PI / 4;
        el("line", { x1: -0.94 * R * Math.sin(th), y1: 0.94 * R * Math.cos(th),
                     x2: 0.94 * R * Math.sin(th), y2: -0.94 * R * Math.cos(th), stroke: C.hoop,
                     "stroke-opacity": 0.35, "stroke-width": 1,
                     "vector-effect": "non-scaling-stroke" }, g);
      }
    } else {
      el("circle", { r: R, fill: C[body.shape] || C.custom, stroke: C.edge, "stroke-width": 1.5,
                     "vector-effect": "non-scaling-stroke" }, g);
    }
    if (body.shape !== "slider") {  // the radius mark shows the rotation
      el("line", { x1: 0, y1: 0, x2: 0, y2: -0.94 * R, stroke: C.mark, "stroke-width": 2.5,
                   "vector-effect": "non-scaling-stroke" }, g);
    }
    el("circle", { r: 0.05 * R, fill: C.edge }, g);
    body.marks.forEach(function (m) {
      el("circle", { cx: m[0] * Math.sin(m[1]), cy: -m[0] * Math.cos(m[1]), r: 0.07 * R,
                     fill: C.spring }, g);
    });
    return g;
  });

  // -- springs, friction arrows, CM and X-hat markers --------------------------------------
  var springLines = D.springs.map(function () {
    return el("polyline", { fill: "none", stroke: C.spring, "stroke-width": 1.6,
                            "stroke-linejoin": "round", "vector-effect": "non-scaling-stroke" },
              springLayer);
  });
  var arrows = D.bodies.map(function () {
    return el("path", { fill: "none", "stroke-width": 2.5, "vector-effect": "non-scaling-stroke" },
              markLayer);
  });
  var cmMark = el("path", { fill: C.cm }, markLayer);
  var xhatMark = D.xhat ? el("path", { fill: C.xhat }, markLayer) : null;

  var readout = D.bodies.map(function (body) {
    return doc.getElementById("readout-" + body.id);
  });

  function render() {
    var s = sample(D, state.time), xs = [], phis = [];
    for (var b = 0; b < nBodies; b++) {
      xs.push(drawnX(b, s.x[b]));
      phis.push(drawnPhi(b, s.phi[b]));
    }
    for (b = 0; b < nBodies; b++) {
      var deg = D.bodies[b].shape === "slider" ? 0 : phis[b] * 180 / Math.PI;
      bodyGroups[b].setAttribute("transform", "translate(" + xs[b] + "," + (-centreY(D, b)) +
                                 ") rotate(" + deg + ")");
      var f = s.f[b], len = f * D.f_scale, y = D.bodies[b].track - 0.12 * D.R_max;
      var head = Math.sign(len) * Math.min(Math.abs(len), 0.12 * D.R_max);
      var colour = s.ratio[b] >= 1 ? C.applied : C.friction;
      arrows[b].setAttribute("stroke", colour);
      var tip = xs[b] + len, back = tip - head, wing = 0.5 * Math.abs(head);
      arrows[b].setAttribute("d", Math.abs(len) < 0.02 * D.R_max ? "" :
        "M" + xs[b] + "," + (-y) + " L" + tip + "," + (-y) +
        " M" + back + "," + (-y - wing) + " L" + tip + "," + (-y) + " L" + back + "," + (-y + wing));
      if (readout[b]) {
        var cells = readout[b].querySelectorAll("td");
        cells[1].textContent = fmt(1000 * (s.x[b] - D.bodies[b].x_ref), 3);
        cells[2].textContent = fmt(s.f[b], 4);
        cells[3].textContent = fmt(s.N[b], 4);
        cells[4].textContent = s.N[b] > 0 ? fmt(Math.abs(s.f[b]) / s.N[b], 4) : "∞";
      }
    }
    D.springs.forEach(function (spring, k) {
      springLines[k].setAttribute("points", springPoints(endPoint(D, spring.ends[0], xs, phis),
                                                         endPoint(D, spring.ends[1], xs, phis),
                                                         D.R_max));
    });
    var floor = D.floor - 0.42 * D.R_max, size = 0.09 * D.R_max;
    cmMark.setAttribute("d", marker(D.cm_ref + state.magnify * (s.cm - D.cm_ref), floor, size,
                                    "triangle"));
    if (xhatMark) {  // one row lower: X-hat and the CM may coincide
      xhatMark.setAttribute("d", marker(D.xhat_ref + state.magnify * (s.xhat - D.xhat_ref),
                                        floor - 2.5 * size, size, "diamond"));
    }
    clock.textContent = "t = " + state.time.toFixed(3) + " s";
    slider.value = String(s.index);
  }

  function tick(now) {
    if (!state.playing) { return; }
    if (state.last !== null) {
      state.time += (now - state.last) / 1000 * parseFloat(speedSelect.value);
      if (state.time > t1) { state.time = t0 + (state.time - t1) % Math.max(t1 - t0, 1e-9); }
    }
    state.last = now;
    render();
    win.requestAnimationFrame(tick);
  }

  function setPlaying(on) {
    state.playing = on;
    state.last = null;
    playButton.textContent = on ? "Pause" : "Play";
    playButton.setAttribute("aria-pressed", on ? "true" : "false");
    if (on) { win.requestAnimationFrame(tick); }
  }

  playButton.addEventListener("click", function () { setPlaying(!state.playing); });
  slider.max = String(nFrames - 1);
  slider.addEventListener("input", function () {
    setPlaying(false);
    state.time = D.t[parseInt(slider.value, 10)];
    render();
  });
  magnifySelect.addEventListener("change", function () {
    state.magnify = parseFloat(magnifySelect.value);
    fitView();
    render();
  });
  win.addEventListener("resize", function () { fitView(); render(); });
  fitView();
  render();
}
