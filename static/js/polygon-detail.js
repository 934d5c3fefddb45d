// polygon-detail.js: a second panel showing part of a polygon at its own scale, for polygons
// too elongated to read (the quick-return and groove acceleration polygons squash into slivers).
//
// Rule (stated in docs/FRONTEND.md): with L the longest drawn segment and s the shortest one
// that is not negligible (s >= L/1000; shorter ones are under a pixel at any size the page
// gives the polygon and are listed in the magnitudes table), the detail is shown when
//   s < L/12,  or  the polygon's bounding box is more than 5 times as long as it is wide and
//   s < L/5.
// It frames the shortest segment and the short ones (< L/5) next to it, grown only while the
// frame stays under 5 s across (7 s with its margins), so that s is at least 1/7 of the
// detail's extent. The region is marked by a dashed box in the polygon; both scales are written
// as "1 cm = …" (a CSS centimetre, 96/2.54 px), from the pixels per unit of each figure.

import { placeLabels, plotArea } from './labels.js';
import { fmt, unitLabel } from './units.js';
import { showFigure, setShapes, clearFigure, pixelsPerUnit } from './plane-figure.js';

export const DETAIL_RULE = { negligible: 1e-3, short: 1 / 12, aspect: 5, sliver: 1 / 5, frame: 5 };
const CM = 96 / 2.54; // CSS px in a CSS centimetre

/** The drawn line segments of `traces` in data units: [[x1, y1], [x2, y2], length]. */
function segmentsOf(traces) {
  const out = [];
  for (const t of traces) {
    if (!String(t.mode || '').includes('lines') || !Array.isArray(t.x)) continue;
    for (let i = 0; i + 1 < t.x.length; i++) {
      if (t.x[i] === null || t.x[i + 1] === null) continue;
      const a = [t.x[i], t.y[i]];
      const b = [t.x[i + 1], t.y[i + 1]];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (len > 0) out.push([a, b, len]);
    }
  }
  return out;
}

const boxOf = (points) => ({
  x0: Math.min(...points.map((p) => p[0])),
  x1: Math.max(...points.map((p) => p[0])),
  y0: Math.min(...points.map((p) => p[1])),
  y1: Math.max(...points.map((p) => p[1])),
});
const extent = (b) => Math.max(b.x1 - b.x0, b.y1 - b.y0);
const gap = (a, b) => Math.hypot(Math.max(0, a.x0 - b.x1, b.x0 - a.x1), Math.max(0, a.y0 - b.y1, b.y0 - a.y1));

/** The region to show in detail, {x: [x0, x1], y: [y0, y1], shortest, longest}, or null. */
export function detailRegion(traces) {
  const segs = segmentsOf(traces);
  if (!segs.length) return null;
  const L = Math.max(...segs.map((s) => s[2]));
  const seen = segs.filter((s) => s[2] >= DETAIL_RULE.negligible * L).sort((a, b) => a[2] - b[2]);
  const s = seen[0][2];
  const all = boxOf(segs.flatMap(([a, b]) => [a, b]));
  const width = Math.min(all.x1 - all.x0, all.y1 - all.y0);
  const sliver = extent(all) > DETAIL_RULE.aspect * width;
  if (!(s < DETAIL_RULE.short * L || (sliver && s < DETAIL_RULE.sliver * L))) return null;
  let frame = boxOf([seen[0][0], seen[0][1]]);
  for (const [a, b, len] of seen.slice(1)) {
    if (len >= DETAIL_RULE.sliver * L) break;
    const box = boxOf([a, b]);
    const grown = boxOf([[frame.x0, frame.y0], [frame.x1, frame.y1], a, b]);
    if (gap(frame, box) < 2 * len && extent(grown) <= DETAIL_RULE.frame * s) frame = grown;
  }
  const pad = Math.max(0.2 * extent(frame), s / 2);
  return { x: [frame.x0 - pad, frame.x1 + pad], y: [frame.y0 - pad, frame.y1 + pad], shortest: s, longest: L };
}

/**
 * Draw `figure` (polygons.js: traces, labels, layout, and whether it is narrow) zoomed on its
 * detail region in `detail`, and mark the region in the polygon `main` (already drawn with its
 * labels, without the box); hide `detail` when no detail is needed. Then `main.dataset.detail` is
 * "shown" or "none" (polygons.js sets "pending" before drawing it).
 */
export function renderDetail(main, detail, figure, kind, units) {
  const region = detailRegion(figure.traces);
  if (!region) {
    // `main` was just drawn from a layout without the dashed box (polygons.js): nothing to clear.
    detail.hidden = true;
    clearFigure(detail);
    main.dataset.detail = 'none';
    return;
  }
  detail.hidden = false;
  const base = {
    ...figure.layout,
    annotations: [],
    showlegend: false,
    margin: { l: 44, r: 12, t: 76, b: 28 }, // fixed, as the polygon's (polygons.js)
    xaxis: { ...figure.layout.xaxis, autorange: false },
    yaxis: { ...figure.layout.yaxis, autorange: false },
  };
  // Drawn with its scale and labels on its plot area (its size less the fixed margins: labels.js,
  // plotArea); the region it shows fitted is marked in the polygon.
  const area = plotArea(detail, base.margin);
  if (!(area.w > 0 && area.h > 0)) return; // not laid out (its polygon was hidden meanwhile)
  const scale = pixelsPerUnit(main.layout); // (drawn: polygons.js calls this once it is)
  const fitted = fittedRanges(region, area);
  showFigure(detail, figure.traces, (ranges) => detailLayout(base, area, figure, scale, kind, units, ranges || fitted));
  const { x, y } = fitted;
  setShapes(main, [{ type: 'rect', xref: 'x', yref: 'y', x0: x[0], x1: x[1], y0: y[0], y1: y[1], line: { color: '#6b7280', width: 1, dash: 'dash' } }]);
  main.dataset.detail = 'shown';
}

/** The axes' ranges {x, y} that show `region` centred in the plot area `area` at equal scales. */
function fittedRanges(region, area) {
  const k = Math.min(area.w / (region.x[1] - region.x[0]), area.h / (region.y[1] - region.y[0]));
  const cx = (region.x[0] + region.x[1]) / 2;
  const cy = (region.y[0] + region.y[1]) / 2;
  return { x: [cx - area.w / (2 * k), cx + area.w / (2 * k)], y: [cy - area.h / (2 * k), cy + area.h / (2 * k)] };
}

/**
 * The detail's layout at the size and plot area `area` ({width, height, w, h} px) and the axes'
 * `ranges` {x, y}: its scale (k px per unit) and the polygon's (`scale` px per unit) in the
 * title, and the labels of the tips inside it.
 */
function detailLayout(base, area, figure, scale, kind, units, { x, y }) {
  const k = area.w / (x[1] - x[0]);
  const u = unitLabel(kind, units);
  const inside = ([px, py]) => px >= x[0] && px <= x[1] && py >= y[0] && py <= y[1];
  const entries = figure.labels.filter(([at]) => inside(at)).map(([at, text, colour]) => ({ at, text, colour }));
  return {
    ...base,
    width: area.width,
    height: area.height,
    title: {
      text: `${kind === 'velocity' ? 'Velocity' : 'Acceleration'} detail (dashed box): 1 cm = ${fmt(CM / k)} ${u}<br><span style="font-size:11px;color:#6b7280">polygon: 1 cm = ${fmt(CM / scale)} ${u}</span>`,
      // Its two lines in the top margin; at 11 px in a narrow figure, so that they fit.
      font: { size: figure.narrow ? 11 : 13 }, x: 0.02, xanchor: 'left',
    },
    annotations: placeLabels({ x, y, w: area.w, h: area.h }, entries, figure.traces),
    xaxis: { ...base.xaxis, range: x },
    yaxis: { ...base.yaxis, range: y },
  };
}
