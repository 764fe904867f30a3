// Draggable bodies and attachment dots over the canvas. Each body has a focusable overlay
// (role="slider") that follows it: drag it horizontally or use the keys — arrows ±1 mm,
// PageUp/PageDown ±1 cm, Home back to the loaded position — to set its initial x. An attachment
// dot (a spring end on a body) dragged with the pointer moves that end on the body.

import { snapDrag } from "./geometry.js";
import { roundTo } from "./format.js";

const SMALL = 0.001;
const BIG = 0.01;

export class Handles {
  /** `layer`: the positioned element over the canvas. `hooks`: {moveBody(id, x, phase),
   * moveDot(dot, canvasPoint, phase), dotAt(canvasPoint) → dot or null, pxPerM() , home(id),
   * x(id)}; phase is "move" while dragging and "end" when committed. */
  constructor(layer, hooks) {
    this.layer = layer;
    this.hooks = hooks;
    this.elements = new Map();
    this.drag = null;
    layer.addEventListener("pointerdown", (e) => this.down(e));
    layer.addEventListener("pointermove", (e) => this.move(e));
    layer.addEventListener("pointerup", (e) => this.up(e));
    layer.addEventListener("pointercancel", (e) => this.up(e));
  }

  point(e) {
    const box = this.layer.getBoundingClientRect();
    return { x: e.clientX - box.left, y: e.clientY - box.top };
  }

  down(e) {
    const q = this.point(e);
    const dot = this.hooks.dotAt(q);
    const handle = e.target.closest("[data-body]");
    if (!dot && !handle) return;
    e.preventDefault();
    this.layer.setPointerCapture(e.pointerId);
    if (dot) {
      this.drag = { dot };
    } else {
      const id = handle.dataset.body;
      handle.focus();
      this.drag = { id, startX: e.clientX, x0: this.hooks.x(id) };
    }
  }

  target(e) {
    if (this.drag.dot) return { q: this.point(e) };
    const dx = snapDrag(e.clientX - this.drag.startX, this.hooks.pxPerM());
    return { x: roundTo(this.drag.x0 + dx, 1e-6) };
  }

  move(e) {
    if (!this.drag) return;
    const { q, x } = this.target(e);
    if (this.drag.dot) this.hooks.moveDot(this.drag.dot, q, "move");
    else this.hooks.moveBody(this.drag.id, x, "move");
  }

  up(e) {
    if (!this.drag) return;
    const { q, x } = this.target(e);
    if (this.drag.dot) this.hooks.moveDot(this.drag.dot, q, "end");
    else this.hooks.moveBody(this.drag.id, x, "end");
    this.drag = null;
  }

  key(e, id) {
    const x = this.hooks.x(id);
    const steps = { ArrowRight: SMALL, ArrowUp: SMALL, ArrowLeft: -SMALL, ArrowDown: -SMALL,
      PageUp: BIG, PageDown: -BIG };
    let next = null;
    if (e.key in steps) next = roundTo(x + steps[e.key], 1e-6);
    else if (e.key === "Home") next = this.hooks.home(id);
    if (next === null) return;
    e.preventDefault();
    this.hooks.moveBody(id, next, "end");
  }

  /** Place one overlay per body: items [{id, left, top, size (the target's), ring (the body's
   * drawn size, for the focus ring; at most size), now (m), text}]. */
  sync(items) {
    const seen = new Set();
    for (const item of items) {
      seen.add(item.id);
      let el = this.elements.get(item.id);
      if (!el) {
        el = document.createElement("div");
        el.className = "body-handle";
        el.tabIndex = 0;
        el.setAttribute("role", "slider");
        el.dataset.body = item.id;
        el.setAttribute("aria-label", `${item.id}: initial position (drag, or arrow keys ±1 mm, `
          + "Page Up/Down ±1 cm, Home: back)");
        el.addEventListener("keydown", (e) => this.key(e, item.id));
        this.layer.append(el);
        this.elements.set(item.id, el);
      }
      el.style.left = `${item.left}px`;
      el.style.top = `${item.top}px`;
      el.style.width = el.style.height = `${item.size}px`;
      el.style.setProperty("--ring", `${item.ring ?? item.size}px`); // the focus ring: the body's size
      el.setAttribute("aria-valuenow", String(item.now));
      el.setAttribute("aria-valuemin", String(item.min));
      el.setAttribute("aria-valuemax", String(item.max));
      el.setAttribute("aria-valuetext", item.text);
    }
    for (const [id, el] of this.elements) {
      if (!seen.has(id)) {
        el.remove();
        this.elements.delete(id);
      }
    }
  }
}
