// polygons.js: the velocity and acceleration polygons (plane-figure.js: SVG, equal axis scales).
//
// Drawn as a textbook draws them: every absolute vector from the pole of the polygon, labelled
// with the lowercase name of its point (b for B); the image of each link joins the tips of its
// points. In the velocity polygon each image segment B->P not from the pole is also drawn as the
// arrow v_PB = omega x r; in the acceleration polygon as its normal part (-omega^2 r, towards the
// base point) then its tangential part (alpha x r), and every slider or moving point as
// transport + Coriolis + relative, head to tail. Each of these vectors is labelled at its
// midpoint with the worked solution's name (v_PB, a^n_PB, a^t_PB, a_P,Cor, a_P,rel).
//
// Every vector is the server's: the segments, their base points and their order are those of the
// worked solution (/solution's `polygons`); this module only places them head to tail.

import { afterPaint } from './playback.js';
import { COLOURS } from './theme.js';
import { linkColours, movingLinks } from './scene.js';
import { toDisplay, unitLabel, fmt } from './units.js';
import { componentSources } from './track.js';
import { imageName, pointName, POLYGON_POLE } from './notation.js';
import { placeLabels, plotArea, equalRanges } from './labels.js';
import { renderDetail } from './polygon-detail.js';
import { showFigure, showTraces, clearFigure, dashArray } from './plane-figure.js';
import { svgEl } from './svg.js';

const TINY = 1e-12;

const lower = imageName;

/** A trace of arrows: segments [from, to, label] drawn as lines with an arrowhead at `to`. */
function arrows(name, segments, colour, { dash = 'solid', width = 2.4, group = name, showlegend = true } = {}) {
  const x = [];
  const y = [];
  const size = [];
  const text = [];
  for (const [a, b, label] of segments) {
    x.push(a[0], b[0], null);
    y.push(a[1], b[1], null);
    size.push(0, 11, 0);
    text.push(label, label, null);
  }
  return {
    type: 'scatter',
    mode: 'lines+markers',
    name,
    legendgroup: group,
    showlegend: showlegend && segments.length > 0,
    x,
    y,
    text,
    hoverinfo: 'text',
    line: { color: colour, width, dash },
    marker: { symbol: 'arrow', angleref: 'previous', size, color: colour },
    cliponaxis: false,
  };
}

function vecText(symbol, v, kind, units) {
  const u = unitLabel(kind, units);
  return `${symbol} = (${fmt(v[0])}, ${fmt(v[1])}) ${u}, |${symbol}| = ${fmt(Math.hypot(v[0], v[1]))} ${u}`;
}

const add = (a, b) => [a[0] + b[0], a[1] + b[1]];
const midpoint = (a, b) => [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];

/** v_CB, aⁿ_CB, aᵗ_CB: the vector of `seg.point` relative to `seg.base` (the worked solution's names). */
const relativeName = (symbol, seg, part = '') => `${symbol}${part ? `<sup>${part}</sup>` : ''}<sub>${pointName(seg.point)}${pointName(seg.base)}</sub>`;

/** v_B,rel, a_B,Cor: a part of the motion of a slider or moving point. */
const slidingName = (symbol, point, part) => `${symbol}<sub>${point},${part}</sub>`;
const norm = (a) => Math.hypot(a[0], a[1]);

/**
 * The layout of a polygon titled `title`, with `note` (optional: {text, colour}) heading its
 * legend.
 */
function baseLayout(title, kind, units, note = null) {
  // The unit goes into the title: axis titles would collide with the legend under the plot.
  const u = unitLabel(kind, units);
  return {
    title: { text: `${title} <span style="font-size:12px;color:#6b7280">[${u}]</span>`, font: { size: 15 }, x: 0.02, xanchor: 'left' },
    // Fixed margins, so that the plot area is the div's size less them, known before the figure
    // is drawn (labels.js, plotArea): the x axis' tick labels end 19 px under the axes, 9 px clear
    // of the legend under the figure.
    margin: { l: 44, r: 12, t: 38, b: 28 },
    xaxis: { zeroline: true, zerolinecolor: '#d1d5db', gridcolor: '#eef0f3' },
    yaxis: { zeroline: true, zerolinecolor: '#d1d5db', gridcolor: '#eef0f3', scaleanchor: 'x', scaleratio: 1 },
    // The legend is drawn in HTML under the figure (drawLegend); this one is an exported image's
    // (`withLegend`), at the bottom of the image, under the tick labels, headed by the note.
    showlegend: false,
    legend: {
      orientation: 'h', yref: 'container', y: 0, yanchor: 'bottom', font: { size: 11 }, tracegroupgap: 0,
      ...(note ? { title: { text: note.text, side: 'top', font: { size: 11, color: note.colour } } } : {}),
    },
    paper_bgcolor: '#ffffff',
    plot_bgcolor: '#ffffff',
    font: { family: 'system-ui, -apple-system, "Segoe UI", Roboto, sans-serif', color: COLOURS.ink },
    hovermode: 'closest',
    annotations: [],
  };
}

// px: a polygon narrower than this is "narrow": its detail's title is written smaller. At 1440x900
// the polygons are 439 px wide (beside), at 1366 406 px and at 1280 369 px (under), on a phone 340.
const NARROW = 430;

/** Points of the analysis with their vectors, converted to display units. */
function collect(scene, analysis, quantity, units) {
  const kind = quantity;
  const out = {};
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const [name, q] of Object.entries(group || {})) {
      if (q[quantity]) out[name] = q[quantity].map((c) => toDisplay(kind, c, units));
    }
  }
  return out;
}

function linkImages(scene, analysis, tips, quantity) {
  const colours = linkColours(scene);
  const traces = [];
  let first = true;
  for (const name of movingLinks(scene)) {
    const pts = scene.links[name].points.filter((p) => tips[p]);
    if (pts.length < 2) continue;
    // Same corner order as the drawn plate, so the image reads as the link turned and scaled.
    const pos = (p) => analysis.points?.[p]?.position || scene.points[p];
    const c = pts.reduce((acc, p) => add(acc, pos(p)), [0, 0]).map((v) => v / pts.length);
    const ordered = pts.length > 2 ? [...pts].sort((a, b) => Math.atan2(pos(a)[1] - c[1], pos(a)[0] - c[0]) - Math.atan2(pos(b)[1] - c[1], pos(b)[0] - c[0])) : pts;
    const loop = [...ordered, ordered[0]];
    traces.push({
      type: 'scatter',
      mode: 'lines',
      // One legend entry for all images keeps the legend short; hover names the link.
      name: 'images of the links',
      legendgroup: 'images',
      showlegend: first,
      text: `${quantity} image of link ${name}`,
      x: loop.map((p) => tips[p][0]),
      y: loop.map((p) => tips[p][1]),
      fill: pts.length > 2 ? 'toself' : 'none',
      fillcolor: hexAlpha(colours[name], 0.14),
      line: { color: colours[name], width: pts.length > 2 ? 1.5 : 3, dash: pts.length > 2 ? 'solid' : 'dot' },
      hoverinfo: 'text',
    });
    first = false;
  }
  return traces;
}

function hexAlpha(hex, alpha) {
  const n = parseInt(hex.slice(1), 16);
  return `rgba(${(n >> 16) & 255},${(n >> 8) & 255},${n & 255},${alpha})`;
}

function poleLabel(pole, tips) {
  const atPole = Object.entries(tips).filter(([, v]) => norm(v) < TINY).map(([n]) => lower(n));
  return atPole.length ? `${pole} ≡ ${atPole.join(', ')}` : pole;
}

export function velocityFigure(scene, analysis, polygons, units, narrow) {
  const tips = collect(scene, analysis, 'velocity', units);
  const segments = polygons?.segments || [];
  const parts = []; // labels of the relative and component vectors, after the points'
  const traces = [...linkImages(scene, analysis, tips, 'velocity')];
  const abs = [];
  const lab = [];
  for (const [name, v] of Object.entries(tips)) {
    if (norm(v) < TINY) continue;
    abs.push([[0, 0], v, vecText(`v_${pointName(name)}`, v, 'velocity', units)]);
    lab.push([v, lower(name)]);
  }
  // Relative velocities v_PB = ω × r_BP of the image segments, in the vector method's order
  // (a segment from a point at the pole is the absolute vector itself: not drawn twice).
  const relative = [];
  for (const seg of segments) {
    const vBase = tips[seg.base];
    if (!vBase || !tips[seg.point] || norm(vBase) < TINY) continue;
    const vr = seg.velocity.map((c) => toDisplay('velocity', c, units));
    if (norm(vr) < TINY) continue;
    relative.push([vBase, add(vBase, vr), vecText(`v_${pointName(seg.point)}${pointName(seg.base)}`, vr, 'velocity', units)]);
    parts.push([midpoint(vBase, add(vBase, vr)), relativeName('v', seg), COLOURS.velocity]);
  }
  traces.push(arrows('v relative to a point, ω×r', relative, COLOURS.velocity, { width: 1.4, dash: 'dot' }));
  traces.push(arrows('absolute velocity', abs, COLOURS.velocity));
  const tr = [];
  const rel = [];
  for (const j of componentSources(analysis)) {
    if (!j.transport_velocity || !j.relative_velocity) continue;
    const vt = j.transport_velocity.map((c) => toDisplay('velocity', c, units));
    const vr = j.relative_velocity.map((c) => toDisplay('velocity', c, units));
    if (norm(vt) > TINY) {
      tr.push([[0, 0], vt, vecText(`v_${j.point},tr`, vt, 'velocity', units)]);
      lab.push([vt, `${lower(j.point)}<sub>tr</sub>`, COLOURS.transport]);
    }
    if (norm(vr) > TINY) {
      rel.push([vt, add(vt, vr), vecText(`v_${j.point},rel`, vr, 'velocity', units)]);
      parts.push([midpoint(vt, add(vt, vr)), slidingName('v', j.point, 'rel'), COLOURS.relative]);
    }
  }
  traces.push(arrows('transport velocity', tr, COLOURS.transport, { dash: 'dash', width: 2 }));
  traces.push(arrows('relative velocity', rel, COLOURS.relative, { width: 2 }));
  lab.unshift([[0, 0], poleLabel(POLYGON_POLE.velocity, tips)]);
  return { traces, labels: [...lab, ...parts], layout: baseLayout('Velocity polygon', 'velocity', units), narrow };
}

export function accelerationFigure(scene, analysis, polygons, units, narrow) {
  const tips = collect(scene, analysis, 'acceleration', units);
  const traces = [...linkImages(scene, analysis, tips, 'acceleration')];
  const abs = [];
  const lab = [];
  const parts = []; // labels of the component vectors, after the points'
  for (const [name, a] of Object.entries(tips)) {
    if (norm(a) < TINY) continue;
    abs.push([[0, 0], a, vecText(`a_${pointName(name)}`, a, 'acceleration', units)]);
    lab.push([a, lower(name)]);
  }
  // Normal and tangential parts of each image segment, in the worked solution's order.
  const normal = [];
  const tangential = [];
  for (const seg of polygons?.segments || []) {
    const aBase = tips[seg.base];
    if (!aBase || !tips[seg.point]) continue;
    const an = seg.normal.map((c) => toDisplay('acceleration', c, units));
    const at = seg.tangential.map((c) => toDisplay('acceleration', c, units));
    const tag = `${pointName(seg.point)}${pointName(seg.base)}`;
    const corner = add(aBase, an);
    if (norm(an) > TINY) {
      normal.push([aBase, corner, vecText(`aⁿ_${tag}`, an, 'acceleration', units)]);
      parts.push([midpoint(aBase, corner), relativeName('a', seg, 'n'), COLOURS.normal]);
    }
    if (norm(at) > TINY) {
      tangential.push([corner, add(corner, at), vecText(`aᵗ_${tag}`, at, 'acceleration', units)]);
      parts.push([midpoint(corner, add(corner, at)), relativeName('a', seg, 't'), COLOURS.tangential]);
    }
  }
  traces.push(arrows('normal part −ω²r', normal, COLOURS.normal, { width: 1.8 }));
  traces.push(arrows('tangential part α×r', tangential, COLOURS.tangential, { width: 1.8 }));
  traces.push(arrows('absolute acceleration', abs, COLOURS.acceleration));

  const tr = [];
  const cor = [];
  const rel = [];
  const zeroCoriolis = [];
  for (const j of componentSources(analysis)) {
    if (!j.transport_acceleration) continue;
    const conv = (v) => (v || [0, 0]).map((c) => toDisplay('acceleration', c, units));
    const at = conv(j.transport_acceleration);
    const ac = conv(j.coriolis_acceleration);
    const ar = conv(j.relative_acceleration);
    if (norm(at) > TINY) {
      tr.push([[0, 0], at, vecText(`a_${j.point},tr`, at, 'acceleration', units)]);
      lab.push([at, `${lower(j.point)}<sub>tr</sub>`, COLOURS.transport]);
    }
    const atc = add(at, ac);
    if (norm(ac) > TINY) {
      cor.push([at, atc, vecText(`a_${j.point},Cor = 2ω×v_rel`, ac, 'acceleration', units)]);
      parts.push([midpoint(at, atc), slidingName('a', j.point, 'Cor'), COLOURS.coriolis]);
    } else zeroCoriolis.push(j.point);
    if (norm(ar) > TINY) {
      rel.push([atc, add(atc, ar), vecText(`a_${j.point},rel`, ar, 'acceleration', units)]);
      parts.push([midpoint(atc, add(atc, ar)), slidingName('a', j.point, 'rel'), COLOURS.relative]);
    }
  }
  traces.push(arrows('transport', tr, COLOURS.transport, { dash: 'dash', width: 2 }));
  traces.push(arrows('Coriolis 2ω×v_rel', cor, COLOURS.coriolis, { width: 2.2 }));
  traces.push(arrows('relative', rel, COLOURS.relative, { width: 2 }));
  lab.unshift([[0, 0], poleLabel(POLYGON_POLE.acceleration, tips)]);
  const note = zeroCoriolis.length
    ? { text: `Coriolis = 0 at ${zeroCoriolis.join(', ')} (guide not turning)`, colour: COLOURS.coriolis }
    : null;
  const layout = baseLayout('Acceleration polygon', 'acceleration', units, note);
  return { traces, labels: [...lab, ...parts], layout, narrow };
}

/** Draw both polygons. */
export function renderPolygons(velDiv, accDiv, scene, analysis, polygons, units) {
  const narrow = velDiv.clientWidth < NARROW; // the two polygons share their column
  if (analysis?.points && Object.values(analysis.points).some((q) => q.velocity)) {
    drawPolygon(velDiv, velocityFigure(scene, analysis, polygons, units, narrow), 'velocity', units);
  }
  if (analysis?.points && Object.values(analysis.points).some((q) => q.acceleration)) {
    drawPolygon(accDiv, accelerationFigure(scene, analysis, polygons, units, narrow), 'acceleration', units);
  }
}

const turns = new WeakMap(); // div -> number of its latest drawing (or clearing)

/**
 * One polygon: its legend (HTML, under the figure), then its figure with its labels, drawn on the
 * plot area the div has with its legend in place (labels.js, plotArea), then (once painted) its
 * detail: the polygon a reader looks at first is not held back by the detail. A newer drawing of
 * the same div stops what is left of an older one, so a fast series of instants never leaves one
 * instant's detail on another's polygon, nor marks a detail done too early.
 */
function drawPolygon(div, figure, kind, units) {
  const turn = (turns.get(div) || 0) + 1;
  turns.set(div, turn);
  const current = () => turns.get(div) === turn;
  drawLegend(div, figure);
  const area = plotArea(div, figure.layout.margin);
  if (!(area.w > 0 && area.h > 0)) return; // not laid out (another family's view is shown)
  div.dataset.detail = 'pending';
  showFigure(div, figure.traces, (ranges) => labelled(figure, area, ranges));
  afterPaint().then(() => current() && renderDetail(div, detailOf(div), figure, kind, units));
}

/** The HTML legend under a polygon (its id the figure's and "-legend"). */
const legendOf = (div) => document.getElementById(`${div.id}-legend`);

/**
 * The legend of `figure` drawn in `div`, in HTML under it, as Plotly's own legend reads (and an
 * exported image's, drawn by Plotly: withLegend): the note (the layout's legend title) first,
 * then one entry per legend group, its first trace's name and line (colour, width, dash; an
 * arrowhead for arrows, a fill for a plate's image). An entry is a button that hides or shows its
 * group's traces (`aria-pressed`).
 */
function drawLegend(div, figure) {
  const note = figure.layout.legend?.title;
  const entries = figure.traces.filter((t) => t.showlegend !== false);
  const items = entries.map((t) => {
    const group = figure.traces.flatMap((u, i) => (u.legendgroup === t.legendgroup ? [i] : []));
    const button = Object.assign(document.createElement('button'), { type: 'button', className: 'legend-entry' });
    button.setAttribute('aria-pressed', 'true');
    button.append(legendSymbol(t), t.name);
    button.addEventListener('click', () => {
      const shown = button.getAttribute('aria-pressed') !== 'true';
      button.setAttribute('aria-pressed', String(shown));
      showTraces(div, group, shown);
    });
    const item = document.createElement('li');
    item.append(button);
    return item;
  });
  if (note) {
    const title = Object.assign(document.createElement('li'), { className: 'legend-note', textContent: note.text });
    title.style.color = note.font.color;
    items.unshift(title);
  }
  legendOf(div).replaceChildren(...items);
}

const SYMBOL_WIDTH = 40; // px, as Plotly's legend draws a trace's line

/** A legend entry's symbol: the trace's line across 40 px, with an arrowhead at its middle for an
 * arrow, over its fill for a plate's image (its dashes the figure's: plane-figure.js, dashArray). */
function legendSymbol(t) {
  const svg = svgEl('svg', { width: SYMBOL_WIDTH, height: 12, 'aria-hidden': 'true' });
  const width = Math.min(t.line.width, 5);
  const dash = dashArray(t.line.dash, t.line.width) || 'none';
  if (t.fill === 'toself') svgEl('rect', { x: 5, y: 1, width: 30, height: 10, fill: t.fillcolor }, svg);
  svgEl('line', { x1: 5, y1: 6, x2: 35, y2: 6, stroke: t.line.color, 'stroke-width': width, 'stroke-dasharray': dash }, svg);
  if (t.marker?.symbol === 'arrow') svgEl('path', { d: 'M 16 2 L 24 6 L 16 10 Z', fill: t.line.color }, svg);
  return svg;
}

/**
 * The figure drawn in `div` with Plotly's legend in it, headed by the note, for an image of it
 * drawn by Plotly (export.js): {data, layout}. The legend takes `room` px at the bottom (as much
 * as the HTML legend takes on the page), under the tick labels: in the figure's own bottom
 * margin it was drawn over them.
 */
export function withLegend(div, room) {
  const { margin } = div.layout;
  return { data: div.data, layout: { ...div.layout, showlegend: true, margin: { ...margin, b: margin.b + room } } };
}

const PAD = 24; // px between the outermost tip and the edge of the plot area (arrowheads)

/**
 * The layout of `figure` at the size and plot area `area` ({width, height, w, h} px: labels.js,
 * plotArea): the axes' `ranges` {x, y} (zoomed: plane-figure.js), or when null ranges that show
 * it whole at equal scales, and the labels of the tips and poles placed on them (labels.js).
 */
function labelled(figure, area, ranges = null) {
  const { x, y } = ranges || equalRanges(figure.traces, area, PAD);
  const entries = figure.labels.map(([at, text, colour]) => ({ at, text, colour }));
  return {
    ...figure.layout,
    width: area.width,
    height: area.height,
    annotations: [...(figure.layout.annotations || []), ...placeLabels({ x, y, w: area.w, h: area.h }, entries, figure.traces)],
    xaxis: { ...figure.layout.xaxis, range: x, autorange: false },
    yaxis: { ...figure.layout.yaxis, range: y, autorange: false },
  };
}

/** The panel under a polygon that shows part of it at its own scale (polygon-detail.js). */
const detailOf = (div) => document.getElementById(`${div.id}-detail`);

export function clearPolygons(...divs) {
  for (const d of divs) {
    turns.set(d, (turns.get(d) || 0) + 1);
    clearFigure(d);
    legendOf(d)?.replaceChildren();
    const detail = detailOf(d);
    if (detail) {
      clearFigure(detail);
      detail.hidden = true;
    }
  }
}
