// series.js: the quantities over the cycle, as named series in display units, from one sweep.
//
// One list serves the plots (a student picks what to plot) and the CSV export (every series),
// so a number in the CSV is the number on the plot. Everything is read from the server's sweep:
// positions, velocities and accelerations of the points, angle, ω and α of the links. What is
// done here is reading, not solving: the x axis (the driver angle brought into 0..360 deg for a
// full turn, the sweep starting at the drawn pose, a rocking crank's angle as swept, or the time
// t = (θ − θ₀)/ω of a driver turning at constant ω).
// The server sends the rest: a slider's displacement s along its guide and its rates
// (`sliders`), the transmission angle μ = ∠BCD of each four-bar loop (`four_bar_loops`) and a
// ram's quick-return time ratio from its extreme positions (`sliders[].quick_return`).

import { pointName } from './notation.js';
import { groundLink, movingLinks } from './scene.js';
import { toDisplay, unitLabel } from './units.js';

const TWO_PI = 2 * Math.PI;
const mod = (a, m) => ((a % m) + m) % m;

/**
 * The driver angle (rad) `value` as the cycle's x axis shows it: brought into [0, 2π) for a full
 * revolution; as it is for a rocking crank (the angles its range, the slider and the analysed
 * instant are named by).
 */
export function plottedAngle(track, value) {
  return track.closed ? mod(value, TWO_PI) : value;
}

/**
 * The order in which to read the samples and the x value of each: for a full revolution the
 * driver angle in [0, 2π] ascending (the first sample repeated one turn later closes it); for a
 * rocking crank its range as swept (plottedAngle); for time the samples as they are.
 */
export function cycleOrder(track) {
  const v = track.values;
  const n = track.n;
  if (track.param === 'time') return { index: v.map((_, i) => i), x: [...v] };
  if (!track.closed) return { index: v.map((_, i) => i), x: v.map((a) => plottedAngle(track, a)) };
  // The sweep's samples cover one turn without repeating the first at its end.
  const plotted = v.map((a) => plottedAngle(track, a));
  const idx = [...Array(n).keys()].sort((a, b) => plotted[a] - plotted[b]);
  const x = idx.map((i) => plotted[i]);
  return { index: [...idx, idx[0]], x: [...x, x[0] + TWO_PI] };
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

/** The sweep's sliders on a fixed guide (the server's `sliders` whose guide is the ground). */
export function groundSliders(scene, track) {
  const ground = groundLink(scene);
  return (track.sliders || []).filter((s) => s.links?.[0] === ground);
}

/** "μ = ∠BCD" for the sweep's four-bar loop of these links (the server names B, C, D; a point
 * named by a Greek letter spelled out is written as the letter: ∠ABΓ). */
export function transmissionName(track, links) {
  const loop = (track?.fourBarLoops || []).find((l) => JSON.stringify(l.links) === JSON.stringify(links));
  return loop ? `μ = ∠${loop.angle_points.map(pointName).join('')}` : 'μ';
}

/**
 * Every series of the sweep in display units, in cycle order:
 * [{key, group, label, unit, y}], key like "link:crank:omega", "point:P:vx", "slider:C:s".
 */
export function allSeries(scene, track, order, units) {
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
    const [g, shown] = [`point ${name}`, pointName(name)];
    if (Array.isArray(q.position) && q.position.length === track.n) {
      push(`point:${name}:x`, g, `x of ${shown}`, 'length', comp(q.position, (v) => v[0]));
      push(`point:${name}:y`, g, `y of ${shown}`, 'length', comp(q.position, (v) => v[1]));
    }
    for (const [quantity, kind, sym] of [['velocity', 'velocity', 'v'], ['acceleration', 'acceleration', 'a']]) {
      if (!Array.isArray(q[quantity])) continue;
      push(`point:${name}:${sym}x`, g, `${sym}x of ${shown}`, kind, comp(q[quantity], (v) => v[0]));
      push(`point:${name}:${sym}y`, g, `${sym}y of ${shown}`, kind, comp(q[quantity], (v) => v[1]));
      push(`point:${name}:${sym}`, g, `|${sym}| of ${shown}`, kind, comp(q[quantity], (v) => Math.hypot(v[0], v[1])));
    }
  }
  for (const s of groundSliders(scene, track)) {
    const [g, shown] = [`slider ${s.point}`, pointName(s.point)];
    if (s.displacement) push(`slider:${s.point}:s`, g, `position s of slider ${shown} along its guide`, 'length', pick(s.displacement));
    if (s.sliding_velocity) push(`slider:${s.point}:v`, g, `velocity of slider ${shown} along its guide`, 'velocity', pick(s.sliding_velocity));
    if (s.sliding_acceleration) push(`slider:${s.point}:a`, g, `acceleration of slider ${shown} along its guide`, 'acceleration', pick(s.sliding_acceleration));
  }
  for (const loop of track.fourBarLoops || []) {
    const [, C] = loop.angle_points;
    push(`transmission:${C}`, 'transmission angle', `transmission angle ${transmissionName(track, loop.links)}`, 'angle', pick(loop.transmission_angle));
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
 * Quick-return time ratio of a ram (slider on a fixed guide) over a full revolution, as the
 * server found it from the ram's two extreme positions: {ratio, slow, fast (rad of crank turn),
 * limits (driver angles)}, or null.
 */
export function timeRatio(slider) {
  const q = slider.quick_return;
  if (!q) return null;
  return { ratio: q.time_ratio, slow: q.slow_stroke, fast: q.fast_stroke, limits: q.extreme_positions.map((e) => e.driver_angle) };
}
