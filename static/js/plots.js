// plots.js: quantities over the cycle, from the one sweep the animation already has.
//
// Stacked panels sharing the x axis (driver angle 0..360 deg or time, see series.js): link
// angles, ω and α of the chosen links, then the chosen quantity (a point's position, velocity
// or acceleration with its components, a slider's s, v, a along its guide, or the transmission
// angle with its extremes). A vertical cursor marks the analysed instant; moving it is a relayout
// of one shape, not a redraw. The series come from series.js, the same list the CSV export writes.

import { pointName } from './notation.js';
import { COLOURS } from './theme.js';
import { linkColours } from './scene.js';
import { unitLabel, toDisplay, fmt } from './units.js';
import { cycleOrder, plottedAngle, xValues, allSeries, extremes, groundSliders, timeRatio } from './series.js';

const CONFIG = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ['select2d', 'lasso2d'], toImageButtonOptions: { filename: 'plots' } };
const TWO_PI = 2 * Math.PI;

/** What the plots can show from this track (a position-only sweep has no omega/alpha). */
export function available(track) {
  const links = Object.entries(track.links || {});
  const has = (q) => links.some(([, l]) => Array.isArray(l[q]));
  const speed = Object.values(track.points).some((p) => Array.isArray(p.velocity));
  return { angle: has('angle'), omega: has('omega'), alpha: has('alpha'), speed };
}

/** The quantities a student can add under the link panels: [{value, label, panels: [[keys]]}]. */
export function quantityChoices(series) {
  const keys = new Set(series.map((s) => s.key));
  const choices = [];
  const points = [...new Set(series.filter((s) => s.key.startsWith('point:')).map((s) => s.key.split(':')[1]))];
  for (const s of series.filter((x) => x.key.startsWith('slider:') && x.key.endsWith(':s'))) {
    const p = s.key.split(':')[1];
    choices.push({ value: `slider:${p}`, label: `slider ${pointName(p)}: position, velocity, acceleration`, panels: ['s', 'v', 'a'].map((k) => [`slider:${p}:${k}`]).filter(([k]) => keys.has(k)) });
  }
  for (const s of series.filter((x) => x.key.startsWith('transmission:'))) {
    choices.push({ value: s.key, label: 'transmission angle μ', panels: [[s.key]] });
  }
  for (const p of points) {
    const has = (k) => keys.has(`point:${p}:${k}`);
    if (has('v')) choices.push({ value: `point:${p}:velocity`, label: `${pointName(p)}: velocity (vx, vy, |v|)`, panels: [[`point:${p}:v`, `point:${p}:vx`, `point:${p}:vy`]] });
    if (has('a')) choices.push({ value: `point:${p}:acceleration`, label: `${pointName(p)}: acceleration (ax, ay, |a|)`, panels: [[`point:${p}:a`, `point:${p}:ax`, `point:${p}:ay`]] });
    if (has('x')) choices.push({ value: `point:${p}:position`, label: `${pointName(p)}: position (x, y)`, panels: [[`point:${p}:x`, `point:${p}:y`]] });
    if (has('v') && has('a')) choices.push({ value: `point:${p}:all`, label: `${pointName(p)}: displacement, velocity, acceleration`, panels: [[`point:${p}:x`, `point:${p}:y`], [`point:${p}:v`, `point:${p}:vx`, `point:${p}:vy`], [`point:${p}:a`, `point:${p}:ax`, `point:${p}:ay`]] });
  }
  return choices;
}

/** The plot's x value of an instant (driver angle or time, SI) on the chosen axis. */
function cursorX(scene, track, axis, value, units) {
  if (value === null || value === undefined) return null;
  if (track.param === 'time') return value;
  if (axis === 'time') {
    const omega = scene.drivers[0].omega;
    return (((value - track.values[0]) / omega) % (TWO_PI / Math.abs(omega)) + TWO_PI / Math.abs(omega)) % (TWO_PI / Math.abs(omega));
  }
  return toDisplay('angle', plottedAngle(track, value), units);
}

/**
 * Draw the panels. `sel` = {links, quantity, axis, units, cursor}. Returns
 * {ok, facts: [sentences]} (facts: transmission extremes, quick-return ratio).
 */
export function renderPlots(div, scene, track, { links = [], quantity = null, axis = 'angle', units = 'si', cursor = null } = {}) {
  const P = globalThis.Plotly;
  if (!P || !track || track.n < 2) return { ok: false, facts: [] };
  const colours = linkColours(scene);
  const order = cycleOrder(track);
  const xs = xValues(scene, track, order, axis, units);
  const series = allSeries(scene, track, order, units);
  const byKey = new Map(series.map((s) => [s.key, s]));
  // On a time axis the samples are reordered by time (one period from t = 0).
  let perm = xs.x.map((_, i) => i);
  if (xs.sort) perm.sort((a, b) => xs.x[a] - xs.x[b]);
  const X = perm.map((i) => xs.x[i]);
  const Y = (s) => perm.map((i) => s.y[i]);

  const panels = [];
  for (const q of ['angle', 'omega', 'alpha']) {
    const keys = links.map((l) => `link:${l}:${q}`).filter((k) => byKey.has(k));
    if (keys.length) panels.push({ keys, title: `${q === 'angle' ? 'φ' : q === 'omega' ? 'ω' : 'α'} [${unitLabel(q, units)}]`, link: true });
  }
  const choice = quantityChoices(series).find((c) => c.value === quantity);
  for (const keys of choice?.panels || []) {
    const first = byKey.get(keys[0]);
    panels.push({ keys, title: `${shortName(keys[0])} [${first.unit}]` });
  }
  if (!panels.length) return { ok: false, facts: [] };

  const traces = [];
  const layout = {
    margin: { l: 64, r: 16, t: 58, b: 44 },
    showlegend: true,
    legend: { orientation: 'h', y: 1, yanchor: 'bottom', x: 0, font: { size: 11 } },
    paper_bgcolor: '#ffffff',
    plot_bgcolor: '#ffffff',
    font: { family: 'system-ui, -apple-system, "Segoe UI", Roboto, sans-serif', color: COLOURS.ink, size: 12 },
    hovermode: 'x unified',
    uirevision: `plots-${scene.title || ''}-${axis}`,
    shapes: [],
    annotations: [],
  };
  const gap = 0.05;
  const h = (1 - gap * (panels.length - 1)) / panels.length;
  const axisFor = (i) => (i === 0 ? '' : String(i + 1));
  const facts = [];
  const componentColours = [COLOURS.velocity, '#2a9d8f', '#d08c2c'];
  panels.forEach((panel, i) => {
    const ax = axisFor(i);
    const top = 1 - i * (h + gap);
    layout[`yaxis${ax}`] = { title: { text: panel.title, font: { size: 12 } }, domain: [top - h, top], gridcolor: '#eef0f3', zerolinecolor: '#d1d5db' };
    panel.keys.forEach((key, k) => {
      const s = byKey.get(key);
      if (!s) return;
      const name = panel.link ? `link ${key.split(':')[1]}` : s.label;
      traces.push({
        type: 'scatter', mode: 'lines', x: X, y: Y(s), xaxis: 'x', yaxis: `y${ax}`,
        name, legendgroup: panel.link ? key.split(':')[1] : key, showlegend: !panel.link || i === 0,
        line: { color: panel.link ? colours[key.split(':')[1]] : componentColours[k % 3], width: k === 0 ? 2.2 : 1.6, dash: !panel.link && k > 0 ? 'dot' : 'solid' },
        hovertemplate: `${s.label}: %{y:.4g} ${s.unit}<extra></extra>`,
      });
      if (key.startsWith('transmission:')) {
        const { lo, hi } = extremes(X, Y(s));
        const xu = xs.kind === 'time' ? 's' : unitLabel('angle', units);
        for (const [e, what] of [[lo, 'min'], [hi, 'max']]) {
          if (!e) continue;
          traces.push({ type: 'scatter', mode: 'markers+text', x: [e.x], y: [e.y], xaxis: 'x', yaxis: `y${ax}`, showlegend: false, text: [`${what} ${fmt(e.y, 4)}`], textposition: what === 'min' ? 'bottom center' : 'top center', marker: { size: 8, color: COLOURS.acceleration }, hoverinfo: 'skip' });
        }
        if (lo && hi) facts.push(`Transmission angle ${s.label.replace('transmission angle ', '')}: min ${fmt(lo.y, 4)} ${s.unit} at ${fmt(lo.x, 4)} ${xu}, max ${fmt(hi.y, 4)} ${s.unit} at ${fmt(hi.x, 4)} ${xu}.`);
      }
    });
  });
  for (const slider of groundSliders(scene, track)) {
    if (quantity !== `slider:${slider.point}`) continue;
    const r = timeRatio(slider);
    if (r) facts.push(`Quick-return time ratio of ${slider.point}: ${fmt(r.ratio, 4)} (slower stroke over ${fmt(toDisplay('angle', r.slow, units), 4)} ${unitLabel('angle', units)} of crank turn, faster over ${fmt(toDisplay('angle', r.fast, units), 4)} ${unitLabel('angle', units)}).`);
  }
  const last = axisFor(panels.length - 1);
  layout.xaxis = { title: { text: xs.title }, anchor: `y${last}`, gridcolor: '#eef0f3', zeroline: false };
  if (xs.kind === 'angle' && track.closed) {
    const full = toDisplay('angle', TWO_PI, units);
    layout.xaxis.range = [0, full];
    if (units !== 'si') layout.xaxis.dtick = 45;
  }
  layout.shapes = cursorShapes(cursorX(scene, track, axis, cursor, units));
  // Each panel keeps a readable height however many are stacked.
  div.style.height = `${Math.max(360, 110 + 120 * panels.length)}px`;
  P.react(div, traces, layout, { ...CONFIG, toImageButtonOptions: { filename: `${slug(scene.title)}-plots` } });
  div.dataset.axis = axis;
  return { ok: true, facts };
}

/** A panel's title: its quantity and point (a Greek letter spelled out written as the letter). */
function shortName(key) {
  const [group, raw, q] = key.split(':');
  const name = pointName(raw);
  if (group === 'slider') return { s: `s of ${name}`, v: `v of ${name}`, a: `a of ${name}` }[q];
  if (group === 'transmission') return 'μ';
  if (group === 'point') return { x: `x, y of ${name}`, y: `y of ${name}`, v: `v of ${name}`, a: `a of ${name}` }[q] || `${q} of ${name}`;
  return key;
}

export function slug(text) {
  return String(text || 'mechanism').toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '') || 'mechanism';
}

function cursorShapes(x) {
  if (x === null || x === undefined) return [];
  return [{ type: 'line', xref: 'x', yref: 'paper', x0: x, x1: x, y0: 0, y1: 1, line: { color: COLOURS.ink, width: 1.5, dash: 'dot' } }];
}

/** Move the cursor to the analysed instant without redrawing the curves. */
export function moveCursor(div, scene, track, cursor, units) {
  const P = globalThis.Plotly;
  if (!P || !div.data) return;
  P.relayout(div, { shapes: cursorShapes(cursorX(scene, track, div.dataset.axis || 'angle', cursor, units)) });
}
