// track.js: one sweep, normalised, and read at a fractional sample index.
//
// The animation plays back a single /sweep answer: a "track" of samples over one revolution of
// the driver (or over a time range for relative-motion scenes). Between two samples the pose is
// interpolated linearly for display only; the analysed instant is always asked of the server,
// so no number a student reads comes from this interpolation.

/** Build a track from a /sweep response. `param` is 'angle' (driver_angle) or 'time'. */
export function trackFromSweep(response) {
  const timeBased = Array.isArray(response.time);
  const values = timeBased ? response.time : response.driver_angle;
  if (!Array.isArray(values) || values.length === 0) {
    throw new Error('The sweep answer has no samples.');
  }
  const points = {};
  const addPoints = (group) => {
    for (const [name, q] of Object.entries(group || {})) points[name] = q;
  };
  addPoints(response.points);
  addPoints(response.moving_points);
  const span = values[values.length - 1] - values[0];
  return {
    param: timeBased ? 'time' : 'angle',
    values,
    n: values.length,
    points,
    links: response.links || {},
    // Computed by the server: sliders along their guides (axis, displacement, rates, a ram's
    // quick return) and four-bar loops with their transmission angle, sample by sample.
    sliders: response.sliders || [],
    fourBarLoops: response.four_bar_loops || [],
    feasible: response.feasible !== false,
    limits: response.limits || [],
    // The server's warnings in words (e.g. a close approach to a change point), shown as they are.
    warnings: response.warnings || [],
    // A full revolution loops; a rocking driver (infeasible) or a time range plays back and forth
    // or restarts (see main.js).
    closed: !timeBased && response.feasible !== false && Math.abs(Math.abs(span) - 2 * Math.PI) < 0.2,
    static: false,
  };
}

/** A one-sample track from the drawn pose, used when there is no sweep to play (see main.js). */
export function staticTrack(scene, param = 'angle', value = 0, positions = null) {
  const points = {};
  for (const [name, xy] of Object.entries(scene.points || {})) points[name] = { position: [positions?.[name] || xy] };
  for (const [name, xy] of Object.entries(positions || {})) if (!points[name]) points[name] = { position: [xy] };
  return { param, values: [value], n: 1, points, links: {}, sliders: [], fourBarLoops: [], feasible: true, limits: [], warnings: [], closed: false, static: true };
}

function lerp2(a, b, f) {
  if (!a) return null;
  if (!b || f === 0) return a;
  return [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f];
}

function split(track, u) {
  const max = track.n - 1;
  const clamped = Math.min(Math.max(u, 0), max);
  const i = Math.min(Math.floor(clamped), Math.max(max - 1, 0));
  return [i, Math.min(i + 1, max), clamped - i];
}

/** The parts of a moving point's (or slider's) motion, as the API names them. */
export const PARTS = ['transport_velocity', 'relative_velocity', 'transport_acceleration', 'relative_acceleration', 'coriolis_acceleration'];

/** Joints and moving points of an /analyze answer that carry transport/relative/Coriolis parts. */
export function componentSources(analysis) {
  const out = [];
  for (const j of analysis.joints || []) if (j.transport_velocity || j.transport_acceleration) out.push(j);
  for (const [name, m] of Object.entries(analysis.moving_points || {})) out.push({ ...m, point: name });
  return out;
}

/**
 * Positions (and velocities, accelerations, and the transport/relative/Coriolis parts of moving
 * points, when the sweep has them) at fractional index u.
 */
export function frameAt(track, u) {
  const [i, j, f] = split(track, u);
  const frame = { position: {}, velocity: {}, acceleration: {}, parts: {}, u };
  for (const [name, q] of Object.entries(track.points)) {
    if (q.position) frame.position[name] = lerp2(q.position[i], q.position[j], f);
    if (q.velocity) frame.velocity[name] = lerp2(q.velocity[i], q.velocity[j], f);
    if (q.acceleration) frame.acceleration[name] = lerp2(q.acceleration[i], q.acceleration[j], f);
    for (const part of PARTS) {
      if (!Array.isArray(q[part])) continue;
      frame.parts[name] = frame.parts[name] || {};
      frame.parts[name][part] = lerp2(q[part][i], q[part][j], f);
    }
  }
  // The slots' axes as the server sent them (a guide's drawn axis turned with it), by point.
  frame.axis = {};
  for (const s of track.sliders || []) if (s.axis) frame.axis[s.point] = lerp2(s.axis[i], s.axis[j], f);
  return frame;
}

export function valueAt(track, u) {
  const [i, j, f] = split(track, u);
  return track.values[i] + (track.values[j] - track.values[i]) * f;
}

/** Fractional index of a driver angle or time (values are monotonic, either direction). */
export function indexOfValue(track, value) {
  const v = track.values;
  if (track.n === 1) return 0;
  const rising = v[v.length - 1] >= v[0];
  let target = value;
  const lo = Math.min(v[0], v[v.length - 1]);
  const hi = Math.max(v[0], v[v.length - 1]);
  if (track.param === 'angle' && track.closed) {
    // Bring the angle into the swept revolution so that 370 deg finds 10 deg.
    target = lo + ((((value - lo) % (2 * Math.PI)) + 2 * Math.PI) % (2 * Math.PI));
  } else if (track.param === 'angle') {
    // A rocking crank: the turn of 2 pi nearest to its range (atan2 gives -pi..pi).
    const mid = (lo + hi) / 2;
    target = value + 2 * Math.PI * Math.round((mid - value) / (2 * Math.PI));
  }
  const key = (x) => (rising ? x : -x);
  const t = key(target);
  if (t <= key(v[0])) return 0;
  if (t >= key(v[v.length - 1])) return v.length - 1;
  let a = 0;
  let b = v.length - 1;
  while (b - a > 1) {
    const mid = (a + b) >> 1;
    if (key(v[mid]) <= t) a = mid;
    else b = mid;
  }
  const d = v[b] - v[a];
  return a + (d === 0 ? 0 : (target - v[a]) / d);
}

/**
 * The fewest samples for which the animation's linear interpolation strays at most `px` screen
 * pixels from the true path, at `pxPerMetre`: between samples h apart a smooth path is missed by
 * at most h²/8 |p''|, i.e. |p[i+1] − 2p[i] + p[i−1]|/8, which falls as 1/n² (benchmarks/
 * bench_tradeoff.py measures this estimate at 0.97 to 1.00 of the true error from 36 samples on).
 * So n' = n √(e/px) from the largest estimate e of this track's n samples, and never fewer than
 * `least` (for the cycle plots) nor more than `most`.
 */
export function samplesFor(track, pxPerMetre, { px = 0.5, least = 2, most = 3601 } = {}) {
  let worst = 0;
  for (const q of Object.values(track.points)) {
    const p = q.position || [];
    for (let i = 1; i + 1 < p.length; i++) {
      if (!p[i - 1] || !p[i] || !p[i + 1]) continue;
      const d = Math.hypot(p[i + 1][0] - 2 * p[i][0] + p[i - 1][0], p[i + 1][1] - 2 * p[i][1] + p[i - 1][1]);
      worst = Math.max(worst, (d / 8) * pxPerMetre);
    }
  }
  const n = Math.ceil(track.n * Math.sqrt(worst / px));
  return Math.min(most, Math.max(least, n));
}

/** Bounding box of every position in the track: [xmin, ymin, xmax, ymax]. */
export function extent(track) {
  let box = [Infinity, Infinity, -Infinity, -Infinity];
  for (const q of Object.values(track.points)) {
    for (const p of q.position || []) {
      if (!p) continue;
      box = [Math.min(box[0], p[0]), Math.min(box[1], p[1]), Math.max(box[2], p[0]), Math.max(box[3], p[1])];
    }
  }
  if (!Number.isFinite(box[0])) box = [-1, -1, 1, 1];
  return box;
}

/**
 * A typical large magnitude of a per-point quantity over the track, for arrow scaling: the 95th
 * percentile, not the maximum, so that one near-singular sample (a guide whipping round) does not
 * shrink every other arrow to a dot.
 */
export function typicalNorm(track, quantity, q = 0.95) {
  const norms = [];
  for (const p of Object.values(track.points)) {
    for (const v of p[quantity] || []) if (v) norms.push(Math.hypot(v[0], v[1]));
  }
  if (!norms.length) return 0;
  norms.sort((a, b) => a - b);
  return norms[Math.min(norms.length - 1, Math.floor(q * norms.length))];
}
