// cam-view.js: the Cams family (issue 24, docs/CAMS.md) — a disc cam and its follower.
//
// While a cam is chosen in the mechanism menu its section (#cam-app) takes the layout. One
// /sweep of the cam (360 samples, 1 deg apart) gives everything drawn: the profile, the contact
// point, the follower's s, v, a, j, the pressure angle and the radius of curvature. The cam turns
// and the follower moves by playing that sweep back (no request while it plays); the SVAJ
// diagrams, stacked with one cam-angle axis, and the pressure-angle and curvature plots carry a
// cursor at the angle shown, and a click on them picks the angle. The segments are edited in a
// table (law, lift, duration), the cam and follower sizes in fields; an edit asks the server
// again, and a refusal is shown in the server's words with the view left as it was. Paused, the
// worked solution at the angle shown comes from /solution with angle_deg.
//
// The page computes no kinematics: it places the follower on the server's contact point (a
// roller's centre at its radius from it on the follower's axis or arm), as drawing.
//
// The page's units switch (units.js, the linkage view's one conversion) applies to the fields,
// the lifts, the readout, the plots and the CSV of the SVAJ table; the cam angle θ and the
// pressure angle φ stay in degrees (the scene gives the segments in degrees of cam angle). A share
// link (share.js) carries the scene, the preset's name and the view: the angle, playing, units.

import { Playback } from './playback.js';
import * as api from './api.js';
import { svgEl, clear } from './svg.js';
import { plotlyReady } from './vendor.js';
import { renderSolution, renderMessage } from './steps.js';
import { fmt, typed, toDisplay, fromDisplay, unitLabel } from './units.js';
import { toCsv } from './export.js';

const SAMPLES = 360;
const CYCLE_SECONDS = 6; // one revolution at 1x
const SOLUTION_DEBOUNCE_MS = 300;
const CURSOR_MS = 200; // the plots' cursor moves at most this often while the cam plays
const MM = 1000; // the drawing is in millimetres
const COLOURS = { cam: '#1f4e9c', camFill: '#dde6f4', follower: '#b5471b', contact: '#111827', s: '#1f4e9c', v: '#2e7d32', a: '#b5471b', j: '#6a1b9a', phi: '#8d6e00', rho: '#00838f' };

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === false || v === null || v === undefined) continue;
    node.setAttribute(k, v === true ? '' : String(v));
  }
  if (text !== null) node.textContent = text;
  return node;
}

/** A number typed in a field: a decimal comma is a point; null for anything else. */
function parseNumber(text) {
  const t = String(text).trim().replace(',', '.');
  if (!/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t)) return null;
  return Number(t);
}

export class CamApp {
  constructor(root) {
    this.root = root;
    this.shown = false;
    this.presets = new Map();
    this.laws = [];
    this.name = null; // the preset shown (null: a scene from a file)
    this.units = 'si';
    this.onChange = () => {}; // main.js keeps the share link up to date
    this.scene = null;
    this.track = null;
    this.index = 0;
    this.u = 0;
    this.playing = !matchMedia('(prefers-reduced-motion: reduce)').matches;
    // one revolution per CYCLE_SECONDS, drawn at each new sample; the plots' cursor every CURSOR_MS
    this.playback = new Playback(() => this.shown, (dt, now) => {
      if (!this.playing || !this.track) return;
      this.u = (this.u + dt / CYCLE_SECONDS) % 1;
      const index = Math.floor(this.u * SAMPLES) % SAMPLES;
      if (index === this.index) return;
      this.index = index;
      this.draw();
      if (now - this.lastCursor > CURSOR_MS) {
        this.lastCursor = now;
        this.moveCursor();
      }
    });
    this.lastCursor = 0;
    this.seq = 0;
    this.solutionSeq = 0;
    this.solutionTimer = null;
    const $ = (id) => root.querySelector(`#${id}`);
    this.el = {
      description: $('cam-description'), fields: $('cam-fields'), table: $('cam-segments'),
      editMessage: $('cam-edit-message'), drawing: $('cam-drawing'), readout: $('cam-readout'),
      play: $('cam-play'), slider: $('cam-angle'), svaj: $('cam-svaj'), geometry: $('cam-geometry'),
      warnings: $('cam-warnings'), message: $('cam-message'), steps: $('cam-steps'),
      mistakes: $('cam-mistakes'), title: $('cam-title'),
    };
    this.el.play.addEventListener('click', () => this.setPlaying(!this.playing));
    this.el.slider.addEventListener('input', () => {
      this.setPlaying(false);
      this.show(Number(this.el.slider.value));
    });
  }

  /** The Cams group of the mechanism menu (GET /presets?family=cams). */
  async addChoices(select) {
    let body;
    try {
      body = await api.getPresetFamily('cams');
    } catch {
      return; // the linkages work without it
    }
    const group = el('optgroup', { label: 'Cams' });
    for (const p of body.presets || []) {
      this.presets.set(p.name, p);
      group.appendChild(el('option', { value: `cam:${p.name}` }, p.title || p.name));
      const law = (p.parameters || []).find((q) => q.name === 'rise_law');
      if (law?.labels) this.laws = law.labels;
    }
    if (group.children.length) select.appendChild(group);
  }

  async open(name) {
    this.name = name;
    this.shown = true;
    this.playback.start();
    this.root.hidden = false;
    document.body.dataset.family = 'cams';
    const meta = this.presets.get(name);
    this.el.description.textContent = meta?.description || '';
    this.el.title.textContent = meta?.title || 'Cam';
    let scene;
    try {
      scene = await api.presetScene(meta?.scene, name);
    } catch (err) {
      this.say(`The cam ${name} could not be built: ${err.detail}`);
      return;
    }
    this.index = 0;
    this.u = 0;
    this.setPlaying(!matchMedia('(prefers-reduced-motion: reduce)').matches);
    await this.load(scene);
  }

  /** A cam scene from elsewhere (a file, a link) shown at `angle` (deg): true, or the reason it cannot be (also shown). */
  async openScene(scene, source = 'file', angle = 0) {
    this.name = null;
    this.shown = true;
    this.playback.start();
    this.root.hidden = false;
    document.body.dataset.family = 'cams';
    this.el.title.textContent = scene.title || 'Cam';
    this.el.description.textContent = `Opened from ${source}.`;
    this.index = ((angle % SAMPLES) + SAMPLES) % SAMPLES;
    this.u = this.index / SAMPLES;
    if (await this.load(scene)) return true;
    const why = this.el.editMessage.textContent;
    this.say(`This cam cannot be shown: ${why}`);
    return why;
  }

  /** What a share link carries: the scene whole, the preset's name, the angle shown, playing. */
  shareState() {
    return {
      scene: this.scene,
      source: this.name ? { type: 'cam', name: this.name } : { type: 'cam-scene' },
      view: { family: 'cams', angle_deg: this.index, playing: this.playing, units: this.units },
    };
  }

  /** Open a share link's state (shareState): the scene as it was, at its angle. */
  async restore(state) {
    const view = state.view || {};
    this.units = view.units === 'mm' ? 'mm' : 'si';
    this.setPlaying(view.playing === true);
    const meta = state.source?.type === 'cam' ? this.presets.get(state.source.name) : null;
    const ok = await this.openScene(state.scene, 'a link', Number.isInteger(view.angle_deg) ? view.angle_deg : 0);
    if (meta && ok === true) {
      this.name = meta.name;
      this.el.title.textContent = meta.title || this.el.title.textContent;
      this.el.description.textContent = meta.description || '';
    }
    return ok;
  }

  /** The units switch: the fields, the table, the readout and the plots in `units`. */
  async setUnits(units) {
    this.units = units;
    if (!this.track) return;
    this.renderFields();
    this.renderTable();
    this.draw();
    await this.renderPlots();
  }

  /** The follower's quantities' kinds in units.js: a translating follower's or an arm's. */
  kinds() {
    return this.scene.follower.motion === 'oscillating'
      ? { s: 'angle', v: 'omega', a: 'alpha', j: 'angular_jerk' }
      : { s: 'length', v: 'velocity', a: 'acceleration', j: 'jerk' };
  }

  /** The SVAJ table, one row per degree of cam angle, in the units chosen (header with units). */
  svajCsv() {
    const t = this.track;
    const k = this.kinds();
    const u = (kind) => unitLabel(kind, this.units);
    const header = ['cam angle θ [deg]', `s [${u(k.s)}]`, `v [${u(k.v)}]`, `a [${u(k.a)}]`, `j [${u(k.j)}]`, 'pressure angle φ [deg]', `ρ cam [${u('length')}]`];
    if (t.pitch_radius_of_curvature) header.push(`ρ pitch [${u('length')}]`);
    const f = t.follower;
    const rows = t.cam_angle.map((theta, i) => {
      const row = [(theta * 180) / Math.PI, toDisplay(k.s, f.displacement[i], this.units), toDisplay(k.v, f.velocity[i], this.units),
        toDisplay(k.a, f.acceleration[i], this.units), toDisplay(k.j, f.jerk[i], this.units), (t.pressure_angle[i] * 180) / Math.PI,
        toDisplay('length', t.radius_of_curvature[i], this.units)];
      if (t.pitch_radius_of_curvature) row.push(toDisplay('length', t.pitch_radius_of_curvature[i], this.units));
      return row;
    });
    return toCsv([header, ...rows]);
  }

  close() {
    this.shown = false;
    this.root.hidden = true;
    if (document.body.dataset.family === 'cams') delete document.body.dataset.family;
  }

  say(text) {
    this.el.message.textContent = text;
    this.el.message.hidden = !text;
  }

  /** Sweep `scene`; on success it replaces what is shown, else the message says why (true/false). */
  async load(scene) {
    const seq = ++this.seq;
    let track;
    try {
      track = await api.sweep(scene, SAMPLES);
    } catch (err) {
      if (seq === this.seq) this.editError(err.detail || err.message);
      return false;
    }
    if (seq !== this.seq) return false;
    this.scene = scene;
    this.track = track;
    this.editError('');
    this.say('');
    this.renderFields();
    this.renderTable();
    this.renderWarnings();
    this.buildDrawing();
    this.draw();
    await this.renderPlots();
    this.scheduleSolution();
    this.onChange();
    return true;
  }

  editError(text) {
    this.el.editMessage.textContent = text;
    this.el.editMessage.hidden = !text;
  }

  /** A copy of the scene with one change, sent to the server. */
  async edit(change) {
    const copy = structuredClone(this.scene);
    change(copy);
    return this.load(copy);
  }

  // ---- the fields and the segment table --------------------------------------------------------

  renderFields() {
    const box = this.el.fields;
    box.replaceChildren(el('legend', {}, 'Cam and follower'));
    const f = this.scene.follower;
    const rows = [
      ['base_radius', 'Base radius R_b', 'length', this.scene.cam.base_radius, (s, v) => { s.cam.base_radius = v; }],
      ['omega', 'Cam speed ω (ccw +)', 'omega', this.scene.cam.omega, (s, v) => { s.cam.omega = v; }],
    ];
    if ('roller_radius' in f) rows.push(['roller_radius', 'Roller radius r_f', 'length', f.roller_radius, (s, v) => { s.follower.roller_radius = v; }]);
    if (f.motion === 'translating') rows.push(['offset', 'Offset e', 'length', f.offset || 0, (s, v) => { s.follower.offset = v; }]);
    if (f.motion === 'oscillating') {
      rows.push(['pivot_x', 'Pivot x', 'length', f.pivot[0], (s, v) => { s.follower.pivot = [v, s.follower.pivot[1]]; }]);
      rows.push(['pivot_y', 'Pivot y', 'length', f.pivot[1], (s, v) => { s.follower.pivot = [s.follower.pivot[0], v]; }]);
      if ('arm_length' in f) rows.push(['arm_length', 'Arm length l', 'length', f.arm_length, (s, v) => { s.follower.arm_length = v; }]);
    }
    box.appendChild(el('p', { class: 'muted small' }, `${f.motion} follower, ${f.contact} contact`));
    for (const [key, label, kind, value, apply] of rows) {
      const id = `cam-f-${key}`;
      const wrap = el('div', { class: 'field' });
      const lab = el('label', { for: id }, `${label} `);
      lab.appendChild(el('span', { class: 'unit' }, `(${unitLabel(kind, this.units)})`));
      const input = el('input', { id, type: 'text', inputmode: 'decimal', spellcheck: 'false', 'data-key': key, 'data-si': String(value) });
      input.value = this.typed(kind, value);
      input.addEventListener('change', () => this.commit(input, (s, v) => apply(s, fromDisplay(kind, v, this.units))));
      wrap.append(lab, input);
      box.appendChild(wrap);
    }
  }

  /** A value of the scene (SI) as typed in the units chosen (units.typed: the factor's rounding
   *  noise dropped). */
  typed(kind, value) {
    return typed(toDisplay(kind, value, this.units));
  }

  async commit(input, apply) {
    const value = parseNumber(input.value);
    if (value === null) {
      input.setAttribute('aria-invalid', 'true');
      this.editError(`${input.value || 'an empty field'} is not a number.`);
      return;
    }
    const ok = await this.edit((s) => apply(s, value));
    if (ok) input.removeAttribute('aria-invalid');
    else input.setAttribute('aria-invalid', 'true');
  }

  renderTable() {
    const table = this.el.table;
    table.replaceChildren();
    const liftKind = this.kinds().s;
    const unit = unitLabel(liftKind, this.units);
    table.appendChild(el('caption', {}, `Segments from cam angle 0: lift in ${unit}, length in degrees of cam angle (summing to 360°)`));
    const head = el('tr');
    for (const h of ['segment', 'law', 'lift', 'length']) head.appendChild(el('th', { scope: 'col' }, h));
    table.appendChild(head);
    this.scene.segments.forEach((seg, i) => {
      const row = el('tr', { 'data-segment': i });
      row.appendChild(el('th', { scope: 'row', title: `segments[${i}]` }, seg.type));
      const lawCell = el('td');
      if (seg.type === 'dwell') lawCell.textContent = '—';
      else {
        const select = el('select', { 'aria-label': `law of segment ${i}`, 'data-field': 'law' });
        for (const law of this.laws) select.appendChild(el('option', { value: law }, law.replaceAll('_', ' ')));
        select.value = seg.law;
        select.addEventListener('change', () => this.edit((s) => { s.segments[i].law = select.value; }));
        lawCell.appendChild(select);
      }
      row.appendChild(lawCell);
      const liftCell = el('td');
      if (seg.type === 'dwell') liftCell.textContent = '—';
      else {
        // A rise and the return that follows carry the same lift: one edit changes both.
        const input = el('input', { type: 'text', inputmode: 'decimal', 'aria-label': `lift of segment ${i}`, 'data-field': 'lift', size: 7 });
        input.value = this.typed(liftKind, seg.lift);
        input.dataset.si = String(seg.lift);
        input.addEventListener('change', () => this.commitCell(input, (s, v) => {
          const before = s.segments[i].lift;
          const lift = fromDisplay(liftKind, v, this.units);
          for (const other of s.segments) if (other.type !== 'dwell' && other.lift === before) other.lift = lift;
        }));
        liftCell.appendChild(input);
      }
      row.appendChild(liftCell);
      const durationCell = el('td');
      const duration = el('input', { type: 'text', inputmode: 'decimal', 'aria-label': `duration of segment ${i} in degrees`, 'data-field': 'duration_deg', size: 5 });
      duration.value = typed(seg.duration_deg);
      // The last dwell takes up the difference, so that the durations keep summing to 360 deg.
      duration.addEventListener('change', () => this.commitCell(duration, (s, v) => {
        const last = s.segments.length - 1;
        const filler = s.segments[last].type === 'dwell' && i !== last ? last : null;
        if (filler !== null) s.segments[filler].duration_deg += s.segments[i].duration_deg - v;
        s.segments[i].duration_deg = v;
      }));
      durationCell.appendChild(duration);
      row.appendChild(durationCell);
      table.appendChild(row);
    });
  }

  async commitCell(input, apply) {
    const value = parseNumber(input.value);
    if (value === null) {
      input.setAttribute('aria-invalid', 'true');
      this.editError(`${input.value || 'an empty cell'} is not a number.`);
      return;
    }
    const ok = await this.edit((s) => apply(s, value));
    if (!ok) input.setAttribute('aria-invalid', 'true');
  }

  renderWarnings() {
    const list = this.el.warnings;
    list.replaceChildren();
    const warnings = this.track.warnings || [];
    if (!warnings.length) {
      list.appendChild(el('li', { class: 'ok' }, 'No warnings: continuous acceleration, the pressure angle within its limit, no undercutting.'));
      return;
    }
    for (const w of warnings) list.appendChild(el('li', { class: 'warning' }, w));
  }

  // ---- the drawing -------------------------------------------------------------------------------

  /** The extent of everything drawn (m), for the view box. */
  extent() {
    const t = this.track;
    let r = 0;
    for (const [x, y] of t.profile) r = Math.max(r, Math.hypot(x, y));
    const f = this.scene.follower;
    const top = Math.max(...t.follower.displacement.map(Math.abs));
    const roller = f.roller_radius || 0;
    if (f.motion === 'oscillating') {
      r = Math.max(r, Math.hypot(...f.pivot) + (f.arm_length || 0) * 0.2 + 0.01 * r);
      return r * 1.15;
    }
    return Math.max(r, t.diagnostics.prime_radius + top + roller) * 1.35;
  }

  buildDrawing() {
    const svg = this.el.drawing;
    clear(svg);
    const R = this.extent() * MM;
    const f = this.scene.follower;
    const up = f.motion === 'translating' ? 1.6 : 1.0; // room for the follower's stem
    svg.setAttribute('viewBox', `${-R} ${-R * up} ${2 * R} ${R * (1 + up)}`);
    const world = svgEl('g', { transform: 'scale(1,-1)' }, svg);
    this.camGroup = svgEl('g', { class: 'cam' }, world);
    const d = this.track.profile.map(([x, y], k) => `${k ? 'L' : 'M'}${(x * MM).toFixed(3)} ${(y * MM).toFixed(3)}`).join(' ') + 'Z';
    svgEl('path', { d, fill: COLOURS.camFill, stroke: COLOURS.cam, 'stroke-width': R / 250 }, this.camGroup);
    svgEl('circle', { cx: 0, cy: 0, r: this.track.diagnostics.base_radius * MM, fill: 'none', stroke: COLOURS.cam, 'stroke-width': R / 500, 'stroke-dasharray': `${R / 60} ${R / 90}` }, this.camGroup);
    // A mark on the cam, so that its turning is seen (the radius to the profile at angle 0).
    const [px, py] = this.track.profile[0];
    svgEl('line', { x1: 0, y1: 0, x2: px * MM * 0.85, y2: py * MM * 0.85, stroke: COLOURS.cam, 'stroke-width': R / 300 }, this.camGroup);
    svgEl('circle', { cx: 0, cy: 0, r: R / 70, fill: COLOURS.contact }, world);
    const follower = { stroke: COLOURS.follower, 'stroke-width': R / 150, fill: 'none', 'stroke-linecap': 'round' };
    this.stem = svgEl('line', { ...follower, class: 'follower' }, world);
    this.roller = f.contact === 'roller' ? svgEl('circle', { ...follower, class: 'roller', r: f.roller_radius * MM }, world) : null;
    this.face = f.contact === 'flat' ? svgEl('line', { ...follower, class: 'face' }, world) : null;
    if (f.motion === 'oscillating') svgEl('circle', { cx: f.pivot[0] * MM, cy: f.pivot[1] * MM, r: R / 60, fill: COLOURS.follower }, world);
    this.contactDot = svgEl('circle', { r: R / 90, fill: COLOURS.contact, class: 'contact' }, world);
    this.R = R;
  }

  /** The follower's pitch point (roller centre, knife tip) drawn on the server's contact point. */
  pitchPoint(contact) {
    const f = this.scene.follower;
    const [cx, cy] = contact;
    const r = f.roller_radius || 0;
    if (f.contact !== 'roller') return contact;
    if (f.motion === 'translating') {
      const e = f.offset || 0;
      return [e, cy + Math.sqrt(Math.max(r * r - (e - cx) ** 2, 0))];
    }
    // On the arm's circle about the pivot and at r from the contact: the point away from the cam.
    const [ox, oy] = f.pivot;
    const l = f.arm_length;
    const dx = cx - ox, dy = cy - oy;
    const dist = Math.hypot(dx, dy);
    const along = (l * l - r * r + dist * dist) / (2 * dist);
    const h = Math.sqrt(Math.max(l * l - along * along, 0));
    const mx = ox + (along * dx) / dist, my = oy + (along * dy) / dist;
    const a = [mx - (h * dy) / dist, my + (h * dx) / dist];
    const b = [mx + (h * dy) / dist, my - (h * dx) / dist];
    return Math.hypot(...a) > Math.hypot(...b) ? a : b;
  }

  draw() {
    if (!this.track) return;
    const k = this.index;
    const t = this.track;
    const f = this.scene.follower;
    const theta = t.cam_angle[k];
    const turn = (Math.sign(this.scene.cam.omega) * theta * 180) / Math.PI;
    this.camGroup.setAttribute('transform', `rotate(${turn.toFixed(3)})`);
    const contact = t.contact_point[k];
    const p = this.pitchPoint(contact);
    const P = [p[0] * MM, p[1] * MM];
    const C = [contact[0] * MM, contact[1] * MM];
    if (f.motion === 'translating') {
      const top = P[1] + this.R * 0.55;
      // The stem on the follower's axis, from the knife tip, roller centre or face upwards.
      const x = f.contact === 'flat' ? (f.offset || 0) * MM : P[0];
      const from = f.contact === 'flat' ? C[1] : P[1];
      this.stem.setAttribute('x1', x); this.stem.setAttribute('y1', from);
      this.stem.setAttribute('x2', x); this.stem.setAttribute('y2', top);
      if (f.contact === 'flat') {
        this.face.setAttribute('x1', x - this.R * 0.55); this.face.setAttribute('x2', x + this.R * 0.55);
        this.face.setAttribute('y1', C[1]); this.face.setAttribute('y2', C[1]);
      }
    } else {
      const [ox, oy] = f.pivot.map((v) => v * MM);
      const end = f.contact === 'flat' ? [ox + (C[0] - ox) * 1.25, oy + (C[1] - oy) * 1.25] : P;
      this.stem.setAttribute('x1', ox); this.stem.setAttribute('y1', oy);
      this.stem.setAttribute('x2', end[0]); this.stem.setAttribute('y2', end[1]);
      if (this.face) {
        this.face.setAttribute('x1', ox); this.face.setAttribute('y1', oy);
        this.face.setAttribute('x2', end[0]); this.face.setAttribute('y2', end[1]);
      }
    }
    if (this.roller) { this.roller.setAttribute('cx', P[0]); this.roller.setAttribute('cy', P[1]); }
    this.contactDot.setAttribute('cx', C[0]); this.contactDot.setAttribute('cy', C[1]);
    const fol = t.follower;
    const kinds = this.kinds();
    const q = (kind, v) => `${fmt(toDisplay(kind, v, this.units))} ${unitLabel(kind, this.units)}`;
    this.el.readout.textContent = `θ = ${k}°: s = ${q(kinds.s, fol.displacement[k])}, v = ${q(kinds.v, fol.velocity[k])}, a = ${q(kinds.a, fol.acceleration[k])}, φ = ${fmt((t.pressure_angle[k] * 180) / Math.PI, 3)}°`;
    this.el.slider.value = String(k);
  }

  // ---- playing, the angle ---------------------------------------------------------------------

  setPlaying(playing) {
    this.playing = playing;
    this.el.play.textContent = playing ? 'Pause' : 'Play';
    this.el.play.setAttribute('aria-pressed', String(playing));
    if (playing) this.solutionWhilePlaying();
    else {
      this.moveCursor();
      this.scheduleSolution();
    }
    this.onChange();
  }

  show(index) {
    this.index = ((Math.round(index) % SAMPLES) + SAMPLES) % SAMPLES;
    this.u = this.index / SAMPLES;
    this.draw();
    this.moveCursor();
    if (!this.playing) this.scheduleSolution();
    this.onChange();
  }

  // ---- the plots -------------------------------------------------------------------------------

  async renderPlots() {
    const Plotly = await plotlyReady();
    if (!Plotly) {
      this.say('The plotting library could not be loaded: the diagrams are not shown.');
      return;
    }
    const t = this.track;
    const x = t.cam_angle.map((a) => (a * 180) / Math.PI);
    const k = this.kinds();
    const y = (kind, values) => values.map((v) => toDisplay(kind, v, this.units));
    const label = (name, kind) => `${name} (${unitLabel(kind, this.units)})`;
    const rows = [
      ['s', y(k.s, t.follower.displacement), label('s', k.s), COLOURS.s],
      ['v', y(k.v, t.follower.velocity), label('v', k.v), COLOURS.v],
      ['a', y(k.a, t.follower.acceleration), label('a', k.a), COLOURS.a],
      ['j', y(k.j, t.follower.jerk), label('j', k.j), COLOURS.j],
    ];
    await this.stacked(Plotly, this.el.svaj, x, rows, 'SVAJ diagrams');
    const geometry = [
      ['φ', t.pressure_angle.map((p) => (p * 180) / Math.PI), 'φ (°)', COLOURS.phi],
      ['ρ', y('length', t.radius_of_curvature), label('ρ cam', 'length'), COLOURS.rho],
    ];
    if (t.pitch_radius_of_curvature) geometry.push(['ρp', y('length', t.pitch_radius_of_curvature), label('ρ pitch', 'length'), COLOURS.cam]);
    await this.stacked(Plotly, this.el.geometry, x, geometry, 'Pressure angle and radius of curvature');
    this.moveCursor();
  }

  async stacked(Plotly, div, x, rows, title) {
    const n = rows.length;
    const gap = 0.04;
    const height = (1 - gap * (n - 1)) / n;
    const layout = {
      height: 110 * n + 60, margin: { l: 70, r: 12, t: 28, b: 40 }, showlegend: false,
      title: { text: title, font: { size: 13 } }, uirevision: 'cam',
      xaxis: { title: { text: 'cam angle θ (°)' }, range: [0, 360], dtick: 60, anchor: `y${n}` },
      shapes: [],
    };
    const traces = rows.map(([name, y, label, colour], i) => {
      const axis = i ? `yaxis${i + 1}` : 'yaxis';
      const top = 1 - i * (height + gap);
      // Nulls (an exact inflection's infinite radius) and huge radii would flatten the plot.
      layout[axis] = { domain: [top - height, top], title: { text: label, font: { size: 11 } }, zeroline: true };
      return { x, y, name, type: 'scatter', mode: 'lines', line: { color: colour, width: 1.6 }, xaxis: 'x', yaxis: i ? `y${i + 1}` : 'y', hovertemplate: `θ %{x}°: ${name} = %{y:.4g}<extra></extra>` };
    });
    await Plotly.react(div, traces, layout, { displaylogo: false, responsive: true, modeBarButtonsToRemove: ['select2d', 'lasso2d'] });
    div.dataset.rows = String(n);
    if (!div.dataset.wired) {
      div.dataset.wired = 'true';
      div.on('plotly_click', (ev) => {
        const point = ev?.points?.[0];
        if (!point) return;
        this.setPlaying(false);
        this.show(Math.round(point.x));
      });
    }
  }

  moveCursor() {
    const Plotly = globalThis.Plotly;
    if (!Plotly || !this.track) return;
    const angle = this.index;
    for (const div of [this.el.svaj, this.el.geometry]) {
      if (!div.data) continue;
      const shapes = [{ type: 'line', xref: 'x', yref: 'paper', x0: angle, x1: angle, y0: 0, y1: 1, line: { color: '#111827', width: 1, dash: 'dot' } }];
      Plotly.relayout(div, { shapes });
    }
  }

  // ---- the worked solution -----------------------------------------------------------------------

  /** While the cam turns no one angle is shown: the worked solution and its typical mistakes
   * (whose numbers are those of the angle solved) give way to a message until it stops. */
  solutionWhilePlaying() {
    clearTimeout(this.solutionTimer);
    this.solutionSeq += 1; // an answer on its way is for an angle no longer shown
    delete this.el.steps.dataset.angle;
    renderMessage(this.el.steps, 'Pause, or pick an angle, for the worked solution at the angle shown.');
    this.el.mistakes.replaceChildren(el('p', { class: 'muted' }, 'With the worked solution, once paused.'));
  }

  scheduleSolution() {
    clearTimeout(this.solutionTimer);
    if (this.playing || !this.scene) return;
    this.solutionTimer = setTimeout(() => this.requestSolution(), SOLUTION_DEBOUNCE_MS);
  }

  async requestSolution() {
    const seq = ++this.solutionSeq;
    const angle = this.index;
    let body;
    try {
      body = await api.camSolution(this.scene, angle);
    } catch (err) {
      if (seq === this.solutionSeq) renderMessage(this.el.steps, `The worked solution cannot be written: ${err.detail || err.message}`);
      return;
    }
    if (seq !== this.solutionSeq) return;
    this.el.steps.dataset.angle = String(angle);
    renderSolution(this.el.steps, this.el.mistakes, body);
    // A long equation scrolls sideways (on a narrow screen): reachable by the keyboard too.
    for (const math of this.el.steps.querySelectorAll('.step-math')) math.setAttribute('tabindex', '0');
  }
}
