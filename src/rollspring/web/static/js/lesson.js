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
 * `play` (it plays on arrival, unless the reader asked for reduced motion), `text` (paragraphs;
 * a `{plot:key|words}` becomes a link to that plot, `{why:id|words}` to a "Why?" panel).
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
      "Two blocks joined by a spring slide on a floor without friction: the paper's Fig. 1 and "
        + "its equations (f1), (f2). The spring pushes the two blocks with equal and opposite "
        + "forces, internal forces that cancel in the sum, so (m₁ + m₂)·Ẍ = 0.",
      "Look at the strip under the floor: it magnifies the centre of mass ×200, and its mark "
        + "stays put while the blocks swing. In {plot:positions|the displacements} the CM is the "
        + "flat bold line.",
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
      "Now a hoop and a solid cylinder of the same mass and radius roll without slipping, their "
        + "centres joined by the spring (Fig. 2). The spring's forces still cancel, but each body "
        + "needs static friction from the floor to roll, and friction is an external force.",
      "The frictions (red arrows) do not cancel, so the centre of mass swings: watch its mark on "
        + "the strip, at the same ×200 as in step 1. {plot:newton|The plot of Σf beside (Σm)·a_CM} "
        + "is Newton's second law for the whole system: the two curves are one. "
        + "{why:why-cm|Why the CM moves}.",
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
      "Friction acts at the contact line, so about that line it has no moment: adding the two "
        + "bodies' rotation equations about their contact lines, and integrating from rest, gives "
        + "I′₁φ̇₁ + I′₂φ̇₂ = 0, the paper's eq. (rel1). So the point "
        + "X̂ = (I′₁x₁ + I′₂x₂)/(I′₁ + I′₂), eq. (c), never moves.",
      "Its weights are I′ = 2mR² for the hoop and 3/2·mR² for the cylinder: 4/7 and 3/7 here, "
        + "not the masses' 1/2 and 1/2. On the strip X̂'s trail is a straight line down; in "
        + "{plot:positions|the displacements} X̂ (bold, dashed) is flat while the CM (bold) swings. "
        + "{why:why-xhat|More on X̂}.",
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
      "Paused at the release, where the compressed spring pushes hardest. The hoop needs the "
        + "friction f₁, the cylinder f₂, and they point opposite ways: f₁/f₂ = 3/2 in size, the "
        + "paper's ratio (after eq. (c), derived in Appendix A; −3/2 with signs).",
      "The hoop needs more because more of its inertia is in its rim: spinning it up as it rolls "
        + "takes a larger torque, and only friction gives one. {plot:forces|The friction plot} shows only the two frictions: one is "
        + "always −3/2 times the other. Press Play to watch them swap sides every half period.",
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
      "Pull a rolling body at the height (1 + γ)R above its contact point, its percussion point "
        + "(marked P), and it needs no friction: 2R on a hoop, 1.5R on a cylinder (the paper's "
        + "eq. (fric) and Fig. 3). Here the hoop's radius is 0.075 m, so both ends are 0.15 m up "
        + "and the spring is level.",
      "The friction arrows, at the same scale as before, all but vanish, and at the same ×200 "
        + "the centre of mass hardly moves: to first order no horizontal external force acts, so "
        + "it stays at rest as in step 1. The slow drift that is left is step 6. "
        + "{why:why-percussion|More on percussion points}.",
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
      "Fig. 3 works only for small angles: the paper asks the spring to stay horizontal. Here "
        + "the same pair starts in its mode with the hoop 2 cm out, turned by 15°, and it swings "
        + "15° each way: its end of the spring leaves the percussion height and the spring tilts.",
      "Friction comes back ({plot:newton|Σf}), and its average is not zero: the pair creeps "
        + "along the floor, further at every swing, and the centre of mass goes with it. The linear "
        + "solution (dashed) stays in place. The bodies still roll: the needed μ stays below μs = 1.",
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

  get open() {
    return this.k !== null;
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
