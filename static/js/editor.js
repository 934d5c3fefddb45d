// editor.js: "New mechanism": draw a planar linkage from scratch and get a scene-v1 document.
//
// Tools: place points (drag to move them), connect points into links (two clicks make a bar,
// further clicks add points to it: a plate), mark fixed pivots, sliders (a pin in a slot) and
// prismatic joints (a block in a guide), each with its axis at the angle given and its guide
// chosen (the ground or any link: a slot in a moving link), and the driver (a link pinned to the
// ground). Points snap to a grid.
// Joints follow from the drawing: a point shared by k links is k − 1 revolute joints (k when it
// is a fixed pivot, pinned to the ground); a slider or prismatic point is that joint between its
// guide and the first of its links that is not the guide (the follower), and revolute joints of
// its other links on the follower. The degrees of freedom are counted by Gruebler's equation
//   F = 3 (n − 1) − 2 j − j₂
// (n links counting the ground, j one-degree joints: revolute and prismatic, j₂ two-degree
// joints: a pin in a slot both slides and turns) and explained until F = 1 and a driver is
// chosen; then the scene goes to the app, which analyses it at once.

import { svgEl, clear, watchTextScale } from './svg.js';
import { COLOURS } from './theme.js';
import { groundLink } from './scene.js';

const $ = (id) => document.getElementById(id);
const WIDTH = 1000;
const HEIGHT = 560;
const GRID = 0.05; // m
const HIT = 14; // px

export class Editor {
  /** @param {{onDone: (scene) => void, onClose: () => void}} callbacks */
  constructor(callbacks) {
    this.callbacks = callbacks;
    this.svg = $('editor');
    this.svg.setAttribute('viewBox', `0 0 ${WIDTH} ${HEIGHT}`);
    watchTextScale(this.svg);
    this.reset();
    this.install();
  }

  reset() {
    this.points = {}; // name -> [x, y] (m)
    this.links = []; // {name, points: []}
    this.ground = new Set();
    this.sliders = new Map(); // point -> {type: 'slider' | 'prismatic', guide: link name, deg: axis angle}
    this.driver = null;
    this.motion = { omega: 10, alpha: 0 }; // the driver's, kept from a loaded scene
    this.pending = []; // points clicked with the link tool, not yet a link
    this.active = null; // the link the next clicked point joins
    this.view = { k: 400, ox: 120, oy: 380 }; // px per m, px of the world origin
  }

  get tool() {
    return document.querySelector('input[name="editor-tool"]:checked')?.value || 'point';
  }

  // ---- opening -------------------------------------------------------------------------------

  open(scene = null) {
    this.reset();
    const refused = scene ? this.load(scene) : '';
    $('editor-panel').hidden = false;
    this.render();
    this.message(refused);
  }

  close() {
    $('editor-panel').hidden = true;
  }

  /** Start from a scene: revolute, slider and prismatic joints (one sliding joint per point).
   *  Returns why not ('' when loaded). */
  load(scene) {
    const ground = groundLink(scene);
    const sliding = (scene.joints || []).filter((j) => j.type !== 'revolute');
    if (sliding.some((j) => !['slider', 'prismatic'].includes(j.type)) || new Set(sliding.map((j) => j.point)).size < sliding.length || scene.moving_points) {
      return 'This mechanism has joints the editor does not draw (moving points, two sliding joints at one point): starting from an empty sheet.';
    }
    this.points = structuredClone(scene.points);
    for (const [name, l] of Object.entries(scene.links)) if (!l.ground) this.links.push({ name, points: [...l.points] });
    for (const j of scene.joints) {
      if (j.type === 'revolute' && j.links.includes(ground)) this.ground.add(j.point);
      const guide = j.links[0] === ground ? 'ground' : j.links[0];
      if (j.type !== 'revolute') this.sliders.set(j.point, { type: j.type, guide, deg: (Math.atan2(j.axis[1], j.axis[0]) * 180) / Math.PI });
    }
    const driver = scene.drivers?.[0];
    this.driver = driver?.link || null;
    if (Number.isFinite(driver?.omega)) this.motion = { omega: driver.omega, alpha: Number.isFinite(driver.alpha) ? driver.alpha : 0 };
    const xs = Object.values(this.points).map((p) => p[0]);
    const ys = Object.values(this.points).map((p) => p[1]);
    const w = Math.max(...xs) - Math.min(...xs) || 1;
    const h = Math.max(...ys) - Math.min(...ys) || 1;
    const k = Math.min((WIDTH - 200) / w, (HEIGHT - 160) / h);
    this.view = { k, ox: 100 - Math.min(...xs) * k, oy: HEIGHT - 80 + Math.min(...ys) * k };
    return '';
  }

  // ---- coordinates ---------------------------------------------------------------------------

  px([x, y]) {
    return [this.view.ox + x * this.view.k, this.view.oy - y * this.view.k];
  }

  world(ev, snap = !ev.shiftKey) {
    const pt = this.svg.createSVGPoint();
    pt.x = ev.clientX;
    pt.y = ev.clientY;
    const q = pt.matrixTransform(this.svg.getScreenCTM().inverse());
    const w = [(q.x - this.view.ox) / this.view.k, (this.view.oy - q.y) / this.view.k];
    return snap ? w.map((v) => Number((Math.round(v / GRID) * GRID).toFixed(6))) : w;
  }

  hitPoint(ev) {
    const pt = this.svg.createSVGPoint();
    pt.x = ev.clientX;
    pt.y = ev.clientY;
    const q = pt.matrixTransform(this.svg.getScreenCTM().inverse());
    let best = null;
    for (const [name, p] of Object.entries(this.points)) {
      const [x, y] = this.px(p);
      const d = Math.hypot(x - q.x, y - q.y);
      if (d < HIT && (!best || d < best.d)) best = { name, d };
    }
    return best?.name ?? null;
  }

  hitLink(ev) {
    const target = ev.target.closest?.('[data-link]');
    return target ? target.dataset.link : null;
  }

  // ---- interaction ---------------------------------------------------------------------------

  install() {
    const svg = this.svg;
    svg.addEventListener('pointerdown', (ev) => {
      ev.preventDefault();
      const tool = this.tool;
      const hit = this.hitPoint(ev);
      if (tool === 'point') {
        if (hit) {
          this.moving = hit;
          svg.setPointerCapture(ev.pointerId);
        } else {
          this.points[this.nextName()] = this.world(ev);
        }
      } else if (tool === 'link') {
        if (!hit) {
          this.pending = [];
          this.active = null;
        } else if (this.active && !this.active.points.includes(hit)) {
          this.active.points.push(hit);
        } else if (!this.active) {
          if (!this.pending.includes(hit)) this.pending.push(hit);
          if (this.pending.length === 2) {
            this.active = { name: this.linkName(this.pending), points: [...this.pending] };
            this.links.push(this.active);
            this.pending = [];
          }
        }
      } else if (tool === 'ground' && hit) {
        this.sliders.delete(hit);
        if (this.ground.has(hit)) this.ground.delete(hit);
        else this.ground.add(hit);
      } else if ((tool === 'slider' || tool === 'prismatic') && hit) {
        this.ground.delete(hit);
        if (this.sliders.get(hit)?.type === tool) this.sliders.delete(hit);
        else this.sliders.set(hit, { type: tool, guide: $('editor-guide').value || 'ground', deg: Number($('editor-axis').value.replace(',', '.')) || 0 });
      } else if (tool === 'driver') {
        const link = this.hitLink(ev);
        if (link) this.driver = this.driver === link ? null : link;
      } else if (tool === 'delete') {
        const link = hit ? null : this.hitLink(ev);
        if (hit) this.removePoint(hit);
        else if (link) {
          this.links = this.links.filter((l) => l.name !== link);
          this.forgetRemovedLinks();
        }
      }
      this.render();
    });
    svg.addEventListener('pointermove', (ev) => {
      if (!this.moving) return;
      this.points[this.moving] = this.world(ev);
      this.render();
    });
    const end = (ev) => {
      if (!this.moving) return;
      this.moving = null;
      if (svg.hasPointerCapture(ev.pointerId)) svg.releasePointerCapture(ev.pointerId);
    };
    svg.addEventListener('pointerup', end);
    svg.addEventListener('pointercancel', end);
    document.addEventListener('keydown', (ev) => {
      if (ev.key !== 'Escape' || $('editor-panel').hidden) return;
      this.pending = [];
      this.active = null;
      this.render();
    });
    for (const r of document.querySelectorAll('input[name="editor-tool"]')) {
      r.addEventListener('change', () => {
        this.pending = [];
        this.active = null;
        this.render();
      });
    }
    $('editor-clear').addEventListener('click', () => {
      this.reset();
      this.render();
    });
    $('editor-cancel').addEventListener('click', () => this.callbacks.onClose());
    $('editor-done').addEventListener('click', () => {
      const { scene, problems } = this.scene();
      if (problems.length) this.message(problems.join(' '));
      else this.callbacks.onDone(scene);
    });
  }

  nextName() {
    for (let i = 0; ; i++) {
      const letter = String.fromCharCode(65 + (i % 26)) + (i >= 26 ? String(Math.floor(i / 26)) : '');
      if (!(letter in this.points)) return letter;
    }
  }

  linkName(points) {
    let name = points.join('');
    for (let i = 2; this.links.some((l) => l.name === name); i++) name = `${points.join('')}${i}`;
    return name;
  }

  removePoint(name) {
    delete this.points[name];
    this.ground.delete(name);
    this.sliders.delete(name);
    for (const l of this.links) l.points = l.points.filter((p) => p !== name);
    this.links = this.links.filter((l) => l.points.length >= 2);
    this.forgetRemovedLinks();
  }

  /** Drop the driver and the sliding joints whose link is gone. */
  forgetRemovedLinks() {
    const names = new Set(this.links.map((l) => l.name));
    if (!names.has(this.driver)) this.driver = null;
    for (const [p, j] of this.sliders) if (j.guide !== 'ground' && !names.has(j.guide)) this.sliders.delete(p);
  }

  // ---- the scene and its degrees of freedom ------------------------------------------------

  joints() {
    const joints = [];
    for (const p of Object.keys(this.points)) {
      const owners = this.links.filter((l) => l.points.includes(p)).map((l) => l.name);
      if (this.ground.has(p)) {
        for (const l of owners) joints.push({ type: 'revolute', point: p, links: ['ground', l] });
      } else if (this.sliders.has(p) && owners.some((l) => l !== this.sliders.get(p).guide)) {
        const { type, guide, deg } = this.sliders.get(p);
        const followers = owners.filter((l) => l !== guide);
        const a = (deg * Math.PI) / 180;
        joints.push({ type, point: p, links: [guide, followers[0]], axis: [Number(Math.cos(a).toFixed(12)), Number(Math.sin(a).toFixed(12))] });
        for (const l of followers.slice(1)) joints.push({ type: 'revolute', point: p, links: [followers[0], l] });
      } else {
        for (const l of owners.slice(1)) joints.push({ type: 'revolute', point: p, links: [owners[0], l] });
      }
    }
    return joints;
  }

  /** Gruebler: F = 3 (n − 1) − 2 j − j₂, with its explanation. */
  freedom() {
    const n = this.links.length + 1;
    const joints = this.joints();
    const j2 = joints.filter((jt) => jt.type === 'slider').length;
    const j = joints.length - j2;
    const f = 3 * (n - 1) - 2 * j - j2;
    let why;
    if (!this.links.length) why = 'Place points, then connect them into links.';
    else if (f === 1) why = 'One degree of freedom: one driver moves the whole mechanism.';
    else if (f <= 0) why = f === 0 ? 'A structure: nothing can move. Remove a link, or free a fixed pivot.' : 'An over-constrained structure: remove links or joints.';
    else why = `${f} degrees of freedom: one driver leaves the rest loose. Add a link between two moving points (each binary link with two new joints removes one), or fix a pivot.`;
    const count = j2
      ? `j = ${j} one-degree joints (revolute, prismatic), j₂ = ${j2} pin${j2 > 1 ? 's' : ''} in a slot (two degrees: it slides and turns), F = 3(n − 1) − 2j − j₂ = 3·${n - 1} − 2·${j} − ${j2}`
      : `j = ${j} joints, F = 3(n − 1) − 2j = 3·${n - 1} − 2·${j}`;
    return { n, j, j2, f, text: `Gruebler: n = ${n} links (with the ground), ${count} = ${f}. ${why}` };
  }

  scene() {
    const problems = [];
    const { f } = this.freedom();
    const loose = Object.keys(this.points).filter((p) => !this.ground.has(p) && !this.links.some((l) => l.points.includes(p)));
    if (loose.length) problems.push(`Points ${loose.join(', ')} belong to no link (connect or delete them).`);
    for (const [p, { guide }] of this.sliders) {
      if (!this.links.some((l) => l.name !== guide && l.points.includes(p))) problems.push(`The sliding point ${p} needs a link of its own besides its guide ${guide} (the pin or block that slides).`);
    }
    if (!this.ground.size) problems.push('Mark at least one fixed pivot (tool "fixed pivot").');
    if (f !== 1) problems.push(`The drawing has F = ${f} degrees of freedom; a mechanism with one driver needs F = 1.`);
    const driver = this.links.find((l) => l.name === this.driver);
    if (!driver) problems.push('Choose the driver: a link pinned to a fixed pivot (tool "driver").');
    else if (!driver.points.some((p) => this.ground.has(p))) problems.push(`The driver ${driver.name} must turn about a fixed pivot.`);
    const links = { ground: { points: [...this.ground], ground: true } };
    for (const l of this.links) links[l.name] = { points: [...l.points] };
    const scene = {
      kind: 'linkage',
      title: $('editor-title').value.trim() || 'my mechanism',
      points: structuredClone(this.points),
      links,
      joints: this.joints(),
      drivers: driver ? [{ link: driver.name, ...this.motion }] : [],
    };
    return { scene, problems };
  }

  message(text) {
    $('editor-message').textContent = text;
    $('editor-message').hidden = !text;
  }

  // ---- drawing -------------------------------------------------------------------------------

  /** The guide choices of the slider and prismatic tools: the ground and every link. */
  renderGuides() {
    const select = $('editor-guide');
    const names = ['ground', ...this.links.map((l) => l.name)];
    if ([...select.options].map((o) => o.value).join('|') === names.join('|')) return;
    const chosen = names.includes(select.value) ? select.value : 'ground';
    select.replaceChildren(...names.map((n) => new Option(n === 'ground' ? 'the ground' : `link ${n}`, n)));
    select.value = chosen;
  }

  render() {
    const svg = this.svg;
    clear(svg);
    svg.setAttribute('viewBox', `0 0 ${WIDTH} ${HEIGHT}`);
    const grid = svgEl('g', { class: 'editor-grid' }, svg);
    const step = GRID * this.view.k;
    if (step > 6) {
      const x0 = this.view.ox % step;
      const y0 = this.view.oy % step;
      for (let x = x0; x < WIDTH; x += step) svgEl('line', { x1: x, y1: 0, x2: x, y2: HEIGHT, stroke: '#eef0f3', 'stroke-width': 1 }, grid);
      for (let y = y0; y < HEIGHT; y += step) svgEl('line', { x1: 0, y1: y, x2: WIDTH, y2: y, stroke: '#eef0f3', 'stroke-width': 1 }, grid);
    }
    svgEl('text', { x: 10, y: HEIGHT - 10, class: 'view-note' }, svg).textContent = `grid ${GRID * 1000} mm (Shift: no snapping)`;
    const colours = ['#3b6ea5', '#2a9d8f', '#c8553d', '#8e5ea2', '#d08c2c', '#5b8c5a'];
    const linkColour = {};
    this.links.forEach((l, i) => {
      const ps = l.points.map((p) => this.px(this.points[p]));
      const colour = colours[i % colours.length];
      linkColour[l.name] = colour;
      const attrs = { stroke: colour, 'data-link': l.name, class: 'editor-link' };
      if (ps.length === 2) svgEl('line', { ...attrs, x1: ps[0][0], y1: ps[0][1], x2: ps[1][0], y2: ps[1][1], 'stroke-width': l.name === this.driver ? 14 : 10, 'stroke-linecap': 'round' }, svg);
      else svgEl('polygon', { ...attrs, points: ps.map((p) => p.join(',')).join(' '), fill: colour, 'fill-opacity': 0.2, 'stroke-width': 5 }, svg);
      const c = ps.reduce((a, p) => [a[0] + p[0] / ps.length, a[1] + p[1] / ps.length], [0, 0]);
      svgEl('text', { x: c[0], y: c[1] - 12, class: 'link-label', fill: colour, 'text-anchor': 'middle' }, svg).textContent = l.name === this.driver ? `${l.name} (driver)` : l.name;
    });
    for (const [name, p] of Object.entries(this.points)) {
      const [x, y] = this.px(p);
      if (this.ground.has(name)) {
        svgEl('path', { d: `M${x},${y} L${x - 13},${y + 20} L${x + 13},${y + 20} Z`, fill: '#eef0f3', stroke: COLOURS.ground, 'stroke-width': 1.5 }, svg);
      }
      if (this.sliders.has(name)) {
        // The axis in the guide's colour (grey: the ground); a pin in a slot is a long block, a
        // prismatic block a square between two guide lines.
        const { type, guide, deg } = this.sliders.get(name);
        const a = (deg * Math.PI) / 180;
        const [dx, dy] = [Math.cos(a) * 60, -Math.sin(a) * 60];
        const [nx, ny] = [-dy / 6, dx / 6];
        const colour = guide === 'ground' ? COLOURS.ground : linkColour[guide];
        const axis = { stroke: colour, 'stroke-width': 2, 'stroke-dasharray': '6 4', class: `editor-${type}`, 'data-guide': guide };
        if (type === 'prismatic') {
          for (const sgn of [1, -1]) svgEl('line', { ...axis, x1: x - dx + sgn * nx, y1: y - dy + sgn * ny, x2: x + dx + sgn * nx, y2: y + dy + sgn * ny }, svg);
        } else svgEl('line', { ...axis, x1: x - dx, y1: y - dy, x2: x + dx, y2: y + dy }, svg);
        const [w, h] = type === 'prismatic' ? [18, 18] : [30, 18];
        svgEl('rect', { x: x - w / 2, y: y - h / 2, width: w, height: h, rx: 3, fill: '#fff', stroke: COLOURS.ink, 'stroke-width': 2, transform: `rotate(${-deg} ${x} ${y})` }, svg);
      }
      const chosen = this.pending.includes(name) || this.active?.points.includes(name);
      svgEl('circle', { cx: x, cy: y, r: 6, fill: chosen ? '#f59e0b' : '#fff', stroke: COLOURS.ink, 'stroke-width': 2.2, 'data-point': name, class: 'editor-point' }, svg);
      svgEl('text', { x: x + 10, y: y - 10, class: 'point-label' }, svg).textContent = name;
    }
    this.renderGuides();
    const dof = this.freedom();
    $('editor-dof').textContent = dof.text;
    $('editor-dof').dataset.f = String(dof.f);
    this.message('');
  }
}
