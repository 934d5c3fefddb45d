// steps.js: the worked solution of the analysed instant, rendered with KaTeX.
//
// The server writes the solution (issue 4: steps are data, built from the solver's numbers);
// this module only typesets it. Each step shows its title, its equation(s) in KaTeX and the
// plain-text form under it, which is also what a screen reader gets. A step whose LaTeX KaTeX
// cannot read is shown as plain text with a visible mark (class `step-error`), so a bad string
// from the server is seen and tested for, never silently dropped.

import { kindOfUnit, toDisplay, unitLabel, fmt } from './units.js';

/**
 * A step's values in the units chosen on the page ("v(B) = (-1.5, 2.6) mm/s"): the working is
 * the server's, in SI; this line converts each value the step lists (values[key] = {value,
 * unit}) so a student reading mm and rpm elsewhere finds the same numbers here. Values whose unit
 * has no display conversion are left out.
 */
export function valuesInUnits(values, units) {
  const parts = [];
  for (const [name, v] of Object.entries(values || {})) {
    const kind = kindOfUnit(v.unit);
    if (!kind || v.value === null || v.value === undefined) continue;
    const conv = (x) => fmt(toDisplay(kind, x, units), 4);
    const shown = Array.isArray(v.value) ? `(${v.value.map(conv).join(', ')})` : conv(v.value);
    parts.push(`${name} = ${shown} ${unitLabel(kind, units)}`);
  }
  return parts.join('; ');
}

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

/**
 * A step's equations as a block: typeset with KaTeX (the LaTeX as text, and the KaTeX error,
 * when it cannot be read) in a group that the keyboard reaches. Once laid out wider than its
 * column (at once, or later: a narrower window, a phone turned), a block is typeset again with
 * each clause on its own line (`narrow`, narrowLatex unless given; once: `data-narrow` holds the
 * width it had); what is still wider scrolls sideways inside the group. Returns [block, error
 * or null].
 */
export function mathBlock(latex, label, narrow = narrowLatex) {
  const math = el('div', { class: 'step-math', tabindex: '0', role: 'group', 'aria-label': label });
  const error = typeset(latex, math);
  const narrowed = error ? latex : narrow(latex);
  if (narrowed !== latex) {
    sources.set(math, [latex, narrowed]);
    narrowing().observe(math);
  }
  return [math, error];
}

const sources = new WeakMap(); // a block watched until it is too wide -> its LaTeX, narrowed
let observer = null;

/** The one ResizeObserver that narrows a block the first time it is laid out too wide; a block
 * that fits is watched until it does not, or until it leaves the page. */
function narrowing() {
  observer = observer || new ResizeObserver((entries) => {
    for (const { target } of entries) {
      if (!target.isConnected) { // removed (a solution drawn again): no longer watched
        observer.unobserve(target);
        sources.delete(target);
        continue;
      }
      const wide = target.scrollWidth;
      if (!target.clientWidth || wide <= target.clientWidth + 1) continue; // hidden, or fits
      observer.unobserve(target);
      // Kept only where it reads better: typeset, and no wider than before (an indented
      // relation can widen a row that holds one long matrix).
      const [latex, narrowed] = sources.get(target);
      sources.delete(target);
      if (!typeset(narrowed, target) && target.scrollWidth <= wide) target.dataset.narrow = String(wide);
      else typeset(latex, target);
    }
  });
  return observer;
}

/**
 * The same equations with each clause on its own line: every `\quad` between two clauses of a
 * row starts a new row of the aligned block, and so does every further relation of a clause (its
 * second `=`, `\Rightarrow`, `\to`, `\approx`, indented by `\qquad`), outside braces,
 * environments and \left…\right (a single-line equation becomes an aligned block). Nothing else
 * changes; with no such place the LaTeX is returned as it is.
 */
export function narrowLatex(latex) {
  const text = latex.trim();
  const aligned = text.match(/^\\begin\{aligned\}([\s\S]*)\\end\{aligned\}$/);
  const parts = clauses(aligned ? aligned[1] : text).filter((p) => p.trim());
  if (parts.length < 2) return latex;
  const rows = aligned ? parts : parts.map((p, i) => (i ? p : `&${p}`));
  return `\\begin{aligned}${rows.join(' \\\\ &')}\\end{aligned}`;
}

const RELATIONS = new Set(['Rightarrow', 'to', 'approx']);

/** True when a break after `before` ends a clause (not one at a row's start). */
function opensClause(before) {
  const b = before.trimEnd();
  return Boolean(b) && !b.endsWith('&') && !b.endsWith('\\\\');
}

/** LaTeX cut at each top-level \quad (dropped) and before each further relation of a clause. */
function clauses(body) {
  const out = [];
  let start = 0;
  let depth = 0; // braces, environments and \left…\right open
  let relations = 0; // relations of the clause so far
  const cut = (at, next) => {
    out.push(body.slice(start, at));
    start = next;
    relations = 0;
  };
  for (let i = 0; i < body.length; i++) {
    const c = body[i];
    if (c === '{') depth += 1;
    else if (c === '}') depth -= 1;
    else if (c === '=' && depth === 0) {
      if (relations && opensClause(body.slice(start, i))) {
        cut(i, i);
        body = `${body.slice(0, i)}\\qquad ${body.slice(i)}`;
        i += 7;
      } else relations += 1;
    } else if (c === '\\') {
      const name = body.slice(i + 1).match(/^[a-zA-Z]+/)?.[0];
      if (!name) {
        if (body[i + 1] === '\\' && depth === 0) relations = 0; // a new row
        i += 1; // an escaped symbol: \{ \} \\ \, …
        continue;
      }
      if (name === 'begin' || name === 'left') depth += 1;
      else if (name === 'end' || name === 'right') depth -= 1;
      else if (depth === 0 && name === 'quad' && opensClause(body.slice(start, i))) {
        cut(i, i + 5);
      } else if (depth === 0 && RELATIONS.has(name)) {
        if (relations && opensClause(body.slice(start, i))) {
          cut(i, i);
          body = `${body.slice(0, i)}\\qquad ${body.slice(i)}`;
          i += 7;
        } else relations += 1;
      }
      i += name.length;
    }
  }
  out.push(body.slice(start));
  return out;
}

function typeset(latex, target) {
  const katex = globalThis.katex;
  if (!katex) {
    target.textContent = latex;
    return 'KaTeX is not loaded';
  }
  try {
    katex.render(latex, target, { displayMode: true, throwOnError: true, strict: 'ignore', trust: false, output: 'htmlAndMathml' });
    return null;
  } catch (err) {
    target.textContent = latex;
    return err.message;
  }
}

/**
 * After the first steps, the rest follow STEPS_PER_TASK at a time, each batch a task of its own
 * run when the page is idle (within IDLE_WAIT_MS at the latest): a click's own work (an edit's
 * answers, the drawing, the polygons) goes first, not after the typesetting of a long solution.
 */
const STEPS_PER_TASK = 4;
const IDLE_WAIT_MS = 500;
const idle = () => new Promise((resolve) => requestIdleCallback(resolve, { timeout: IDLE_WAIT_MS }));
const rendering = new WeakMap(); // a steps container -> the render under way in it
const waiting = new WeakMap(); // a steps container -> how to release the render waiting for it

/**
 * Resolves once `stepsEl` is rendered: the later steps of a solution in a closed tab wait for the
 * tab, so that a student who never opens it pays for its first steps only (a few instead of
 * thousands of typeset elements after each preset or edit). A newer render into the container
 * releases the older one's wait (which then stops: `rendering`).
 */
function shown(stepsEl) {
  waiting.get(stepsEl)?.();
  if (stepsEl.checkVisibility()) return Promise.resolve();
  return new Promise((resolve) => {
    const release = () => {
      watch.disconnect();
      waiting.delete(stepsEl);
      resolve();
    };
    const watch = new ResizeObserver(() => { if (stepsEl.checkVisibility()) release(); });
    watch.observe(stepsEl);
    waiting.set(stepsEl, release);
  });
}

/**
 * Render {steps, mistakes} into the two containers, with each step's values also in `units`
 * when they are not SI. With `first`, the first steps (those a reader sees first) are typeset at
 * once and the rest in later tasks, once the container is shown (`shown`), so that a long
 * solution never holds the page for its whole typesetting (without it, every step at once); a
 * newer render into the same container stops an older one. `stepsEl.dataset.typeset` is
 * `partial` until every step is in, then `done`.
 * Resolves to the number of LaTeX failures.
 */
export async function renderSolution(stepsEl, mistakesEl, solution, units = 'si', { first = Infinity } = {}) {
  const token = {};
  rendering.set(stepsEl, token);
  stepsEl.replaceChildren();
  stepsEl.dataset.typeset = 'partial';
  let failures = 0;
  if (units !== 'si') {
    stepsEl.appendChild(el('p', { class: 'hint units-note' }, `The working is in SI units, as the equations are written; each step's values are also given in ${unitLabel('length', units)}, ${unitLabel('angle', units)}, ${unitLabel('omega', units)} (the units chosen above).`));
  }
  const list = el('ol', { class: 'step-list' });
  stepsEl.appendChild(list);
  renderMistakes(mistakesEl, solution.mistakes || []);
  const steps = solution.steps || [];
  for (let i = 0; i < steps.length; i++) {
    if (i >= first && (i - first) % STEPS_PER_TASK === 0) {
      await shown(stepsEl);
      await idle();
      if (rendering.get(stepsEl) !== token) return failures;
    }
    const [item, error] = stepItem(steps[i], i, units);
    if (error) failures += 1;
    list.appendChild(item);
  }
  stepsEl.dataset.typeset = 'done';
  return failures;
}

/** One step as a list item: title, equations, text, values in `units`, figure. [item, error]. */
function stepItem(step, i, units) {
  const item = el('li', { class: 'step' });
  if (step.title) item.appendChild(el('h3', { class: 'step-title' }, step.title));
  let error = null;
  if (step.latex) {
    let math;
    [math, error] = mathBlock(step.latex, `Equations of step ${i + 1}`);
    if (error) {
      math.classList.add('step-error');
      math.title = `KaTeX could not read this step: ${error}`;
    }
    item.appendChild(math);
  }
  if (step.text) item.appendChild(el('p', { class: 'step-text' }, step.text));
  const converted = units !== 'si' ? valuesInUnits(step.values, units) : '';
  if (converted) item.appendChild(el('p', { class: 'step-units' }, `In ${unitLabel('length', units)}, ${unitLabel('angle', units)}, ${unitLabel('omega', units)}: ${converted}`));
  if (step.figure) {
    const figure = el('div', { class: 'step-figure' });
    figure.innerHTML = step.figure;
    item.appendChild(figure);
  }
  return [item, error];
}

function renderMistakes(mistakesEl, mistakes) {
  mistakesEl.replaceChildren();
  if (mistakes.length) {
    const ul = el('ul', { class: 'mistake-list' });
    for (const m of mistakes) {
      const li = el('li');
      li.appendChild(el('strong', {}, m.title || ''));
      if (m.text) li.appendChild(el('p', {}, m.text));
      ul.appendChild(li);
    }
    mistakesEl.appendChild(ul);
  } else {
    mistakesEl.appendChild(el('p', { class: 'muted' }, 'No typical mistakes listed for this mechanism.'));
  }
}

export function renderMessage(stepsEl, text) {
  rendering.delete(stepsEl);
  delete stepsEl.dataset.typeset;
  stepsEl.replaceChildren(el('p', { class: 'panel-message' }, text));
}
