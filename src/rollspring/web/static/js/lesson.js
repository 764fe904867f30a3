// The guided lesson (issue 26, point 4): the paper in six steps. Each step loads one of the
// paper's systems (a preset, or a preset started along its mode), sets the view — the force
// arrows, the markers, the plots and lines shown, the strip's magnification, the time, play or
// pause — and says in a few sentences what to look at, naming the paper's figure and equation.
// `STEPS` is pure data (tested in Node); `LessonPanel` is the panel with its step indicator and
// Back/Next/Leave buttons; main.js applies a step's system and view.
//
// The issue called it "the paper in five steps" and listed six; the six are kept, and the title
// says six.

export const LESSON_TITLE = "The paper in six steps";

/** The strip's magnification in steps 1, 2, 3 and 5: one value, so that the CM's motion can be
 * compared from step to step (the default system's CM swings ±0.7 mm: ±0.14 m on the strip's
 * scale, well inside it on a laptop and on a phone). */
export const LESSON_MAGNIFICATION = 200;

/** The lines of the friction plot step 4 keeps (series labels of series.js's forceSeries). */
const FRICTIONS_ONLY = ["hoop f", "cylinder f"];

/**
 * Each step: `key` (its name in tests and links), `title`, `figure` (the paper's figure or
 * equations it is about), `preset`, `start` (a mode start, {mode, amplitude}, or null),
 * `show` (the view options set on top of the page's defaults), `magnification` (the strip's,
 * or null: chosen to fit), `plots` (the plots shown, in order; the others hidden while the
 * lesson is on), `lines` ({plot key: the only series shown}), `t` (s, where the clock starts),
 * `play` (it plays on arrival, unless the reader asked for reduced motion), `text` (two
 * paragraphs, three or four sentences in all; a `{plot:key|words}` becomes a link to that
 * plot, `{why:id|words}` to a "Why?" panel).
 */
export const STEPS = [
  {
    key: "fig1",
    title: "Two blocks on a frictionless floor",
    figure: "Fig. 1",
    preset: "two-masses",
    start: null,
    show: { spring: true, friction: false, normal: false, markers: true, percussion: false },
    magnification: LESSON_MAGNIFICATION,
    plots: ["positions", "newton"],
    lines: {},
    t: 0,
    play: true,
    text: [
      "Two blocks joined by a spring slide on a floor without friction (the paper's Fig. 1, its "
        + "equations (f1) and (f2)). The spring pushes them with equal and opposite forces, which "
        + "cancel in the sum: (m₁ + m₂)·Ẍ = 0.",
      "Watch the strip under the floor: it magnifies the centre of mass ×200, and its mark "
        + "stays put while the blocks swing ({plot:positions|in the displacements the CM is the "
        + "flat bold line}).",
    ],
  },
  {
    key: "fig2",
    title: "A hoop and a cylinder: the centre of mass moves",
    figure: "Fig. 2",
    preset: "hoop-cylinder",
    start: null,
    show: { spring: false, friction: true, normal: false, markers: true, percussion: false },
    magnification: LESSON_MAGNIFICATION,
    plots: ["newton", "positions"],
    lines: {},
    t: 0,
    play: true,
    text: [
      "A hoop and a solid cylinder of the same mass and radius roll without slipping, their "
        + "centres joined by the spring (Fig. 2). The spring's forces still cancel, but each body "
        + "needs static friction from the floor to roll, and friction is an external force.",
      "The two frictions (red arrows) do not cancel, so the centre of mass swings on the strip, "
        + "at the same ×200 as in step 1: {plot:newton|Σf beside (Σm)·a_CM} is Newton's second law "
        + "for the whole system ({why:why-cm|why the CM moves}).",
    ],
  },
  {
    key: "xhat",
    title: "X̂: the point that stays put",
    figure: "eqs. (rel1) and (c)",
    preset: "hoop-cylinder",
    start: null,
    show: { spring: false, friction: false, normal: false, markers: true, percussion: false },
    magnification: LESSON_MAGNIFICATION,
    plots: ["positions"],
    lines: {},
    t: 0,
    play: true,
    text: [
      "Friction has no moment about the contact line, so adding the rotation equations about "
        + "the contact lines and integrating from rest gives I′₁φ̇₁ + I′₂φ̇₂ = 0, eq. (rel1): the "
        + "point X̂ = (I′₁x₁ + I′₂x₂)/(I′₁ + I′₂), eq. (c), never moves. Its weights are 4/7 and "
        + "3/7 here (I′ = 2mR² for the hoop, 3/2·mR² for the cylinder), not the masses' 1/2 and "
        + "1/2.",
      "On the strip X̂'s trail falls straight down, and in {plot:positions|the displacements} "
        + "X̂ (bold, dashed) stays flat while the CM (bold) swings ({why:why-xhat|more on X̂}).",
    ],
  },
  {
    key: "frictions",
    title: "The frictions: 3 : 2, in opposite directions",
    figure: "Appendix A",
    preset: "hoop-cylinder",
    start: null,
    show: { spring: true, friction: true, normal: false, markers: true, percussion: false,
      values: true },
    magnification: LESSON_MAGNIFICATION,
    plots: ["forces"],
    lines: { forces: FRICTIONS_ONLY },
    t: 0,
    play: false,
    text: [
      "Paused at the release, where the compressed spring pushes hardest: the hoop needs the "
        + "friction f₁, the cylinder f₂, pointing opposite ways, with f₁/f₂ = 3/2 in size (the "
        + "paper, after eq. (c); Appendix A). The hoop needs more because more of its inertia is in "
        + "its rim: spinning it up as it rolls takes a larger torque, and only friction gives one.",
      "{plot:forces|The friction plot} shows only the two frictions, one always −3/2 times the "
        + "other; press Play to watch them swap sides every half period.",
    ],
  },
  {
    key: "fig3",
    title: "Percussion points: no friction, the centre of mass at rest",
    figure: "Fig. 3, eq. (fric)",
    preset: "frictionless",
    start: null,
    show: { spring: false, friction: true, normal: false, markers: true, percussion: true,
      values: true },
    magnification: LESSON_MAGNIFICATION,
    plots: ["newton", "forces"],
    lines: { forces: FRICTIONS_ONLY },
    t: 0,
    play: true,
    text: [
      "Pulled at its percussion point, (1 + γ)R above the contact (marked P), a rolling body "
        + "needs no friction: 2R for a hoop, 1.5R for a cylinder (eq. (fric), Fig. 3). With the "
        + "hoop's radius 0.075 m both ends are 0.15 m up, and the spring is level.",
      "The friction arrows, at the same scale as before, all but vanish, and at the same ×200 "
        + "the centre of mass hardly moves: to first order no horizontal external force acts "
        + "({why:why-percussion|more on percussion points}; the slow drift left is step 6).",
    ],
  },
  {
    key: "large",
    title: "What breaks at large amplitude",
    figure: "Fig. 3, small angles",
    preset: "frictionless",
    start: { mode: 1, amplitude: 0.02 },
    show: { spring: false, friction: true, normal: false, markers: true, percussion: true,
      linear: true },
    magnification: null,
    plots: ["newton", "positions"],
    lines: {},
    t: 0,
    play: true,
    text: [
      "Fig. 3 holds only for small angles: the paper asks the spring to stay horizontal. Here "
        + "the pair starts in its mode with the hoop 2 cm out, turned by 15°, so its end of the "
        + "spring leaves the percussion height and the spring tilts.",
      "Friction comes back ({plot:newton|Σf}) with an average that is not zero, and the pair "
        + "creeps along the floor, the centre of mass with it, while the linear solution (dashed) "
        + "stays; the bodies still roll, needing a μ below μs = 1.",
    ],
  },
];

/** The paragraphs of a step as DOM nodes: text with its {plot:…} and {why:…} links. */
export function stepParagraphs(step, doc = document) {
  return step.text.map((paragraph) => {
    const p = doc.createElement("p");
    let last = 0;
    for (const m of paragraph.matchAll(/\{(plot|why):([\w-]+)\|([^}]+)\}/g)) {
      p.append(paragraph.slice(last, m.index));
      const a = doc.createElement("a");
      a.href = m[1] === "plot" ? `#plot-${m[2]}` : `#${m[2]}`;
      a.dataset.why = m[1] === "plot" ? `plot-${m[2]}` : m[2];
      a.textContent = m[3];
      p.append(a);
      last = m.index + m[0].length;
    }
    p.append(paragraph.slice(last));
    return p;
  });
}

/** The lesson's panel: its heading, the step indicator (a button per step, the current one
 * marked aria-current="step"), the step's title and text, Back, Next and Leave. `hooks`:
 * {go(k), leave()}. */
export class LessonPanel {
  constructor(root, hooks) {
    this.root = root;
    this.hooks = hooks;
    this.k = null;
    this.title = root.querySelector("#lesson-step-title");
    this.text = root.querySelector("#lesson-text");
    this.progress = root.querySelector("#lesson-progress");
    this.back = root.querySelector("#lesson-back");
    this.next = root.querySelector("#lesson-next");
    this.link = root.querySelector("#lesson-link");
    const list = root.querySelector("#lesson-steps");
    this.dots = STEPS.map((step, k) => {
      const li = doc(root).createElement("li");
      const b = doc(root).createElement("button");
      b.type = "button";
      b.textContent = String(k + 1);
      b.setAttribute("aria-label", `Step ${k + 1}: ${step.title}`);
      b.addEventListener("click", () => hooks.go(k, { focus: "keep" }));
      li.append(b);
      list.append(li);
      return b;
    });
    this.back.addEventListener("click", () => this.k > 0 && hooks.go(this.k - 1, { focus: "keep" }));
    this.next.addEventListener("click", () => this.k < STEPS.length - 1 && hooks.go(this.k + 1, { focus: "keep" }));
    root.querySelector("#lesson-leave").addEventListener("click", () => hooks.leave());
  }

  /** Show step k (its text, the indicator, the buttons); `href` the step's own link. */
  show(k, href) {
    const step = STEPS[k];
    this.k = k;
    this.root.hidden = false;
    this.root.dataset.step = step.key;
    this.title.textContent = `${k + 1}. ${step.title} (${step.figure})`;
    this.text.replaceChildren(...stepParagraphs(step, doc(this.root)));
    this.progress.textContent = `Step ${k + 1} of ${STEPS.length}: ${step.title}`;
    this.dots.forEach((b, j) => (j === k ? b.setAttribute("aria-current", "step") : b.removeAttribute("aria-current")));
    this.back.disabled = k === 0;
    this.next.disabled = k === STEPS.length - 1;
    this.link.href = href;
  }

  hide() {
    this.k = null;
    this.root.hidden = true;
  }
}

function doc(node) {
  return node.ownerDocument;
}
