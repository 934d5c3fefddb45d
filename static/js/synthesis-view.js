// synthesis-view.js: "Design a linkage" (issue 26, docs/SYNTHESIS.md "In the app"). The student
// gives a task (two or three coupler positions with the moving or the fixed pivots, a function
// y = f(x), or a quick-return time ratio) by typing it or by dragging its handles, and sees at
// once the server's four-bar (POST /synthesis) moving, its defects, warnings, checks, the
// function's desired and generated curves with the structural error, and the worked solution.
//
// Requests per decision, never per frame: a change of a field, the end of a drag or a pause in
// the keys asks /synthesis, then one /sweep of the returned scene. The linkage is drawn by the
// app's own LinkageView (js/linkage-view.js) playing that sweep back; the positions and the given
// pivots are handles drawn over it in the same SVG, at the same scale. Nothing kinematic is
// computed here: the handles are the task's own numbers, everything else is the server's.

import { Playback } from './playback.js';
import * as api from './api.js';
import { LinkageView } from './linkage-view.js';
import { trackFromSweep, frameAt, indexOfValue, valueAt } from './track.js';
import { svgEl } from './svg.js';
import { renderSolution, renderMessage } from './steps.js';
import { katexReady, plotlyReady } from './vendor.js';
import { fmt, typed } from './units.js';
import { markerBox } from './drawing-labels.js';

const SAMPLES = 241;
const CYCLE_SECONDS = 5; // the whole sweep played once (a rocking crank: one way) at 1x
const KEY_DELAY_MS = 350;
const PIVOT_HALF = 15; // half the side of a given pivot's square (viewBox px)
const POSITION_REACH = 26; // a position's body, turned any way, stays within this of its dot (px) // a design after the last key press on a handle
const ARROW_PX = 64; // a position's direction arrow, viewBox px
const INK = '#6a1b9a'; // the task's handles (positions, given pivots)

const el = (tag, attrs = {}, text = '') => {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text) node.textContent = text;
  return node;
};

/** The largest 1, 2 or 5 times a power of ten not above v (the handles' grid step). */
function niceBelow(v) {
  const p = 10 ** Math.floor(Math.log10(v));
  return [5, 2, 1].map((m) => m * p).find((x) => x <= v) || p;
}

const roundTo = (v, step) => Number((Math.round(v / step) * step).toPrecision(12));

// The function task's fields: [key in the state, label, unit, the request's field it belongs to].
const FUNCTION_FIELDS = [
  ['function', 'y = f(x)', 'expression in x', 'function'],
  ['x0', 'x from', '', 'x_range'],
  ['xf', 'x to', '', 'x_range'],
  ['in0', 'crank angle θ₂ at x from', 'deg', 'input_range_deg'],
  ['inf', 'crank angle θ₂ at x to', 'deg', 'input_range_deg'],
  ['out0', 'rocker angle θ₄ at f(x from)', 'deg', 'output_range_deg'],
  ['outf', 'rocker angle θ₄ at f(x to)', 'deg', 'output_range_deg'],
  ['ground', 'ground |AD|', 'm', 'ground_length'],
];
const QUICK_FIELDS = [
  ['time_ratio', 'time ratio Q (slow / fast stroke)', '', 'time_ratio'],
  ['rocker_length', 'rocker length |DC|', 'm', 'rocker_length'],
  ['swing_deg', 'rocker swing', 'deg', 'swing_deg'],
];
const HINTS = {
  motion: "Drag a position's dot to move it and its arrow's tip to turn it, or drag a given pivot (B₁, C₁: where B and C are at the first position); with the keyboard, Tab to a handle: the arrow keys move it, Page Up and Page Down turn a position. Dragging the crank turns the linkage.",
  function: 'The crank turns through the input range as x goes from its first to its last value, the rocker through the output range as y = f(x) does. The buttons show the linkage at the precision points; dragging the crank turns it.',
  quick_return: 'The rocker swings between its two limit positions (the buttons), where the crank and the coupler are in line; the slow stroke takes the time ratio times the fast one at a constant crank speed.',
};
const DEFECTS = {
  branch: ['Branch defect', 'a position is met only on the other assembly of the linkage'],
  order: ['Order defect', 'the positions are not met in the given order'],
  grashof: ['Grashof defect', 'the crank cannot turn fully; it rocks between limit positions'],
};

export class LinkageDesigner {
  /** `root`: the #synthesis-app section; `onOpen(scene)`: open a scene in the analyser. */
  constructor(root, { onOpen }) {
    this.root = root;
    this.onOpen = onOpen;
    this.shown = false;
    this.running = null;
    this.pending = false;
    this.designs = 0;
    this.answer = null;
    this.track = null;
    this.u = 0;
    this.direction = 1;
    this.keyTimer = null;
    // one revolution per CYCLE_SECONDS; a crank that cannot turn fully rocks between its limits
    this.playback = new Playback(() => this.shown, (dt) => {
      const t = this.track;
      if (!this.playing || !t || t.n < 2) return;
      const span = t.n - 1;
      this.u += (this.direction * dt * span) / CYCLE_SECONDS;
      if (t.closed) this.u = ((this.u % span) + span) % span;
      else if (this.u > span || this.u < 0) {
        this.direction = -this.direction;
        this.u = Math.min(Math.max(this.u, 0), span);
      }
      this.drawFrame();
    });
    this.playing = !matchMedia('(prefers-reduced-motion: reduce)').matches;
    this.task = 'motion';
    this.motion = {
      count: 3,
      positions: [[0, 0, 0], [1, 0.5, 30], [2, 0.3, 60]],
      kind: 'moving_pivots',
      pivots: { moving_pivots: [[-0.5, -0.2], [0.5, -0.3]], fixed_pivots: [[0.68, -2.57], [2.26, -1.57]] },
    };
    this.fn = { function: 'x^2', x0: 1, xf: 2, in0: 30, inf: 120, out0: 60, outf: 150, ground: 1, spacing: 'chebyshev', given: [1.1, 1.5, 1.9] };
    this.quick = { time_ratio: 1.25, rocker_length: 0.1, swing_deg: 60 };
    const $ = (id) => root.querySelector(`#${id}`);
    this.el = {
      form: $('syn-form'), positions: $('syn-positions'), pivotRows: $('syn-pivot-rows'),
      pivotCaption: $('syn-pivot-caption'), fnFields: $('syn-function-fields'), given: $('syn-given-fields'),
      quickFields: $('syn-quick-fields'), error: $('syn-error'), svg: $('syn-linkage'), play: $('syn-play'),
      goto: $('syn-goto'), open: $('syn-open'), message: $('syn-message'), readout: $('syn-readout'),
      defects: $('syn-defects'), warnings: $('syn-warnings'), dimensions: $('syn-dimensions'),
      checks: $('syn-checks'), curves: $('syn-curves'), errorPlot: $('syn-error-plot'),
      steps: $('syn-steps'), mistakes: $('syn-mistakes'),
    };
    // The app's drawing of a linkage; a press on the crank turns it (the instant shown).
    this.view = new LinkageView(this.el.svg, { onDrag: (angle) => this.showAngle(angle), onDragEnd: () => {} });
    this.view.setOptions({ showVelocity: false, showAcceleration: false, showPoles: false });
    this.wire();
    this.buildFields();
  }

  /** "Design a linkage" in the mechanism menu: its own group, `design:linkage`. */
  addChoices(select) {
    const group = el('optgroup', { label: 'Synthesis' });
    group.appendChild(el('option', { value: 'design:linkage' }, 'Design a linkage'));
    select.appendChild(group);
  }

  async open() {
    this.shown = true;
    this.root.hidden = false;
    document.body.dataset.family = 'synthesis';
    this.playback.start();
    if (!this.answer) await this.design();
  }

  close() {
    this.shown = false;
    this.root.hidden = true;
    if (document.body.dataset.family === 'synthesis') delete document.body.dataset.family;
  }

  // ---- the form -------------------------------------------------------------------------------

  wire() {
    const form = this.el.form;
    form.addEventListener('submit', (ev) => {
      ev.preventDefault();
      this.design();
    });
    for (const radio of form.querySelectorAll('input[name="syn-task"]')) {
      radio.addEventListener('change', () => this.setTask(radio.value));
    }
    for (const radio of form.querySelectorAll('input[name="syn-count"]')) {
      radio.addEventListener('change', () => {
        this.motion.count = Number(radio.value);
        this.buildFields();
        this.design();
      });
    }
    for (const radio of form.querySelectorAll('input[name="syn-pivots"]')) {
      radio.addEventListener('change', () => {
        this.motion.kind = radio.value;
        // The inverse problem starts from the design shown: its fixed pivots give it back.
        const s = this.answer?.task === 'motion' ? this.answer.scene.points : null;
        if (s) this.motion.pivots[radio.value] = radio.value === 'fixed_pivots' ? [[...s.A], [...s.D]] : [[...s.B], [...s.C]];
        this.buildFields();
        this.design();
      });
    }
    for (const radio of form.querySelectorAll('input[name="syn-spacing"]')) {
      radio.addEventListener('change', () => {
        this.fn.spacing = radio.value;
        this.el.given.hidden = radio.value !== 'given';
        this.design();
      });
    }
    this.el.play.addEventListener('click', () => this.setPlaying(!this.playing));
    this.el.open.addEventListener('click', () => {
      if (this.answer) this.onOpen(structuredClone(this.answer.scene));
    });
    this.setPlaying(this.playing);
    this.el.open.disabled = true; // until there is a design
  }

  setTask(task) {
    this.task = task;
    for (const set of this.el.form.querySelectorAll('fieldset[data-task]')) set.hidden = set.dataset.task !== task;
    this.root.querySelector('#syn-hint').textContent = HINTS[task];
    this.design();
  }

  /** A number (or text) field; a change sets `set(value)` and designs again. */
  field(parent, { id, label, unit = '', value, text = false, set, request }) {
    const wrap = el('div', { class: 'field' });
    const lab = el('label', { for: id }, `${label} `);
    if (unit) lab.appendChild(el('span', { class: 'unit' }, `[${unit}]`));
    const input = this.input({ id, value, text, set, request });
    wrap.append(lab, input);
    parent.appendChild(wrap);
    return input;
  }

  input({ id, value, text = false, set, request, label = null }) {
    const attrs = { id, type: 'text', inputmode: text ? 'text' : 'decimal', spellcheck: 'false', 'aria-describedby': 'syn-error', 'data-request': request };
    if (label) attrs['aria-label'] = label;
    const input = el('input', attrs);
    input.value = typed(value);
    input.addEventListener('change', () => {
      const raw = input.value.trim();
      const number = Number(raw.replace(',', '.'));
      if (!text && (!raw || !Number.isFinite(number))) {
        this.refuse(`Not a number: "${input.value}".`, [input]);
        return;
      }
      set(text ? raw : number);
      this.design();
    });
    return input;
  }

  buildFields() {
    const m = this.motion;
    this.el.positions.replaceChildren();
    for (let j = 0; j < m.count; j += 1) {
      const row = el('tr');
      row.appendChild(el('th', { scope: 'row' }, `${j + 1}`));
      ['x', 'y', 'angle'].forEach((name, k) => {
        const cell = el('td');
        const unit = k === 2 ? 'deg' : 'm';
        cell.appendChild(this.input({ id: `syn-p${j + 1}-${name}`, label: `Position ${j + 1}: ${name} (${unit})`, value: m.positions[j][k], request: 'positions', set: (v) => { m.positions[j][k] = v; } }));
        row.appendChild(cell);
      });
      this.el.positions.appendChild(row);
    }
    const fixed = m.kind === 'fixed_pivots';
    const names = fixed ? ['A', 'D'] : ['B', 'C'];
    this.el.pivotCaption.textContent = fixed ? 'The fixed pivots (m): the moving ones are found' : "The coupler's pivots at the first position (m): the fixed ones are found";
    this.el.pivotRows.replaceChildren();
    names.forEach((name, i) => {
      const row = el('tr');
      row.appendChild(el('th', { scope: 'row' }, name));
      ['x', 'y'].forEach((axis, k) => {
        const cell = el('td');
        cell.appendChild(this.input({ id: `syn-${name}-${axis}`, label: `Pivot ${name}: ${axis} (m)`, value: m.pivots[m.kind][i][k], request: m.kind, set: (v) => { m.pivots[m.kind][i][k] = v; } }));
        row.appendChild(cell);
      });
      this.el.pivotRows.appendChild(row);
    });
    if (!this.el.fnFields.children.length) {
      for (const [key, label, unit, request] of FUNCTION_FIELDS) {
        this.field(this.el.fnFields, { id: `syn-fn-${key}`, label, unit, value: this.fn[key], text: key === 'function', request, set: (v) => { this.fn[key] = v; } });
      }
      this.fn.given.forEach((x, i) => {
        this.el.given.appendChild(this.input({ id: `syn-fn-given-${i + 1}`, label: `Precision point ${i + 1}: x`, value: x, request: 'precision_points', set: (v) => { this.fn.given[i] = v; } }));
      });
      for (const [key, label, unit, request] of QUICK_FIELDS) {
        this.field(this.el.quickFields, { id: `syn-qr-${key}`, label, unit, value: this.quick[key], request, set: (v) => { this.quick[key] = v; } });
      }
    }
  }

  /** The fields again from the state (after a handle moved). */
  syncFields() {
    const m = this.motion;
    for (let j = 0; j < m.count; j += 1) {
      ['x', 'y', 'angle'].forEach((name, k) => {
        const input = this.root.querySelector(`#syn-p${j + 1}-${name}`);
        if (input) input.value = typed(m.positions[j][k]);
      });
    }
    const names = m.kind === 'fixed_pivots' ? ['A', 'D'] : ['B', 'C'];
    names.forEach((name, i) => ['x', 'y'].forEach((axis, k) => {
      const input = this.root.querySelector(`#syn-${name}-${axis}`);
      if (input) input.value = typed(m.pivots[m.kind][i][k]);
    }));
  }

  /** The task as the API reads it (docs/SYNTHESIS.md). */
  request() {
    if (this.task === 'motion') {
      const m = this.motion;
      return {
        task: 'motion',
        positions: m.positions.slice(0, m.count).map(([x, y, a]) => ({ point: [x, y], angle_deg: a })),
        [m.kind]: m.pivots[m.kind].map((p) => [...p]),
      };
    }
    if (this.task === 'function') {
      const f = this.fn;
      return {
        task: 'function', function: f.function, x_range: [f.x0, f.xf], input_range_deg: [f.in0, f.inf],
        output_range_deg: [f.out0, f.outf], precision_points: f.spacing === 'given' ? [...f.given] : 3, ground_length: f.ground,
      };
    }
    return { task: 'quick_return', ...this.quick };
  }

  // ---- the server's answer ----------------------------------------------------------------------

  /**
   * Ask for the task as the fields now hold it. One design at a time (a client's share of slow
   * requests is small, docs/SERVING.md): a change made while one is on its way waits for it,
   * and only the newest task is then asked for.
   */
  design() {
    this.pending = true;
    this.root.dataset.state = 'working';
    if (!this.running) {
      this.running = (async () => {
        while (this.pending) {
          this.pending = false;
          await this.designOnce();
        }
        this.running = null;
      })();
    }
    return this.running;
  }

  async designOnce() {
    const request = this.request();
    let answer;
    let sweep;
    try {
      answer = await api.synthesis(request);
      sweep = await api.sweep(answer.scene, SAMPLES, ['position']);
    } catch (err) {
      if (!this.pending) this.refuse(err.detail || err.message, null, err.code);
      return;
    }
    if (this.pending) return; // overtaken by a newer task
    this.asked = request;
    this.accept(answer, sweep);
  }

  /**
   * The server refused the task (or a field is not a number): its reason beside the fields, the
   * fields it names marked, the last design left as it was (its handles where the task now is).
   */
  refuse(text, inputs = null, code = '') {
    this.clearInvalid();
    const named = inputs || this.fieldsNamedIn(text);
    for (const input of named) input.setAttribute('aria-invalid', 'true');
    this.el.error.textContent = text;
    this.root.dataset.state = 'refused';
    if (code) this.root.dataset.refusal = code;
    this.placeHandles();
  }

  clearInvalid() {
    for (const input of this.el.form.querySelectorAll('[aria-invalid]')) input.removeAttribute('aria-invalid');
    this.el.error.textContent = '';
    delete this.root.dataset.refusal;
  }

  /** The shown fields of the request's field that a refusal names first ("time_ratio: ..."). */
  fieldsNamedIn(text) {
    const visible = [...this.el.form.querySelectorAll('fieldset[data-task]:not([hidden]) input[data-request]')];
    const keys = [...new Set(visible.map((i) => i.dataset.request))];
    const first = keys.map((k) => [k, text.indexOf(k)]).filter(([, at]) => at >= 0).sort((a, b) => a[1] - b[1])[0];
    if (first) return visible.filter((i) => i.dataset.request === first[0]);
    if (/pole|position/i.test(text) && this.task === 'motion') return visible.filter((i) => i.dataset.request === 'positions');
    return [];
  }

  accept(answer, sweep) {
    this.clearInvalid();
    const focusKey = document.activeElement?.closest?.('[data-handle]')?.dataset.handle;
    this.answer = answer;
    this.el.open.disabled = false;
    const track = trackFromSweep(sweep);
    // The task's handles stay in the picture: extra positions for the fit only (never drawn by
    // the view, which draws the scene's points).
    if (answer.task === 'motion') {
      this.motion.positions.slice(0, this.motion.count).forEach(([x, y], j) => { track.points[`~P${j + 1}`] = { position: [[x, y]] }; });
    }
    this.track = track;
    this.view.setOptions({ trace: answer.task === 'motion' ? 'P' : null });
    this.view.setScene(answer.scene, track);
    this.buildHandles();
    this.u = this.indexOfCheck(0);
    this.direction = 1;
    this.drawFrame();
    if (focusKey) this.root.querySelector(`[data-handle="${focusKey}"]`)?.focus();
    this.el.message.hidden = track.feasible;
    this.el.message.textContent = track.feasible ? '' : 'The crank cannot turn fully: the drawing rocks it between its limit positions.';
    this.renderGoto();
    this.renderDefects();
    this.renderTables();
    this.renderPlots();
    this.renderSteps();
    this.designs += 1;
    this.root.dataset.designs = String(this.designs);
    this.root.dataset.task = answer.task;
    this.root.dataset.state = 'ready';
  }

  /** The sweep's index of check k's crank angle (where the linkage reaches it). */
  indexOfCheck(k) {
    const check = this.answer.checks[k];
    return check ? indexOfValue(this.track, (check.driver_angle_deg * Math.PI) / 180) : 0;
  }

  renderGoto() {
    const box = this.el.goto;
    box.replaceChildren();
    this.answer.checks.forEach((check, k) => {
      const name = check.limit ? check.limit : this.answer.task === 'function' ? `x${k + 1}` : `${check.position ?? k + 1}`;
      const what = check.limit ? `the ${check.limit} limit position` : this.answer.task === 'function' ? `precision point ${k + 1}` : `position ${name}`;
      const button = el('button', { type: 'button', class: 'secondary small-button', 'data-check': String(k), 'aria-label': `Show the linkage at ${what}` }, name);
      button.addEventListener('click', () => {
        this.setPlaying(false);
        this.u = this.indexOfCheck(k);
        this.drawFrame();
      });
      box.appendChild(button);
    });
  }

  renderDefects() {
    const { defects, warnings } = this.answer;
    this.el.defects.replaceChildren();
    for (const [key, [title, meaning]] of Object.entries(DEFECTS)) {
      const present = Boolean(defects[key]);
      const extra = key === 'grashof' ? ` (${defects.grashof_class})` : '';
      const item = el('li', { class: present ? 'warning' : 'ok', 'data-defect': key, 'data-present': String(present) },
        `${title}: ${present ? `yes, ${meaning}${extra}` : `none${key === 'grashof' ? extra : ''}`}.`);
      this.el.defects.appendChild(item);
    }
    this.el.warnings.replaceChildren();
    for (const text of warnings) this.el.warnings.appendChild(el('li', { class: 'warning' }, text));
    if (!warnings.length) this.el.warnings.appendChild(el('li', { class: 'ok' }, 'None.'));
  }

  renderTables() {
    const a = this.answer;
    const d = a.dimensions;
    const dims = this.el.dimensions;
    dims.replaceChildren(el('caption', {}, `Link lengths (m); ${d.grashof}`));
    const body = dims.appendChild(el('tbody'));
    const row = (name, value) => {
      const tr = body.appendChild(el('tr'));
      tr.append(el('th', { scope: 'row' }, name), el('td', { 'data-value': String(value) }, value));
    };
    for (const link of ['ground', 'crank', 'coupler', 'rocker']) row(link, fmt(d[link], 5));
    if (d.coupler_point) row('coupler point BP', `${fmt(d.coupler_point.BP, 5)} m at ${fmt(d.coupler_point.angle_deg, 4)}° from BC`);
    if (a.transmission_angle) row('smallest transmission angle', `${fmt(a.transmission_angle.min_deg, 4)}° at crank ${fmt(a.transmission_angle.at_driver_angle_deg, 4)}°`);
    if (a.task === 'quick_return') {
      row('time ratio (from the analysis)', fmt(a.time_ratio, 6));
      row('swing (from the analysis)', `${fmt(a.swing_deg, 6)}°`);
      row('α = 180° (Q − 1)/(Q + 1)', `${fmt(a.construction.alpha_deg, 5)}°`);
    }
    if (a.task === 'function') {
      const s = a.structural_error;
      row('largest structural error', `${fmt(s.max, 4)} at x = ${fmt(s.at_x, 4)} (${fmt(s.max_output_angle_deg, 4)}° of the rocker)`);
    }
    const checks = this.el.checks;
    checks.replaceChildren(el('caption', {}, 'Checks by analysis of the returned linkage'));
    const head = el('tr');
    for (const h of ['where', 'crank angle (deg)', 'error', 'reached']) head.appendChild(el('th', { scope: 'col' }, h));
    checks.appendChild(el('thead')).appendChild(head);
    const rows = checks.appendChild(el('tbody'));
    // An error within NOISE of the linkage's size is 0 (the server's "reached" uses 1e-9 of it).
    const size = Math.max(d.ground, d.crank, d.coupler, d.rocker);
    a.checks.forEach((c, k) => {
      const where = c.limit ? `${c.limit} limit` : a.task === 'function' ? `x = ${fmt(c.x, 4)}` : `position ${c.position}`;
      const tr = rows.appendChild(el('tr', { 'data-reached': String(c.reached) }));
      tr.append(el('th', { scope: 'row' }, where), el('td', {}, fmt(c.driver_angle_deg, 5)), el('td', {}, fmt(c.error, 2, size)), el('td', {}, c.reached ? 'yes' : 'no'));
      tr.dataset.check = String(k);
    });
  }

  /** The function task: desired and generated y over x, and the structural error. */
  async renderPlots() {
    const a = this.answer;
    const show = a.task === 'function';
    this.el.curves.hidden = !show;
    this.el.errorPlot.hidden = !show;
    if (!show) return;
    const Plotly = await plotlyReady();
    if (!Plotly || a !== this.answer) {
      if (!Plotly) this.el.curves.textContent = 'The plots cannot be drawn: Plotly did not load.';
      return;
    }
    const s = a.structural_error;
    const px = a.precision_points.map((p) => p.x);
    const config = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ['select2d', 'lasso2d'] };
    const layout = (title, ytitle) => ({
      height: 260, margin: { l: 64, r: 12, t: 34, b: 42 }, title: { text: title, font: { size: 13 } },
      xaxis: { title: { text: 'x' } }, yaxis: { title: { text: ytitle }, exponentformat: 'e' }, legend: { orientation: 'h', y: -0.28 }, uirevision: 'syn',
    });
    await Plotly.react(this.el.curves, [
      { x: s.x, y: s.y_desired, name: 'desired f(x)', type: 'scatter', mode: 'lines', line: { color: '#1f4e9c', width: 2 } },
      { x: s.x, y: s.y_generated, name: 'generated by the linkage', type: 'scatter', mode: 'lines', line: { color: '#b5471b', width: 2, dash: 'dash' } },
      { x: px, y: a.precision_points.map((p) => p.y), name: 'precision points', type: 'scatter', mode: 'markers', marker: { color: '#222222', size: 8 } },
    ], { ...layout(`Desired and generated y = ${this.asked.function}`, 'y'), height: 300 }, config);
    await Plotly.react(this.el.errorPlot, [
      { x: s.x, y: s.error, name: 'structural error', type: 'scatter', mode: 'lines', line: { color: '#6a1b9a', width: 2 } },
      { x: px, y: px.map(() => 0), name: 'precision points', type: 'scatter', mode: 'markers', marker: { color: '#222222', size: 8 } },
    ], { ...layout('Structural error y generated − f(x)', 'error in y'), showlegend: false }, config);
    this.el.curves.dataset.traces = '3';
  }

  async renderSteps() {
    const answer = this.answer;
    await katexReady();
    if (answer !== this.answer) return;
    if (!answer.steps?.length) {
      renderMessage(this.el.steps, 'The server gave no worked solution for this design.');
      return;
    }
    renderSolution(this.el.steps, this.el.mistakes, { steps: answer.steps, mistakes: [] });
  }

  // ---- the handles: the positions and the given pivots, over the linkage -------------------------

  /** The motion task's handles, drawn after the view's layers (the view rebuilds its SVG). */
  buildHandles() {
    this.handles = [];
    if (this.answer?.task !== 'motion' || !this.view.map) return;
    const layer = svgEl('g', { class: 'syn-handles' }, this.el.svg);
    const m = this.motion;
    for (let j = 0; j < m.count; j += 1) {
      const g = svgEl('g', { class: 'syn-position', tabindex: '0', role: 'button', 'aria-roledescription': 'movable position', 'data-handle': `P${j + 1}` }, layer);
      const body = svgEl('rect', { x: -21, y: -14, width: 42, height: 28, rx: 6, fill: INK, 'fill-opacity': 0.16, stroke: INK, 'stroke-width': 1.5, 'data-part': 'move' }, g);
      const line = svgEl('line', { stroke: INK, 'stroke-width': 3.5 }, g);
      const tip = svgEl('path', { d: 'M4,0 L-16,-10 L-16,10 Z', fill: INK, 'data-part': 'turn', class: 'syn-tip' }, g);
      const dot = svgEl('circle', { r: 7, fill: INK, 'data-part': 'move' }, g);
      const label = svgEl('text', { class: 'syn-handle-label', fill: INK }, g);
      label.textContent = `${j + 1}`;
      this.handles.push({ kind: 'position', index: j, g, body, line, tip, dot, label });
      this.wireHandle(g, { kind: 'position', index: j });
    }
    m.pivots[m.kind].forEach((_, i) => {
      const name = m.kind === 'fixed_pivots' ? ['A', 'D'][i] : ['B', 'C'][i];
      const g = svgEl('g', { class: 'syn-pivot', tabindex: '0', role: 'button', 'aria-roledescription': 'movable pivot', 'data-handle': name }, layer);
      const box = svgEl('rect', { x: -PIVOT_HALF, y: -PIVOT_HALF, width: 2 * PIVOT_HALF, height: 2 * PIVOT_HALF, fill: 'transparent', stroke: INK, 'stroke-width': 3, 'data-part': 'move' }, g);
      // A moving pivot is given where it is at the first position: B₁, C₁ (A and D stay put).
      const label = svgEl('text', { class: 'syn-handle-label syn-pivot-label', fill: INK, x: -44, y: 30 }, g);
      label.textContent = m.kind === 'fixed_pivots' ? '' : `${name}₁`;
      this.handles.push({ kind: 'pivot', index: i, name, g, box, label });
      this.wireHandle(g, { kind: 'pivot', index: i });
    });
    this.placeHandles();
  }

  /**
   * Each handle where the task puts it (at the drawing's scale); the handles' boxes and their
   * labels' are given to the view, whose names of points keep clear of them ("B" off B₁).
   */
  placeHandles() {
    this.view.overlayMarks = [];
    if (!this.handles?.length || !this.view.map) return;
    const m = this.motion;
    for (const h of this.handles) {
      if (h.kind === 'position') {
        const [x, y, deg] = m.positions[h.index];
        const [px, py] = this.view.px([x, y]);
        const a = (deg * Math.PI) / 180;
        h.g.setAttribute('transform', `translate(${px.toFixed(1)},${py.toFixed(1)})`);
        this.view.overlayMarks.push(markerBox([px, py], POSITION_REACH));
        h.body.setAttribute('transform', `rotate(${(-deg).toFixed(2)})`);
        const [tx, ty] = [ARROW_PX * Math.cos(a), -ARROW_PX * Math.sin(a)];
        h.line.setAttribute('x2', tx.toFixed(1));
        h.line.setAttribute('y2', ty.toFixed(1));
        h.tip.setAttribute('transform', `translate(${tx.toFixed(1)},${ty.toFixed(1)}) rotate(${(-deg).toFixed(2)})`);
        // the number on the side away from the arrow
        h.label.setAttribute('x', (-32 * Math.cos(a) - 8).toFixed(1));
        h.label.setAttribute('y', (32 * Math.sin(a) + 9).toFixed(1));
        h.g.setAttribute('aria-label', `Position ${h.index + 1}: P at (${fmt(x, 4)}, ${fmt(y, 4)}) m, coupler at ${fmt(deg, 4)} deg. Arrow keys move it, Page Up and Page Down turn it.`);
      } else {
        const p = m.pivots[m.kind][h.index];
        const [px, py] = this.view.px(p);
        h.g.setAttribute('transform', `translate(${px.toFixed(1)},${py.toFixed(1)})`);
        this.view.overlayMarks.push(markerBox([px, py], PIVOT_HALF + 2));
        if (h.label.textContent) {
          const b = h.label.getBBox();
          this.view.overlayMarks.push({ x0: px + b.x, y0: py + b.y, x1: px + b.x + b.width, y1: py + b.y + b.height });
        }
        h.g.setAttribute('aria-label', `Given ${m.kind === 'fixed_pivots' ? 'fixed' : 'moving'} pivot ${h.name} at (${fmt(p[0], 4)}, ${fmt(p[1], 4)}) m. Arrow keys move it.`);
      }
    }
  }

  /** The grid the handles snap to: about 1/40 of the picture, a round number of metres. */
  step() {
    return niceBelow((this.view.map?.size || 1) / 40);
  }

  wireHandle(g, { kind, index }) {
    const svg = this.el.svg;
    const world = (ev) => {
      const pt = svg.createSVGPoint();
      pt.x = ev.clientX;
      pt.y = ev.clientY;
      const q = pt.matrixTransform(svg.getScreenCTM().inverse());
      return this.view.world(q.x, q.y);
    };
    let drag = null;
    g.addEventListener('pointerdown', (ev) => {
      ev.stopPropagation(); // not a press on the crank
      ev.preventDefault();
      drag = { part: ev.target.dataset?.part || 'move', moved: false };
      g.setPointerCapture(ev.pointerId);
      g.focus();
      this.setPlaying(false);
    });
    g.addEventListener('pointermove', (ev) => {
      if (!drag) return;
      const w = world(ev);
      const step = this.step();
      const snap = (v) => (ev.shiftKey ? Number(v.toPrecision(6)) : roundTo(v, step));
      if (kind === 'pivot') {
        this.motion.pivots[this.motion.kind][index] = [snap(w[0]), snap(w[1])];
      } else if (drag.part === 'turn') {
        const p = this.motion.positions[index];
        p[2] = Math.round((Math.atan2(w[1] - p[1], w[0] - p[0]) * 180) / Math.PI);
      } else {
        const p = this.motion.positions[index];
        p[0] = snap(w[0]);
        p[1] = snap(w[1]);
      }
      drag.moved = true;
      this.placeHandles();
      this.syncFields();
    });
    const end = (ev) => {
      if (!drag) return;
      const moved = drag.moved;
      drag = null;
      if (g.hasPointerCapture(ev.pointerId)) g.releasePointerCapture(ev.pointerId);
      if (moved) this.design();
    };
    g.addEventListener('pointerup', end);
    g.addEventListener('pointercancel', end);
    g.addEventListener('keydown', (ev) => {
      const step = this.step();
      const moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
      const target = kind === 'pivot' ? this.motion.pivots[this.motion.kind][index] : this.motion.positions[index];
      if (moves[ev.key]) {
        target[0] = roundTo(target[0] + moves[ev.key][0], step / 1000);
        target[1] = roundTo(target[1] + moves[ev.key][1], step / 1000);
      } else if (kind === 'position' && (ev.key === 'PageUp' || ev.key === 'PageDown')) {
        target[2] += ev.key === 'PageUp' ? 5 : -5;
      } else {
        return;
      }
      ev.preventDefault();
      this.setPlaying(false);
      this.placeHandles();
      this.syncFields();
      clearTimeout(this.keyTimer);
      this.keyTimer = setTimeout(() => this.design(), KEY_DELAY_MS);
    });
  }

  // ---- the motion ------------------------------------------------------------------------------

  setPlaying(playing) {
    this.playing = playing;
    this.el.play.textContent = playing ? 'Pause' : 'Play';
    this.el.play.setAttribute('aria-pressed', String(playing));
  }

  /** The crank dragged in the drawing: the sweep's pose nearest that crank angle. */
  showAngle(angle) {
    if (!this.track) return;
    this.setPlaying(false);
    this.u = indexOfValue(this.track, angle);
    this.drawFrame();
  }

  drawFrame() {
    if (!this.track) return;
    this.view.draw(frameAt(this.track, this.u));
    const deg = (valueAt(this.track, this.u) * 180) / Math.PI;
    this.el.readout.textContent = `crank angle θ₂ = ${fmt(deg, 4)}°`;
    this.el.svg.dataset.u = this.u.toFixed(3);
  }
}
