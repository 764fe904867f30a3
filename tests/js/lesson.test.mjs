import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { LESSON_MAGNIFICATION, LESSON_TITLE, STEPS }
  from "../../src/rollspring/web/static/js/lesson.js";
import { shortcutFor, SHORTCUTS } from "../../src/rollspring/web/static/js/shortcuts.js";

const EXAMPLES = new URL("../../examples/", import.meta.url);
const presets = new Set(readdirSync(EXAMPLES).filter((f) => f.endsWith(".toml")).map((f) => f.replace(/\.toml$/, "")));
const PLOTS = ["positions", "newton", "forces", "ratio", "energy"];
const SHOW = ["spring", "friction", "normal", "markers", "linear", "dots", "values", "absolute", "percussion"];
const page = readFileSync(new URL("../../src/rollspring/web/static/index.html", import.meta.url), "utf8");

test("the lesson's title counts its steps", () => {
  assert.equal(STEPS.length, 6);
  assert.equal(LESSON_TITLE, "The paper in six steps");
  assert.ok(page.includes(`>${LESSON_TITLE}</h2>`) && page.includes(`>${LESSON_TITLE}</button>`));
});

test("every step names a preset, the paper's figure or equation, plots and view options that exist", () => {
  assert.equal(new Set(STEPS.map((s) => s.key)).size, STEPS.length);
  for (const step of STEPS) {
    assert.ok(presets.has(step.preset), step.preset);
    assert.match(step.figure, /Fig\. \d|eq|Appendix/);
    assert.ok(step.plots.length >= 1 && step.plots.every((p) => PLOTS.includes(p)), step.key);
    assert.ok(Object.keys(step.lines).every((p) => step.plots.includes(p)), step.key);
    assert.ok(Object.keys(step.show).every((k) => SHOW.includes(k)), step.key);
    assert.ok(step.magnification === null || step.magnification === LESSON_MAGNIFICATION);
    assert.equal(typeof step.play, "boolean");
    assert.ok(step.t >= 0);
    assert.ok(step.start === null || (Number.isInteger(step.start.mode) && Math.abs(step.start.amplitude) <= 1));
  }
});

test("each step says what to look at in two paragraphs, 2 to 4 sentences in all, links well formed", () => {
  for (const step of STEPS) {
    assert.equal(step.text.length, 2);
    const plain = step.text.join(" ").replace(/\{(plot|why):([\w-]+)\|([^}]+)\}/g, (_, kind, target, words) => {
      if (kind === "plot") assert.ok(PLOTS.includes(target), target);
      else assert.ok(page.includes(`id="${target}"`), target);
      return words;
    });
    assert.ok(!/[{}]/.test(plain), step.key);
    // 2 to 4 sentences in all (the paper's abbreviations "Fig." and "eq." end none)
    const ends = (plain.match(/[.!?](\s|$)/g) || []).length;
    const abbreviations = (plain.match(/\b(Fig|eqs?)\.\s/g) || []).length;
    assert.ok(ends - abbreviations >= 2 && ends - abbreviations <= 4, `${step.key}: ${plain}`);
  }
});

test("N and P move through the lesson; the plot keys are listed", () => {
  const key = (k) => ({ key: k, target: { tagName: "BODY" } });
  assert.equal(shortcutFor(key("n")), "lessonNext");
  assert.equal(shortcutFor(key("P")), "lessonBack");
  assert.equal(shortcutFor({ key: "n", target: { tagName: "INPUT", type: "text" } }), null);
  const listed = SHORTCUTS.map(([keys]) => keys.join(" "));
  for (const keys of ["N", "P", "+ −", "← →", "Home"]) assert.ok(listed.includes(keys), keys);
});
