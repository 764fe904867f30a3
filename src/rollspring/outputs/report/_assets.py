"""The report's inline style sheet and its animation player (plain JavaScript, no library).

The player draws the system as an SVG scene from the embedded frame data (``animation-data``,
see :func:`rollspring.outputs.report._build.animation_data`): each body is a group translated to
its centre and rotated by its angle, each spring a zigzag between its two attachment points, the
friction each body needs an arrow at its contact, and markers for the centre of mass and the
stationary point X̂. Controls: Play/Pause, a speed selector, a frame slider (dragging it pauses)
and a magnification of the displacements from equilibrium. Time runs on
``requestAnimationFrame``; positions between two stored frames are interpolated linearly.
"""

from __future__ import annotations

__all__ = ["CSS", "PLAYER_JS"]

CSS = r"""
:root { --ink: #1d232b; --muted: #5b6573; --line: #d5dbe3; --bg: #ffffff; --band: #f4f6f9;
        --accent: #2457a6; --ok: #1f7a3a; --bad: #b3261e; --warn: #9a6700; }
* { box-sizing: border-box; }
html { font-size: 15px; }
body { margin: 0; color: var(--ink); background: var(--bg);
       font-family: system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
       line-height: 1.45; }
main { max-width: 1120px; margin: 0 auto; padding: 1.2rem 1.4rem 3rem; }
header.page { border-bottom: 2px solid var(--ink); margin-bottom: 1rem; padding-bottom: .6rem; }
header.page h1 { margin: 0 0 .2rem; font-size: 1.7rem; }
header.page p { margin: .2rem 0; color: var(--muted); }
nav.toc { font-size: .9rem; margin-top: .5rem; }
nav.toc a { color: var(--accent); text-decoration: none; margin-right: .9rem; white-space: nowrap; }
section { margin: 1.6rem 0; }
section > h2 { font-size: 1.3rem; border-bottom: 1px solid var(--line); padding-bottom: .2rem; }
h3 { font-size: 1.05rem; margin: 1.1rem 0 .4rem; }
p.note, .note { color: var(--muted); font-size: .92rem; }
table { border-collapse: collapse; margin: .5rem 0 1rem; font-size: .92rem; }
caption { text-align: left; font-weight: 600; padding: .2rem 0 .35rem; }
th, td { border-bottom: 1px solid var(--line); padding: .28rem .6rem; text-align: left;
         vertical-align: top; }
th { background: var(--band); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tbody tr:nth-child(even) td { background: #fafbfc; }
.verdict-ok { color: var(--ok); font-weight: 600; }
.verdict-bad { color: var(--bad); font-weight: 600; }
.verdict-other { color: var(--warn); font-weight: 600; }
ul.warnings li { color: var(--warn); }
math { font-family: "STIX Two Math", "Latin Modern Math", "Cambria Math", math; font-size: 1.08em; }
math[display="block"] { margin: .45rem 0; }
mtd[columnalign="right"] { text-align: right; }
mtd[columnalign="left"] { text-align: left; }
table#paper-claims { table-layout: fixed; width: 100%; }
table#paper-claims td { overflow-wrap: anywhere; }
table#paper-claims th:nth-child(1) { width: 9%; }
table#paper-claims th:nth-child(2) { width: 31%; }
table#paper-claims th:nth-child(3) { width: 9%; }
table#paper-claims th:nth-child(4) { width: 26%; }
.cellmath { display: block; overflow-x: auto; max-width: 100%; padding: .15rem 0; }
/* phones: the claims table scrolls sideways with readable columns instead of squeezing them */
@media (max-width: 760px) {
  table#paper-claims { display: block; overflow-x: auto; table-layout: auto; }
  table#paper-claims th, table#paper-claims td { min-width: 8rem; max-width: 20rem; }
  table#paper-claims td { overflow-wrap: break-word; }
}
span.ref { color: var(--muted); font-size: .85em; }
.formula { overflow-x: auto; }
pre.tex-source, code.tex-source { background: #fff4f4; border: 1px dashed var(--bad);
                                  padding: .2rem .4rem; white-space: pre-wrap; }
figure { margin: 1rem 0; }
figure img, figure svg { max-width: 100%; height: auto; }
figcaption { color: var(--muted); font-size: .9rem; }
.grid2 { display: grid; grid-template-columns: repeat(auto-fit, minmax(430px, 1fr)); gap: 1rem; }
.method { border-left: 3px solid var(--line); padding-left: .9rem; margin: 1rem 0 1.4rem; }
.step { margin: .5rem 0 .8rem; }
.step .why { color: var(--muted); font-size: .92rem; margin: 0; }
#player { border: 1px solid var(--line); border-radius: 6px; padding: .6rem; background: #fcfdfe; }
#scene { display: block; width: 100%; height: 340px; background: #fff; }
.controls { display: flex; flex-wrap: wrap; gap: .8rem; align-items: center; margin: .5rem 0; }
.controls button { font: inherit; padding: .25rem 1.1rem; min-width: 6rem; cursor: pointer;
                   border: 1px solid var(--accent); background: var(--accent); color: #fff;
                   border-radius: 4px; }
.controls label { font-size: .9rem; color: var(--muted); }
.controls input[type=range] { flex: 1 1 260px; }
#clock { font-variant-numeric: tabular-nums; min-width: 7.5rem; }
.legend span { margin-right: 1rem; font-size: .88rem; color: var(--muted); }
.download a { color: var(--accent); }
footer { margin-top: 2.5rem; border-top: 1px solid var(--line); padding-top: .5rem;
         color: var(--muted); font-size: .85rem; }
@media print {
  @page { size: A4; margin: 12mm; }
  html { font-size: 9.5pt; }
  main { max-width: none; padding: 0; }
  .controls, nav.toc, .download { display: none; }
  figure, tr, .step, #player, caption { break-inside: avoid; }
  h2, h3, caption { break-after: avoid; }
  .grid2 { grid-template-columns: 1fr 1fr; gap: .5rem; }
  #scene { height: 220px; }
}
"""

PLAYER_JS = r"""
(function () {
  "use strict";
  var node = document.getElementById("animation-data");
  if (!node) { return; }
  var D = JSON.parse(node.textContent);
  var C = D.colors;  // the figures' palette (rollspring.outputs.figures.COLORS)
  var NS = "http://www.w3.org/2000/svg";
  var svg = document.getElementById("scene");
  var playButton = document.getElementById("play");
  var speedSelect = document.getElementById("speed");
  var slider = document.getElementById("frame");
  var magnifySelect = document.getElementById("magnify");
  var clock = document.getElementById("clock");
  var nFrames = D.t.length, nBodies = D.bodies.length;
  var t0 = D.t[0], t1 = D.t[nFrames - 1];
  var dt = nFrames > 1 ? (t1 - t0) / (nFrames - 1) : 1;
  var state = { time: t0, playing: false, last: null, magnify: D.magnify };

  function el(name, attrs, parent) {
    var e = document.createElementNS(NS, name);
    for (var k in attrs) { e.setAttribute(k, attrs[k]); }
    if (parent) { parent.appendChild(e); }
    return e;
  }

  // -- the state at a time: linear interpolation between stored frames ---------------------
  function sample(time) {
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

  // displacements from equilibrium drawn magnified (labelled on the page)
  function drawnX(b, x) { return D.bodies[b].x_ref + state.magnify * (x - D.bodies[b].x_ref); }
  function drawnPhi(b, p) {
    return D.bodies[b].phi_ref + state.magnify * (p - D.bodies[b].phi_ref);
  }
  function centreY(b) { return D.bodies[b].track + D.bodies[b].R; }
  function endPoint(end, xs, phis) {
    if (end.anchor) { return end.anchor; }
    var b = end.body, th = end.alpha + phis[b];
    return [xs[b] + end.r * Math.sin(th), centreY(b) + end.r * Math.cos(th)];
  }

  // -- the view box: every frame fits, at the current magnification -------------------------
  function fitView() {
    var xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
    function take(x, y) { xmin = Math.min(xmin, x); xmax = Math.max(xmax, x);
                          ymin = Math.min(ymin, y); ymax = Math.max(ymax, y); }
    var stride = Math.max(1, Math.floor(nFrames / 200));
    for (var k = 0; k < nFrames; k += stride) {
      for (var b = 0; b < nBodies; b++) {
        var x = drawnX(b, D.x[k][b]), R = D.bodies[b].R;
        take(x - R, D.bodies[b].track); take(x + R, centreY(b) + R);
      }
    }
    D.anchors.forEach(function (a) { take(a.x, a.y); });
    var w = xmax - xmin, h = ymax - ymin, pad = 0.08 * Math.max(w, h) + 0.02;
    xmin -= pad; xmax += pad; ymin -= pad + 0.8 * D.R_max; ymax += pad;
    var aspect = svg.clientWidth > 0 ? svg.clientWidth / svg.clientHeight : 3;
    w = xmax - xmin; h = ymax - ymin;
    if (w / h < aspect) { var c = 0.5 * (xmin + xmax); w = h * aspect; xmin = c - w / 2; }
    else { var m = 0.5 * (ymin + ymax); h = w / aspect; ymin = m - h / 2; }
    svg.setAttribute("viewBox", [xmin, -(ymin + h), w, h].join(" "));
    state.view = { xmin: xmin, xmax: xmin + w, ymin: ymin, ymax: ymin + h };
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
    var R = body.R, stroke = { "vector-effect": "non-scaling-stroke" };
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

  function zigzag(p, q) {
    var dx = q[0] - p[0], dy = q[1] - p[1], L = Math.sqrt(dx * dx + dy * dy);
    if (L === 0) { return p[0] + "," + (-p[1]); }
    var ux = dx / L, uy = dy / L, nx = -uy, ny = ux, coils = 14, lead = 0.12 * L;
    var amp = Math.min(0.25 * D.R_max, 0.06 * L), pts = [p];
    pts.push([p[0] + ux * lead, p[1] + uy * lead]);
    for (var k = 1; k < 2 * coils; k++) {
      var s = lead + (L - 2 * lead) * k / (2 * coils), side = (k % 2 ? 1 : -1) * amp;
      pts.push([p[0] + ux * s + nx * side, p[1] + uy * s + ny * side]);
    }
    pts.push([q[0] - ux * lead, q[1] - uy * lead]); pts.push(q);
    return pts.map(function (pt) { return pt[0] + "," + (-pt[1]); }).join(" ");
  }

  function marker(x, y, size, kind) {
    var Y = -y;
    if (kind === "triangle") {
      return "M" + x + "," + (Y - size) + " L" + (x - size) + "," + (Y + size * 0.7) +
             " L" + (x + size) + "," + (Y + size * 0.7) + " Z";
    }
    return "M" + x + "," + (Y - size) + " L" + (x + size) + "," + Y + " L" + x + "," + (Y + size) +
           " L" + (x - size) + "," + Y + " Z";
  }

  function fmt(v, d) { return (Math.abs(v) < 5e-13 ? 0 : v).toFixed(d); }
  var readout = D.bodies.map(function (body) {
    return document.getElementById("readout-" + body.id);
  });

  function render() {
    var s = sample(state.time), xs = [], phis = [];
    for (var b = 0; b < nBodies; b++) {
      xs.push(drawnX(b, s.x[b]));
      phis.push(drawnPhi(b, s.phi[b]));
    }
    for (b = 0; b < nBodies; b++) {
      var deg = D.bodies[b].shape === "slider" ? 0 : phis[b] * 180 / Math.PI;
      bodyGroups[b].setAttribute("transform", "translate(" + xs[b] + "," + (-centreY(b)) +
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
      springLines[k].setAttribute("points", zigzag(endPoint(spring.ends[0], xs, phis),
                                                   endPoint(spring.ends[1], xs, phis)));
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
    window.requestAnimationFrame(tick);
  }

  function setPlaying(on) {
    state.playing = on;
    state.last = null;
    playButton.textContent = on ? "Pause" : "Play";
    playButton.setAttribute("aria-pressed", on ? "true" : "false");
    if (on) { window.requestAnimationFrame(tick); }
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
  window.addEventListener("resize", function () { fitView(); render(); });
  fitView();
  render();
})();
"""
