// spatial-motion.js: a spatial chain over time, and its fields (joint offsets, link lengths).
//
// The motion is one /sweep with time_range (the server moves joint k by
// q_k(t) = rate t + rate_dot t^2 / 2 from the scene's pose and analyses every sample). Between two
// samples the drawing is interpolated linearly for display only; the values a student reads
// (the list under the drawing, the plots, the worked solution) are the server's, at a sample.
//
// The fields rebuild the scene at t = 0 and the app asks the server again:
// - a joint offset q0 turns (slides) everything after joint k about (along) its axis through its
//   origin by q0: Rodrigues' formula v cos q + (e x v) sin q + e (e . v)(1 - cos q);
// - a link length moves everything after body k along O_k -> O_{k+1} (for the last body, along
//   O_n -> its first point) so that the distance becomes the new length.
import { typed } from './units.js';

const SPATIAL_SAMPLES = 241;
const TURNS = 1; // the time range: one turn of the fastest revolute joint (2 s to 20 s)

const sub = (a, b) => a.map((c, i) => c - b[i]);
const add = (a, b) => a.map((c, i) => c + b[i]);
const scale = (a, k) => a.map((c) => c * k);
const dot = (a, b) => a.reduce((s, c, i) => s + c * b[i], 0);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(...a);
const lerp = (a, b, f) => (a && b ? a.map((c, i) => c + (b[i] - c) * f) : a);

/** v turned by q about the unit axis e (Rodrigues). */
export function rodrigues(v, e, q) {
  const c = Math.cos(q);
  const s = Math.sin(q);
  return add(add(scale(v, c), scale(cross(e, v), s)), scale(e, dot(e, v) * (1 - c)));
}

/** The time range the app sweeps: one turn of the fastest revolute joint, within 2 to 20 s. */
export function timeRange(scene) {
  const fastest = Math.max(0, ...(scene.joints || []).filter((j) => j.type === 'revolute').map((j) => Math.abs(j.rate)));
  const turn = fastest > 0 ? (TURNS * 2 * Math.PI) / fastest : 10;
  return [0, Math.min(20, Math.max(2, turn))];
}

export const sweepRequest = (scene) => ({ samples: SPATIAL_SAMPLES, quantities: ['position', 'velocity', 'acceleration'], timeRange: timeRange(scene) });

/** A track (see track.js) over the sweep's samples, with the spatial sweep kept whole. */
export function spatialTrack(sweep) {
  return { param: 'time', values: sweep.time, n: sweep.time.length, points: {}, links: {}, feasible: true, limits: [], warnings: sweep.warnings || [], closed: false, static: false, spatial: sweep };
}

function split(track, u) {
  const max = track.n - 1;
  const clamped = Math.min(Math.max(u, 0), max);
  const i = Math.min(Math.floor(clamped), Math.max(max - 1, 0));
  return [i, Math.min(i + 1, max), clamped - i];
}

/**
 * The chain at fractional sample u as a scene-v1 document and an /analyze-shaped answer: at a
 * whole u, exactly the server's sample; between two, interpolated for the drawing only.
 */
export function chainAt(scene, track, u) {
  const s = track.spatial;
  const [i, j, f] = split(track, u);
  const moved = {
    ...scene,
    joints: scene.joints.map((joint, k) => ({
      ...joint,
      origin: lerp(s.joints[k].origin[i], s.joints[k].origin[j], f),
      axis: lerp(s.joints[k].axis[i], s.joints[k].axis[j], f),
      rate: s.joints[k].rate[i] + (s.joints[k].rate[j] - s.joints[k].rate[i]) * f,
    })),
    points: Object.fromEntries(Object.entries(scene.points || {}).map(([name, p]) => [name, { ...p, position: lerp(s.points[name].position[i], s.points[name].position[j], f) }])),
  };
  const analysis = {
    bodies: Object.fromEntries(Object.entries(s.bodies).map(([name, b]) => [name, { omega: lerp(b.omega[i], b.omega[j], f), alpha: lerp(b.alpha[i], b.alpha[j], f) }])),
    points: Object.fromEntries(Object.entries(s.points).map(([name, p]) => [name, {
      position: lerp(p.position[i], p.position[j], f),
      velocity: lerp(p.velocity[i], p.velocity[j], f),
      acceleration: lerp(p.acceleration[i], p.acceleration[j], f),
    }])),
  };
  return { scene: moved, analysis, exact: f === 0 || i === j };
}

/** Every position the chain takes over the sweep: the drawing's frame stays still. */
export function extentOf(track) {
  const s = track.spatial;
  const out = [];
  for (const j of s.joints) out.push(...j.origin);
  for (const p of Object.values(s.points)) out.push(...p.position);
  return out;
}

// ---- the scene rebuilt from the fields ----------------------------------------------------------

const order = (scene) => Object.fromEntries([['ground', 0], ...scene.joints.map((j, k) => [j.name, k + 1])]);

/** The scene with joint k turned (revolute, rad) or slid (prismatic, m) by q from its pose. */
export function moveJoint(scene, k, q) {
  const joint = scene.joints[k];
  const e = scale(joint.axis, 1 / norm(joint.axis));
  const o = joint.origin;
  const move = (x) => (joint.type === 'revolute' ? add(o, rodrigues(sub(x, o), e, q)) : add(x, scale(e, q)));
  const turn = (v) => (joint.type === 'revolute' ? rodrigues(v, e, q) : v);
  const rank = order(scene);
  return {
    ...scene,
    joints: scene.joints.map((j, i) => (i > k ? { ...j, origin: move(j.origin), axis: turn(j.axis) } : j)),
    points: Object.fromEntries(Object.entries(scene.points || {}).map(([name, p]) => [name, rank[p.body] > k ? { ...p, position: move(p.position) } : p])),
  };
}

/** Body k's length: |O_k O_{k+1}|, or for the last body |O_n P| to its first point (null: none). */
export function lengthEnds(scene, k) {
  const from = scene.joints[k].origin;
  if (k + 1 < scene.joints.length) return [from, scene.joints[k + 1].origin];
  const first = Object.values(scene.points || {}).find((p) => p.body === scene.joints[k].name && norm(sub(p.position, from)) > 1e-12);
  return first ? [from, first.position] : null;
}

/** The scene with body k's length set to `length`: everything beyond it moved along the bar. */
export function setLength(scene, k, length) {
  const ends = lengthEnds(scene, k);
  if (!ends) return scene;
  const bar = sub(ends[1], ends[0]);
  const shift = scale(bar, length / norm(bar) - 1);
  const rank = order(scene);
  const last = k + 1 === scene.joints.length;
  const at = (p, x) => norm(sub(p.position, x)) <= 1e-9 * (1 + norm(x));
  // After body k, or on body k at the far end (for the last body: every point but its origin).
  const beyond = (p) => rank[p.body] > k + 1 || (rank[p.body] === k + 1 && (at(p, ends[1]) || (last && !at(p, ends[0]))));
  return {
    ...scene,
    joints: scene.joints.map((j, i) => (i > k ? { ...j, origin: add(j.origin, shift) } : j)),
    points: Object.fromEntries(Object.entries(scene.points || {}).map(([name, p]) => [name, beyond(p) ? { ...p, position: add(p.position, shift) } : p])),
  };
}

/**
 * The fields under the drawing: each joint's offset at t = 0 (deg, or mm for a prismatic joint)
 * and each body's length (m). A change rebuilds the scene from the base scene and calls onChange.
 */
export class SpatialFields {
  constructor(container, onChange) {
    this.container = container;
    this.onChange = onChange;
    this.base = null;
  }

  /** Fields for `current`, built from `base` (the chain as opened), with these joint offsets (none: 0). */
  show(base, current, offsets = null) {
    this.base = base;
    this.offsets = offsets ? [...offsets] : base.joints.map(() => 0);
    this.lengths = base.joints.map((_, k) => {
      const ends = lengthEnds(current, k);
      return ends ? norm(sub(ends[1], ends[0])) : null;
    });
    const rows = [];
    base.joints.forEach((j, k) => {
      const revolute = j.type === 'revolute';
      rows.push(this.field(`spatial-offset-${k}`, `Joint ${j.name} offset (${revolute ? 'deg' : 'm'})`, revolute ? (this.offsets[k] * 180) / Math.PI : this.offsets[k], (v) => {
        this.offsets[k] = revolute ? (v * Math.PI) / 180 : v;
        return true;
      }));
      if (this.lengths[k] !== null) {
        rows.push(this.field(`spatial-length-${k}`, `Body ${j.name} length (m)`, this.lengths[k], (v) => {
          if (!(v > 0)) return false;
          this.lengths[k] = v;
          return true;
        }));
      }
    });
    this.container.replaceChildren(...rows);
  }

  field(id, label, value, accept) {
    const wrap = document.createElement('label');
    wrap.className = 'inline';
    wrap.textContent = `${label} `;
    const input = Object.assign(document.createElement('input'), { id, type: 'text', inputMode: 'decimal', value: typed(value) });
    input.setAttribute('aria-invalid', 'false');
    const commit = () => {
      const v = Number(input.value.trim().replace(',', '.'));
      const ok = input.value.trim() !== '' && Number.isFinite(v) && accept(v);
      input.setAttribute('aria-invalid', String(!ok));
      if (ok) this.onChange(this.scene());
    };
    input.addEventListener('change', commit);
    wrap.append(input);
    return wrap;
  }

  /** The base scene with the lengths set (in chain order), then the offsets applied. */
  scene() {
    let scene = this.base;
    this.lengths.forEach((length, k) => {
      if (length !== null) scene = setLength(scene, k, length);
    });
    this.offsets.forEach((q, k) => {
      if (q) scene = moveJoint(scene, k, q);
    });
    return scene;
  }
}

/** Plots over time: |omega| and |alpha| of each body, |v| and |a| of each point (Plotly). */
export function renderSpatialPlots(div, track, Plotly) {
  const s = track.spatial;
  const t = s.time;
  const traces = [];
  const mags = (rows) => rows.map((r) => norm(r));
  for (const [name, b] of Object.entries(s.bodies)) {
    traces.push({ x: t, y: mags(b.omega), name: `|ω${name}| (rad/s)`, xaxis: 'x', yaxis: 'y' });
    traces.push({ x: t, y: mags(b.alpha), name: `|α${name}| (rad/s²)`, xaxis: 'x', yaxis: 'y', line: { dash: 'dot' } });
  }
  for (const [name, p] of Object.entries(s.points)) {
    traces.push({ x: t, y: mags(p.velocity), name: `|v${name}| (m/s)`, xaxis: 'x2', yaxis: 'y2' });
    traces.push({ x: t, y: mags(p.acceleration), name: `|a${name}| (m/s²)`, xaxis: 'x2', yaxis: 'y2', line: { dash: 'dot' } });
  }
  const layout = {
    grid: { rows: 2, columns: 1, pattern: 'independent' },
    height: 520,
    margin: { l: 60, r: 10, t: 30, b: 40 },
    xaxis: { title: { text: 't (s)' } },
    xaxis2: { title: { text: 't (s)' } },
    yaxis: { title: { text: 'bodies: |ω| (rad/s), |α| (rad/s²)' } },
    yaxis2: { title: { text: 'points: |v| (m/s), |a| (m/s²)' } },
    legend: { orientation: 'h' },
  };
  return Plotly.react(div, traces, layout, { displaylogo: false, responsive: true });
}
