// The system editor: every body, spring, anchor and gravity as labelled fields (with sliders for
// the values one explores), add/remove, and the server's one-line error shown next to the field
// it names. Fields edit `system` (the JSON form) in place; `onEdit(kind)` is then called with
// kind "input" (a slider moving) or "commit" (a field or slider committed: change event).

const SHAPES = ["hoop", "cylinder", "sphere", "shell", "custom", "slider"];

const BODY_FIELDS = [
  { key: "mass", label: "mass", unit: "kg", slider: [0.05, 10, 0.05] },
  { key: "radius", label: "radius", unit: "m", slider: [0.01, 0.5, 0.005] },
  { key: "inertia_factor", label: "inertia factor γ (I = γmR²)", unit: "", only: "custom",
    slider: [0.01, 1, 0.01] },
  { key: "mu_static", label: "μs (static friction; inf = no slip)", unit: "", text: true },
  { key: "mu_kinetic", label: "μk (kinetic friction; empty = μs)", unit: "", optional: true },
  { key: "rolling_resistance", label: "rolling resistance C_rr (0 to 0.5; empty = 0)", unit: "",
    optional: true, not: "slider", slider: [0, 0.5, 0.0005] }, // the model's range (schema RANGES)
  { key: "track_height", label: "track height", unit: "m" },
  { key: "x", label: "initial x", unit: "m" },
  { key: "v", label: "initial v", unit: "m/s" },
];

const SPRING_FIELDS = [
  { key: "stiffness", label: "stiffness k", unit: "N/m", slider: [1, 1000, 1] },
  { key: "rest_length", label: "rest length (empty = initial length)", unit: "m", optional: true },
  { key: "damping", label: "damping", unit: "N s/m" },
];

/** Read the value at a dotted path ("bodies.0.mass") of an object. */
export function getPath(object, path) {
  return path.split(".").reduce((o, k) => (o == null ? undefined : o[k]), object);
}

/** Set (or with `undefined`, delete) the value at a dotted path, creating objects on the way. */
export function setPath(object, path, value) {
  const keys = path.split(".");
  const last = keys.pop();
  const parent = keys.reduce((o, k) => (o[k] ??= {}), object);
  if (value === undefined) delete parent[last];
  else parent[last] = value;
}

/** A field's text → its JSON value: a number, "inf" (μs), undefined (empty optional), or the
 * text itself when it is not a number (the server then names the problem). */
export function parseField(text, { optional = false, allowInf = false } = {}) {
  const t = text.trim();
  if (t === "" && optional) return undefined;
  if (allowInf && /^(inf|infinity|∞)$/i.test(t)) return "inf";
  const n = Number(t);
  return t !== "" && Number.isFinite(n) ? n : t;
}

let uid = 0;
const nextId = (prefix) => `${prefix}-${++uid}`;

export class Editor {
  constructor(container, onEdit) {
    this.container = container;
    this.onEdit = onEdit;
    this.system = null;
  }

  /** Show `system` (rebuilds the form). */
  load(system) {
    this.system = system;
    this.render();
  }

  render() {
    const s = this.system;
    const root = document.createElement("div");
    root.className = "editor";
    root.append(this.group("Gravity", [this.numberField("gravity", "gravity g", "m/s²", [0, 20, 0.01])]));
    s.bodies.forEach((body, i) => root.append(this.bodyGroup(body, i)));
    root.append(this.addButton("Add body", () => this.addBody()));
    s.springs.forEach((spring, i) => root.append(this.springGroup(spring, i)));
    root.append(this.addButton("Add spring", () => this.addSpring()));
    (s.anchors || []).forEach((anchor, i) => root.append(this.anchorGroup(anchor, i)));
    root.append(this.addButton("Add wall anchor", () => this.addAnchor()));
    this.container.replaceChildren(root);
  }

  group(title, children, path = "", onRemove = null) {
    const fieldset = document.createElement("fieldset");
    fieldset.className = "group";
    const legend = document.createElement("legend");
    legend.textContent = title;
    fieldset.append(legend, ...children);
    if (path) fieldset.append(this.errorSlot(path));
    if (onRemove) {
      const remove = document.createElement("button");
      remove.type = "button";
      remove.className = "remove";
      remove.textContent = `Remove ${title}`;
      remove.addEventListener("click", onRemove);
      fieldset.append(remove);
    }
    return fieldset;
  }

  errorSlot(path) {
    const slot = document.createElement("p");
    slot.className = "field-error";
    slot.dataset.errorFor = path;
    slot.id = nextId("error");
    slot.hidden = true;
    return slot;
  }

  addButton(text, action) {
    const button = document.createElement("button");
    button.type = "button";
    button.className = "add";
    button.textContent = text;
    button.addEventListener("click", () => {
      action();
      this.render();
      this.onEdit("commit");
    });
    return button;
  }

  /** A labelled number (or "inf"-accepting text) input at `path`, with an optional range slider
   * [min, max, step] kept in step with it, and its error slot. */
  numberField(path, label, unit, slider = null, { text = false, optional = false } = {}) {
    const wrap = document.createElement("div");
    wrap.className = "field";
    const id = nextId("f");
    const labelEl = document.createElement("label");
    labelEl.htmlFor = id;
    labelEl.textContent = unit ? `${label} (${unit})` : label;
    const input = document.createElement("input");
    input.id = id;
    input.type = "text";
    input.inputMode = text ? "text" : "decimal";
    input.dataset.path = path;
    input.autocomplete = "off";
    const value = getPath(this.system, path);
    input.value = value === undefined || value === null ? "" : String(value);
    const error = this.errorSlot(path);
    input.setAttribute("aria-describedby", error.id);
    wrap.append(labelEl, input);
    let range = null;
    if (slider) {
      range = document.createElement("input");
      range.type = "range";
      [range.min, range.max, range.step] = slider.map(String);
      range.value = Number.isFinite(Number(value)) ? String(value) : slider[0];
      range.setAttribute("aria-label", `${label} slider`);
      range.dataset.sliderFor = path;
      range.addEventListener("input", () => {
        input.value = range.value;
        setPath(this.system, path, Number(range.value));
        this.onEdit("input");
      });
      range.addEventListener("change", () => this.onEdit("commit"));
      wrap.append(range);
    }
    input.addEventListener("change", () => {
      const parsed = parseField(input.value, { optional, allowInf: text });
      setPath(this.system, path, parsed);
      if (range && typeof parsed === "number") range.value = String(parsed);
      this.onEdit("commit");
    });
    wrap.append(error);
    return wrap;
  }

  select(path, label, options, onChange) {
    const wrap = document.createElement("div");
    wrap.className = "field";
    const id = nextId("f");
    const labelEl = document.createElement("label");
    labelEl.htmlFor = id;
    labelEl.textContent = label;
    const select = document.createElement("select");
    select.id = id;
    select.dataset.path = path;
    for (const o of options) select.append(new Option(o, o));
    select.value = getPath(this.system, path);
    select.addEventListener("change", () => {
      setPath(this.system, path, select.value);
      if (onChange) onChange(select.value);
      this.render();
      this.onEdit("commit");
      this.container.querySelector(`select[data-path="${path}"]`)?.focus();
    });
    wrap.append(labelEl, select, this.errorSlot(path));
    return wrap;
  }

  bodyGroup(body, i) {
    const base = `bodies.${i}`;
    const fields = [this.select(`${base}.shape`, "shape", SHAPES, (shape) => {
      if (shape === "custom") body.inertia_factor ??= 0.5;
      else delete body.inertia_factor;
      if (shape === "slider") delete body.rolling_resistance; // a slider does not roll
    })];
    for (const f of BODY_FIELDS) {
      if (f.only && body.shape !== f.only) continue;
      if (f.not && body.shape === f.not) continue;
      fields.push(this.numberField(`${base}.${f.key}`, f.label, f.unit, f.slider || null,
        { text: !!f.text, optional: !!f.optional }));
    }
    return this.group(`Body “${body.id}”`, fields, base,
      this.system.bodies.length > 1 ? () => this.removeEnd("bodies", i) : null);
  }

  springGroup(spring, i) {
    const base = `springs.${i}`;
    const ids = [...this.system.bodies.map((b) => b.id), ...(this.system.anchors || []).map((a) => a.id)];
    const fields = [0, 1].map((j) => this.select(`${base}.ends.${j}`, `end ${j + 1}`, ids, () => {
      delete spring.at;
    }));
    for (const f of SPRING_FIELDS) {
      fields.push(this.numberField(`${base}.${f.key}`, f.label, f.unit, f.slider || null,
        { optional: !!f.optional }));
    }
    spring.ends.forEach((end, j) => {
      const body = this.system.bodies.find((b) => b.id === end);
      if (body && body.shape !== "slider") fields.push(this.attachmentFields(spring, i, j));
    });
    return this.group(`Spring ${i + 1}: ${spring.ends.join(" – ")}`, fields, base,
      () => this.removeItem("springs", i));
  }

  /** Where end j of spring i is attached: centre, a height on the centre vertical, or a point
   * {radius, angle}; the point is also draggable on the canvas. */
  attachmentFields(spring, i, j) {
    const at = spring.at ? spring.at[j] : {};
    const form = at.height != null ? "height" : at.radius != null ? "point" : "centre";
    const wrap = document.createElement("fieldset");
    wrap.className = "attachment";
    const legend = document.createElement("legend");
    legend.textContent = `end ${j + 1} (${spring.ends[j]}) attached at`;
    const id = nextId("f");
    const label = document.createElement("label");
    label.htmlFor = id;
    label.textContent = "form";
    const select = document.createElement("select");
    select.id = id;
    for (const [value, text] of [["centre", "centre"], ["height", "height on the centre vertical"],
      ["point", "point (radius, angle)"]]) select.append(new Option(text, value));
    select.value = form;
    select.addEventListener("change", () => {
      spring.at ??= [{}, {}];
      const body = this.system.bodies.find((b) => b.id === spring.ends[j]);
      spring.at[j] = select.value === "height" ? { height: body.radius * 2 }
        : select.value === "point" ? { radius: body.radius, angle: 0 } : {};
      this.render();
      this.onEdit("commit");
    });
    const row = document.createElement("div");
    row.className = "field";
    row.append(label, select);
    wrap.append(legend, row);
    const base = `springs.${i}.at.${j}`;
    if (form === "height") wrap.append(this.numberField(`${base}.height`, "height above track", "m"));
    if (form === "point") {
      wrap.append(this.numberField(`${base}.radius`, "distance from centre", "m"),
        this.numberField(`${base}.angle`, "angle clockwise from up", "°", [0, 360, 1]));
    }
    wrap.append(this.errorSlot(`springs.${i}.at`));
    return wrap;
  }

  anchorGroup(anchor, i) {
    const base = `anchors.${i}`;
    return this.group(`Wall anchor “${anchor.id}”`, [
      this.numberField(`${base}.x`, "x", "m"),
      this.numberField(`${base}.y`, "y", "m"),
    ], base, () => this.removeEnd("anchors", i));
  }

  /** Remove a body or anchor and every spring or force that uses it. */
  removeEnd(kind, i) {
    const [gone] = this.system[kind].splice(i, 1);
    this.system.springs = this.system.springs.filter((s) => !s.ends.includes(gone.id));
    if (this.system.forces) this.system.forces = this.system.forces.filter((f) => f.body !== gone.id);
    this.render();
    this.onEdit("commit");
  }

  removeItem(kind, i) {
    this.system[kind].splice(i, 1);
    this.render();
    this.onEdit("commit");
  }

  freeId(prefix) {
    const used = new Set([...this.system.bodies, ...(this.system.anchors || [])].map((o) => o.id));
    let n = 1;
    while (used.has(`${prefix}${n}`)) n += 1;
    return `${prefix}${n}`;
  }

  addBody() {
    const last = this.system.bodies[this.system.bodies.length - 1];
    this.system.bodies.push({ id: this.freeId("body"), shape: "cylinder", mass: 1, radius: 0.1,
      x: Math.round(((last ? last.x : 0) + 0.5) * 1000) / 1000, v: 0, mu_static: 1 });
  }

  addSpring() {
    const b = this.system.bodies;
    const ends = b.length > 1 ? [b[b.length - 2].id, b[b.length - 1].id]
      : [(this.system.anchors || [])[0]?.id ?? b[0].id, b[0].id];
    this.system.springs.push({ ends, stiffness: 100 });
  }

  addAnchor() {
    const xmin = Math.min(...this.system.bodies.map((b) => b.x - b.radius));
    this.system.anchors ??= [];
    this.system.anchors.push({ id: this.freeId("wall"), x: Math.round((xmin - 0.4) * 1000) / 1000, y: 0.1 });
  }

  /** Mark the field at `path` (or its nearest enclosing group) invalid with `message`;
   * returns false when no field on the form matches. */
  showError(path, message) {
    const parts = path.split(".");
    while (parts.length) {
      const p = parts.join(".");
      const slot = this.container.querySelector(`[data-error-for="${CSS.escape(p)}"]`);
      if (slot) {
        slot.textContent = message;
        slot.hidden = false;
        this.container.querySelector(`[data-path="${CSS.escape(p)}"]`)?.setAttribute("aria-invalid", "true");
        return true;
      }
      parts.pop();
    }
    return false;
  }

  clearErrors() {
    for (const slot of this.container.querySelectorAll(".field-error")) {
      slot.hidden = true;
      slot.textContent = "";
    }
    for (const el of this.container.querySelectorAll("[aria-invalid]")) el.removeAttribute("aria-invalid");
  }

  /** Show a value changed elsewhere (a drag on the canvas) in its field. */
  refreshField(path) {
    const input = this.container.querySelector(`input[data-path="${CSS.escape(path)}"]`);
    if (input) input.value = String(getPath(this.system, path));
  }
}
