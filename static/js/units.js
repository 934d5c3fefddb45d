// units.js: display units.
//
// The scene and every server answer stay in SI (spec: "SI units everywhere"). The units switch
// only changes how numbers are shown and typed: SI (m, rad, rad/s) or workshop units (mm, deg,
// rpm). Converting at the edge of the display keeps a single source of truth and means a
// shared link never depends on the unit setting of whoever made it.

const SYSTEMS = {
  si: {
    length: ['m', 1],
    angle: ['rad', 1],
    omega: ['rad/s', 1],
    alpha: ['rad/s²', 1],
    velocity: ['m/s', 1],
    acceleration: ['m/s²', 1],
    time: ['s', 1],
    jerk: ['m/s³', 1],
    angular_jerk: ['rad/s³', 1],
  },
  mm: {
    length: ['mm', 1000],
    angle: ['deg', 180 / Math.PI],
    omega: ['rpm', 60 / (2 * Math.PI)],
    alpha: ['rad/s²', 1],
    velocity: ['mm/s', 1000],
    acceleration: ['mm/s²', 1000],
    time: ['s', 1],
    jerk: ['mm/s³', 1000],
    angular_jerk: ['rad/s³', 1],
  },
};

/** Which physical kind a unit string of the API (preset parameters) denotes, or null. */
export function kindOfUnit(unit) {
  const u = String(unit || '').replace(/\s/g, '').replace('²', '^2');
  if (u === 'm') return 'length';
  if (u === 'rad') return 'angle';
  if (u === 'rad/s') return 'omega';
  if (u === 'rad/s^2' || u === 'rad/s2') return 'alpha';
  if (u === 'm/s') return 'velocity';
  if (u === 'm/s^2' || u === 'm/s2') return 'acceleration';
  if (u === 's') return 'time';
  return null;
}

function entry(kind, system) {
  const table = SYSTEMS[system] || SYSTEMS.si;
  return table[kind] || null;
}

export function unitLabel(kind, system, fallback = '') {
  const e = entry(kind, system);
  return e ? e[0] : fallback;
}

export function toDisplay(kind, value, system) {
  const e = entry(kind, system);
  return e && value !== null && value !== undefined ? value * e[1] : value;
}

export function fromDisplay(kind, value, system) {
  const e = entry(kind, system);
  return e && value !== null && value !== undefined ? value / e[1] : value;
}

/**
 * The app's one rounding rule: a number as a textbook prints it, `digits` significant digits
 * with trailing zeros dropped (0.29, not 0.289999 or 0.2900), no exponent for everyday
 * magnitudes (1e-3 <= |x| < 1e6) and a short one otherwise (1.5e-7, not 1.500e-7); with `scale`
 * (the size of the figure the value belongs to) a value within NOISE · scale of zero is 0.
 * Every view prints numbers through this function (or `show`, `typed`, which use it).
 */
export function fmt(value, digits = 4, scale = 0) {
  if (value === null || value === undefined || Number.isNaN(value)) return '—';
  if (!Number.isFinite(value)) return value > 0 ? '∞' : '−∞';
  const v = denoise(value, scale);
  if (v === 0) return '0';
  const abs = Math.abs(v);
  if (abs >= 1e-3 && abs < 1e6) {
    const decimals = digits - 1 - Math.floor(Math.log10(abs));
    // Above 10^digits the last places are zeros: 123456.7 to 4 digits is 123500.
    const rounded = decimals >= 0 ? v.toFixed(Math.min(decimals, 10)) : Math.round(v / 10 ** -decimals) * 10 ** -decimals;
    const text = Number(rounded).toString();
    return text === '-0' ? '0' : text;
  }
  const [mantissa, exponent] = v.toExponential(digits - 1).split('e');
  return `${Number(mantissa)}e${exponent.replace('+', '')}`;
}

/** Significant digits of a value put back into a field: 15, every digit a double holds without its last-place noise. */
export const TYPED_DIGITS = 15;

/**
 * A value shown in a field, in the digits the user typed: the value at TYPED_DIGITS significant
 * digits, trailing zeros dropped, so 0.1 + 0.2 reads 0.3 and 0.28999999999999998 reads 0.29.
 */
export function typed(value) {
  if (typeof value !== 'number') return String(value ?? '');
  if (!Number.isFinite(value)) return String(value);
  return Number(value.toPrecision(TYPED_DIGITS)).toString();
}

/** Relative size under which a value is rounding noise of the figure it belongs to. */
export const NOISE = 1e-12;

/**
 * 0 where |value| <= NOISE · scale (scale: the size of the figure the value belongs to, e.g. the
 * drawing's extent in m): a pole at (-3.7e-41, 2.09) m is at (0, 2.09) m as a textbook prints it.
 */
export function denoise(value, scale) {
  return scale > 0 && Math.abs(value) <= NOISE * scale ? 0 : value;
}

/** "1.234 m/s" in the chosen system; with `scale` (SI, as value), float noise shown as 0. */
export function show(kind, value, system, digits = 4, scale = 0) {
  return `${fmt(toDisplay(kind, denoise(value, scale), system), digits)} ${unitLabel(kind, system)}`;
}
