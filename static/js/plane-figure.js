// plane-figure.js: a figure on axes of equal scales drawn as the page's own SVG: the velocity and
// acceleration polygons and their details (polygons.js, polygon-detail.js).
//
// A figure is described as Plotly describes one: `data`, scatter traces of lines (solid, dot or
// dash; `null` between segments), arrowheads at segment ends (marker 'arrow', sized per point)
// and filled plates ('toself'); `layout`, its size, fixed margins, the axes' ranges (given, never
// autoranged), its title, its labels (annotations shifted from their anchors by xshift/yshift, or
// tied to them by a leader line ax/ay) and dashed rectangles (shapes). The div keeps the figure
// shown as a Plotly div does (`div.data`, `div.layout`), so that an exported image is that figure
// drawn by Plotly (export.js). Plotly drew a polygon in 30 to 50 ms (its axes and layers, and the
// text measures its annotations force); this draws it in a few, without reading the page's layout.
//
// Once the figure has the focus (a click on it, or Tab), the wheel zooms it about the pointer and
// + and − zoom it; so does a pinch on a touchpad (a wheel with Ctrl) at any time, while a wheel
// over a figure not focused scrolls the page, as it did over Plotly's. A mouse drag pans it, a
// double click (or 0) fits it again. A new figure in the div is shown fitted.

import { svgEl, clear } from './svg.js';
import { textWidth, LABEL_HEIGHT } from './labels.js';

const FONT = 'system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const TICK_COLOUR = '#444444';
const TICK_SIZE = 12; // px
const ZOOM_STEP = 1.25;

/** The plot area's pixel of the data point (x, y) in `layout` (fixed margins and ranges). */
function toPixel(layout) {
  const { l, t } = layout.margin;
  const [w, h] = plotSize(layout);
  const [x0, x1] = layout.xaxis.range;
  const [y0, y1] = layout.yaxis.range;
  return ([x, y]) => [l + (w * (x - x0)) / (x1 - x0), t + (h * (y1 - y)) / (y1 - y0)];
}

/** Pixels per data unit of a figure's layout (equal on both axes). */
export function pixelsPerUnit(layout) {
  const [x0, x1] = layout.xaxis.range;
  return plotSize(layout)[0] / (x1 - x0);
}

const plotSize = (layout) => [
  layout.width - layout.margin.l - layout.margin.r,
  layout.height - layout.margin.t - layout.margin.b,
];

/**
 * Tick values over `range` for an axis `px` long, as Plotly chooses them: about one tick per
 * `minPx` px (80 on x, 40 on y), 4 to 9 intervals, the step 1, 2 or 5 times a power of ten.
 * Returns {values, step}.
 */
function niceTicks([a, b], px, minPx) {
  const intervals = Math.min(Math.max(px / minPx, 4), 9) + 1;
  const rough = Math.abs(b - a) / intervals;
  if (!(rough > 0) || !Number.isFinite(rough)) return { values: [], step: 0 };
  const base = 10 ** Math.floor(Math.log10(rough));
  const step = base * [2, 5, 10].find((m) => m >= rough / base);
  const values = [];
  for (let k = Math.ceil(Math.min(a, b) / step); k * step <= Math.max(a, b) + step * 1e-9; k++) values.push(k * step);
  return { values, step };
}

/**
 * A tick's label as Plotly writes it: as many decimals as the step needs, trailing zeros dropped
 * (−1, −0.5, 0), a minus sign for negatives.
 */
function tickText(value, step) {
  const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const text = (Math.abs(value) < step * 1e-9 ? 0 : value).toFixed(decimals);
  return (text.includes('.') ? text.replace(/\.?0+$/, '') : text).replace(/^-/, '−');
}

/**
 * The text `html` (Plotly's subset: <sub>, <sup>, <br>, and <span style="font-size:…;color:…">)
 * as tspans of `text`, line after line `lineHeight` px apart.
 */
function richText(text, html, size, lineHeight) {
  const lines = String(html).split(/<br\s*\/?>/);
  lines.forEach((line, i) => {
    let first = true;
    const parts = line.split(/(<su[bp]>.*?<\/su[bp]>|<span style="[^"]*">.*?<\/span>)/).filter((p) => p !== '');
    let shift = 0; // the baseline's offset left by the previous part (a subscript's)
    for (const part of parts) {
      const sub = part.match(/^<(su[bp])>(.*?)<\/su[bp]>$/);
      const span = part.match(/^<span style="([^"]*)">(.*?)<\/span>$/);
      const attrs = {};
      let content = part;
      let dy = 0;
      if (sub) {
        content = sub[2];
        attrs['font-size'] = `${0.7 * size}`;
        dy = sub[1] === 'sub' ? 0.3 * size : -0.4 * size;
      } else if (span) {
        content = span[2];
        const style = Object.fromEntries(span[1].split(';').filter(Boolean).map((s) => s.split(':').map((v) => v.trim())));
        if (style['font-size']) attrs['font-size'] = parseFloat(style['font-size']);
        if (style.color) attrs.fill = style.color;
      }
      if (first && i > 0) Object.assign(attrs, { x: text.getAttribute('x'), dy: lineHeight });
      else if (dy - shift) attrs.dy = dy - shift;
      shift = dy;
      first = false;
      svgEl('tspan', attrs, text).textContent = content.replace(/<[^>]+>/g, '');
    }
    if (shift) svgEl('tspan', { dy: -shift }, text).textContent = '\u200b';
  });
}

/** Plotly's dashes for a line `width` px wide: dot d d, dash 3d 3d, d = max(width, 3). */
export function dashArray(dash, width) {
  const d = Math.max(width, 3);
  return { dot: `${d},${d}`, dash: `${3 * d},${3 * d}` }[dash] || null;
}

const views = new WeakMap(); // div -> {data, layoutAt, ranges, shapes}: the figure shown, its zoom

/**
 * Show the figure (`data`, and `layoutAt(ranges)`: its layout with the axes' ranges `ranges`
 * {x, y}, or fitted when null) in `div`, fitted; the wheel, a drag and a double click zoom, pan
 * and fit it again (its labels placed again at each view).
 */
export function showFigure(div, data, layoutAt) {
  watch(div);
  views.set(div, { data, layoutAt, ranges: null, shapes: [] });
  draw(div);
}

/** The dashed rectangles `shapes` (Plotly's rect shapes, in data units) over the figure in `div`. */
export function setShapes(div, shapes) {
  const view = views.get(div);
  if (!view) return;
  view.shapes = shapes;
  draw(div);
}

/** Show or hide (Plotly's `visible`: true or 'legendonly') the traces `indices` of `div`'s figure. */
export function showTraces(div, indices, shown) {
  const view = views.get(div);
  if (!view) return;
  for (const i of indices) view.data[i] = { ...view.data[i], visible: shown ? true : 'legendonly' };
  draw(div);
}

/** Remove the figure from `div`. */
export function clearFigure(div) {
  views.delete(div);
  delete div.data;
  delete div.layout;
  clear(div);
}

function draw(div) {
  const view = views.get(div);
  const layout = { ...view.layoutAt(view.ranges), shapes: view.shapes };
  div.data = view.data;
  div.layout = layout;
  render(div, view.data, layout);
}

/** Zoom by `factor` about the pixel `at` of the figure (its plot area's centre when null). */
function zoomBy(div, factor, at = null) {
  const view = views.get(div);
  if (!view) return;
  const { xaxis, yaxis, margin } = div.layout;
  const [w, h] = plotSize(div.layout);
  const [px, py] = at || [margin.l + w / 2, margin.t + h / 2];
  const fx = (px - margin.l) / w;
  const fy = (py - margin.t) / h;
  const scale = (r, f) => {
    const c = r[0] + f * (r[1] - r[0]);
    return [c - (c - r[0]) / factor, c + (r[1] - c) / factor];
  };
  view.ranges = { x: scale(xaxis.range, fx), y: scale([yaxis.range[1], yaxis.range[0]], fy).reverse() };
  draw(div);
}

function panBy(div, dx, dy) {
  const view = views.get(div);
  if (!view) return;
  const k = pixelsPerUnit(div.layout);
  const { xaxis, yaxis } = div.layout;
  view.ranges = { x: xaxis.range.map((v) => v - dx / k), y: yaxis.range.map((v) => v + dy / k) };
  draw(div);
}

function fit(div) {
  const view = views.get(div);
  if (!view || !view.ranges) return;
  view.ranges = null;
  draw(div);
}

const watched = new WeakSet();

/** The div's zoom and pan: wheel (focused, or with Ctrl), mouse drag, double click, + − 0 (focused). */
function watch(div) {
  if (watched.has(div)) return;
  watched.add(div);
  div.tabIndex = 0;
  const local = (ev) => {
    const r = div.getBoundingClientRect();
    return [ev.clientX - r.left, ev.clientY - r.top];
  };
  div.addEventListener('wheel', (ev) => {
    if (!views.has(div) || !(ev.ctrlKey || document.activeElement === div)) return;
    ev.preventDefault();
    const lines = ev.deltaMode === 1 ? 33 : 1;
    zoomBy(div, Math.exp(-ev.deltaY * lines * 0.002), local(ev));
  }, { passive: false });
  let last = null;
  div.addEventListener('pointerdown', (ev) => {
    if (ev.pointerType !== 'mouse' || ev.button !== 0 || !views.has(div)) return;
    last = [ev.clientX, ev.clientY];
    div.setPointerCapture(ev.pointerId);
  });
  div.addEventListener('pointermove', (ev) => {
    if (!last) return;
    panBy(div, ev.clientX - last[0], ev.clientY - last[1]);
    last = [ev.clientX, ev.clientY];
  });
  const stop = () => { last = null; };
  div.addEventListener('pointerup', stop);
  div.addEventListener('pointercancel', stop);
  div.addEventListener('dblclick', () => fit(div));
  div.addEventListener('keydown', (ev) => {
    const zoom = { '+': ZOOM_STEP, '=': ZOOM_STEP, '-': 1 / ZOOM_STEP, '0': 0 }[ev.key];
    if (zoom === undefined || ev.ctrlKey || ev.metaKey || ev.altKey) return;
    ev.preventDefault();
    ev.stopPropagation(); // not the drawing's zoom (main.js: the same keys on the page)
    if (zoom) zoomBy(div, zoom);
    else fit(div);
  });
}

/** Build the SVG of the figure (`data`, `layout`) in `div`. */
function render(div, data, layout) {
  const { width, height, margin } = layout;
  const [w, h] = plotSize(layout);
  const px = toPixel(layout);
  const title = layout.title?.text || '';
  const svg = svgEl('svg', {
    class: 'plane-figure', width, height, viewBox: `0 0 ${width} ${height}`, role: 'img',
    'aria-label': `${title.replace(/<[^>]+>/g, ' ').replace(/\s+/g, ' ').trim()}; focused, the wheel or + − zoom, a drag pans, a double click or 0 fits`,
    'font-family': FONT,
  });
  const clipId = `${div.id}-plot-area`;
  const clip = svgEl('clipPath', { id: clipId }, svgEl('defs', {}, svg));
  svgEl('rect', { x: margin.l, y: margin.t, width: w, height: h }, clip);

  // Grid, zero lines and tick labels.
  const grid = svgEl('g', { class: 'grid', stroke: '#eef0f3', 'stroke-width': 1 }, svg);
  const ticks = svgEl('g', { class: 'tick-labels', fill: TICK_COLOUR, 'font-size': TICK_SIZE }, svg);
  const zero = svgEl('g', { class: 'zero-lines', stroke: '#d1d5db', 'stroke-width': 1 }, svg);
  const x = niceTicks(layout.xaxis.range, w, 80);
  for (const v of x.values) {
    const [gx] = px([v, 0]);
    svgEl('line', { x1: gx, y1: margin.t, x2: gx, y2: margin.t + h }, Math.abs(v) < x.step * 1e-9 ? zero : grid);
    svgEl('text', { class: 'tick-label', 'data-axis': 'x', x: gx, y: margin.t + h + 15, 'text-anchor': 'middle' }, ticks).textContent = tickText(v, x.step);
  }
  const y = niceTicks(layout.yaxis.range, h, 40);
  for (const v of y.values) {
    const [, gy] = px([0, v]);
    svgEl('line', { x1: margin.l, y1: gy, x2: margin.l + w, y2: gy }, Math.abs(v) < y.step * 1e-9 ? zero : grid);
    svgEl('text', { class: 'tick-label', 'data-axis': 'y', x: margin.l - 4, y: gy, dy: '0.35em', 'text-anchor': 'end' }, ticks).textContent = tickText(v, y.step);
  }

  // The traces, clipped to the plot area (a zoomed figure stays clear of its ticks and title).
  const drawn = svgEl('g', { class: 'traces', 'clip-path': `url(#${clipId})` }, svg);
  data.forEach((t, i) => { if (t.visible !== 'legendonly') trace(svgEl('g', { class: 'trace', 'data-index': i }, drawn), t, px); });

  const shapes = svgEl('g', { class: 'shapes', 'clip-path': `url(#${clipId})` }, svg);
  for (const s of layout.shapes || []) {
    const [[x0, y0], [x1, y1]] = [px([s.x0, s.y0]), px([s.x1, s.y1])];
    svgEl('rect', {
      x: Math.min(x0, x1), y: Math.min(y0, y1), width: Math.abs(x1 - x0), height: Math.abs(y1 - y0), fill: 'none',
      stroke: s.line.color, 'stroke-width': s.line.width, 'stroke-dasharray': dashArray(s.line.dash, s.line.width),
    }, shapes);
  }

  const labels = svgEl('g', { class: 'labels' }, svg);
  for (const a of layout.annotations || []) label(labels, a, px, { l: margin.l, t: margin.t, r: margin.l + w, b: margin.t + h });

  if (title) titleText(svg, layout);
  div.replaceChildren(svg);
}

/** One trace: its segments (a path, `null` between them), fill, arrowheads and hover texts. */
function trace(g, t, px) {
  const { color, width = 2, dash } = t.line || {};
  const runs = [];
  let run = [];
  for (let i = 0; i < t.x.length; i++) {
    if (t.x[i] === null || t.y[i] === null) {
      if (run.length) runs.push(run);
      run = [];
    } else run.push(i);
  }
  if (run.length) runs.push(run);
  const pathOf = (idx) => idx.map((i, k) => `${k ? 'L' : 'M'}${px([t.x[i], t.y[i]]).map((v) => v.toFixed(2)).join(',')}`).join('');
  if (t.fill === 'toself') {
    svgEl('path', { d: runs.map((r) => `${pathOf(r)}Z`).join(''), fill: t.fillcolor, stroke: 'none' }, g);
  }
  for (const r of runs) {
    const part = runs.length > 1 || t.text ? svgEl('g', {}, g) : g;
    svgEl('path', {
      d: pathOf(r), fill: 'none', stroke: color, 'stroke-width': width,
      'stroke-dasharray': dashArray(dash, width), 'stroke-linejoin': 'round',
    }, part);
    // Arrowheads: a marker 'arrow' (sized per point) at a point, along the segment that ends there.
    const sizes = t.marker?.symbol === 'arrow' ? t.marker.size : null;
    for (let k = 1; sizes && k < r.length; k++) {
      const size = Array.isArray(sizes) ? sizes[r[k]] : sizes;
      if (size > 0) arrowhead(part, px([t.x[r[k - 1]], t.y[r[k - 1]]]), px([t.x[r[k]], t.y[r[k]]]), size, t.marker.color || color);
    }
    const hover = Array.isArray(t.text) ? t.text[r[r.length - 1]] : t.text;
    if (hover) svgEl('title', {}, part).textContent = hover;
  }
}

/** A filled arrowhead `size` px long with its tip at `to`, pointing from `from`. */
function arrowhead(g, from, to, size, colour) {
  const d = Math.hypot(to[0] - from[0], to[1] - from[1]);
  if (!(d > 0)) return;
  const [ux, uy] = [(to[0] - from[0]) / d, (to[1] - from[1]) / d];
  const [bx, by] = [to[0] - ux * size, to[1] - uy * size];
  const half = size / 2;
  const points = [to, [bx - uy * half, by + ux * half], [bx + uy * half, by - ux * half]];
  svgEl('polygon', { points: points.map((p) => p.map((v) => v.toFixed(2)).join(',')).join(' '), fill: colour }, g);
}

/**
 * A label (an annotation: its text centred xshift/yshift px from its anchor, or ax/ay px with a
 * leader line to it) on a translucent white box; hidden when its anchor is out of the plot area.
 */
function label(g, a, px, area) {
  const [ax, ay] = px([a.x, a.y]);
  if (ax < area.l - 0.5 || ax > area.r + 0.5 || ay < area.t - 0.5 || ay > area.b + 0.5) return;
  const [cx, cy] = a.showarrow ? [ax + a.ax, ay + a.ay] : [ax + (a.xshift || 0), ay - (a.yshift || 0)];
  const size = a.font?.size || 14;
  const colour = a.font?.color || '#1f2933';
  const w = textWidth(a.text);
  const h = LABEL_HEIGHT;
  const node = svgEl('g', { class: 'figure-label', 'data-text': a.text }, g);
  if (a.showarrow) {
    // From the anchor (less a standoff) to the box's edge.
    const [dx, dy] = [cx - ax, cy - ay];
    const inside = Math.min(dx ? w / 2 / Math.abs(dx) : Infinity, dy ? h / 2 / Math.abs(dy) : Infinity);
    const d = Math.hypot(dx, dy);
    const s = (a.standoff || 0) / d;
    svgEl('line', {
      x1: ax + dx * s, y1: ay + dy * s, x2: cx - dx * inside, y2: cy - dy * inside,
      stroke: a.arrowcolor || colour, 'stroke-width': a.arrowwidth || 1,
    }, node);
  }
  svgEl('rect', { x: cx - w / 2, y: cy - h / 2, width: w, height: h, fill: a.bgcolor || 'none' }, node);
  const text = svgEl('text', { x: cx, y: cy, dy: '0.35em', 'text-anchor': 'middle', 'font-size': size, fill: colour }, node);
  richText(text, a.text, size, 1.3 * size);
}

/**
 * The title (15 px, its unit in a smaller grey span; a second line after <br>) from 2 % of the
 * width, its lines centred in the top margin.
 */
function titleText(svg, layout) {
  const size = layout.title.font?.size || 15;
  const lineHeight = 1.3 * size;
  const lines = String(layout.title.text).split(/<br\s*\/?>/).length;
  const top = layout.margin.t / 2 - ((lines - 1) * lineHeight) / 2;
  const text = svgEl('text', {
    class: 'figure-title', x: 0.02 * layout.width, y: top, dy: '0.35em', 'font-size': size, fill: layout.font?.color || '#1f2933',
  }, svg);
  richText(text, layout.title.text, size, lineHeight);
}
