// plots.js: quantities over the cycle, from the one sweep the animation already has.
//
// Four stacked panels sharing the x axis (driver angle, or time for relative-motion scenes):
// link angles, link omegas, link alphas, and the speed of a chosen point. A vertical cursor
// marks the analysed instant; moving it is a relayout of one shape, not a redraw.

import { COLOURS } from './theme.js';
import { linkColours } from './scene.js';
import { toDisplay, unitLabel } from './units.js';

const CONFIG = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ['select2d', 'lasso2d', 'toImage'] };

function unwrap(values) {
  // Angles from atan2 jump by 2 pi; a plot of a crank angle should be a straight line.
  const out = [];
  let offset = 0;
  for (let i = 0; i < values.length; i++) {
    if (i > 0 && values[i] !== null && values[i - 1] !== null) {
      const d = values[i] + offset - out[i - 1];
      if (d > Math.PI) offset -= 2 * Math.PI;
      else if (d < -Math.PI) offset += 2 * Math.PI;
    }
    out.push(values[i] === null ? null : values[i] + offset);
  }
  return out;
}

function xValues(track, units) {
  if (track.param === 'time') return { x: track.values, title: `time t [s]` };
  return {
    x: track.values.map((v) => toDisplay('angle', v, units)),
    title: `driver angle [${unitLabel('angle', units)}]`,
  };
}

/** What the plots can show from this track (a position-only sweep has no omega/alpha). */
export function available(track) {
  const links = Object.entries(track.links || {});
  const has = (q) => links.some(([, l]) => Array.isArray(l[q]));
  const speed = Object.values(track.points).some((p) => Array.isArray(p.velocity));
  return { angle: has('angle'), omega: has('omega'), alpha: has('alpha'), speed };
}

export function renderPlots(div, scene, track, { links = [], point = null, units = 'si', cursor = null } = {}) {
  const P = globalThis.Plotly;
  if (!P || !track || track.n < 2) return false;
  const colours = linkColours(scene);
  const { x, title } = xValues(track, units);
  const rows = [
    ['angle', `angle [${unitLabel('angle', units)}]`, 'angle'],
    ['omega', `ω [${unitLabel('omega', units)}]`, 'omega'],
    ['alpha', `α [${unitLabel('alpha', units)}]`, 'alpha'],
  ];
  const have = available(track);
  const shown = rows.filter(([q]) => have[q]);
  const panels = shown.length + (have.speed && point ? 1 : 0);
  if (!panels) return false;
  const traces = [];
  const layout = {
    margin: { l: 64, r: 16, t: 16, b: 44 },
    showlegend: true,
    legend: { orientation: 'h', y: 1.06, x: 0, font: { size: 11 } },
    paper_bgcolor: '#ffffff',
    plot_bgcolor: '#ffffff',
    font: { family: 'system-ui, -apple-system, "Segoe UI", Roboto, sans-serif', color: COLOURS.ink, size: 12 },
    hovermode: 'x unified',
    uirevision: `plots-${scene.title || ''}`,
    shapes: [],
  };
  const gap = 0.05;
  const h = (1 - gap * (panels - 1)) / panels;
  const axisFor = (i) => (i === 0 ? '' : String(i + 1));
  shown.forEach(([q, label, kind], i) => {
    const ax = axisFor(i);
    const top = 1 - i * (h + gap);
    layout[`yaxis${ax}`] = { title: { text: label, font: { size: 12 } }, domain: [top - h, top], gridcolor: '#eef0f3', zerolinecolor: '#d1d5db' };
    for (const name of links) {
      const series = track.links?.[name]?.[q];
      if (!Array.isArray(series)) continue;
      const y = (q === 'angle' ? unwrap(series) : series).map((v) => (v === null ? null : toDisplay(kind, v, units)));
      traces.push({
        type: 'scatter', mode: 'lines', x, y, xaxis: 'x', yaxis: `y${ax}`,
        name: `link ${name}`, legendgroup: name, showlegend: i === 0,
        line: { color: colours[name], width: 2 },
        hovertemplate: `${q} ${name}: %{y:.4g}<extra></extra>`,
      });
    }
  });
  if (have.speed && point && track.points[point]?.velocity) {
    const i = shown.length;
    const ax = axisFor(i);
    const top = 1 - i * (h + gap);
    layout[`yaxis${ax}`] = { title: { text: `|v_${point}| [${unitLabel('velocity', units)}]`, font: { size: 12 } }, domain: [top - h, top], gridcolor: '#eef0f3', rangemode: 'tozero' };
    traces.push({
      type: 'scatter', mode: 'lines', x, xaxis: 'x', yaxis: `y${ax}`,
      y: track.points[point].velocity.map((v) => (v ? toDisplay('velocity', Math.hypot(v[0], v[1]), units) : null)),
      name: `speed of ${point}`, line: { color: COLOURS.velocity, width: 2 },
      hovertemplate: `|v_${point}|: %{y:.4g}<extra></extra>`,
    });
  }
  layout.xaxis = { title: { text: title }, anchor: `y${axisFor(panels - 1)}`, gridcolor: '#eef0f3', zeroline: false };
  // Every panel shares the x axis; show tick labels only on the bottom one.
  layout.shapes = cursorShapes(cursor, track, units);
  P.react(div, traces, layout, CONFIG);
  return true;
}

function cursorShapes(cursor, track, units) {
  if (cursor === null || cursor === undefined) return [];
  const x = track.param === 'time' ? cursor : toDisplay('angle', cursor, units);
  return [{ type: 'line', xref: 'x', yref: 'paper', x0: x, x1: x, y0: 0, y1: 1, line: { color: COLOURS.ink, width: 1.5, dash: 'dot' } }];
}

/** Move the cursor to the analysed instant without redrawing the curves. */
export function moveCursor(div, track, cursor, units) {
  const P = globalThis.Plotly;
  if (!P || !div.data) return;
  P.relayout(div, { shapes: cursorShapes(cursor, track, units) });
}
