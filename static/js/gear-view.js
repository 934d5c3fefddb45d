// gear-view.js: the Gear trains family (issue 25, docs/GEARS.md). Its choices in the mechanism
// menu, the train drawn to scale with teeth marks turning at the server's speeds and the carriers
// turning, a table of speeds, the preset's parameters (or an example's inputs and teeth) as fields,
// and the worked solution (the tabular and formula methods).
//
// Requests per decision, never per frame: a change of train or of a field asks for the scene
// (POST /presets/{name}), its speeds (POST /analyze), one /sweep over a time range (each member's
// angle at its samples) and the worked solution. The animation plays the sweep back: between two
// samples it interpolates, past its end it goes on by whole sweeps (the speeds are constant, so
// a member's angle after k sweeps is k times its angle at the end plus the angle within the
// sweep). The drawing itself (pitch circles, teeth marks, a planet's centre turned with its
// carrier) is geometry: no speed is computed here.
//
// The page's units switch (units.js, the linkage view's one conversion) applies to the speed
// fields, the table of speeds and its CSV (rad/s or rpm). A share link (share.js) carries the
// scene, the preset and its parameters (or the example) and the view: the time shown, playing.

import { Playback } from './playback.js';
import * as api from './api.js';
import { svgEl, clear } from './svg.js';
import { renderSolution, renderMessage } from './steps.js';
import { katexReady } from './vendor.js';
import { fmt, typed, toDisplay, fromDisplay, unitLabel, kindOfUnit } from './units.js';
import { toCsv } from './export.js';

const FAMILY = 'gear_trains';
const SAMPLES = 61;
const TURN_SECONDS = 6; // the fastest member's turn, played back at 1x
const VIEW = 1000; // the drawing's viewBox is VIEW x VIEW * ASPECT
const ASPECT = 0.62;
const COLOURS = ['#1f4e9c', '#b5471b', '#2e7d32', '#6a1b9a', '#8d6e00', '#00838f', '#555555'];

const el = (tag, attrs = {}, text = '') => {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text) node.textContent = text;
  return node;
};

export class GearTrains {
  /** `root`: the #gear-train section (its children are found by id inside it). */
  constructor(root) {
    this.root = root;
    this.svg = root.querySelector('#gear-view');
    this.fields = root.querySelector('#gear-fields');
    this.table = root.querySelector('#gear-speeds');
    this.message = root.querySelector('#gear-message');
    this.playButton = root.querySelector('#gear-play');
    this.readout = root.querySelector('#gear-readout');
    this.presets = new Map();
    this.examples = [];
    this.shown = false;
    this.seq = 0;
    this.units = 'si';
    this.onChange = () => {}; // main.js keeps the share link up to date
    // paused where the system asks for reduced motion, and the button says so (its markup says
    // Pause: it read Pause over a still train, and a click on it started the train)
    this.setPlaying(!matchMedia('(prefers-reduced-motion: reduce)').matches);
    this.t = 0; // display time within the playback, s
    // while playing, the display time runs at one turn of the input per TURN_SECONDS
    this.playback = new Playback(() => this.shown, (dt) => {
      if (!this.playing || !this.sweep) return;
      this.t += dt * (this.span / TURN_SECONDS);
      this.drawAt(this.t);
    });
    this.playButton.addEventListener('click', () => this.setPlaying(!this.playing));
  }

  /** The family's presets (GET /presets?family=gear_trains) and the gear-train examples. */
  async load(examples) {
    try {
      const body = await api.getPresetFamily(FAMILY);
      for (const p of body.presets || []) this.presets.set(p.name, p);
    } catch {
      this.presets.clear(); // the menu simply has no gear trains
    }
    this.examples = examples.filter((x) => x.kind === 'gear_train');
  }

  /** An optgroup "Gear trains" at the end of the mechanism menu: `gear:<preset>`, `gear-example:<file>`. */
  addChoices(select) {
    if (!this.presets.size && !this.examples.length) return;
    const group = el('optgroup', { label: 'Gear trains' });
    for (const p of this.presets.values()) group.appendChild(el('option', { value: `gear:${p.name}` }, p.title || p.name));
    for (const x of this.examples) group.appendChild(el('option', { value: `gear-example:${x.file}` }, x.title));
    select.appendChild(group);
  }

  /** Show the panel with a preset (`gear`) or an example (`gear-example`). */
  async open(type, name) {
    return this.show({ type, name }, {}, null, null);
  }

  /** A gear-train scene from elsewhere (an uploaded file), its inputs and teeth as fields. */
  async openScene(scene) {
    return this.show({ type: 'gear-scene', name: null }, {}, scene, null);
  }

  /** What a share link carries: the scene whole, the preset and its parameters (or the example),
   * the time shown and playing. */
  shareState() {
    const source = this.source.type === 'gear' ? { ...this.source, params: { ...this.params } } : { ...this.source };
    return { scene: this.scene, source, view: { family: FAMILY, time: this.t, playing: this.playing, units: this.units } };
  }

  /** Open a share link's state (shareState): the scene as it was, at its time. */
  async restore(state) {
    const view = state.view || {};
    this.units = view.units === 'mm' ? 'mm' : 'si';
    this.setPlaying(view.playing === true);
    const src = state.source || {};
    const source = ['gear', 'gear-example'].includes(src.type) ? { type: src.type, name: src.name } : { type: 'gear-scene', name: null };
    const time = Number.isFinite(view.time) ? view.time : 0;
    return this.show(source, src.type === 'gear' ? { ...(src.params || {}) } : {}, state.scene, time);
  }

  /** The units switch: the fields and the table of speeds in `units`. */
  setUnits(units) {
    this.units = units;
    if (!this.scene) return;
    this.buildFields();
    this.renderTable();
  }

  /** The table of speeds as CSV, in the units chosen (header with units). */
  speedsCsv() {
    const unit = unitLabel('omega', this.units);
    const rows = [['member', 'type', 'teeth', `ω [${unit}]`, `ω relative to its carrier [${unit}]`, 'carrier', 'train value']];
    for (const [name, m] of Object.entries(this.analysis.members)) {
      const planet = m.type === 'gear' && m.carrier;
      rows.push([name, m.type, m.type === 'gear' ? m.teeth : null, toDisplay('omega', m.omega, this.units),
        planet ? toDisplay('omega', m.omega_relative, this.units) : null, planet ? m.carrier : null, m.train_value]);
    }
    return toCsv(rows);
  }

  /** Show `source` (a preset with `params`, an example, a scene) with `scene` when given, at
   * `time` (null: from 0); true, or the reason it cannot be shown (also on the page). */
  async show(source, params, scene, time) {
    this.shown = true;
    document.body.dataset.family = FAMILY;
    this.root.hidden = false;
    this.source = source;
    let ok;
    try {
      this.params = params;
      this.doc = source.type === 'gear' ? null : scene || await api.getExample(source.name);
      this.buildFields();
      ok = await this.update(source.type === 'gear' ? scene : null, time);
    } catch (err) {
      ok = err.detail || err.message;
    }
    if (typeof ok === 'string') {
      this.message.textContent = `This gear train cannot be shown: ${ok}`;
      this.message.hidden = false;
    }
    this.playback.start();
    return ok;
  }

  close() {
    this.shown = false;
    this.root.hidden = true;
    delete document.body.dataset.family;
  }

  setPlaying(playing) {
    this.playing = playing;
    this.playButton.textContent = playing ? 'Pause' : 'Play';
    this.playButton.setAttribute('aria-pressed', String(playing));
    this.onChange();
  }

  // ---- fields --------------------------------------------------------------------------------

  /** A preset's parameters, or an example's input speeds and teeth. */
  buildFields() {
    clear(this.fields);
    this.fields.appendChild(el('legend', {}, 'Inputs and teeth'));
    const rows = [];
    if (this.source.type === 'gear') {
      const meta = this.presets.get(this.source.name);
      for (const p of meta?.parameters || []) rows.push({ key: p.name, label: p.name, unit: p.unit, kind: kindOfUnit(p.unit), value: this.params[p.name] ?? p.default, help: p.description });
    } else {
      for (const [name, w] of Object.entries(this.doc.inputs)) rows.push({ key: `input:${name}`, label: `ω ${name}`, unit: 'rad/s', kind: 'omega', value: w, help: `Angular velocity of ${name} (0: fixed).` });
      for (const [name, g] of Object.entries(this.doc.gears)) rows.push({ key: `teeth:${name}`, label: `N ${name}`, unit: 'teeth', kind: null, value: g.teeth, help: `Teeth of ${name}.` });
    }
    for (const row of rows) {
      const id = `gear-f-${row.key.replace(/[^a-zA-Z0-9_-]/g, '_')}`;
      const wrap = el('div', { class: 'field' });
      const label = el('label', { for: id }, `${row.label} `);
      label.appendChild(el('span', { class: 'unit' }, `[${unitLabel(row.kind, this.units, row.unit)}]`));
      const input = el('input', { id, type: 'text', inputmode: 'decimal', spellcheck: 'false', 'data-key': row.key, 'aria-describedby': `${id}-error`, title: row.help, 'data-si': String(row.value) });
      // typed in the units chosen, the factor's rounding noise dropped
      input.value = typed(row.kind ? toDisplay(row.kind, row.value, this.units) : row.value);
      const error = el('div', { id: `${id}-error`, class: 'field-error', role: 'alert' });
      input.addEventListener('change', () => this.onField(row.key, input, error, row.kind));
      wrap.append(label, input, error);
      this.fields.appendChild(wrap);
    }
  }

  async onField(key, input, error, kind) {
    const number = Number(input.value.trim().replace(',', '.'));
    const value = kind ? fromDisplay(kind, number, this.units) : number;
    const mark = (text) => {
      error.textContent = text;
      if (text) input.setAttribute('aria-invalid', 'true');
      else input.removeAttribute('aria-invalid');
    };
    if (!input.value.trim() || !Number.isFinite(value)) return mark('Not a number.');
    const before = { params: { ...this.params }, doc: this.doc && structuredClone(this.doc) };
    if (this.source.type === 'gear') this.params[key] = value;
    else if (key.startsWith('input:')) this.doc.inputs[key.slice(6)] = value;
    else this.doc.gears[key.slice(6)].teeth = value;
    const ok = await this.update();
    if (ok === true) {
      input.dataset.si = String(value);
      for (const other of this.fields.querySelectorAll('[aria-invalid]')) other.removeAttribute('aria-invalid');
      for (const other of this.fields.querySelectorAll('.field-error')) other.textContent = '';
    } else if (ok !== null) {
      this.params = before.params;
      this.doc = before.doc;
      mark(ok);
    }
  }

  // ---- the server's answers --------------------------------------------------------------------

  /** The scene, its speeds, its sweep and its solution: true, or the server's message (null for
   * an answer overtaken by a newer request). */
  async update(given = null, time = null) {
    const seq = ++this.seq;
    let scene;
    let analysis;
    let sweep;
    try {
      const listed = this.presets.get(this.source.name)?.scene;
      scene = given || (this.source.type === 'gear' ? await api.presetScene(listed, this.source.name, this.params || {}) : this.doc);
      analysis = await api.analyze(scene);
      const fastest = Math.max(...Object.values(analysis.members).map((m) => Math.abs(m.omega)));
      this.span = fastest > 0 ? (2 * Math.PI) / fastest : 1;
      sweep = await api.sweep(scene, SAMPLES, undefined, [0, this.span]);
    } catch (err) {
      if (seq !== this.seq) return null;
      return err.detail || err.message;
    }
    if (seq !== this.seq) return null;
    this.scene = scene;
    this.analysis = analysis;
    this.sweep = sweep;
    this.t = time ?? 0;
    this.message.hidden = true;
    this.root.querySelector('#gear-title').textContent = scene.title || 'Gear train';
    this.layout();
    this.renderTable();
    this.drawAt(this.t);
    this.solve(seq);
    this.onChange();
    return true;
  }

  async solve(seq) {
    const steps = this.root.querySelector('#gear-steps');
    const mistakes = this.root.querySelector('#gear-mistakes');
    try {
      const [solution] = await Promise.all([api.solution(this.scene, 'vector', 4), katexReady()]);
      if (seq !== this.seq) return;
      renderSolution(steps, mistakes, solution);
      // no typical mistakes listed (a gear train's solution has none): the steps take the width
      this.root.querySelector('.gear-solution .solution').classList.toggle('no-mistakes', !(solution.mistakes || []).length);
    } catch (err) {
      if (seq === this.seq) renderMessage(steps, `No worked solution: ${err.detail || err.message}`);
    }
  }

  // ---- drawing ---------------------------------------------------------------------------------

  /** Members in the drawing: every gear with its pitch circle and centre, each carrier with its
   * planets; trains on one axis that no mesh joins (two stages in series) side by side. */
  layout() {
    const members = this.analysis.members;
    const gears = Object.entries(members).filter(([, m]) => m.type === 'gear');
    const noModule = gears.some(([, m]) => m.pitch_radius === null);
    // Without a module the pitch radii are unknown: draw each gear in proportion to its teeth.
    const radius = (m) => (noModule ? m.teeth : m.pitch_radius);
    const centre = (m, i) => (noModule ? [i * 2.5 * Math.max(...gears.map(([, g]) => g.teeth)), 0] : m.centre);
    // Groups joined by meshes (a planet with its carrier): each stands on its own.
    const group = new Map(Object.keys(members).map((n) => [n, n]));
    const find = (n) => (group.get(n) === n ? n : find(group.get(n)));
    const join = (a, b) => group.set(find(a), find(b));
    for (const mesh of this.analysis.meshes) join(mesh.gears[0], mesh.gears[1]);
    for (const [name, m] of gears) if (m.carrier) join(name, m.carrier);
    const parts = new Map();
    gears.forEach(([name, m], i) => {
      const key = find(name);
      if (!parts.has(key)) parts.set(key, { names: [], box: [Infinity, Infinity, -Infinity, -Infinity], shift: 0 });
      const part = parts.get(key);
      let [x, y] = centre(m, i);
      let r = radius(m) * (m.internal ? 1.18 : 1.12);
      if (m.carrier && !noModule) {
        // a planet sweeps a circle about its carrier's axis: the whole of it stays in view
        const axis = members[m.carrier].centre;
        r += Math.hypot(x - axis[0], y - axis[1]);
        [x, y] = axis;
      }
      part.names.push(name);
      part.box = [Math.min(part.box[0], x - r), Math.min(part.box[1], y - r), Math.max(part.box[2], x + r), Math.max(part.box[3], y + r)];
    });
    let right = -Infinity;
    for (const part of parts.values()) {
      const width = part.box[2] - part.box[0];
      if (part.box[0] < right) part.shift = right + 0.12 * width - part.box[0];
      right = part.box[2] + part.shift;
    }
    const shiftOf = new Map();
    for (const part of parts.values()) for (const n of part.names) shiftOf.set(n, part.shift);
    const all = [...parts.values()];
    const box = [Math.min(...all.map((p) => p.box[0] + p.shift)), Math.min(...all.map((p) => p.box[1])), Math.max(...all.map((p) => p.box[2] + p.shift)), Math.max(...all.map((p) => p.box[3]))];
    // room above and below for the labels (an annulus is labelled under its rim)
    const scale = Math.min((VIEW * 0.92) / (box[2] - box[0]), (VIEW * ASPECT * 0.8) / (box[3] - box[1]));
    const ox = VIEW / 2 - scale * (box[0] + box[2]) / 2;
    const oy = (VIEW * ASPECT) / 2 + scale * (box[1] + box[3]) / 2;
    const px = ([x, y]) => [ox + scale * x, oy - scale * y];
    this.geometry = new Map();
    gears.forEach(([name, m], i) => {
      const [x, y] = centre(m, i);
      this.geometry.set(name, { at: px([x + shiftOf.get(name), y]), r: scale * radius(m), teeth: m.teeth, internal: m.internal, carrier: m.carrier });
    });
    for (const [name, m] of Object.entries(members)) {
      if (m.type !== 'carrier') continue;
      const planets = gears.filter(([, g]) => g.carrier === name).map(([n]) => n);
      const at = planets.length ? this.carrierAxis(planets[0]) : px(noModule ? [0, 0] : m.centre);
      this.geometry.set(name, { at, planets });
    }
    this.build();
  }

  /** A carrier's axis in the drawing: the axis of the fixed gears its planets mesh with. */
  carrierAxis(planet) {
    for (const mesh of this.analysis.meshes) {
      const other = mesh.gears[0] === planet ? mesh.gears[1] : mesh.gears[1] === planet ? mesh.gears[0] : null;
      if (other && !this.analysis.members[other].carrier) return this.geometry.get(other).at;
    }
    return this.geometry.get(planet).at;
  }

  build() {
    const svg = this.svg;
    clear(svg);
    this.labelSize = null;
    svg.setAttribute('viewBox', `0 0 ${VIEW} ${VIEW * ASPECT}`);
    svg.setAttribute('aria-label', `Drawing of the ${this.scene.title || 'gear train'}: pitch circles to scale with teeth marks, carriers as bars`);
    this.nodes = new Map();
    let colour = 0;
    const gearLayer = svgEl('g', { class: 'gears' }, svg);
    const armLayer = svgEl('g', { class: 'carriers' }, svg);
    const labelLayer = svgEl('g', { class: 'gear-labels' }, svg);
    for (const [name, g] of this.geometry) {
      if (g.r === undefined) continue;
      const ink = COLOURS[colour++ % COLOURS.length];
      const body = svgEl('g', { class: 'gear', 'data-member': name }, gearLayer);
      const spin = svgEl('g', {}, body);
      if (g.internal) {
        svgEl('circle', { cx: 0, cy: 0, r: g.r * 1.16, fill: 'none', stroke: ink, 'stroke-width': g.r * 0.12, 'stroke-opacity': 0.25 }, spin);
      } else {
        svgEl('circle', { cx: 0, cy: 0, r: g.r, fill: ink, 'fill-opacity': 0.08 }, spin);
      }
      svgEl('circle', { cx: 0, cy: 0, r: g.r, fill: 'none', stroke: ink, 'stroke-width': 2, 'stroke-dasharray': '6 4' }, spin);
      // Teeth marks: a short radial tick per tooth, outward (inward for an annulus).
      const depth = Math.min(g.r * 0.12, 14) * (g.internal ? -1 : 1);
      let d = '';
      for (let k = 0; k < g.teeth; k += 1) {
        const a = (2 * Math.PI * k) / g.teeth;
        const [c, s] = [Math.cos(a), Math.sin(a)];
        d += `M${(g.r - depth) * c},${-(g.r - depth) * s}L${(g.r + depth) * c},${-(g.r + depth) * s}`;
      }
      svgEl('path', { d, stroke: ink, 'stroke-width': 2, fill: 'none' }, spin);
      // One tooth marked, so the turning reads at a glance.
      const [inner, outer] = g.internal ? [g.r, g.r * 1.16] : [g.r * 0.55, g.r];
      svgEl('line', { x1: inner, y1: 0, x2: outer, y2: 0, stroke: ink, 'stroke-width': 4, 'stroke-linecap': 'round' }, spin);
      svgEl('circle', { cx: 0, cy: 0, r: 5, fill: '#ffffff', stroke: '#222222', 'stroke-width': 2 }, body);
      const label = svgEl('text', { class: 'gear-label', 'text-anchor': 'middle', fill: ink }, labelLayer);
      label.textContent = `${name} (${g.teeth})`;
      this.nodes.set(name, { body, spin, label, g });
    }
    for (const [name, c] of this.geometry) {
      if (!c.planets) continue;
      const arm = svgEl('g', { class: 'carrier', 'data-member': name }, armLayer);
      const bars = c.planets.map(() => svgEl('line', { stroke: '#b5471b', 'stroke-width': 9, 'stroke-linecap': 'round', 'stroke-opacity': 0.85 }, arm));
      svgEl('circle', { cx: c.at[0], cy: c.at[1], r: 9, fill: '#b5471b' }, arm);
      const label = svgEl('text', { class: 'gear-label', 'text-anchor': 'middle', fill: '#b5471b' }, labelLayer);
      label.textContent = name;
      this.nodes.set(name, { arm, bars, c, label });
    }
  }

  /** Each member's angle at display time t (s): the sweep played back, lap after lap. */
  angles(t) {
    const time = this.sweep.time;
    const n = time.length;
    const span = time[n - 1] - time[0];
    const lap = Math.floor(t / span);
    const within = t - lap * span;
    const k = Math.min(n - 2, Math.floor(((n - 1) * within) / span));
    const f = (within - time[k]) / (time[k + 1] - time[k]);
    const out = new Map();
    for (const [name, m] of Object.entries(this.sweep.members)) {
      const a = m.angle;
      out.set(name, lap * a[n - 1] + a[k] + f * (a[k + 1] - a[k]));
    }
    return out;
  }

  drawAt(t) {
    const angle = this.angles(t);
    const deg = (a) => (-a * 180) / Math.PI; // counter-clockwise in the model, y down on screen
    const centreOf = (name) => {
      const { g } = this.nodes.get(name);
      if (!g.carrier) return g.at;
      const axis = this.geometry.get(g.carrier).at;
      const a = angle.get(g.carrier);
      const [dx, dy] = [g.at[0] - axis[0], g.at[1] - axis[1]];
      // turned with the carrier about its axis (screen y points down: the sense flips)
      return [axis[0] + dx * Math.cos(a) + dy * Math.sin(a), axis[1] - dx * Math.sin(a) + dy * Math.cos(a)];
    };
    const wanted = []; // each label with the places it may go, in order of preference
    for (const [name, node] of this.nodes) {
      if (node.g) {
        const [x, y] = centreOf(name);
        node.body.setAttribute('transform', `translate(${x.toFixed(2)},${y.toFixed(2)})`);
        node.spin.setAttribute('transform', `rotate(${deg(angle.get(name)).toFixed(3)})`);
        const r = node.g.r;
        const places = node.g.internal
          ? [[x, y + r * 1.16 + 34], [x, y - r * 1.16 - 14], [x, y + r * 0.92]]
          : [[x, y - r - 22], [x, y + r + 34], [x - r - 12, y + 8, 'end'], [x + r + 12, y + 8, 'start'], [x, y - r * 0.4]];
        wanted.push({ label: node.label, places, fixed: !node.g.carrier });
      } else {
        const places = [];
        node.c.planets.forEach((planet, i) => {
          const [x, y] = centreOf(planet);
          const bar = node.bars[i];
          bar.setAttribute('x1', node.c.at[0].toFixed(2));
          bar.setAttribute('y1', node.c.at[1].toFixed(2));
          bar.setAttribute('x2', x.toFixed(2));
          bar.setAttribute('y2', y.toFixed(2));
          // beside the middle of a bar, either side
          const [mx, my] = [(node.c.at[0] + x) / 2, (node.c.at[1] + y) / 2];
          const length = Math.hypot(x - node.c.at[0], y - node.c.at[1]) || 1;
          const [nx, ny] = [-(y - node.c.at[1]) / length, (x - node.c.at[0]) / length];
          places.push([mx + 26 * nx, my + 26 * ny + 7], [mx - 26 * nx, my - 26 * ny + 7]);
        });
        places.push([node.c.at[0], node.c.at[1] + 34]);
        wanted.push({ label: node.label, places, fixed: false });
      }
    }
    placeLabels(wanted, this.fontSize());
    const slow = this.span / TURN_SECONDS;
    this.readout.textContent = `t = ${fmt(t, 4)} s, shown ${fmt(1 / slow, 3)}× slower than real time`;
  }

  /** The labels' font size in the drawing's units (larger on a phone, css/gears.css). */
  fontSize() {
    if (!this.labelSize) {
      const label = this.svg.querySelector('.gear-label');
      this.labelSize = label ? parseFloat(getComputedStyle(label).fontSize) || 22 : 22;
    }
    return this.labelSize;
  }

  // ---- the table of speeds ---------------------------------------------------------------------

  renderTable() {
    const table = this.table;
    clear(table);
    const first = this.analysis.first_input;
    const unit = unitLabel('omega', this.units);
    table.appendChild(el('caption', {}, `Speeds (${unit}, counter-clockwise positive); train value ω/ω_${first ?? '?'}`));
    const head = el('tr');
    for (const h of ['member', 'teeth', 'ω', 'ω relative to its carrier', 'train value']) head.appendChild(el('th', { scope: 'col' }, h));
    table.appendChild(el('thead')).appendChild(head);
    const body = table.appendChild(el('tbody'));
    const inputs = this.scene.inputs || {};
    for (const [name, m] of Object.entries(this.analysis.members)) {
      const row = el('tr', { 'data-member': name });
      const given = name in inputs ? (inputs[name] === 0 ? ' (fixed)' : ' (input)') : '';
      row.appendChild(el('th', { scope: 'row' }, `${name}${m.type === 'carrier' ? ' (carrier)' : ''}${given}`));
      row.appendChild(el('td', {}, m.type === 'gear' ? `${m.teeth}${m.internal ? ' int.' : ''}` : '–'));
      row.appendChild(el('td', { 'data-omega': String(m.omega) }, fmt(toDisplay('omega', m.omega, this.units))));
      row.appendChild(el('td', {}, m.type === 'gear' && m.carrier ? `${fmt(toDisplay('omega', m.omega_relative, this.units))} (${m.carrier})` : '–'));
      row.appendChild(el('td', {}, m.train_value === null ? '–' : fmt(m.train_value)));
      body.appendChild(row);
    }
    this.root.querySelector('#gear-facts').textContent = `${this.analysis.degrees_of_freedom} degree${this.analysis.degrees_of_freedom === 1 ? '' : 's'} of freedom; ${this.analysis.meshes.length} meshes.`;
  }
}

/**
 * Each label at the first of its places where it overlaps no label placed before it (the fixed
 * gears' first, then the planets' and the carriers'); at its first place when none is free. The
 * box of a label is estimated from its length and the font size, with a margin.
 */
function placeLabels(wanted, size) {
  const placed = [];
  const boxOf = (text, [x, y, anchor = 'middle']) => {
    const w = 0.62 * size * text.length + 6;
    const left = anchor === 'start' ? x : anchor === 'end' ? x - w : x - w / 2;
    return [left, y - 0.95 * size, left + w, y + 0.3 * size];
  };
  const apart = (a, b) => a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
  const order = [...wanted.filter((w) => w.fixed), ...wanted.filter((w) => !w.fixed)];
  for (const { label, places } of order) {
    const text = label.textContent;
    const place = places.find((p) => placed.every((b) => apart(boxOf(text, p), b))) || places[0];
    placed.push(boxOf(text, place));
    label.setAttribute('x', place[0].toFixed(1));
    label.setAttribute('y', place[1].toFixed(1));
    label.setAttribute('text-anchor', place[2] || 'middle');
  }
}
