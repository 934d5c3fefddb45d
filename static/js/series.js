// series.js: the quantities over the cycle, as named series in display units, from one sweep.
//
// One list serves the plots (a student picks what to plot) and the CSV export (every series),
// so a number in the CSV is the number on the plot. Everything is read from the server's sweep:
// positions, velocities and accelerations of the points, angle, ω and α of the links. What is
// done here is reading, not solving:
//   - the x axis: the driver angle brought into 0..360 deg (the sweep starts at the drawn pose),
//     or the time t = (θ − θ₀)/ω of a driver turning at constant ω;
//   - a slider on a fixed guide: its position s = (r − r₀)·e, velocity v·e and acceleration a·e
//     along the guide's unit vector e (the point's own vectors, which lie along e);
//   - the transmission angle μ = ∠BCD of a four-bar loop the server reported (the same formula
//     as the solver's four_bar.transmission_angle), from the swept positions;
//   - the quick-return time ratio: the crank angles between the zero crossings of the ram's
//     velocity (its limit positions), interpolated linearly between samples.

import { groundLink, movingLinks } from './scene.js';
import { toDisplay, unitLabel } from './units.js';

const TWO_PI = 2 * Math.PI;
const mod = (a, m) => ((a % m) + m) % m;
const dot = (a, b) => a[0] * b[0] + a[1] * b[1];

/**
 * The order in which to read the samples and the x value of each: for a full revolution the
 * driver angle in [0, 2π] ascending (the first sample repeated one turn later closes it); for a
 * rocking crank its range shifted into [0, 2π); for time the samples as they are.
 */
export function cycleOrder(track) {
  const v = track.values;
  const n = track.n;
  if (track.param === 'time') return { index: v.map((_, i) => i), x: [...v] };
  if (track.closed) {
    // The sweep's samples cover one turn without repeating the first at its end.
    const idx = [...Array(n).keys()].sort((a, b) => mod(v[a], TWO_PI) - mod(v[b], TWO_PI));
    const x = idx.map((i) => mod(v[i], TWO_PI));
    return { index: [...idx, idx[0]], x: [...x, x[0] + TWO_PI] };
  }
  const lo = Math.min(v[0], v[n - 1]);
  const shift = TWO_PI * Math.floor(lo / TWO_PI);
  return { index: v.map((_, i) => i), x: v.map((a) => a - shift) };
}

/** The x axes the plots offer: driver angle, and time when the driver turns at constant ω. */
export function xAxes(scene, track) {
  if (track.param === 'time') return ['time'];
  const d = scene.drivers?.[0];
  return d && typeof d.omega === 'number' && d.omega !== 0 && !d.alpha ? ['angle', 'time'] : ['angle'];
}

/** x values (display units) and the axis title. */
export function xValues(scene, track, order, axis, units) {
  if (track.param === 'time') return { x: order.x, title: 'time t [s]', kind: 'time' };
  if (axis === 'time') {
    const omega = scene.drivers[0].omega;
    const start = track.values[0];
    // t from the crank at 0 (the sweep's first sample), over one period 2π/|ω|.
    const period = TWO_PI / Math.abs(omega);
    const x = order.index.map((i) => mod((track.values[i] - start) / omega, period));
    if (track.closed) x[x.length - 1] = x[x.length - 1] || period;
    return { x, title: 'time t from θ = 0 [s]', kind: 'time', sort: true };
  }
  const driver = scene.drivers?.[0]?.link || 'driver';
  return { x: order.x.map((a) => toDisplay('angle', a, units)), title: `angle of ${driver} θ [${unitLabel('angle', units)}]`, kind: 'angle' };
}

function unwrap(values) {
  // Angles from atan2 jump by 2π; a plot of a crank angle should be continuous.
  const out = [];
  let offset = 0;
  for (let i = 0; i < values.length; i++) {
    if (i > 0 && values[i] !== null && values[i - 1] !== null && out[i - 1] !== null) {
      const d = values[i] + offset - out[i - 1];
      if (d > Math.PI) offset -= TWO_PI;
      else if (d < -Math.PI) offset += TWO_PI;
    }
    out.push(values[i] === null ? null : values[i] + offset);
  }
  return out;
}

/** Sliders on a fixed guide: {point, axis (unit), origin (drawn position)}. */
export function groundSliders(scene) {
  const ground = groundLink(scene);
  return (scene.joints || [])
    .filter((j) => (j.type === 'slider' || j.type === 'prismatic') && j.links[0] === ground && scene.points[j.point])
    .map((j) => {
      const a = j.axis || [1, 0];
      const n = Math.hypot(a[0], a[1]) || 1;
      return { point: j.point, axis: [a[0] / n, a[1] / n], origin: scene.points[j.point] };
    });
}

/** Four-bar loops as B (crank–coupler), C (coupler–rocker), D (rocker–ground) from the server's loops. */
export function transmissionLoops(scene, loops) {
  const jointAt = (a, b) => (scene.joints || []).find((j) => j.type === 'revolute' && j.links.includes(a) && j.links.includes(b))?.point;
  const out = [];
  for (const loop of loops || []) {
    const { ground, crank, coupler, rocker } = loop.links || {};
    const B = jointAt(crank, coupler);
    const C = jointAt(coupler, rocker);
    const D = jointAt(rocker, ground);
    if (B && C && D) out.push({ B, C, D, name: `μ = ∠${B}${C}${D}`, grashof: loop.grashof });
  }
  return out;
}

/** μ = ∠BCD in 0..π (solver/kinematics/four_bar.py transmission_angle). */
export function angleBCD(B, C, D) {
  const u = [B[0] - C[0], B[1] - C[1]];
  const w = [D[0] - C[0], D[1] - C[1]];
  return Math.atan2(Math.abs(u[0] * w[1] - u[1] * w[0]), dot(u, w));
}

/**
 * Every series of the sweep in display units, in cycle order:
 * [{key, group, label, unit, y}], key like "link:crank:omega", "point:P:vx", "slider:C:s".
 */
export function allSeries(scene, track, order, units, loops = []) {
  const out = [];
  const pick = (arr) => order.index.map((i) => (arr ? arr[i] ?? null : null));
  const push = (key, group, label, kind, values) => out.push({ key, group, label, unit: unitLabel(kind, units), y: values.map((v) => (v === null ? null : toDisplay(kind, v, units))) });
  for (const name of movingLinks(scene)) {
    const l = track.links?.[name];
    if (!l) continue;
    if (Array.isArray(l.angle)) push(`link:${name}:angle`, `link ${name}`, `angle of ${name} φ`, 'angle', unwrap(pick(l.angle)));
    if (Array.isArray(l.omega)) push(`link:${name}:omega`, `link ${name}`, `ω of ${name}`, 'omega', pick(l.omega));
    if (Array.isArray(l.alpha)) push(`link:${name}:alpha`, `link ${name}`, `α of ${name}`, 'alpha', pick(l.alpha));
  }
  const comp = (arr, f) => pick(arr).map((v) => (v ? f(v) : null));
  for (const [name, q] of Object.entries(track.points)) {
    const g = `point ${name}`;
    if (Array.isArray(q.position) && q.position.length === track.n) {
      push(`point:${name}:x`, g, `x of ${name}`, 'length', comp(q.position, (v) => v[0]));
      push(`point:${name}:y`, g, `y of ${name}`, 'length', comp(q.position, (v) => v[1]));
    }
    for (const [quantity, kind, sym] of [['velocity', 'velocity', 'v'], ['acceleration', 'acceleration', 'a']]) {
      if (!Array.isArray(q[quantity])) continue;
      push(`point:${name}:${sym}x`, g, `${sym}x of ${name}`, kind, comp(q[quantity], (v) => v[0]));
      push(`point:${name}:${sym}y`, g, `${sym}y of ${name}`, kind, comp(q[quantity], (v) => v[1]));
      push(`point:${name}:${sym}`, g, `|${sym}| of ${name}`, kind, comp(q[quantity], (v) => Math.hypot(v[0], v[1])));
    }
  }
  for (const s of groundSliders(scene)) {
    const q = track.points[s.point];
    if (!q?.position) continue;
    const g = `slider ${s.point}`;
    push(`slider:${s.point}:s`, g, `position s of slider ${s.point} along its guide`, 'length', comp(q.position, (p) => dot([p[0] - s.origin[0], p[1] - s.origin[1]], s.axis)));
    if (q.velocity) push(`slider:${s.point}:v`, g, `velocity of slider ${s.point} along its guide`, 'velocity', comp(q.velocity, (v) => dot(v, s.axis)));
    if (q.acceleration) push(`slider:${s.point}:a`, g, `acceleration of slider ${s.point} along its guide`, 'acceleration', comp(q.acceleration, (v) => dot(v, s.axis)));
  }
  for (const loop of transmissionLoops(scene, loops)) {
    const [B, C, D] = [loop.B, loop.C, loop.D].map((p) => track.points[p]?.position);
    if (!B || !C || !D) continue;
    push(`transmission:${loop.C}`, 'transmission angle', `transmission angle ${loop.name}`, 'angle', order.index.map((i) => (B[i] && C[i] && D[i] ? angleBCD(B[i], C[i], D[i]) : null)));
  }
  return out;
}

/** Smallest and largest value with their x (for the transmission angle's extremes). */
export function extremes(x, y) {
  let lo = null;
  let hi = null;
  y.forEach((v, i) => {
    if (v === null) return;
    if (!lo || v < lo.y) lo = { x: x[i], y: v };
    if (!hi || v > hi.y) hi = { x: x[i], y: v };
  });
  return { lo, hi };
}

/**
 * Quick-return time ratio of a ram (slider on a fixed guide) driven by a crank at constant ω:
 * the limit positions are where the ram's velocity changes sign; time is proportional to crank
 * angle, so ratio = (slower stroke angle) / (faster stroke angle). Null unless exactly two sign
 * changes occur over a full revolution.
 */
export function timeRatio(track, slider) {
  const q = track.points[slider.point];
  if (track.param !== 'angle' || !track.closed || !q?.velocity) return null;
  // The turn closes: the first sample again, one revolution on.
  const turn = Math.sign(track.values[track.n - 1] - track.values[0]) * TWO_PI;
  const angles = [...track.values, track.values[0] + turn];
  const v = [...q.velocity, q.velocity[0]].map((w) => (w ? dot(w, slider.axis) : null));
  const crossings = [];
  for (let i = 0; i + 1 < v.length; i++) {
    const [a, b] = [v[i], v[i + 1]];
    if (a === null || b === null || a === b) continue;
    // A sign change; a zero sample counts once (as the end of the interval that reaches it).
    if ((a < 0 && b >= 0) || (a > 0 && b <= 0)) {
      crossings.push(angles[i] + (a / (a - b)) * (angles[i + 1] - angles[i]));
    }
  }
  if (crossings.length !== 2) return null;
  const first = Math.abs(crossings[1] - crossings[0]);
  const second = TWO_PI - first;
  const [slow, fast] = first >= second ? [first, second] : [second, first];
  return { ratio: slow / fast, slow, fast, limits: crossings };
}
