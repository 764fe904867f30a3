// The time plots (uPlot), each with a time cursor that follows the animation's clock.

import uPlot from "/vendor/uplot/uPlot.esm.js";
import { energySeries, forceSeries, newtonSeries, positionSeries, ratioSeries } from "./series.js";

const POSITION_TITLES = {
  equilibrium: "Displacements from equilibrium: the CM (bold) moves, X̂ (bold, dashed) stays put",
  "t = 0": "Displacements from t = 0: the CM (bold) and X̂ (bold, dashed)",
  absolute: "Centre positions, the CM (bold) and X̂ (bold, dashed)",
};

const PLOTS = [
  { key: "positions", name: "Positions", title: POSITION_TITLES.equilibrium, unit: "x (m)", build: positionSeries },
  { key: "newton", name: "Σf and (Σm)·a_CM", title: "The whole system: Σf, the frictions, is (Σm)·a_CM — friction moves the CM",
    unit: "force (N)", build: newtonSeries },
  { key: "forces", name: "Friction and normal force", title: "Friction f and normal force N, with ±μs N", unit: "force (N)",
    build: forceSeries },
  { key: "ratio", name: "Friction used", title: "Friction used, |f| / (μs N)", unit: "|f| / (μs N)", build: ratioSeries },
  { key: "energy", name: "Energy", title: "Energy: kinetic (translational + rotational), potential, total",
    unit: "energy (J)", build: energySeries },
];

/** One uPlot per figure in `container`; `setRun` replaces the data, `setTime` moves the
 * cursors, `onSeek(t)` is called when the user clicks a plot to set the clock. Dragging across
 * a plot zooms every plot to that time window, Shift + drag pans it; on a focused plot + and −
 * zoom, ← and → pan, Home shows the whole run; `zoomButton` shows the whole run again. */
export class Plots {
  constructor(container, onSeek, zoomButton = null) {
    this.container = container;
    this.onSeek = onSeek;
    this.zoomed = null; // [t0, t1] shown by every plot, or null: the whole run
    this.t = 0;
    this.zoomButton = zoomButton;
    if (zoomButton) zoomButton.addEventListener("click", () => this.resetZoom());
    this.showZoom();
    this.figures = PLOTS.map((spec) => {
      const figure = document.createElement("figure");
      figure.className = "plot";
      figure.id = `plot-${spec.key}`;
      figure.dataset.plot = spec.key;
      figure.tabIndex = 0;
      figure.setAttribute("aria-label", `${spec.name} (plot: + and − zoom the time window, ← and → `
        + "pan it, Home shows the whole run)");
      figure.setAttribute("aria-keyshortcuts", "+ - ArrowLeft ArrowRight Home");
      figure.addEventListener("keydown", (e) => this.key(e, figure));
      this.panByDrag(figure);
      const caption = document.createElement("figcaption");
      caption.textContent = spec.title;
      figure.append(caption);
      container.append(figure);
      const lines = document.createElement("details");
      lines.className = "plot-lines";
      const summary = document.createElement("summary");
      summary.textContent = "Lines shown";
      const boxes = document.createElement("div");
      boxes.className = "boxes";
      lines.append(summary, boxes);
      figure.append(lines);
      return { spec, figure, caption, boxes, hidden: new Set(), plot: null, signature: "", cursor: null,
        revision: 0, built: null, only: null };
    });
    new ResizeObserver(() => this.resize()).observe(container);
  }

  width(figure) {
    return Math.max(200, Math.floor(figure.getBoundingClientRect().width));
  }

  resize() {
    for (const f of this.figures) if (f.plot) f.plot.setSize({ width: this.width(f.figure), height: 200 });
  }

  /** Show the trajectory `run` of `system`; `view`: how positions are shown (positionSeries). */
  setRun(run, system, view = {}) {
    for (const f of this.figures) this.show(f, run, system, view);
  }

  /** Show the plot `key` again (its view changed). */
  update(key, run, system, view = {}) {
    const f = this.figures.find((g) => g.spec.key === key);
    if (f && run) this.show(f, run, system, view);
  }

  /** The plot `key` as plotted: {labels, data} (data[0] is t). */
  plotted(key) {
    const f = this.figures.find((g) => g.spec.key === key);
    if (!f || !f.built) return null;
    return { labels: f.built.series.map((s) => s.label), unit: f.built.unit ?? f.spec.unit,
      styles: f.built.series.map((s) => ({ stroke: s.stroke, width: s.width || 1.6, dash: s.dash || [],
        markers: Boolean(s.markers) })),
      shown: f.built.series.map((s) => !f.hidden.has(s.label)),
      data: f.built.data.map((column) => Array.from(column)) };
  }

  show(f, run, system, view) {
    const built = f.spec.build(run, system, view);
    const { data, series } = built;
    const unit = built.unit ?? f.spec.unit;
    const signature = `${unit}|${series.map((s) => s.label).join("|")}`;
    if (f.plot && signature === f.signature) {
      f.plot.setData(data);
    } else {
      if (f.plot) f.plot.destroy();
      f.plot = this.make(f, series, data, unit);
      f.signature = signature;
      this.lineBoxes(f, series);
    }
    if (this.zoomed) {
      // the window zoomed to stays while it is within the run; a shorter run shows all of it
      const end = data[0][data[0].length - 1];
      if (this.zoomed[0] < end) f.plot.setScale("x", { min: this.zoomed[0], max: Math.min(this.zoomed[1], end) });
      else this.resetZoom();
    }
    if (built.reference) f.caption.textContent = POSITION_TITLES[built.reference];
    f.built = built;
    if (f.only) {
      // the lines a lesson step keeps: the others hidden (the reader can show them again)
      series.forEach((s, i) => {
        const want = f.only.has(s.label);
        if (f.plot.series[i + 1].show !== want) f.plot.setSeries(i + 1, { show: want });
      });
      f.only = null;
    }
    f.revision += 1;
    f.figure.dataset.revision = String(f.revision);
  }

  make(f, series, data, unit) {
    const plot = new uPlot({
      width: this.width(f.figure),
      height: 200,
      scales: { x: { time: false } },
      axes: [{ label: "t (s)", size: 36, labelSize: 18 }, { label: unit, size: 58, labelSize: 18 }],
      legend: { live: true },
      cursor: { drag: { x: true, y: false, setScale: false } },
      hooks: {
        setSelect: [(u) => {
          if (u.select.width > 3) {
            this.zoom(u.posToVal(u.select.left, "x"), u.posToVal(u.select.left + u.select.width, "x"));
          }
          u.setSelect({ left: 0, top: 0, width: 0, height: 0 }, false);
        }],
        setScale: [(u, key) => key === "x" && this.placeCursor(u)],
        setSeries: [(u, i, opts) => i != null && opts && "show" in opts && this.seriesShown(f, i - 1, opts.show)],
      },
      series: [{ label: "t (s)" }, ...series.map((s) => (s.markers ? {
        // a measured table: markers only, no line
        label: s.label, stroke: s.stroke, width: 1, show: !f.hidden.has(s.label),
        paths: () => null, points: { show: true, size: 3, width: 1, stroke: s.stroke, fill: s.stroke },
      } : {
        label: s.label, stroke: s.stroke, width: s.width || 1.6, dash: s.dash, spanGaps: Boolean(s.spanGaps),
        show: !f.hidden.has(s.label),
        points: { show: false },
      }))],
    }, data, f.figure);
    lineMarkers(plot, series);
    const cursor = document.createElement("div");
    cursor.className = "time-cursor";
    plot.over.append(cursor);
    let down = null;
    plot.over.addEventListener("mousedown", () => (down = plot.cursor.left));
    plot.over.addEventListener("click", () => {
      const left = plot.cursor.left;
      const dragged = down != null && left != null && Math.abs(left - down) > 3; // a zoom, not a click
      down = null;
      if (!dragged && left != null && left >= 0) this.onSeek(plot.posToVal(left, "x"));
    });
    f.cursor = cursor;
    return plot;
  }

  /** The plot's choice of lines: a checkbox per series (also toggled by a click on its legend
   * entry); a line hidden stays hidden while its plot keeps that series. */
  lineBoxes(f, series) {
    f.boxes.replaceChildren(...series.map((s, i) => {
      const label = document.createElement("label");
      const box = document.createElement("input");
      box.type = "checkbox";
      box.checked = !f.hidden.has(s.label);
      box.dataset.series = s.label;
      box.addEventListener("change", () => f.plot.setSeries(i + 1, { show: box.checked }));
      label.append(box, ` ${s.label}`);
      return label;
    }));
  }

  /** Only the plots `keys` shown (null: every plot), and in a plot of `lines` ({key: [labels]})
   * only those lines, from its next data on. */
  showOnly(keys, lines = {}) {
    for (const f of this.figures) {
      f.figure.hidden = Boolean(keys) && !keys.includes(f.spec.key);
      f.only = keys && lines[f.spec.key] ? new Set(lines[f.spec.key]) : null;
    }
  }

  /** Every line of every plot shown again. */
  showAllLines() {
    for (const f of this.figures) {
      f.only = null;
      f.hidden.clear();
      if (f.plot) f.plot.series.forEach((s, i) => i > 0 && !s.show && f.plot.setSeries(i, { show: true }));
    }
  }

  seriesShown(f, i, show) {
    const label = f.built ? f.built.series[i]?.label : null;
    if (label == null) return;
    if (show) f.hidden.delete(label);
    else f.hidden.add(label);
    const box = f.boxes.children[i]?.querySelector("input");
    if (box) box.checked = show;
  }

  /** Move every time cursor to t. */
  setTime(t) {
    this.t = t;
    for (const f of this.figures) if (f.plot) this.placeCursor(f.plot, f);
  }

  placeCursor(plot, f = this.figures.find((g) => g.plot === plot)) {
    if (!f || !f.cursor) return;
    const left = plot.valToPos(this.t, "x");
    f.cursor.style.transform = `translateX(${left}px)`;
    f.cursor.hidden = !(left >= 0 && left <= plot.over.clientWidth);
  }

  /** Show the time window [t0, t1] in every plot. */
  zoom(t0, t1) {
    this.zoomed = [Math.min(t0, t1), Math.max(t0, t1)];
    for (const f of this.figures) if (f.plot) f.plot.setScale("x", { min: this.zoomed[0], max: this.zoomed[1] });
    this.showZoom();
  }

  /** Show the whole run in every plot. */
  resetZoom() {
    this.zoomed = null;
    for (const f of this.figures) {
      if (!f.plot || !f.built) continue;
      const t = f.built.data[0];
      f.plot.setScale("x", { min: t[0], max: t[t.length - 1] });
    }
    this.showZoom();
  }

  /** The whole run: [first, last] output time (null before any data). */
  range() {
    const f = this.figures.find((g) => g.built);
    if (!f) return null;
    const t = f.built.data[0];
    return [t[0], t[t.length - 1]];
  }

  /** Show [t0, t1], kept inside the run (the same width when it can be), in every plot; the
   * whole run when it covers it. */
  setWindow(t0, t1) {
    const range = this.range();
    if (!range) return;
    const [start, end] = range;
    const width = Math.min(t1 - t0, end - start);
    const a = Math.max(start, Math.min(t0, end - width));
    if (width >= end - start - 1e-12) {
      this.resetZoom();
      return;
    }
    this.zoom(a, a + width);
  }

  /** The time window shown now: [t0, t1]. */
  shown() {
    return this.zoomed ? [...this.zoomed] : this.range();
  }

  /** The keys of a focused plot: + zoom in (about the clock, when it is in the window, or the
   * window's middle), − zoom out, ← → pan by a quarter of the window, Home the whole run. */
  key(e, figure) {
    if (e.target !== figure || e.ctrlKey || e.altKey || e.metaKey) return;
    const shown = this.shown();
    if (!shown) return;
    const [a, b] = shown;
    const w = b - a;
    const range = this.range();
    const least = Math.max((range[1] - range[0]) / 1000, 1e-9);
    const centre = this.t >= a && this.t <= b ? this.t : (a + b) / 2;
    if (e.key === "+" || e.key === "=") {
      const half = Math.max(w / 4, least / 2);
      this.setWindow(centre - half, centre + half);
    } else if (e.key === "-" || e.key === "_" || e.key === "−") {
      this.setWindow((a + b) / 2 - w, (a + b) / 2 + w);
    } else if (e.key === "ArrowLeft" || e.key === "ArrowRight") {
      const d = (e.key === "ArrowLeft" ? -w : w) / 4;
      if (this.zoomed) this.setWindow(a + d, b + d);
    } else if (e.key === "Home") {
      this.resetZoom();
    } else {
      return;
    }
    e.preventDefault();
  }

  /** Shift + drag across a plot pans every plot's time window (a plain drag zooms). */
  panByDrag(figure) {
    let pan = null;
    let panned = false;
    const move = (e) => {
      if (!pan) return;
      const dt = ((e.clientX - pan.x) / pan.width) * (pan.window[1] - pan.window[0]);
      if (Math.abs(e.clientX - pan.x) > 2) panned = true;
      this.setWindow(pan.window[0] - dt, pan.window[1] - dt);
    };
    const up = () => {
      pan = null;
      window.removeEventListener("mousemove", move);
      window.removeEventListener("mouseup", up);
    };
    figure.addEventListener("mousedown", (e) => {
      const over = e.target.closest && e.target.closest(".u-over");
      if (!e.shiftKey || !over || e.button !== 0) return;
      // before uPlot's own handler (a drag that selects a window to zoom to)
      e.stopPropagation();
      e.preventDefault();
      const shown = this.shown();
      if (!shown) return;
      pan = { x: e.clientX, width: Math.max(1, over.clientWidth), window: shown };
      panned = false;
      window.addEventListener("mousemove", move);
      window.addEventListener("mouseup", up);
    }, true);
    figure.addEventListener("click", (e) => {
      if (panned) {
        // the click that ends a pan does not also move the clock
        e.stopPropagation();
        panned = false;
      }
    }, true);
  }

  /** The time window plot `key` shows: [min, max]. */
  window(key) {
    const f = this.figures.find((g) => g.spec.key === key);
    return f && f.plot ? [f.plot.scales.x.min, f.plot.scales.x.max] : null;
  }

  showZoom() {
    if (this.zoomButton) this.zoomButton.disabled = this.zoomed === null;
  }
}

const SVG = "http://www.w3.org/2000/svg";

/** Each legend entry's marker drawn as a short piece of its line: colour, width and dash as
 * plotted (uPlot's own marker is a square with a CSS border, which cannot show a dash pattern). */
function lineMarkers(plot, series) {
  const rows = plot.root.querySelectorAll(".u-legend .u-series");
  series.forEach((s, i) => {
    const marker = rows[i + 1] && rows[i + 1].querySelector(".u-marker");
    if (!marker) return;
    const width = s.width || 1.6;
    const dash = s.dash || [];
    const svg = document.createElementNS(SVG, "svg");
    if (s.markers) {
      svg.setAttribute("viewBox", "0 0 32 10");
      svg.setAttribute("aria-hidden", "true");
      for (const cx of [6, 16, 26]) {
        const dot = document.createElementNS(SVG, "circle");
        Object.entries({ cx, cy: 5, r: 2.2, fill: s.stroke }).forEach(([k, v]) => dot.setAttribute(k, String(v)));
        svg.append(dot);
      }
      marker.classList.add("line-marker");
      marker.dataset.markers = "true";
      marker.replaceChildren(svg);
      return;
    }
    svg.setAttribute("viewBox", "0 0 32 10");
    svg.setAttribute("preserveAspectRatio", "none");
    svg.setAttribute("aria-hidden", "true");
    const line = document.createElementNS(SVG, "line");
    Object.entries({ x1: 0, y1: 5, x2: 32, y2: 5, stroke: s.stroke, "stroke-width": width,
      "stroke-dasharray": dash.length ? dash.join(" ") : "none" })
      .forEach(([k, v]) => line.setAttribute(k, String(v)));
    svg.append(line);
    marker.classList.add("line-marker");
    marker.dataset.dash = dash.join(" ");
    marker.dataset.width = String(width);
    marker.replaceChildren(svg);
  });
}
