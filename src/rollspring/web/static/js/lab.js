// The lab: a measured table (a track CSV, a plain CSV or a Tracker data file), loaded from the
// file picker or dropped on the panel, is sent to the server and read there
// (POST /api/lab/data: rollspring.lab.data), drawn over the model's positions; its tracks are
// matched to the bodies by name or, with one select per track, as the user chooses (the
// request's mapping, a track "not used" mapped to null); Fit sends it, with that mapping,
// with the system and the chosen free numbers (POST /api/fit = rollspring fit --json), shows
// the fitted values ± standard errors, the residual RMS per body and the paper's claims
// measured, and hands the fitted system to the page (its editor and plots).

import { ApiError, postJson } from "./api.js";
import { sig } from "./format.js";
import { watchScrollBoxes } from "./scrollbox.js";

/** The numbers a fit may free, for `system`: every spring's stiffness and damping (chosen by
 * default, as `rollspring fit` with the report's defaults), each rolling body's mass and
 * rolling resistance. [{path, label, checked}] */
export function freeChoices(system) {
  const out = [];
  (system.springs || []).forEach((spring, i) => {
    const name = `spring ${i + 1} (${spring.ends.join(" – ")})`;
    out.push({ path: `springs.${i}.stiffness`, label: `${name}: stiffness k`, checked: true });
    out.push({ path: `springs.${i}.damping`, label: `${name}: damping`, checked: true });
  });
  for (const body of system.bodies) {
    out.push({ path: `bodies.${body.id}.mass`, label: `${body.id}: mass`, checked: false });
    if (body.shape !== "slider") {
      out.push({ path: `bodies.${body.id}.rolling_resistance`, label: `${body.id}: rolling resistance C_rr`,
        checked: false });
    }
  }
  return out;
}

/** "1.234 ± 0.005": the value to the standard error's second significant digit (as the CLI). */
export function withError(value, stderr) {
  if (value == null) return "—";
  if (stderr == null || !(stderr > 0) || !Number.isFinite(stderr)) return sig(value, 6);
  const digits = Math.max(0, 1 - Math.floor(Math.log10(stderr)));
  if (Math.abs(value) >= 1e5 || (value !== 0 && Math.abs(value) < 1e-3 && digits > 8)) {
    return `${value.toExponential(3)} ± ${stderr.toExponential(1)}`;
  }
  return `${value.toFixed(digits)} ± ${stderr.toFixed(digits)}`;
}

const CLAIMS = [
  ["cm_peak_to_peak", "the centre of mass moves: its peak-to-peak", "m"],
  ["stationary_peak_to_peak", "X̂ stays put: its peak-to-peak", "m"],
  ["friction_ratio", "the frictions' ratio", ""],
];

export class LabPanel {
  /** `root` the panel; `page`: {system() → the system now, drawn(data) the data to draw (or
   * null), fitted(system) the fitted system to show}. */
  constructor(root, page) {
    this.root = root;
    this.page = page;
    this.text = null; // the file's text
    this.name = "";
    this.data = null; // the table as drawn ({source, t, bodies: {id: {x, phi}}, points})
    this.result = null; // the last /api/fit answer
    this.tracks = null; // the file's track names
    this.mapping = null; // {track: body id or null}: the match sent
    this.asked = 0; // the last /api/lab/data request (answers to earlier ones are dropped)
    this.busy = 0;
    this.$ = (selector) => root.querySelector(selector);
    this.$("#lab-file").addEventListener("change", (e) => {
      const file = e.target.files && e.target.files[0];
      if (file) this.load(file);
    });
    const drop = this.$("#lab-drop");
    drop.addEventListener("dragover", (e) => {
      e.preventDefault();
      drop.classList.add("over");
    });
    drop.addEventListener("dragleave", () => drop.classList.remove("over"));
    drop.addEventListener("drop", (e) => {
      e.preventDefault();
      drop.classList.remove("over");
      const file = e.dataTransfer && e.dataTransfer.files[0];
      if (file) this.load(file);
    });
    this.$("#lab-fit").addEventListener("click", () => this.fit());
    this.$("#lab-download").addEventListener("click", () => this.download());
    this.$("#lab-clear").addEventListener("click", () => this.clear());
  }

  /** The free-number boxes for the system now shown (kept ticked as they were, by PATH). */
  syncChoices(system) {
    const map = this.$("#lab-map-list");
    if (this.tracks && !this.$("#lab-map").hidden
        && map.dataset.signature !== system.bodies.map((b) => b.id).join("|")) {
      // the bodies renamed, added or removed: the selects offer them, and the table is read
      // again with what they now show
      this.renderMap(system);
      this.remap();
    }
    const box = this.$("#lab-free-list");
    const was = new Map([...box.querySelectorAll("input[data-free]")].map((i) => [i.dataset.free, i.checked]));
    const signature = freeChoices(system).map((c) => c.path).join("|");
    if (signature === box.dataset.signature) return;
    box.dataset.signature = signature;
    box.replaceChildren(...freeChoices(system).map((c) => {
      const label = document.createElement("label");
      const input = document.createElement("input");
      input.type = "checkbox";
      input.dataset.free = c.path;
      input.checked = was.has(c.path) ? was.get(c.path) : c.checked;
      label.append(input, ` ${c.label}`);
      return label;
    }));
  }

  /** One select per track of the file, each set to its body in this.mapping ("" = not used),
   * offering the bodies of `system`. */
  renderMap(system) {
    const list = this.$("#lab-map-list");
    const ids = system.bodies.map((b) => b.id);
    list.dataset.signature = ids.join("|");
    list.replaceChildren(...this.tracks.map((track, i) => {
      const row = document.createElement("div");
      row.className = "lab-map-row";
      const label = document.createElement("label");
      label.htmlFor = `lab-map-${i}`;
      label.textContent = `track '${track}' is`;
      const select = document.createElement("select");
      select.id = `lab-map-${i}`;
      select.dataset.track = track;
      select.setAttribute("aria-describedby", "lab-map-error");
      for (const [value, text] of [...ids.map((id) => [id, id]), ["", "not used"]]) {
        const option = document.createElement("option");
        option.value = value;
        option.textContent = text;
        select.append(option);
      }
      const body = this.mapping[track];
      select.value = body != null && ids.includes(body) ? body : "";
      select.addEventListener("change", () => this.remap());
      row.append(label, select);
      return row;
    }));
    this.$("#lab-map").hidden = false;
  }

  /** The match the selects show: {track: body id or null}. */
  chosen() {
    return Object.fromEntries([...this.$("#lab-map-list").querySelectorAll("select[data-track]")]
      .map((s) => [s.dataset.track, s.value || null]));
  }

  /** The table read again with the match the selects show, and drawn (or the server's refusal
   * — two tracks on one body — shown next to the selects). */
  async remap() {
    if (this.text == null) return;
    const mapping = this.chosen();
    const asked = ++this.asked;
    this.setError("#lab-fit-error", "");
    this.busy += 1;
    try {
      const answer = await postJson("/api/lab/data", { system: this.page.system(), data: this.text,
        filename: this.name, mapping });
      if (asked !== this.asked) return;
      this.mapping = mapping;
      this.mapError("");
      this.show(answer);
    } catch (error) {
      if (asked !== this.asked) return;
      this.mapping = mapping;
      this.mapError(error.message);
      this.data = null;
      this.$("#lab-fit").disabled = true;
      this.$("#lab-file-info").textContent = "";
      this.page.drawn(null);
    } finally {
      this.busy -= 1;
    }
  }

  mapError(message) {
    this.setError("#lab-map-error", message);
    for (const select of this.$("#lab-map-list").querySelectorAll("select")) {
      if (message) select.setAttribute("aria-invalid", "true");
      else select.removeAttribute("aria-invalid");
    }
  }

  /** A /api/lab/data answer shown: what was read, and the data drawn. */
  show(answer) {
    this.data = answer;
    this.result = null;
    this.$("#lab-result").replaceChildren();
    this.$("#lab-download").disabled = true;
    const bodies = Object.keys(answer.bodies);
    this.$("#lab-fit").disabled = bodies.length === 0;
    const t = answer.t;
    this.$("#lab-file-info").textContent = bodies.length === 0
      ? `${this.name}: no track matched to a body — choose each track's body below.`
      : `${this.name}: ${t.length} times over ${sig(t[t.length - 1] - t[0], 4)} s, `
        + `${answer.points} positions of ${bodies.join(", ")} — drawn as dots over the model's positions.`;
    this.page.drawn(bodies.length ? this.data : null);
  }

  /** The PATHs ticked. */
  free() {
    return [...this.$("#lab-free-list").querySelectorAll("input[data-free]:checked")].map((i) => i.dataset.free);
  }

  setError(slot, message) {
    const el = this.$(slot);
    el.textContent = message || "";
    el.hidden = !message;
    if (slot === "#lab-file-error") {
      if (message) this.$("#lab-file").setAttribute("aria-invalid", "true");
      else this.$("#lab-file").removeAttribute("aria-invalid");
    }
  }

  status(text) {
    this.$("#lab-status").textContent = text;
  }

  /** Read `file` (a File) and send it to the server to be read and matched to the bodies. */
  async load(file) {
    this.setError("#lab-file-error", "");
    this.setError("#lab-fit-error", "");
    this.busy += 1;
    this.status(`Reading ${file.name}…`);
    try {
      const text = await file.text();
      const system = this.page.system();
      const asked = ++this.asked;
      const answer = await postJson("/api/lab/data", { system, data: text, filename: file.name, unmatched: "omit" });
      if (asked !== this.asked) return;
      this.text = text;
      this.name = file.name;
      this.tracks = answer.tracks;
      this.mapping = answer.mapping;
      this.mapError("");
      this.$("#lab-clear").disabled = false;
      // the selects, when a track's name is no body's id
      if (this.tracks.some((track) => this.mapping[track] !== track)) this.renderMap(system);
      else this.$("#lab-map").hidden = true;
      this.show(answer);
      this.status("");
    } catch (error) {
      this.setError("#lab-file-error", error instanceof ApiError ? error.message : `${file.name}: ${error.message}`);
      this.status("");
    } finally {
      this.busy -= 1;
      this.$("#lab-file").value = "";
    }
  }

  /** Fit the system now shown to the data loaded (in a worker of the server, under its time
   * budget); show the result and hand the fitted system to the page. */
  async fit() {
    if (this.text == null) return;
    this.setError("#lab-fit-error", "");
    const button = this.$("#lab-fit");
    button.disabled = true;
    this.busy += 1;
    this.status("Fitting…");
    try {
      const answer = await postJson("/api/fit", { system: this.page.system(), data: this.text, filename: this.name,
        free: this.free(), fix_initial: this.$("#lab-fix-initial").checked,
        posterior: this.$("#lab-posterior").checked, mapping: this.mapping || {} });
      this.result = answer;
      this.data = answer.data;
      this.render(answer);
      this.$("#lab-download").disabled = false;
      const fit = answer.fit;
      this.status(`${fit.message} (${fit.points} positions; ${fit.motion}).`);
      this.page.fitted(answer.system, this.data);
    } catch (error) {
      this.setError("#lab-fit-error", error.message);
      this.status("");
    } finally {
      button.disabled = false;
      this.busy -= 1;
    }
  }

  render(answer) {
    const fit = answer.fit;
    const table = document.createElement("table");
    table.className = "lab-table";
    table.id = "lab-parameters";
    const caption = document.createElement("caption");
    const intervals = (fit.posterior && fit.posterior.credible_intervals) || null;
    caption.textContent = "Fitted values ± standard errors";
    const head = document.createElement("thead");
    head.innerHTML = '<tr><th scope="col">parameter</th><th scope="col">value</th>'
      + (intervals ? '<th scope="col">95 % credible interval (MCMC)</th>' : "") + '<th scope="col">unit</th></tr>';
    const body = document.createElement("tbody");
    for (const [name, p] of Object.entries(fit.parameters)) {
      const row = document.createElement("tr");
      row.dataset.parameter = name;
      row.dataset.value = String(p.value);
      row.dataset.stderr = String(p.stderr);
      const th = document.createElement("th");
      th.scope = "row";
      th.textContent = name;
      const value = document.createElement("td");
      value.className = "value";
      value.textContent = p.fixed ? `${sig(p.value, 6)} (held)` : withError(p.value, p.stderr);
      const unit = document.createElement("td");
      unit.textContent = p.unit || "";
      row.append(th, value);
      if (intervals) {
        const cell = document.createElement("td");
        cell.className = "interval";
        const interval = intervals[name];
        if (interval) {
          row.dataset.low = String(interval.low);
          row.dataset.high = String(interval.high);
          const digits = p.stderr > 0 ? Math.max(2, Math.ceil(Math.log10(Math.abs(p.value) / p.stderr)) + 2) : 6;
          cell.textContent = `${sig(interval.low, digits)} … ${sig(interval.high, digits)}`;
        } else {
          cell.textContent = "—";
        }
        row.append(cell);
      }
      row.append(unit);
      body.append(row);
    }
    table.append(caption, head, body);
    const rms = document.createElement("ul");
    rms.id = "lab-rms";
    rms.className = "lab-list";
    for (const [id, value] of Object.entries(fit.residual_rms)) {
      const item = document.createElement("li");
      item.dataset.body = id;
      item.dataset.value = String(value);
      item.textContent = `residual RMS of ${id}: ${value == null ? "—" : `${sig(value * 1000, 3)} mm`}`;
      rms.append(item);
    }
    const parts = [table, rms];
    const claims = fit.claims || {};
    if (claims.cm_peak_to_peak) {
      const list = document.createElement("ul");
      list.id = "lab-claims";
      list.className = "lab-list";
      for (const [key, text, unit] of CLAIMS) {
        const c = claims[key];
        if (!c) continue;
        const item = document.createElement("li");
        item.dataset.claim = key;
        item.dataset.value = String(c.value);
        item.dataset.stderr = String(c.stderr);
        item.textContent = `${text}: ${withError(c.value, c.stderr)}${unit ? ` ${unit}` : ""}`;
        list.append(item);
      }
      const title = document.createElement("p");
      title.className = "lab-subtitle";
      title.textContent = "The paper's claims, measured:";
      parts.push(title, list);
    }
    for (const warning of fit.warnings || []) {
      const p = document.createElement("p");
      p.className = "note";
      p.textContent = `⚠ ${warning}`;
      parts.push(p);
    }
    const scroll = document.createElement("div");
    scroll.className = "table-scroll lab-scroll";
    scroll.setAttribute("role", "region");
    scroll.setAttribute("aria-label", "The fitted values");
    scroll.append(...parts.splice(0, 1));
    this.$("#lab-result").replaceChildren(scroll, ...parts);
    watchScrollBoxes(scroll);
  }

  download() {
    if (!this.result) return;
    const blob = new Blob([this.result.toml], { type: "application/toml" });
    const a = document.createElement("a");
    a.href = URL.createObjectURL(blob);
    a.download = `${this.name.replace(/\.[^.]*$/, "") || "data"}-fitted.toml`;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  /** Forget the data (the plots show the model alone again). */
  clear() {
    this.asked += 1;
    this.text = null;
    this.tracks = null;
    this.mapping = null;
    this.$("#lab-map").hidden = true;
    this.$("#lab-map-list").replaceChildren();
    this.setError("#lab-map-error", "");
    this.data = null;
    this.result = null;
    this.$("#lab-result").replaceChildren();
    this.$("#lab-file-info").textContent = "";
    this.$("#lab-fit").disabled = true;
    this.$("#lab-download").disabled = true;
    this.$("#lab-clear").disabled = true;
    this.setError("#lab-file-error", "");
    this.setError("#lab-fit-error", "");
    this.status("");
    this.page.drawn(null);
  }
}
