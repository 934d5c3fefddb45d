// linkage-view.js: the #linkage SVG of a planar linkage.
//
// Built once per geometry (rebuild) and then only moved (draw): every frame of the animation
// sets a few attributes on existing elements, which is what keeps the page at 60 fps. The view
// draws what it is given (a frame of positions, optionally velocities and accelerations, and the
// server's analysis of the analysed instant); it never computes motion itself.

import { svgEl, setAttrs, clear, arrowMarker, hatchPattern, watchTextScale } from './svg.js';
import { COLOURS } from './theme.js';
import { groundLink, movingLinks, movingPoints, linkColours, driverHandle } from './scene.js';
import { extent, typicalNorm, PARTS, componentSources } from './track.js';
import { show } from './units.js';
import { velocityPoleName, accelerationPoleName, linkNumbers, pointName } from './notation.js';
import { measureLabel, aroundPoint, besideBar, boxAt, markerBox, placeAll } from './drawing-labels.js';
import { drawCentres } from './instant-centres.js';

const WIDTH = 1000;
const MARGIN = 70;
const BLOCK = [30, 18]; // slider block, px along and across the slot
const ZOOM = [0.25, 40]; // the least and the greatest zoom over the fitted drawing
export const ZOOM_STEP = 1.25; // one press of + or −
const PAN_STEP = 60; // viewBox px panned by an arrow key
const CLICK = 4; // px a press may move and still be a click (a tap on a point)

/**
 * How the drawing fits a track into the viewBox, WIDTH wide: its box (the extent of every position
 * plus 12% room for arrows and labels), k in viewBox px per metre, the offsets that centre it.
 */
function fitDrawing(track) {
  const [x0, y0, x1, y1] = extent(track);
  const dx = Math.max(x1 - x0, 1e-6);
  const dy = Math.max(y1 - y0, 1e-6);
  const size = Math.max(dx, dy);
  // Room for arrows and labels around the mechanism.
  const pad = size * 0.12;
  const box = [x0 - pad, y0 - pad, x1 + pad, y1 + pad];
  const w = box[2] - box[0];
  const h = box[3] - box[1];
  const height = Math.min(Math.max((WIDTH * h) / w, WIDTH * 0.5), WIDTH * 0.9);
  const k = Math.min((WIDTH - 2 * MARGIN) / w, (height - 2 * MARGIN) / h);
  // Centre the drawing in the viewBox.
  const ox = (WIDTH - k * w) / 2;
  const oy = (height - k * h) / 2;
  return { box, k, ox, oy, height, size };
}

export class LinkageView {
  /**
   * @param {SVGSVGElement} svg
   * @param {{onDrag?: (linkAngle: number) => void, onDragEnd?: () => void}} callbacks; also
   *   onPointDrop, onPointPick, onPointHover and onLinkPick(link, at, frame): a click on a link's
   *   bar or plate (not the driver's) at world point `at` of the frame shown
   */
  constructor(svg, callbacks = {}) {
    this.svg = svg;
    this.editable = false; // joints can be dragged (set by main.js for scenes without time laws)
    // Turn (the default: pressing anywhere on the driver turns it) or Edit (joints move).
    this.mode = 'turn';
    this.pointDrag = null; // {name, pointerId, moved} while a joint is dragged
    this.callbacks = callbacks;
    this.options = { showVelocity: true, showAcceleration: false, showPoles: true, showCentres: false, kennedy: null, trace: null, units: 'si' };
    this.scene = null;
    this.track = null;
    this.analysis = null;
    this.lastFrame = null;
    this.dragging = false;
    // Zoom and pan: the scale over the fitted drawing and the world point (m) at the centre of
    // the picture (null: the fitted drawing's centre). Kept across frames, options, analyses and
    // edits of the same mechanism; a mechanism with other points starts fitted.
    this.view = { scale: 1, centre: null };
    this.pan = null; // {pointers: Map(id -> viewBox point)} while panning or pinching
    // Paths traced besides the one of the options (point-readout.js adds and removes them), and
    // the point whose readout is shown (ringed in the drawing).
    this.traces = [];
    this.picked = null;
    this.afterDraw = []; // functions of the frame, called after each frame is drawn
    // Boxes (viewBox px) its owner draws over the linkage (the designer's handles): the names of
    // points and links are placed clear of them too.
    this.overlayMarks = [];
    this.noteMarks = []; // the boxes of the notes' lines and scale bars (viewBox px)
    this.installPointer();
    this.installZoom();
    // A new size of the names (the drawing drawn at another width): every name measured again
    // and placed anew; what the owner draws over the linkage (the designer's handles) stays.
    this.textScale = watchTextScale(svg, () => {
      if (!this.layers) return;
      for (const label of this.labelNodes) label.size = measureLabel(label.node);
      this.rebuildVectors();
      if (this.lastFrame) this.draw(this.lastFrame);
    });
  }

  /**
   * A scene and its track to draw. The zoom, the paths and the picked point are kept for the same
   * mechanism (the same point names, or `sameMechanism`: a point added to or removed from it).
   */
  setScene(scene, track, { sameMechanism = false } = {}) {
    const names = Object.keys(scene.points);
    const same = this.scene && (sameMechanism || sameNames(Object.keys(this.scene.points), names));
    if (!same) {
      this.view = { scale: 1, centre: null };
      this.traces = [];
      this.picked = null;
    } else {
      this.traces = this.traces.filter((n) => names.includes(n));
      if (!names.includes(this.picked)) this.picked = null;
    }
    this.scene = scene;
    this.track = track;
    this.analysis = null;
    this.rebuild();
  }

  setOptions(options) {
    this.options = { ...this.options, ...options };
    if (this.scene) {
      this.rebuild();
      if (this.lastFrame) this.draw(this.lastFrame);
    }
  }

  /** The paths traced besides the options' one (names of points), drawn from the sweep. */
  setTraces(names) {
    this.traces = [...names];
    this.redraw();
  }

  /** The point whose readout is shown, ringed in the drawing (null: none). */
  setPicked(name) {
    this.picked = name;
    this.redraw();
  }

  /** 'turn' or 'edit': what a press in the drawing does (the toggle above the drawing). */
  setMode(mode) {
    this.mode = mode === 'edit' ? 'edit' : 'turn';
    this.svg.dataset.mode = this.mode;
    if (this.scene) {
      this.rebuild();
      if (this.lastFrame) this.draw(this.lastFrame);
    }
  }

  /** Joints move: Edit mode, on a scene that can be edited by dragging. */
  movesJoints() {
    return this.editable && this.mode === 'edit';
  }

  /** The server's answer for the analysed instant (poles, slider parts); null while playing. */
  setAnalysis(analysis) {
    this.analysis = analysis;
    if (this.scene) {
      this.rebuildVectors();
      if (this.lastFrame) this.draw(this.lastFrame);
    }
  }

  // ---- geometry of the picture -------------------------------------------------------------

  /**
   * Screen pixels per metre of the drawing of `track`: the SVG is as wide as its box and as tall
   * as the viewBox's proportions allow within its max-height (viewBox px where it is hidden).
   */
  pixelsPerMetre(track) {
    const fit = fitDrawing(track);
    const width = this.svg.getBoundingClientRect().width;
    const tallest = parseFloat(getComputedStyle(this.svg).maxHeight) || Infinity;
    return width ? fit.k * Math.min(width / WIDTH, tallest / fit.height) : fit.k;
  }

  /**
   * The map from the world to the viewBox: the fitted drawing (fitDrawing) zoomed by view.scale
   * about view.centre, the world point drawn at the middle of the picture. Zooming changes the
   * map, not the SVG's viewBox, so lines, markers and names keep their size.
   */
  computeBox() {
    const fit = fitDrawing(this.track);
    const { scale, centre } = this.view;
    const k = fit.k * scale;
    const c = centre || [(fit.box[0] + fit.box[2]) / 2, (fit.box[1] + fit.box[3]) / 2];
    this.map = { ...fit, k, ox: WIDTH / 2 - (c[0] - fit.box[0]) * k, oy: fit.height / 2 - (c[1] - fit.box[1]) * k };
    this.svg.setAttribute('viewBox', `0 0 ${WIDTH} ${Math.round(this.map.height)}`);
    this.textScale(false); // the names built next take the size for this viewBox
    this.svg.dataset.zoom = String(Number(scale.toFixed(4)));
  }

  // ---- zoom and pan ----------------------------------------------------------------------------

  /** Zoom by `factor` about the viewBox point `at` (the middle by default), which stays put. */
  zoomBy(factor, at = null) {
    if (!this.map) return;
    const q = at || [WIDTH / 2, this.map.height / 2];
    const w = this.world(q[0], q[1]);
    const scale = Math.min(Math.max(this.view.scale * factor, ZOOM[0]), ZOOM[1]);
    const k = (this.map.k / this.view.scale) * scale;
    this.view = { scale, centre: [w[0] - (q[0] - WIDTH / 2) / k, w[1] + (q[1] - this.map.height / 2) / k] };
    this.redraw();
  }

  /** Move the picture by (dx, dy) viewBox px (the drawing follows the hand). */
  panBy(dx, dy) {
    if (!this.map) return;
    this.view = { ...this.view, centre: this.world(WIDTH / 2 - dx, this.map.height / 2 - dy) };
    this.redraw();
  }

  /** Back to the whole mechanism, fitted to the picture (the Fit button, the key 0). */
  fit() {
    this.view = { scale: 1, centre: null };
    this.redraw();
  }

  /** Rebuild at the current map and draw the last frame again. */
  redraw() {
    if (!this.scene) return;
    this.rebuild();
    if (this.lastFrame) this.draw(this.lastFrame);
  }

  /** A pointer event's position in viewBox px. */
  viewBoxPoint(ev) {
    const pt = this.svg.createSVGPoint();
    pt.x = ev.clientX;
    pt.y = ev.clientY;
    const q = pt.matrixTransform(this.svg.getScreenCTM().inverse());
    return [q.x, q.y];
  }

  /**
   * The wheel zooms about the pointer; with the drawing focused, + and − zoom, 0 fits and the
   * arrow keys pan (the buttons and the global keys are wired by main.js to zoomBy and fit).
   */
  installZoom() {
    const svg = this.svg;
    svg.addEventListener('wheel', (ev) => {
      if (!this.scene) return;
      ev.preventDefault();
      const lines = ev.deltaMode === 1 ? 16 : ev.deltaMode === 2 ? 400 : 1;
      this.zoomBy(Math.exp(-ev.deltaY * lines * 0.002), this.viewBoxPoint(ev));
    }, { passive: false });
    svg.addEventListener('keydown', (ev) => {
      const pan = { ArrowLeft: [PAN_STEP, 0], ArrowRight: [-PAN_STEP, 0], ArrowUp: [0, PAN_STEP], ArrowDown: [0, -PAN_STEP] }[ev.key];
      // a key a handle inside the drawing used (the designer's positions) does not pan
      if (!pan || ev.defaultPrevented || ev.ctrlKey || ev.metaKey || ev.altKey) return;
      ev.preventDefault();
      this.panBy(pan[0], pan[1]);
    });
  }

  /** World (m, y up) to viewBox (px, y down). */
  px(p) {
    const { box, k, ox, oy, height } = this.map;
    return [ox + (p[0] - box[0]) * k, height - (oy + (p[1] - box[1]) * k)];
  }

  world(x, y) {
    const { box, k, ox, oy, height } = this.map;
    return [(x - ox) / k + box[0], (height - y - oy) / k + box[1]];
  }

  inView(p) {
    const [x, y] = this.px(p);
    // Keep a marker and its label clear of the border.
    return x >= 24 && x <= WIDTH - 60 && y >= 24 && y <= this.map.height - 24;
  }

  // ---- building ----------------------------------------------------------------------------

  rebuild() {
    const svg = this.svg;
    clear(svg);
    this.computeBox();
    const scene = this.scene;
    const colours = linkColours(scene);
    this.colours = colours;

    const defs = svgEl('defs', {}, svg);
    this.hatch = hatchPattern(defs, 'lk-hatch', COLOURS.ground);
    this.markers = {};
    for (const key of ['velocity', 'acceleration', 'transport', 'relative', 'coriolis', 'normal', 'tangential']) {
      this.markers[key] = arrowMarker(defs, `lk-arrow-${key}`, COLOURS[key]);
    }
    svgEl('title', {}, svg).textContent = `${scene.title || 'Mechanism'}: drawing of the linkage`;

    this.layers = {};
    // The crank's handle ring lies under the joints: the ring turns the crank, a joint's own
    // circle moves the joint (editing the geometry).
    for (const name of ['ground', 'trace', 'paths', 'links', 'slots', 'blocks', 'handle', 'joints', 'pick', 'vectors', 'centres', 'poles', 'labels', 'notes']) {
      this.layers[name] = svgEl('g', { class: `layer-${name}` }, svg);
    }
    this.buildGround();
    this.buildTrace();
    this.buildPaths();
    this.buildLinks();
    this.buildJoints();
    this.buildLabels();
    this.buildHandle();
    this.rebuildVectors();
  }

  buildGround() {
    const scene = this.scene;
    const g = this.layers.ground;
    const ground = groundLink(scene);
    const gpts = scene.links[ground]?.points || [];
    // What the names must not cover: the pivots' triangles and hatching, the guides' axes.
    this.fixedMarks = [];
    this.fixedBars = [];
    // The frame line between ground points, dashed: it is the fixed link, not a bar.
    for (let i = 0; i + 1 < gpts.length; i++) {
      const [a, b] = [this.px(scene.points[gpts[i]]), this.px(scene.points[gpts[i + 1]])];
      svgEl('line', { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: COLOURS.ground, 'stroke-width': 1.5, 'stroke-dasharray': '6 5', class: 'frame-line' }, g);
    }
    for (const j of scene.joints || []) {
      if (j.type === 'revolute' && j.links.includes(ground)) this.drawPivot(g, this.px(scene.points[j.point]));
      if ((j.type === 'slider' || j.type === 'prismatic') && j.links[0] === ground) this.drawFixedGuide(g, j);
    }
  }

  drawPivot(g, [x, y]) {
    this.fixedMarks.push({ x0: x - 20, x1: x + 20, y0: y, y1: y + 28 });
    svgEl('path', { d: `M${x},${y} L${x - 13},${y + 20} L${x + 13},${y + 20} Z`, fill: '#eef0f3', stroke: COLOURS.ground, 'stroke-width': 1.5, class: 'ground-pivot' }, g);
    svgEl('rect', { x: x - 20, y: y + 20, width: 40, height: 8, fill: this.hatch, stroke: 'none', class: 'ground-hatch' }, g);
    svgEl('line', { x1: x - 20, y1: y + 20, x2: x + 20, y2: y + 20, stroke: COLOURS.ground, 'stroke-width': 1.5 }, g);
  }

  /** A straight guide fixed in the ground, drawn along the slot axis over the swept range (the
   * slider's displacement from its drawn position, as the server sent it). */
  drawFixedGuide(g, joint) {
    const axis = unit(joint.axis || [1, 0]);
    const base = this.scene.points[joint.point];
    const travel = (this.track.sliders || []).find((s) => s.point === joint.point)?.displacement || [0];
    const lo = travel.reduce((m, s) => Math.min(m, s), Infinity);
    const hi = travel.reduce((m, s) => Math.max(m, s), -Infinity);
    const pad = (BLOCK[0] / this.map.k) * 1.2;
    const a = this.px([base[0] + (lo - pad) * axis[0], base[1] + (lo - pad) * axis[1]]);
    const b = this.px([base[0] + (hi + pad) * axis[0], base[1] + (hi + pad) * axis[1]]);
    this.fixedBars.push([a, b]);
    const d = unit([b[0] - a[0], b[1] - a[1]]);
    const n = [-d[1], d[0]];
    const h = BLOCK[1] / 2 + 1.5;
    // Two walls of the slot; hatching behind the lower one (the side of the "ground").
    for (const s of [h, -h]) {
      svgEl('line', { x1: a[0] + n[0] * s, y1: a[1] + n[1] * s, x2: b[0] + n[0] * s, y2: b[1] + n[1] * s, stroke: COLOURS.ground, 'stroke-width': 1.5, class: 'guide' }, g);
    }
    const s1 = h;
    const s2 = h + 8;
    const poly = [
      [a[0] + n[0] * s1, a[1] + n[1] * s1],
      [b[0] + n[0] * s1, b[1] + n[1] * s1],
      [b[0] + n[0] * s2, b[1] + n[1] * s2],
      [a[0] + n[0] * s2, a[1] + n[1] * s2],
    ];
    svgEl('polygon', { points: poly.map((p) => p.join(',')).join(' '), fill: this.hatch, stroke: 'none', class: 'guide-hatch' }, g);
  }

  /**
   * The paths of the traced points over the sweep already fetched (no request): the options'
   * point dashed in the trace colour, each added one (a click on a point, point-readout.js) in
   * its own colour, solid.
   */
  buildTrace() {
    const names = [this.options.trace, ...this.traces.filter((n) => n !== this.options.trace)];
    names.forEach((name, i) => {
      const positions = name && this.track.points[name]?.position;
      if (!positions || positions.length < 2) return;
      const pts = positions.filter(Boolean).map((p) => this.px(p).join(',')).join(' ');
      const extra = i > 0;
      svgEl('polyline', {
        points: pts, fill: 'none', stroke: extra ? traceColour(i - 1) : COLOURS.trace, 'stroke-width': 1.8,
        'stroke-dasharray': extra ? null : '5 4', class: extra ? 'coupler-curve added-trace' : 'coupler-curve', 'data-trace': name,
      }, this.layers.trace);
    });
    this.pickNode = this.picked ? svgEl('circle', { r: 12, fill: 'none', stroke: COLOURS.trace, 'stroke-width': 2.5, class: 'picked-point', 'pointer-events': 'none' }, this.layers.pick) : null;
  }

  buildPaths() {
    // The groove of a moving point, fixed in its link: redrawn each frame where the link is.
    // Drawn as a slot cut in the link (a wide band in the link's colour with a white channel),
    // so that it reads as a groove and not as the dashed path a point traces.
    this.paths = movingPoints(this.scene).map((m) => {
      const tag = m.path?.type === 'arc' ? 'circle' : 'line';
      const colour = this.colours[m.link] || COLOURS.ink;
      const band = svgEl(tag, { fill: 'none', stroke: colour, 'stroke-width': 11, 'stroke-linecap': 'round', class: 'groove' }, this.layers.paths);
      const channel = svgEl(tag, { fill: 'none', stroke: '#ffffff', 'stroke-width': 5, 'stroke-linecap': 'round', class: 'groove-channel' }, this.layers.paths);
      return { m, nodes: [band, channel] };
    });
  }

  buildLinks() {
    const scene = this.scene;
    this.linkNodes = [];
    for (const name of movingLinks(scene)) {
      const pts = scene.links[name].points;
      const colour = this.colours[name];
      if (pts.length === 2) {
        const outer = svgEl('line', { stroke: colour, 'stroke-width': 11, 'stroke-linecap': 'round', class: 'link', 'data-link': name }, this.layers.links);
        const inner = svgEl('line', { stroke: '#ffffff', 'stroke-opacity': 0.35, 'stroke-width': 3, 'stroke-linecap': 'round', 'pointer-events': 'none' }, this.layers.links);
        this.linkNodes.push({ name, pts, kind: 'bar', nodes: [outer, inner] });
      } else if (this.isDisc(name)) {
        // A turning link that carries a circular groove is a disc about its pivot.
        const disc = svgEl('circle', { fill: colour, 'fill-opacity': 0.16, stroke: colour, 'stroke-width': 3, class: 'link disc', 'data-link': name }, this.layers.links);
        // The link's points joined on the disc: they show it turning.
        const marks = svgEl('polygon', { fill: 'none', stroke: colour, 'stroke-opacity': 0.6, 'stroke-width': 2, 'stroke-dasharray': '2 3', class: 'disc-marks' }, this.layers.links);
        this.linkNodes.push({ name, pts, kind: 'disc', nodes: [disc, marks] });
      } else if (pts.length > 2) {
        const poly = svgEl('polygon', { fill: colour, 'fill-opacity': 0.22, stroke: colour, 'stroke-width': 5, 'stroke-linejoin': 'round', class: 'link', 'data-link': name }, this.layers.links);
        this.linkNodes.push({ name, pts, kind: 'plate', nodes: [poly] });
      }
    }
    // Slots in moving guides and blocks of sliders.
    this.slotNodes = [];
    this.blockNodes = [];
    const ground = groundLink(scene);
    for (const j of scene.joints || []) {
      if (j.type !== 'slider' && j.type !== 'prismatic') continue;
      const [guide, follower] = j.links;
      if (guide !== ground) {
        // A slotted bar along the axis, as long as the guide link and the block's travel.
        const bar = svgEl('line', { stroke: this.colours[guide], 'stroke-width': 13, 'stroke-linecap': 'round', class: 'slot-bar' }, this.layers.slots);
        const slot = svgEl('line', { stroke: '#ffffff', 'stroke-width': 5, 'stroke-linecap': 'round', class: 'slot' }, this.layers.slots);
        this.slotNodes.push({ joint: j, guide, nodes: [bar, slot] });
      }
      const colour = this.colours[follower] || COLOURS.ink;
      const rect = svgEl('rect', { width: BLOCK[0], height: BLOCK[1], x: -BLOCK[0] / 2, y: -BLOCK[1] / 2, rx: 3, fill: '#ffffff', stroke: colour, 'stroke-width': 2.5, class: 'slider-block' }, this.layers.blocks);
      this.blockNodes.push({ joint: j, guide, node: rect });
    }
  }

  buildJoints() {
    const scene = this.scene;
    this.jointNodes = [];
    const jointPoints = new Set((scene.joints || []).filter((j) => j.type === 'revolute').map((j) => j.point));
    const sliderPoints = new Set((scene.joints || []).filter((j) => j.type !== 'revolute').map((j) => j.point));
    for (const name of Object.keys(scene.points)) {
      const isJoint = jointPoints.has(name);
      const node = svgEl('circle', {
        r: isJoint ? 5.5 : sliderPoints.has(name) ? 3.5 : 3.5,
        fill: isJoint ? '#ffffff' : COLOURS.ink,
        stroke: COLOURS.ink,
        'stroke-width': isJoint ? 2.2 : 1,
        class: isJoint ? 'joint' : 'point',
        'data-point': name,
      }, this.layers.joints);
      if (this.movesJoints()) svgEl('title', {}, node).textContent = `Drag ${name} to change the geometry (Shift: no snapping)`;
      this.jointNodes.push({ name, node });
    }
    for (const m of movingPoints(scene)) {
      const node = svgEl('circle', { r: 7, fill: COLOURS.trace, stroke: '#ffffff', 'stroke-width': 2, class: 'moving-point' }, this.layers.joints);
      this.jointNodes.push({ name: m.name, node });
    }
  }

  /**
   * The names of the points, then of the moving links (with the number that names their poles,
   * I₁₃, Γ₁₃), centred where drawing-labels.js places them each frame.
   */
  buildLabels() {
    this.labelNodes = [];
    const add = (text, attrs, named) => {
      const node = svgEl('text', { 'text-anchor': 'middle', 'dominant-baseline': 'central', ...attrs }, this.layers.labels);
      node.textContent = text;
      this.labelNodes.push({ ...named, node, size: measureLabel(node), last: -1 });
    };
    for (const name of [...Object.keys(this.scene.points), ...movingPoints(this.scene).map((m) => m.name)]) {
      add(pointName(name), { class: 'point-label' }, { point: name });
    }
    const numbers = linkNumbers(this.scene);
    for (const name of movingLinks(this.scene)) {
      add(`${name} (${numbers[name]})`, { class: 'link-label', fill: this.colours[name] }, { link: name });
    }
  }

  buildHandle() {
    this.handle = null;
    if (this.track.param !== 'angle' || this.track.n < 2) return;
    const h = driverHandle(this.scene);
    if (!h) return;
    const node = svgEl('circle', { r: 17, fill: 'transparent', stroke: COLOURS.ink, 'stroke-opacity': 0.35, 'stroke-width': 1.5, 'stroke-dasharray': '3 3', class: 'crank-handle' }, this.layers.handle);
    svgEl('title', {}, node).textContent = 'Drag to turn the crank (or use the crank-angle slider)';
    this.handle = { ...h, node };
  }

  /** Vectors and poles: rebuilt when the analysis or the options change, moved per frame. */
  rebuildVectors() {
    clear(this.layers.vectors);
    clear(this.layers.poles);
    clear(this.layers.centres);
    clear(this.layers.notes);
    this.vectorNodes = [];
    const opt = this.options;
    const names = [...Object.keys(this.scene.points), ...movingPoints(this.scene).map((m) => m.name)];
    // One scale per cycle, so arrows can be compared between instants: a typical large vector of
    // the sweep is a fifth of the picture (the analysis alone when there is no sweep).
    const vmax = typicalNorm(this.track, 'velocity') || analysisMax(this.analysis, 'velocity');
    const amax = typicalNorm(this.track, 'acceleration') || analysisMax(this.analysis, 'acceleration');
    const reach = this.map.size * 0.22;
    this.scale = { velocity: vmax > 0 ? reach / vmax : 0, acceleration: amax > 0 ? reach / amax : 0 };
    const add = (kind, quantity, point, extra = {}) => {
      const node = svgEl('line', { stroke: COLOURS[kind], 'stroke-width': extra.width || 2.6, 'marker-end': this.markers[kind], 'stroke-dasharray': extra.dash || null, class: `vector vector-${kind}` }, this.layers.vectors);
      this.vectorNodes.push({ kind, quantity, point, node });
    };
    if (opt.showVelocity) for (const n of names) add('velocity', 'velocity', n);
    if (opt.showAcceleration) for (const n of names) add('acceleration', 'acceleration', n);

    // Transport, relative and Coriolis parts at sliders and moving points: from the analysis at
    // the analysed instant, and from the sweep while a relative-motion scene plays.
    const partPoints = new Set();
    if (this.analysis) for (const p of componentSources(this.analysis)) partPoints.add(p.point);
    for (const [name, q] of Object.entries(this.track.points)) if (PARTS.some((k) => Array.isArray(q[k]))) partPoints.add(name);
    for (const point of partPoints) {
      if (opt.showVelocity) {
        add('transport', { part: 'transport_velocity', from: [] }, point, { width: 2, dash: '5 3' });
        add('relative', { part: 'relative_velocity', from: ['transport_velocity'] }, point, { width: 2 });
      }
      if (opt.showAcceleration) {
        add('transport', { part: 'transport_acceleration', from: [], accel: true }, point, { width: 2, dash: '5 3' });
        add('coriolis', { part: 'coriolis_acceleration', from: ['transport_acceleration'], accel: true }, point, { width: 2 });
        add('relative', { part: 'relative_acceleration', from: ['transport_acceleration', 'coriolis_acceleration'], accel: true }, point, { width: 2 });
      }
    }
    const notes = [];
    this.poleMarks = [];
    this.poleLabels = [];
    if (this.analysis && opt.showPoles) notes.push(...this.buildPoles());
    if (this.analysis && opt.showCentres) {
      const joints = [];
      for (const group of [this.analysis.points, this.analysis.moving_points]) {
        for (const q of Object.values(group || {})) if (q.position) joints.push(markerBox(this.px(q.position), 8));
      }
      const centres = drawCentres(this, this.layers.centres, this.analysis, opt.kennedy, [...this.fixedMarks, ...this.poleMarks, ...joints], opt.showPoles);
      notes.push(...centres.notes);
      this.poleMarks.push(...centres.marks);
    }
    this.buildNotes(notes);
    // The poles' names last: clear of the centres' and of the notes' lines too.
    this.placePoleLabels(this.poleLabels);
  }

  buildPoles() {
    const offView = [];
    // A link turning about a fixed pivot has both poles there; marking them only hides the pivot.
    const atFixed = (p) => this.isGroundPoint(p);
    const colourOf = (link) => this.colours[link] || COLOURS.pole;
    const labels = [];
    for (const [name, l] of Object.entries(this.analysis.links || {})) {
      for (const [key, naming, shape] of [['velocity_pole', velocityPoleName, 'circle'], ['acceleration_pole', accelerationPoleName, 'diamond']]) {
        const p = l[key];
        if (!p || atFixed(p)) continue;
        const label = naming(this.scene, name);
        if (!this.inView(p)) {
          const at = (c) => show('length', c, this.options.units, 3, this.map.size);
          offView.push(`${label} (${at(p[0])}, ${at(p[1])})`);
          continue;
        }
        const [x, y] = this.px(p);
        const g = svgEl('g', { class: `pole pole-${key}`, transform: `translate(${x},${y})` }, this.layers.poles);
        if (shape === 'circle') {
          svgEl('circle', { r: 6, fill: '#ffffff', stroke: COLOURS.velocity, 'stroke-width': 2 }, g);
          svgEl('path', { d: 'M-4,0 L4,0 M0,-4 L0,4', stroke: COLOURS.velocity, 'stroke-width': 1.5 }, g);
        } else {
          svgEl('path', { d: 'M0,-7 L7,0 L0,7 L-7,0 Z', fill: '#ffffff', stroke: COLOURS.acceleration, 'stroke-width': 2 }, g);
        }
        const t = svgEl('text', { class: 'pole-label', fill: colourOf(name), 'text-anchor': 'middle', 'dominant-baseline': 'central' }, g);
        t.textContent = label;
        this.poleMarks.push(markerBox([x, y], 8));
        labels.push({ node: t, at: [x, y], size: measureLabel(t), last: -1 });
        svgEl('title', {}, g).textContent = `${label}: ${key === 'velocity_pole' ? 'velocity pole (instant centre with the ground)' : 'acceleration pole'} of link ${name}`;
      }
    }
    this.poleLabels = labels;
    return offView.length ? [`Poles outside the picture: ${offView.join(', ')}`] : [];
  }

  /**
   * The poles' names around their markers, clear of each other, of every pole marker and of the
   * joints where the analysed instant has them; the names of points and links then keep clear
   * of these (poleMarks) whenever the poles are shown.
   */
  placePoleLabels(labels) {
    if (!labels.length) return;
    const markers = [...this.fixedMarks, ...this.poleMarks, ...this.noteMarks];
    for (const group of [this.analysis.points, this.analysis.moving_points]) {
      for (const q of Object.values(group || {})) if (q.position) markers.push(markerBox(this.px(q.position), 8));
    }
    for (const label of labels) label.candidates = aroundPoint(label.at, label.size);
    const chosen = placeAll(labels, markers, [], { x0: 0, y0: 0, x1: WIDTH, y1: this.map.height });
    labels.forEach((label, i) => {
      const at = label.candidates[chosen[i]].at;
      setAttrs(label.node, { x: (at[0] - label.at[0]).toFixed(1), y: (at[1] - label.at[1]).toFixed(1) });
      this.poleMarks.push(boxAt(at, label.size));
    });
  }

  isGroundPoint(p) {
    const ground = groundLink(this.scene);
    return (this.scene.links[ground]?.points || []).some((n) => {
      const q = this.scene.points[n];
      return Math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9 * (1 + this.map.size);
    });
  }

  /** Text notes and scale bars (a round value of each quantity drawn at its arrow scale). */
  buildNotes(notes) {
    const bars = [];
    for (const kind of ['velocity', 'acceleration']) {
      const on = kind === 'velocity' ? this.options.showVelocity : this.options.showAcceleration;
      const scale = this.scale[kind];
      if (!on || !scale) continue;
      const value = niceBelow((this.map.size * 0.22) / this.view.scale / scale);
      bars.push({ kind, value, px: value * scale * this.map.k });
    }
    // The notes' size is the stylesheet's (at least 11 screen px): lines spaced and broken by it.
    const node = (x, text) => {
      const t = svgEl('text', { x, class: 'view-note' }, this.layers.notes);
      t.textContent = text;
      return t;
    };
    const nodes = bars.map((b) => node(20 + b.px, `${show(b.kind, b.value, this.options.units, 3)} (${b.kind} scale)`));
    for (const note of notes) nodes.push(...this.brokenLines(note, (words) => node(12, words)));
    const lineHeight = nodes.length ? measureLabel(nodes[0]).h : 0;
    let y = this.map.height - 12 - (nodes.length - 1) * lineHeight;
    this.noteMarks = [];
    nodes.forEach((t, i) => {
      t.setAttribute('y', y.toFixed(1));
      const { w, h } = measureLabel(t);
      const x = Number(t.getAttribute('x'));
      this.noteMarks.push({ x0: i < bars.length ? 12 : x, x1: x + w, y0: y - 0.75 * h, y1: y + 0.25 * h });
      if (i < bars.length) {
        const b = bars[i];
        svgEl('line', { x1: 12, y1: y - 4, x2: 12 + b.px, y2: y - 4, stroke: COLOURS[b.kind], 'stroke-width': 2.6, 'marker-end': this.markers[b.kind], class: 'scale-bar' }, this.layers.notes);
      }
      y += lineHeight;
    });
  }

  /** A note in lines that fit the picture's width, broken between words (`make` draws a line). */
  brokenLines(note, make) {
    const lines = [];
    let line = '';
    const probe = make('');
    for (const word of note.split(' ')) {
      const longer = line ? `${line} ${word}` : word;
      probe.textContent = longer;
      if (line && measureLabel(probe).w > WIDTH - 24) {
        lines.push(line);
        line = word;
      } else line = longer;
    }
    probe.remove();
    return [...lines, line].map(make);
  }

  // ---- drawing one frame -------------------------------------------------------------------

  /** Move everything to the frame {position, velocity, acceleration} (world units, SI). */
  draw(frame) {
    this.lastFrame = frame;
    if (!this.map) return;
    const bars = [...this.drawLinks(frame), ...this.drawSlots(frame)];
    this.drawPaths(frame);
    for (const { name, node } of this.jointNodes) {
      const p = frame.position[name];
      if (!p) {
        node.setAttribute('visibility', 'hidden');
        continue;
      }
      const [cx, cy] = this.px(p);
      setAttrs(node, { cx, cy, visibility: null });
    }
    this.drawLabels(frame, bars);
    const picked = this.pickNode && frame.position[this.picked];
    if (this.pickNode) setAttrs(this.pickNode, picked ? { cx: this.px(picked)[0], cy: this.px(picked)[1], visibility: null } : { visibility: 'hidden' });
    if (this.handle) {
      const p = frame.position[this.handle.handle];
      if (p) {
        const [cx, cy] = this.px(p);
        setAttrs(this.handle.node, { cx, cy });
      }
    }
    this.drawVectors(frame);
    for (const f of this.afterDraw) f(frame);
  }

  /** Bars, plates and discs at the frame; returns the bars' axes (px) for the label placer. */
  drawLinks(frame) {
    const bars = [];
    for (const { name, pts, kind, nodes } of this.linkNodes) {
      const ps = pts.map((n) => frame.position[n]).filter(Boolean).map((p) => this.px(p));
      if (ps.length < 2) continue;
      if (kind === 'bar') {
        for (const n of nodes) setAttrs(n, { x1: ps[0][0], y1: ps[0][1], x2: ps[1][0], y2: ps[1][1] });
        bars.push([ps[0], ps[1]]);
      } else if (kind === 'plate') {
        setAttrs(nodes[0], { points: hullOrder(ps).map((p) => p.join(',')).join(' ') });
      } else if (kind === 'disc') {
        setAttrs(nodes[0], this.discAt(name, frame));
        setAttrs(nodes[1], { points: hullOrder(ps).map((p) => p.join(',')).join(' ') });
      }
    }
    return bars;
  }

  /** Slotted bars along their axes and the sliders' blocks; returns the slots' axes (px). */
  drawSlots(frame) {
    const P = (name) => frame.position[name];
    const bars = [];
    for (const { joint, guide, nodes } of this.slotNodes) {
      const p = P(joint.point);
      if (!p) continue;
      const axis = this.axisAt(joint, frame);
      const gp = (this.scene.links[guide]?.points || []).map(P).filter(Boolean);
      let lo = 0;
      let hi = 0;
      for (const q of [...gp, p]) {
        const s = (q[0] - p[0]) * axis[0] + (q[1] - p[1]) * axis[1];
        lo = Math.min(lo, s);
        hi = Math.max(hi, s);
      }
      const a = this.px([p[0] + lo * axis[0], p[1] + lo * axis[1]]);
      const b = this.px([p[0] + hi * axis[0], p[1] + hi * axis[1]]);
      for (const n of nodes) setAttrs(n, { x1: a[0], y1: a[1], x2: b[0], y2: b[1] });
      bars.push([a, b]);
    }
    for (const { joint, node } of this.blockNodes) {
      const p = P(joint.point);
      if (!p) continue;
      const axis = this.axisAt(joint, frame);
      const [x, y] = this.px(p);
      const deg = (-Math.atan2(axis[1], axis[0]) * 180) / Math.PI;
      setAttrs(node, { transform: `translate(${x.toFixed(2)},${y.toFixed(2)}) rotate(${deg.toFixed(2)})` });
    }
    return bars;
  }

  /** The grooves of moving points, where their links are in this frame. */
  drawPaths(frame) {
    const P = (name) => frame.position[name];
    for (const { m, nodes } of this.paths) {
      const path = m.path || {};
      let attrs;
      if (path.type === 'arc') {
        const c = P(path.center);
        const s = P(path.start);
        if (!c || !s) continue;
        const [cx, cy] = this.px(c);
        attrs = { cx, cy, r: Math.hypot(s[0] - c[0], s[1] - c[1]) * this.map.k };
      } else {
        const a = P(path.start);
        const b = P(path.through);
        if (!a || !b) continue;
        const [x1, y1] = this.px(a);
        const [x2, y2] = this.px(b);
        attrs = { x1, y1, x2, y2 };
      }
      for (const n of nodes) setAttrs(n, attrs);
    }
  }

  /**
   * Point and link names, none on another nor on a marker (joints, fixed pivots, blocks, the
   * poles when shown): a point's name around it, a bar's beside its middle, a plate's around its
   * centroid (drawing-labels.js).
   */
  drawLabels(frame, bars) {
    const markers = [...this.fixedMarks, ...this.overlayMarks, ...this.noteMarks];
    for (const { name, node } of this.jointNodes) {
      const p = frame.position[name];
      if (p) markers.push(markerBox(this.px(p), Number(node.getAttribute('r')) + 2));
    }
    for (const { joint } of this.blockNodes) {
      const p = frame.position[joint.point];
      if (p) markers.push(markerBox(this.px(p), BLOCK[0] / 2));
    }
    if (frame.exact) markers.push(...this.poleMarks);
    const shown = [];
    for (const label of this.labelNodes) {
      const pts = label.point ? [label.point] : this.scene.links[label.link].points;
      const ps = pts.map((n) => frame.position[n]).filter(Boolean).map((p) => this.px(p));
      const bar = label.link && ps.length === 2;
      if (!ps.length) continue;
      label.candidates = bar ? besideBar(ps[0], ps[1], label.size, 6) : aroundPoint(centroid(ps), label.size);
      shown.push(label);
    }
    const chosen = placeAll(shown, markers, [...this.fixedBars, ...bars], { x0: 0, y0: 0, x1: WIDTH, y1: this.map.height });
    shown.forEach((label, i) => {
      label.last = chosen[i];
      const [x, y] = label.candidates[chosen[i]].at;
      setAttrs(label.node, { x: x.toFixed(1), y: y.toFixed(1) });
    });
  }

  drawVectors(frame) {
    for (const v of this.vectorNodes) {
      const p = frame.position[v.point];
      let vec;
      let from = [0, 0];
      let scale;
      if (typeof v.quantity === 'string') {
        vec = frame[v.quantity]?.[v.point];
        scale = this.scale[v.quantity];
      } else {
        const parts = frame.parts?.[v.point];
        vec = parts?.[v.quantity.part];
        from = v.quantity.from.reduce((acc, k) => sum(acc, parts?.[k]), [0, 0]);
        scale = v.quantity.accel ? this.scale.acceleration : this.scale.velocity;
      }
      if (!p || !vec || !scale || Math.hypot(vec[0], vec[1]) * scale * this.map.k < 2) {
        v.node.setAttribute('visibility', 'hidden');
        continue;
      }
      const a = this.px([p[0] + from[0] * scale, p[1] + from[1] * scale]);
      const b = this.px([p[0] + (from[0] + vec[0]) * scale, p[1] + (from[1] + vec[1]) * scale]);
      setAttrs(v.node, { x1: a[0], y1: a[1], x2: b[0], y2: b[1], visibility: null });
    }
    this.layers.poles.setAttribute('visibility', frame.exact ? 'visible' : 'hidden');
    this.layers.centres.setAttribute('visibility', frame.exact ? 'visible' : 'hidden');
  }

  /** True for a link pinned to the ground that carries a moving point's circular groove. */
  isDisc(name) {
    const ground = groundLink(this.scene);
    const pinned = (this.scene.joints || []).some((j) => j.type === 'revolute' && j.links.includes(name) && j.links.includes(ground));
    return pinned && movingPoints(this.scene).some((m) => m.link === name && m.path?.type === 'arc');
  }

  /** The disc of link `name` in this frame: centred on its pivot, wide enough for its groove. */
  discAt(name, frame) {
    const ground = groundLink(this.scene);
    const pivot = (this.scene.joints || []).find((j) => j.type === 'revolute' && j.links.includes(name) && j.links.includes(ground)).point;
    const c = frame.position[pivot];
    let r = 0;
    for (const p of this.scene.links[name].points) {
      const q = frame.position[p];
      if (q) r = Math.max(r, Math.hypot(q[0] - c[0], q[1] - c[1]));
    }
    for (const m of movingPoints(this.scene)) {
      if (m.link !== name || m.path?.type !== 'arc') continue;
      const gc = frame.position[m.path.center];
      const gs = frame.position[m.path.start];
      if (gc && gs) r = Math.max(r, Math.hypot(gc[0] - c[0], gc[1] - c[1]) + Math.hypot(gs[0] - gc[0], gs[1] - gc[1]));
    }
    const [cx, cy] = this.px(c);
    return { cx, cy, r: r * this.map.k * 1.08 + 12 };
  }

  /** The grid step for snapping a dragged joint: a round value near 1/40 of the picture. */
  gridStep() {
    return niceBelow(this.map.size / 40 / this.view.scale);
  }

  snap(p) {
    const g = this.gridStep();
    return [Math.round(p[0] / g) * g, Math.round(p[1] / g) * g].map((v) => Number(v.toFixed(10)));
  }

  /** Slot axis at this frame, as the server sent it (the scene's drawn axis where the track
   * has none: a static track, the drawn pose). */
  axisAt(joint, frame) {
    const axis = frame.axis?.[joint.point];
    return unit(axis || joint.axis || [1, 0]);
  }

  // ---- dragging the crank (Turn) or a joint (Edit), panning, pinching, picking a point ------

  installPointer() {
    const svg = this.svg;
    const toWorld = (ev) => {
      const [x, y] = this.viewBoxPoint(ev);
      return this.world(x, y);
    };
    // What a press lands on: the topmost joint, ring or link under the pointer, seen through the
    // arrows, poles and names drawn above them (a velocity arrow starts on the crank's end joint).
    const grabbed = (ev) => {
      const under = document.elementsFromPoint(ev.clientX, ev.clientY).filter((e) => svg.contains(e));
      return under.find((e) => e.dataset?.point || e.dataset?.link || e.classList.contains('crank-handle')) || ev.target;
    };
    // A press that ends where it began on a point picks that point (its readout and trace); on a
    // link's bar or plate away from its named points, it asks for that point of the link.
    let press = null;
    svg.addEventListener('pointerdown', (ev) => {
      const target = grabbed(ev);
      const name = target.dataset?.point;
      const link = name ? null : target.dataset?.link || null;
      press = { id: ev.pointerId, name, link, at: this.lastFrame ? toWorld(ev) : null, x: ev.clientX, y: ev.clientY };
      if (this.movesJoints() && name && this.lastFrame?.position[name]) {
        this.pointDrag = { name, frame: this.lastFrame, at: this.lastFrame.position[name] };
        press = null;
        svg.setPointerCapture(ev.pointerId);
        svg.classList.add('dragging');
        ev.preventDefault();
        return;
      }
      // Anywhere on the driver turns it: its ring, its bar, its points other than the pivot.
      const onDriver = this.handle && this.lastFrame && !this.pan && (target.classList.contains('crank-handle') || target.dataset?.link === this.handle.link
        || (name && name !== this.handle.pivot && this.scene.links[this.handle.link].points.includes(name)));
      if (onDriver) {
        press.link = null; // a press on the driver turns it, even one that does not move
        this.dragging = true;
        svg.setPointerCapture(ev.pointerId);
        svg.classList.add('dragging');
        ev.preventDefault();
        return;
      }
      // Elsewhere one pointer pans the picture and two pinch it.
      if (!this.scene) return;
      this.pan = this.pan || { pointers: new Map() };
      this.pan.pointers.set(ev.pointerId, this.viewBoxPoint(ev));
      svg.setPointerCapture(ev.pointerId);
      svg.classList.add('panning');
      ev.preventDefault();
    });
    svg.addEventListener('pointermove', (ev) => {
      if (press && press.id === ev.pointerId && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) > CLICK) press = null;
      if (this.pointDrag) {
        // The joint follows the pointer, snapped to the grid; the bars follow it (drawing only).
        const d = this.pointDrag;
        d.at = ev.shiftKey ? toWorld(ev) : this.snap(toWorld(ev));
        const frame = { ...d.frame, position: { ...d.frame.position, [d.name]: d.at }, velocity: {}, acceleration: {}, parts: {}, exact: false };
        this.draw(frame);
        this.lastFrame = d.frame;
        return;
      }
      if (this.pan?.pointers.has(ev.pointerId)) {
        this.movePan(ev.pointerId, this.viewBoxPoint(ev));
        return;
      }
      if (!this.dragging) return;
      const frame = this.lastFrame;
      const pivot = frame.position[this.handle.pivot];
      const handle = frame.position[this.handle.handle];
      const pts = this.scene.links[this.handle.link].points;
      const a = frame.position[pts[0]];
      const b = frame.position[pts[1]];
      if (!pivot || !handle || !a || !b) return;
      const w = toWorld(ev);
      // The link angle is measured first point -> second point; the hand turns the handle about
      // the pivot. Both turn by the same amount.
      const pointer = Math.atan2(w[1] - pivot[1], w[0] - pivot[0]);
      const now = Math.atan2(handle[1] - pivot[1], handle[0] - pivot[0]);
      const linkAngle = Math.atan2(b[1] - a[1], b[0] - a[0]);
      this.callbacks.onDrag?.(linkAngle + wrap(pointer - now));
    });
    const end = (ev) => {
      const clicked = press && press.id === ev.pointerId && ev.type === 'pointerup' ? press : null;
      const picked = clicked?.name || null;
      press = null;
      if (svg.hasPointerCapture(ev.pointerId)) svg.releasePointerCapture(ev.pointerId);
      if (this.pointDrag) {
        const d = this.pointDrag;
        this.pointDrag = null;
        svg.classList.remove('dragging');
        const start = d.frame.position[d.name];
        if (Math.hypot(d.at[0] - start[0], d.at[1] - start[1]) > 0) this.callbacks.onPointDrop?.(d.name, d.at, d.frame);
        else this.draw(d.frame);
        return;
      }
      if (this.pan?.pointers.delete(ev.pointerId) && !this.pan.pointers.size) {
        this.pan = null;
        svg.classList.remove('panning');
      }
      if (this.dragging) {
        this.dragging = false;
        svg.classList.remove('dragging');
        this.callbacks.onDragEnd?.();
      }
      if (picked) this.callbacks.onPointPick?.(picked);
      else if (clicked?.link && clicked.at && this.lastFrame) this.callbacks.onLinkPick?.(clicked.link, clicked.at, this.lastFrame);
    };
    svg.addEventListener('pointerup', end);
    svg.addEventListener('pointercancel', end);
    // Hovering a point reads it out until the pointer leaves it (a tap or a click keeps it).
    svg.addEventListener('pointerover', (ev) => {
      const name = ev.target.dataset?.point;
      if (name && ev.pointerType === 'mouse' && !this.dragging && !this.pan) this.callbacks.onPointHover?.(name);
    });
    svg.addEventListener('pointerout', (ev) => {
      if (ev.target.dataset?.point && ev.pointerType === 'mouse') this.callbacks.onPointHover?.(null);
    });
  }

  /**
   * One pointer of a pan moved to `at` (viewBox px): alone it drags the picture; with a second
   * one the pair pinches, zooming by the ratio of their distances about their midpoint, which
   * also moves with the hand.
   */
  movePan(id, at) {
    const pointers = this.pan.pointers;
    const before = pointers.get(id);
    const others = [...pointers.entries()].filter(([k]) => k !== id).map(([, p]) => p);
    pointers.set(id, at);
    if (!others.length) {
      this.panBy(at[0] - before[0], at[1] - before[1]);
      return;
    }
    const other = others[0];
    const d0 = Math.hypot(before[0] - other[0], before[1] - other[1]);
    const d1 = Math.hypot(at[0] - other[0], at[1] - other[1]);
    const m0 = [(before[0] + other[0]) / 2, (before[1] + other[1]) / 2];
    const m1 = [(at[0] + other[0]) / 2, (at[1] + other[1]) / 2];
    if (d0 > 1 && d1 > 1) this.zoomBy(d1 / d0, m0);
    this.panBy(m1[0] - m0[0], m1[1] - m0[1]);
  }
}

// ---- small geometry helpers for drawing ------------------------------------------------------

/** The colours of added traces, in turn (distinct from the quantities' colours). */
const TRACE_COLOURS = ['#9333ea', '#0f766e', '#b45309', '#be123c', '#1d4ed8', '#4d7c0f'];
export const traceColour = (i) => TRACE_COLOURS[i % TRACE_COLOURS.length];

function sameNames(a, b) {
  return a.length === b.length && a.every((n) => b.includes(n));
}

function unit(v) {
  const n = Math.hypot(v[0], v[1]) || 1;
  return [v[0] / n, v[1] / n];
}

function sum(a, b) {
  return [(a?.[0] || 0) + (b?.[0] || 0), (a?.[1] || 0) + (b?.[1] || 0)];
}

function wrap(a) {
  return Math.atan2(Math.sin(a), Math.cos(a));
}

function centroid(ps) {
  const s = ps.reduce((acc, p) => [acc[0] + p[0], acc[1] + p[1]], [0, 0]);
  return [s[0] / ps.length, s[1] / ps.length];
}

/** Order the corners of a plate around its centre so the polygon never crosses itself. */
function hullOrder(ps) {
  const c = centroid(ps);
  return [...ps].sort((a, b) => Math.atan2(a[1] - c[1], a[0] - c[0]) - Math.atan2(b[1] - c[1], b[0] - c[0]));
}

/** The largest 1, 2 or 5 times a power of ten not above v: a scale bar with a round label. */
function niceBelow(v) {
  const p = 10 ** Math.floor(Math.log10(v));
  return [5, 2, 1].map((m) => m * p).find((x) => x <= v) || p;
}

function analysisMax(analysis, quantity) {
  if (!analysis) return 0;
  let m = 0;
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const q of Object.values(group || {})) {
      const v = q[quantity];
      if (v) m = Math.max(m, Math.hypot(v[0], v[1]));
    }
  }
  return m;
}
