// Boxes that scroll sideways inside the page (the modes table, the derivation's formulas, the
// claims' formulas): while a box's content is wider than the box it is marked
// data-overflowing="true" (the style sheet's cue: shadows at the side that has more), the hint
// just before it (a `.scroll-hint`) is shown, and it is made focusable, so that the keyboard can
// scroll it too (WCAG 2.1.1; axe-core's "scrollable-region-focusable"). Sizes are read only when a
// box or its content is resized, never per frame.

/** What scrolls sideways in the page's panels. */
export const SCROLL_BOXES = ".table-scroll, .derivation .math, .tex-math, .claims .claim-math, .claims .correction";

const boxOf = new WeakMap(); // an observed element → the box it belongs to
const observer = typeof ResizeObserver === "function"
  ? new ResizeObserver((entries) => {
    for (const box of new Set(entries.map((e) => boxOf.get(e.target)))) if (box) mark(box);
  })
  : null;

/** Watch every scrolling box in `root` (itself included), now and as it or its content resizes. */
export function watchScrollBoxes(root) {
  const boxes = [...(root.matches(SCROLL_BOXES) ? [root] : []), ...root.querySelectorAll(SCROLL_BOXES)];
  for (const box of boxes) {
    mark(box);
    if (!observer) continue;
    for (const el of [box, ...box.children]) {
      boxOf.set(el, box);
      observer.observe(el);
    }
  }
}

/** Mark `box` by whether its content is wider than it is. */
export function mark(box) {
  const over = box.scrollWidth > box.clientWidth + 1;
  if (box.dataset.overflowing !== String(over)) box.dataset.overflowing = String(over);
  if (over && !box.hasAttribute("tabindex")) {
    box.tabIndex = 0;
    box.dataset.focusableWhileOverflowing = "";
  } else if (!over && "focusableWhileOverflowing" in box.dataset) {
    box.removeAttribute("tabindex");
    delete box.dataset.focusableWhileOverflowing;
  }
  const hint = box.previousElementSibling;
  if (hint && hint.classList.contains("scroll-hint")) hint.hidden = !over;
}
