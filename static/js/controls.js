// controls.js: the inputs of the page, in the units the student chose.
//
// Every field keeps its value in SI in a data attribute and shows it converted; what goes out
// through the callbacks is always SI. The server's validation messages are shown next to the
// field that caused them (an element with class field-error under each field, aria-linked), and
// a field in error keeps what the student typed so it can be corrected.

import { toDisplay, fromDisplay, unitLabel, kindOfUnit, fmt } from './units.js';
import { COLOURS, LEGEND } from './theme.js';
import { greekPointNames, pointName } from './notation.js';

const $ = (id) => document.getElementById(id);

/** The preset parameter that only places the drawn pose (the crank angle of the drawing). */
export const POSE_PARAMETER = 'crank_angle_deg';

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== null && v !== undefined && v !== false) node.setAttribute(k, v === true ? '' : v);
  }
  if (text !== null) node.textContent = text;
  return node;
}

/**
 * The number a student typed, or null: a decimal comma is a decimal point ("0,2" -> 0.2);
 * letters, an empty field or anything but one plain number is not a number.
 */
export function parseNumber(text) {
  const t = String(text).trim().replace(/\s+/g, '').replace(',', '.');
  if (!/^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i.test(t)) return null;
  const v = Number(t);
  return Number.isFinite(v) ? v : null;
}

function debounce(fn, ms) {
  let timer = null;
  return (...args) => {
    clearTimeout(timer);
    timer = setTimeout(() => fn(...args), ms);
  };
}

export class Controls {
  /** @param {object} on callbacks: preset, param, point, driver, law, instant, play, speed, units, options, plot, method, share */
  constructor(on) {
    this.on = on;
    this.units = 'si';
    this.fields = new Map(); // key -> {input, kind, error}
    this.instant = { param: 'angle', min: 0, max: 360 };
    this.el = {
      preset: $('preset'), description: $('preset-description'), dimensions: $('dimensions'), driver: $('driver'),
      play: $('play'), speed: $('speed'), slider: $('crank-angle'), sliderLabel: $('crank-angle-label'), sliderValue: $('crank-angle-value'),
      units: $('units'), share: $('share'), shareUrl: $('share-url'),
      showVelocity: $('show-velocity'), showAcceleration: $('show-acceleration'), showPoles: $('show-poles'), trace: $('trace-point'),
      plotLinks: $('plot-links'), plotPoint: $('plot-point'), plotX: $('plot-x'), legend: $('legend'),
    };
    this.buildLegend();
    this.wire();
  }

  wire() {
    const e = this.el;
    e.preset.addEventListener('change', () => this.on.preset(e.preset.value));
    $('dimension-form').addEventListener('submit', (ev) => ev.preventDefault());
    e.play.addEventListener('click', () => this.on.play(e.play.getAttribute('aria-pressed') !== 'true'));
    e.speed.addEventListener('change', () => this.on.speed(Number(e.speed.value)));
    e.slider.addEventListener('input', () => this.on.instant(this.sliderToSI(Number(e.slider.value)), false));
    e.slider.addEventListener('change', () => this.on.instant(this.sliderToSI(Number(e.slider.value)), true));
    e.units.addEventListener('change', () => this.on.units(e.units.value));
    e.share.addEventListener('click', () => this.on.share());
    const opts = () => this.on.options(this.options());
    for (const k of ['showVelocity', 'showAcceleration', 'showPoles']) e[k].addEventListener('change', opts);
    e.trace.addEventListener('change', opts);
    e.plotPoint.addEventListener('change', () => this.on.plot(this.plotSelection()));
    e.plotX.addEventListener('change', () => this.on.plot(this.plotSelection()));
    e.plotLinks.addEventListener('change', () => this.on.plot(this.plotSelection()));
    for (const r of document.querySelectorAll('input[name="method"]')) {
      r.addEventListener('change', () => r.checked && this.on.method(r.value));
    }
    // Space toggles play anywhere except in a text field or on a button (where it clicks); on
    // the crank slider and the cam's or gear train's slider too, as the hint says (a range input
    // does nothing with Space).
    document.addEventListener('keydown', (ev) => {
      if (ev.key !== ' ' || ev.ctrlKey || ev.metaKey || ev.altKey) return;
      const t = ev.target;
      const slider = t.matches?.('input[type="range"]');
      if (!slider && t.closest && t.closest('input, select, textarea, button, [contenteditable]')) return;
      ev.preventDefault();
      e.play.click();
    });
  }

  buildLegend() {
    for (const item of LEGEND) {
      const li = el('li');
      const sw = el('span', { class: 'swatch', 'aria-hidden': 'true' });
      sw.style.borderTopColor = COLOURS[item.key] || COLOURS.ink;
      if (item.dash) sw.style.borderTopStyle = 'dashed';
      if (item.groove) sw.classList.add('swatch-groove');
      li.append(sw, document.createTextNode(` ${item.label}`));
      this.el.legend.appendChild(li);
    }
  }

  // ---- mechanism selector --------------------------------------------------------------------

  setPresetChoices(presets, examples) {
    const sel = this.el.preset;
    sel.replaceChildren();
    if (presets.length) {
      const g = el('optgroup', { label: 'Textbook mechanisms' });
      for (const p of presets) g.appendChild(el('option', { value: `preset:${p.name}` }, p.title || p.name));
      sel.appendChild(g);
    }
    if (examples.length) {
      const g = el('optgroup', { label: 'Seed problems' });
      for (const x of examples) g.appendChild(el('option', { value: `example:${x.file}` }, x.title));
      sel.appendChild(g);
    }
  }

  selectSource(value, description = '') {
    const sel = this.el.preset;
    if (![...sel.options].some((o) => o.value === value)) {
      sel.appendChild(el('option', { value }, 'Shared scene'));
    }
    sel.value = value;
    // The first paragraph of a preset's description; the rest is for the API documentation.
    // A point named by a Greek letter spelled out is written as the letter, as in the drawing.
    this.el.description.textContent = greekPointNames(String(description || '').split(/\n\s*\n/)[0].replace(/\s*\n\s*/g, ' '));
  }

  // ---- dimension fields ----------------------------------------------------------------------

  /** A number field; `kind` is a unit kind of units.js (or null for a raw unit). */
  numberField(parent, key, label, valueSI, { kind = null, rawUnit = '', min = null, max = null, help = '', onCommit }) {
    const id = `f-${key.replace(/[^a-zA-Z0-9_-]/g, '_')}`;
    const wrap = el('div', { class: 'field' });
    const lab = el('label', { for: id });
    lab.append(document.createTextNode(label), el('span', { class: 'unit' }));
    // A text field, not type=number: the browser's number field drops "0,2" and letters
    // silently (its value becomes ""), so the page could neither read a decimal comma nor say
    // that a value is not a number.
    const input = el('input', { id, type: 'text', inputmode: 'decimal', spellcheck: 'false', 'data-key': key, 'aria-describedby': `${id}-error` });
    if (help) input.title = help;
    const error = el('p', { id: `${id}-error`, class: 'field-error', role: 'alert', hidden: true });
    wrap.append(lab, input, error);
    parent.appendChild(wrap);
    const field = { input, kind, rawUnit, min, max, error, label: lab, valueSI, lastSent: valueSI };
    this.fields.set(key, field);
    this.paintField(field);
    const commit = () => {
      const typed = parseNumber(input.value);
      if (typed === null) {
        field.lastSent = null;
        this.showFieldError(key, input.value.trim() === ''
          ? 'Empty: type a number (a decimal comma is fine).'
          : `"${input.value.trim()}" is not a number: type a value such as 0.25 or 0,25.`);
        return;
      }
      const si = fromDisplay(kind, typed, this.units);
      if (si === field.valueSI) {
        // The value the server last accepted: valid as it stands, nothing to ask.
        field.lastSent = si;
        this.clearFieldError(key);
        return;
      }
      if (si === field.lastSent) return; // already sent, answer pending
      field.lastSent = si;
      onCommit(si);
    };
    input.addEventListener('change', commit);
    input.addEventListener('input', debounce(commit, 800));
    return field;
  }

  textField(parent, key, label, value, { help = '', onCommit }) {
    const id = `f-${key.replace(/[^a-zA-Z0-9_-]/g, '_')}`;
    const wrap = el('div', { class: 'field' });
    const lab = el('label', { for: id }, label);
    const input = el('input', { id, type: 'text', spellcheck: 'false', 'data-key': key, 'aria-describedby': `${id}-error`, class: 'mono' });
    input.value = value;
    if (help) input.title = help;
    const error = el('p', { id: `${id}-error`, class: 'field-error', role: 'alert', hidden: true });
    wrap.append(lab, input, error);
    parent.appendChild(wrap);
    const field = { input, kind: 'text', error, label: lab, lastSent: value };
    this.fields.set(key, field);
    input.addEventListener('change', () => {
      if (input.value === field.lastSent) return;
      field.lastSent = input.value;
      onCommit(input.value);
    });
    return field;
  }

  paintField(field) {
    if (field.kind === 'text') return;
    const unit = field.kind ? unitLabel(field.kind, this.units) : field.rawUnit;
    field.label.querySelector('.unit').textContent = unit ? ` [${unit}]` : '';
    if (field.valueSI !== null && field.valueSI !== undefined && !field.input.getAttribute('aria-invalid')) {
      field.input.value = fmt(toDisplay(field.kind, field.valueSI, this.units), 6);
    }
    const bound = (v) => (v === null || v === undefined ? null : fmt(toDisplay(field.kind, v, this.units), 6));
    for (const [attr, v] of [['min', bound(field.min)], ['max', bound(field.max)]]) {
      if (v === null) field.input.removeAttribute(attr);
      else field.input.setAttribute(attr, v);
    }
  }

  /** Preset parameters: {name, default, unit, description, minimum, maximum, choices, labels}. */
  setPresetFields(parameters, values, onParam) {
    this.clearFields(this.el.dimensions);
    for (const p of parameters) {
      if (/^(omega|alpha)$/i.test(p.name)) continue; // shown with the driver
      // One crank angle on the page: the slider's (the analysed instant). The preset's drawn
      // pose follows it when the mechanism is rebuilt (main.js), it is not a dimension.
      if (p.name === POSE_PARAMETER) continue;
      const kind = kindOfUnit(p.unit);
      const value = values[p.name] ?? p.default;
      if (Array.isArray(p.choices) && p.choices.length) {
        this.choiceField(this.el.dimensions, `param:${p.name}`, p.name, value, p.choices, p.labels, p.description, (v) => onParam(p.name, v));
      } else {
        this.numberField(this.el.dimensions, `param:${p.name}`, p.name.replace(/_/g, ' '), value, {
          kind, rawUnit: p.unit, min: p.minimum, max: p.maximum, help: p.description || '', onCommit: (v) => onParam(p.name, v),
        });
      }
    }
  }

  choiceField(parent, key, label, value, choices, labels, help, onCommit) {
    const id = `f-${key.replace(/[^a-zA-Z0-9_-]/g, '_')}`;
    const wrap = el('div', { class: 'field' });
    const lab = el('label', { for: id }, label.replace(/_/g, ' '));
    const select = el('select', { id, 'data-key': key, 'aria-describedby': `${id}-error` });
    if (help) select.title = help;
    choices.forEach((c, i) => select.appendChild(el('option', { value: JSON.stringify(c) }, labels?.[i] ?? String(c))));
    select.value = JSON.stringify(value);
    const error = el('p', { id: `${id}-error`, class: 'field-error', role: 'alert', hidden: true });
    wrap.append(lab, select, error);
    parent.appendChild(wrap);
    this.fields.set(key, { input: select, kind: 'text', error, label: lab });
    select.addEventListener('change', () => onCommit(JSON.parse(select.value)));
  }

  /** Example scenes have no parameters: their drawn point coordinates are the dimensions. */
  setPointFields(scene, fixedPoints, onPoint) {
    this.clearFields(this.el.dimensions);
    const note = el('p', { class: 'hint' }, 'Coordinates of the drawn pose; the links keep the lengths drawn.');
    this.el.dimensions.appendChild(note);
    for (const [name, xy] of Object.entries(scene.points || {})) {
      const row = el('div', { class: 'pair' });
      this.el.dimensions.appendChild(row);
      ['x', 'y'].forEach((axis, i) => {
        this.numberField(row, `point:${name}:${i}`, `${name} ${axis}`, xy[i], {
          kind: 'length', help: fixedPoints.has(name) ? `${name} is fixed to the ground` : '', onCommit: (v) => onPoint(name, i, v),
        });
      });
    }
  }

  setSpatialFields(scene, onJoint) {
    this.clearFields(this.el.dimensions);
    this.clearFields(this.el.driver);
    for (const j of scene.joints || []) {
      const kind = j.type === 'prismatic' ? 'velocity' : 'omega';
      this.numberField(this.el.driver, `joint:${j.name}:rate`, `joint ${j.name} rate`, j.rate ?? 0, { kind, onCommit: (v) => onJoint(j.name, 'rate', v) });
      this.numberField(this.el.driver, `joint:${j.name}:rate_dot`, `joint ${j.name} rate′`, j.rate_dot ?? 0, {
        kind: j.type === 'prismatic' ? 'acceleration' : 'alpha', onCommit: (v) => onJoint(j.name, 'rate_dot', v),
      });
    }
  }

  setDriverFields(scene, onDriver, onLaw) {
    this.clearFields(this.el.driver);
    const d = (scene.drivers || [])[0];
    if (d && typeof d.angle_law === 'string') {
      this.textField(this.el.driver, 'law:angle', `rotation of ${d.link}, φ(t) [rad]`, d.angle_law, { help: 'Expression in t, e.g. 2*t - 0.3*t^2', onCommit: (v) => onLaw('angle', null, v) });
    } else if (d) {
      this.numberField(this.el.driver, 'driver:omega', `ω of ${d.link}`, d.omega ?? 0, { kind: 'omega', help: 'Counter-clockwise positive', onCommit: (v) => onDriver('omega', v) });
      this.numberField(this.el.driver, 'driver:alpha', `α of ${d.link}`, d.alpha ?? 0, { kind: 'alpha', help: 'Counter-clockwise positive', onCommit: (v) => onDriver('alpha', v) });
    }
    const mps = Array.isArray(scene.moving_points) ? scene.moving_points : Object.entries(scene.moving_points || {}).map(([name, m]) => ({ name, ...m }));
    for (const m of mps) {
      this.textField(this.el.driver, `law:s:${m.name}`, `path of ${m.name}, s(t) [m]`, m.s_law || '', { help: 'Arc length along the groove, an expression in t', onCommit: (v) => onLaw('s', m.name, v) });
    }
  }

  clearFields(container) {
    for (const [key, f] of this.fields) if (container.contains(f.input)) this.fields.delete(key);
    for (const child of [...container.children]) if (child.tagName !== 'LEGEND') child.remove();
  }

  /** Update a field's SI value after the server accepted it (or a shared link restored it). */
  setFieldValue(key, valueSI) {
    const f = this.fields.get(key);
    if (!f) return;
    if (f.kind === 'text') {
      f.input.value = valueSI;
      f.lastSent = valueSI;
      return;
    }
    f.valueSI = valueSI;
    f.lastSent = valueSI;
    this.paintField(f);
  }

  /** Accept what was typed: the server took it (shown again in canonical form, "0,2" -> 0.2). */
  acceptField(key, valueSI) {
    const f = this.fields.get(key);
    if (!f) return;
    this.clearFieldError(key);
    if (f.kind === 'text') return;
    f.valueSI = valueSI;
    this.paintField(f);
  }

  showFieldError(key, message, position = null) {
    const f = this.fields.get(key);
    if (!f) return false;
    f.input.setAttribute('aria-invalid', 'true');
    f.error.hidden = false;
    f.error.textContent = message;
    if (position !== null && position !== undefined && f.kind === 'text') {
      // Point at the offending character of an expression.
      const pre = el('pre', { class: 'caret' });
      pre.textContent = `${f.input.value}\n${' '.repeat(Math.max(0, position))}^`;
      f.error.appendChild(pre);
      f.input.focus();
      f.input.setSelectionRange(position, Math.min(position + 1, f.input.value.length));
    }
    return true;
  }

  clearFieldError(key) {
    const f = this.fields.get(key);
    if (!f) return;
    f.input.removeAttribute('aria-invalid');
    f.error.hidden = true;
    f.error.textContent = '';
  }

  clearAllErrors() {
    for (const key of this.fields.keys()) this.clearFieldError(key);
  }

  /** A field in error whose value was not accepted: go back to the last good value. */
  revertField(key) {
    const f = this.fields.get(key);
    if (!f || f.kind === 'text') return;
    f.lastSent = f.valueSI;
  }

  // ---- units --------------------------------------------------------------------------------

  setUnits(units) {
    this.units = units;
    this.el.units.value = units;
    for (const f of this.fields.values()) this.paintField(f);
    this.paintSliderValue();
  }

  // ---- motion -------------------------------------------------------------------------------

  setPlaying(playing) {
    this.el.play.setAttribute('aria-pressed', String(playing));
    this.el.play.textContent = playing ? 'Pause' : 'Play';
  }

  setSpeed(speed) {
    this.el.speed.value = String(speed);
  }

  /** Configure the instant slider for a track: angle (deg steps) or time (s). */
  setInstantRange(param, lo, hi, enabled = true) {
    const s = this.el.slider;
    this.instant = { param, lo, hi };
    $('motion-hint').textContent = param === 'time'
      ? 'The motion follows the time laws. Focus the slider and use the arrow keys to choose the instant. Space plays and pauses.'
      : 'Drag the crank in the drawing, or focus the slider and use the arrow keys. Space plays and pauses.';
    if (param === 'time') {
      this.el.sliderLabel.textContent = 'Time';
      s.min = '0';
      s.max = '1000';
      s.step = '1';
    } else {
      this.el.sliderLabel.textContent = 'Crank angle';
      // Steps of one degree from the start of the sweep: one arrow key press is one degree.
      const a = (lo * 180) / Math.PI;
      const b = (hi * 180) / Math.PI;
      s.min = String(Math.min(a, b));
      s.max = String(Math.max(a, b));
      s.step = '1';
    }
    s.disabled = !enabled;
  }

  sliderToSI(v) {
    const { param, lo, hi } = this.instant;
    if (param === 'time') return lo + ((hi - lo) * v) / 1000;
    return (v * Math.PI) / 180;
  }

  setInstant(valueSI) {
    const { param, lo, hi } = this.instant;
    this.currentInstant = valueSI;
    if (param === 'time') this.el.slider.value = String(hi > lo ? ((valueSI - lo) / (hi - lo)) * 1000 : 0);
    else this.el.slider.value = String((valueSI * 180) / Math.PI);
    this.paintSliderValue();
  }

  paintSliderValue() {
    const v = this.currentInstant;
    if (v === undefined || v === null) return;
    const text = this.instant.param === 'time'
      ? `t = ${fmt(v, 4)} s`
      : this.units === 'si' ? `${fmt(v, 4)} rad` : `${fmt((v * 180) / Math.PI, 4)}°`;
    this.el.sliderValue.textContent = text;
    this.el.slider.setAttribute('aria-valuetext', text);
  }

  // ---- display options ------------------------------------------------------------------------

  options() {
    const e = this.el;
    return { showVelocity: e.showVelocity.checked, showAcceleration: e.showAcceleration.checked, showPoles: e.showPoles.checked, trace: e.trace.value || null };
  }

  setOptions(o) {
    const e = this.el;
    if (o.showVelocity !== undefined) e.showVelocity.checked = o.showVelocity;
    if (o.showAcceleration !== undefined) e.showAcceleration.checked = o.showAcceleration;
    if (o.showPoles !== undefined) e.showPoles.checked = o.showPoles;
    if (o.trace !== undefined && [...e.trace.options].some((x) => x.value === (o.trace || ''))) e.trace.value = o.trace || '';
  }

  setPointChoices(names, trace) {
    const fill = (sel, selected, none) => {
      sel.replaceChildren();
      if (none) sel.appendChild(el('option', { value: '' }, none));
      for (const n of names) sel.appendChild(el('option', { value: n }, pointName(n)));
      sel.value = names.includes(selected) ? selected : none ? '' : names[0] || '';
    };
    fill(this.el.trace, trace, 'none');
  }

  /** The quantity plotted under the link panels: [{value, label}] and the chosen value. */
  setQuantityChoices(choices, selected) {
    const sel = this.el.plotPoint;
    sel.replaceChildren(...choices.map((c) => el('option', { value: c.value }, c.label)));
    sel.value = choices.some((c) => c.value === selected) ? selected : choices[0]?.value || '';
    return sel.value || null;
  }

  /** The x axes offered ('angle', 'time'); returns the one chosen. */
  setAxisChoices(axes, selected) {
    const sel = this.el.plotX;
    for (const o of sel.options) o.hidden = !axes.includes(o.value);
    sel.value = axes.includes(selected) ? selected : axes[0];
    sel.disabled = axes.length < 2;
    return sel.value;
  }

  setLinkChoices(links, colours, checked) {
    const box = this.el.plotLinks;
    box.replaceChildren();
    for (const name of links) {
      const lab = el('label', { class: 'check chip' });
      const input = el('input', { type: 'checkbox', value: name });
      input.checked = checked.includes(name);
      const sw = el('span', { class: 'dot', 'aria-hidden': 'true' });
      sw.style.background = colours[name];
      lab.append(input, sw, document.createTextNode(` ${name}`));
      box.appendChild(lab);
    }
  }

  plotSelection() {
    const links = [...this.el.plotLinks.querySelectorAll('input:checked')].map((i) => i.value);
    return { links, quantity: this.el.plotPoint.value || null, axis: this.el.plotX.value };
  }

  setMethod(method) {
    for (const r of document.querySelectorAll('input[name="method"]')) r.checked = r.value === method;
  }

  showShareUrl(url) {
    this.el.shareUrl.hidden = false;
    this.el.shareUrl.value = url;
    this.el.shareUrl.select();
  }
}
