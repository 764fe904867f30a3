// The page's keyboard shortcuts and their help dialog. A shortcut acts only when the focus is
// not in a field that takes typing (a text box, a text area, a select) and no Ctrl/Alt/Meta is
// held; Space is left to a focused button, checkbox or slider, whose own action it is.

/** The shortcuts, as listed in the help dialog: [keys, what it does, action name]. */
export const SHORTCUTS = [
  [["Space", "K"], "play or pause", "playPause"],
  [[","], "step back one output interval", "stepBack"],
  [["."], "step forward one output interval", "step"],
  [["0"], "back to t = 0", "restart"],
  [["N"], "the lesson's next step (while the lesson is on)", "lessonNext"],
  [["P"], "the lesson's previous step", "lessonBack"],
  [["+", "−"], "on a focused plot: zoom every plot's time window in or out", null],
  [["←", "→"], "on a focused plot: pan the time window (Shift + drag across a plot pans too)", null],
  [["Home"], "on a focused plot: show the whole run", null],
  [["?"], "this list of shortcuts", "help"],
  [["Esc"], "close this list", null],
];

const KEYS = { " ": "playPause", k: "playPause", K: "playPause", ",": "stepBack", ".": "step",
  0: "restart", "?": "help", n: "lessonNext", N: "lessonNext", p: "lessonBack", P: "lessonBack" };

function typing(el) {
  if (!el || !el.tagName) return false;
  if (el.isContentEditable) return true;
  if (el.tagName === "TEXTAREA" || el.tagName === "SELECT") return true;
  return el.tagName === "INPUT" && !["checkbox", "radio", "range", "button", "submit", "reset", "file"]
    .includes(el.type);
}

/** The action a keydown asks for (a name of SHORTCUTS), or null. */
export function shortcutFor(event) {
  if (event.ctrlKey || event.altKey || event.metaKey) return null;
  const action = KEYS[event.key] ?? null;
  if (!action) return null;
  const el = event.target;
  if (typing(el)) return null;
  // Space presses a focused button or ticks a checkbox: theirs, not a shortcut
  if (event.key === " " && el && el.closest && el.closest("button, summary, input, a[href], [role=slider]")) return null;
  return action;
}

/** Wire the shortcuts (`actions`: name → function) and the help dialog `dialog` (a <dialog>),
 * opened by `button` and by "?". */
export function wireShortcuts(actions, dialog, button) {
  const list = dialog.querySelector("dl");
  list.replaceChildren(...SHORTCUTS.flatMap(([keys, what]) => {
    const dt = document.createElement("dt");
    keys.forEach((k, i) => {
      if (i) dt.append(" or ");
      const kbd = document.createElement("kbd");
      kbd.textContent = k;
      dt.append(kbd);
    });
    const dd = document.createElement("dd");
    dd.textContent = what;
    return [dt, dd];
  }));
  let opener = null;
  const open = () => {
    if (dialog.open) return;
    opener = document.activeElement;
    dialog.showModal();
    dialog.querySelector(".close").focus();
  };
  dialog.addEventListener("close", () => {
    if (opener && opener.isConnected && opener.focus) opener.focus();
    opener = null;
  });
  dialog.querySelector(".close").addEventListener("click", () => dialog.close());
  button.addEventListener("click", open);
  document.addEventListener("keydown", (event) => {
    if (dialog.open) return; // Escape closes it (the browser's own)
    const action = shortcutFor(event);
    if (!action) return;
    event.preventDefault();
    if (action === "help") open();
    else actions[action]();
  });
}
