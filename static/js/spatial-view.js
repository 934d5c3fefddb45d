// spatial-view.js: a rotatable axonometric SVG of a spatial chain (kind spatial_chain).
//
// The chain is drawn at one instant (the app moves it over time: spatial-motion.js): joint axes
// (dashed), the bodies as bars from joint to joint and to their points, and the server's velocity
// and acceleration vectors at the points. Each point's circle carries its world position in
// data-position. With an extent (every position over the motion) the frame stays still.
// Dragging (or the arrow keys when the drawing has focus) turns the camera; the projection is
// the only arithmetic here and it is pure drawing.

import { svgEl, clear, arrowMarker, watchTextScale } from './svg.js';
import { COLOURS } from './theme.js';
import { fmt, toDisplay, unitLabel } from './units.js';
import { pointName } from './notation.js';

const W = 1000;
const H = 640;
const PALETTE = ['#3b6ea5', '#2a9d8f', '#c8553d', '#8e5ea2', '#d08c2c', '#5b8c5a'];

export class SpatialView {
  constructor(svg, { onRotate } = {}) {
    this.svg = svg;
    this.onRotate = onRotate;
    this.yaw = -35;
    this.pitch = 22;
    this.options = { showVelocity: true, showAcceleration: false, units: 'si' };
    this.scene = null;
    this.analysis = null;
    this.extent = null;
    svg.setAttribute('viewBox', `0 0 ${W} ${H}`);
    this.installControls();
    watchTextScale(svg);
  }

  setScene(scene) {
    this.scene = scene;
    this.analysis = null;
    this.render();
  }

  /** Every position the chain takes (a list of [x, y, z]), or null: the frame is fitted to it. */
  setExtent(points) {
    this.extent = points;
  }

  setAnalysis(analysis) {
    this.analysis = analysis;
    this.render();
  }

  setOptions(options) {
    this.options = { ...this.options, ...options };
    this.render();
  }

  setCamera(yaw, pitch) {
    this.yaw = yaw;
    this.pitch = Math.max(-89, Math.min(89, pitch));
    this.render();
  }

  /** World (x, y, z up) to screen: turn about z by yaw, tilt by pitch, drop the depth. */
  project(p) {
    const psi = (this.yaw * Math.PI) / 180;
    const th = (this.pitch * Math.PI) / 180;
    const x1 = Math.cos(psi) * p[0] + Math.sin(psi) * p[1];
    const y1 = -Math.sin(psi) * p[0] + Math.cos(psi) * p[1];
    const up = p[2] * Math.cos(th) + y1 * Math.sin(th);
    return [W / 2 + (x1 - this.c[0]) * this.k, H / 2 - (up - this.c[1]) * this.k];
  }

  frameScale() {
    const pts = [[0, 0, 0]];
    if (this.extent) pts.push(...this.extent);
    else {
      for (const j of this.scene.joints || []) pts.push(j.origin);
      for (const p of Object.values(this.scene.points || {})) pts.push(this.positionOf(p));
    }
    const mid = [0, 1, 2].map((i) => (Math.min(...pts.map((p) => p[i])) + Math.max(...pts.map((p) => p[i]))) / 2);
    const radius = Math.max(...pts.map((p) => Math.hypot(p[0] - mid[0], p[1] - mid[1], p[2] - mid[2])), 1e-3);
    this.radius = radius;
    this.k = (Math.min(W, H) / 2 - 30) / radius;
    // Centre the projected middle of the chain.
    this.c = [0, 0];
    const [x, y] = this.project(mid);
    this.c = [(x - W / 2) / this.k, -(y - H / 2) / this.k];
  }

  positionOf(point) {
    return point.position || point;
  }

  render() {
    const svg = this.svg;
    clear(svg);
    if (!this.scene) return;
    this.frameScale();
    const defs = svgEl('defs', {}, svg);
    const marks = {};
    for (const key of ['velocity', 'acceleration']) marks[key] = arrowMarker(defs, `sp-arrow-${key}`, COLOURS[key]);
    const axisMark = arrowMarker(defs, 'sp-arrow-axis', COLOURS.muted, 8);
    svgEl('title', {}, svg).textContent = `${this.scene.title || 'Spatial chain'}: axonometric view (drag or use the arrow keys to turn it)`;

    // World axes at the origin.
    const L = this.radius * 0.35;
    const o = this.project([0, 0, 0]);
    for (const [v, name] of [[[L, 0, 0], 'x'], [[0, L, 0], 'y'], [[0, 0, L], 'z']]) {
      const e = this.project(v);
      svgEl('line', { x1: o[0], y1: o[1], x2: e[0], y2: e[1], stroke: COLOURS.muted, 'stroke-width': 1.2, 'marker-end': axisMark }, svg);
      svgEl('text', { x: e[0] + 6, y: e[1] - 4, class: 'axis-label' }, svg).textContent = name;
    }
    // Ground under the first joint.
    const joints = this.scene.joints || [];
    if (joints.length) {
      const [gx, gy] = this.project(joints[0].origin);
      svgEl('path', { d: `M${gx - 24},${gy + 14} L${gx + 24},${gy + 14}`, stroke: COLOURS.ground, 'stroke-width': 2 }, svg);
      for (let i = -24; i < 24; i += 7) svgEl('line', { x1: gx + i, y1: gy + 14, x2: gx + i - 6, y2: gy + 22, stroke: COLOURS.ground, 'stroke-width': 1.2 }, svg);
    }
    const colourOf = (body) => PALETTE[Math.max(0, joints.findIndex((j) => j.name === body)) % PALETTE.length];
    // Bodies: joint k to joint k+1 (body k carries the next joint's axis), and to its points.
    joints.forEach((j, i) => {
      const a = this.project(j.origin);
      const ends = [];
      if (joints[i + 1]) ends.push(joints[i + 1].origin);
      for (const p of Object.values(this.scene.points || {})) if (p.body === j.name) ends.push(this.positionOf(p));
      for (const end of ends) {
        const b = this.project(end);
        svgEl('line', { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: colourOf(j.name), 'stroke-width': 9, 'stroke-linecap': 'round', class: 'body', 'data-body': j.name }, svg);
      }
    });
    // Joint axes, dashed through each origin, and the joints themselves.
    joints.forEach((j) => {
      const n = Math.hypot(...j.axis) || 1;
      const d = j.axis.map((c) => (c / n) * this.radius * 0.3);
      const a = this.project(j.origin.map((c, i) => c - d[i]));
      const b = this.project(j.origin.map((c, i) => c + d[i]));
      svgEl('line', { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: COLOURS.ink, 'stroke-width': 1.2, 'stroke-dasharray': '7 4', class: 'joint-axis' }, svg);
      const [x, y] = this.project(j.origin);
      if (j.type === 'prismatic') svgEl('rect', { x: x - 7, y: y - 7, width: 14, height: 14, fill: '#ffffff', stroke: COLOURS.ink, 'stroke-width': 2 }, svg);
      else svgEl('circle', { cx: x, cy: y, r: 7, fill: '#ffffff', stroke: COLOURS.ink, 'stroke-width': 2, class: 'joint' }, svg);
      svgEl('text', { x: b[0] + 6, y: b[1] - 6, class: 'joint-label' }, svg).textContent = `axis ${j.name}`;
    });
    // Points, labels and vectors.
    const results = this.analysis?.points || {};
    const max = (q) => Math.max(0, ...Object.values(results).map((r) => (r[q] ? Math.hypot(...r[q]) : 0)));
    const reach = this.radius * 0.45;
    for (const [name, p] of Object.entries(this.scene.points || {})) {
      const pos = results[name]?.position || this.positionOf(p);
      const [x, y] = this.project(pos);
      for (const q of ['velocity', 'acceleration']) {
        const on = q === 'velocity' ? this.options.showVelocity : this.options.showAcceleration;
        const v = results[name]?.[q];
        const m = max(q);
        if (!on || !v || !m || Math.hypot(...v) < 1e-12) continue;
        const tip = this.project(pos.map((c, i) => c + (v[i] / m) * reach));
        svgEl('line', { x1: x, y1: y, x2: tip[0], y2: tip[1], stroke: COLOURS[q], 'stroke-width': 2.6, 'marker-end': marks[q], class: `vector vector-${q}` }, svg);
      }
      svgEl('circle', { cx: x, cy: y, r: 5, fill: COLOURS.ink, class: 'point', 'data-point': name, 'data-position': pos.join(',') }, svg);
      svgEl('text', { x: x + 9, y: y - 9, class: 'point-label' }, svg).textContent = pointName(name);
    }
    svgEl('text', { x: 14, y: H - 14, class: 'view-note' }, svg).textContent =
      `yaw ${Math.round(this.yaw)}°, pitch ${Math.round(this.pitch)}°: drag, or focus and use the arrow keys`;
  }

  /** Text lines for the side panel: angular velocities and accelerations of the bodies. */
  summary() {
    const u = this.options.units;
    const f = (v, kind) => `(${v.map((c) => fmt(toDisplay(kind, c, u))).join(', ')}) ${unitLabel(kind, u)}`;
    const lines = [];
    for (const [name, b] of Object.entries(this.analysis?.bodies || {})) {
      if (b.omega) lines.push(`ω${name} = ${f(b.omega, 'omega')}`);
      if (b.alpha) lines.push(`α${name} = ${f(b.alpha, 'alpha')}`);
    }
    for (const [name, p] of Object.entries(this.analysis?.points || {})) {
      if (p.velocity) lines.push(`v${name} = ${f(p.velocity, 'velocity')}`);
      if (p.acceleration) lines.push(`a${name} = ${f(p.acceleration, 'acceleration')}`);
    }
    return lines;
  }

  installControls() {
    const svg = this.svg;
    let drag = null;
    svg.addEventListener('pointerdown', (ev) => {
      if (!this.scene) return;
      drag = { x: ev.clientX, y: ev.clientY, yaw: this.yaw, pitch: this.pitch };
      svg.setPointerCapture(ev.pointerId);
    });
    svg.addEventListener('pointermove', (ev) => {
      if (!drag) return;
      this.setCamera(drag.yaw - (ev.clientX - drag.x) * 0.4, drag.pitch + (ev.clientY - drag.y) * 0.4);
    });
    const end = () => {
      if (drag) this.onRotate?.(this.yaw, this.pitch);
      drag = null;
    };
    svg.addEventListener('pointerup', end);
    svg.addEventListener('pointercancel', end);
    svg.addEventListener('keydown', (ev) => {
      const step = ev.shiftKey ? 15 : 5;
      const moves = { ArrowLeft: [step, 0], ArrowRight: [-step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
      const m = moves[ev.key];
      if (!m || !this.scene) return;
      ev.preventDefault();
      this.setCamera(this.yaw + m[0], this.pitch + m[1]);
      this.onRotate?.(this.yaw, this.pitch);
    });
  }
}
