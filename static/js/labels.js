// labels.js: labels of a polygon (plane-figure.js) placed so that no two overlap and few sit on a line.
//
// On the figure's frame (its axes' ranges, at equal scales, and its plot area), each label is tried
// at growing distances in eight directions around its anchor (the tip it names); the position
// with the least cost wins: overlapping a label already placed costs most, then leaving the plot
// area, then crossing a drawn line (arrows, images, ticks are lines), then distance. Labels are
// placed in order of importance (poles, then images, then relative and component vectors at their
// midpoints) and become annotations named "label:<text>" (xshift/yshift in pixels from the
// anchor; from 42 px on, ax/ay with a thin leader line to the anchor).

import { overlaps, segmentHitsBox } from './boxes.js';

const FONT = '600 14px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
/** px: the height of a label's box (its line of 14 px text). */
export const LABEL_HEIGHT = 17;
const PAD = 2;
const RADII = [6, 12, 20, 30, 42, 56, 72, 90, 110, 135, 165];
const LEADER = 42; // px: labels placed this far from their anchor get a leader line
const DIRECTIONS = [[1, -1], [-1, -1], [1, 1], [-1, 1], [1, 0], [-1, 0], [0, -1], [0, 1]];

let context = null;
/** px: the width of the label `html` at 14 px (its subscripts and superscripts at 70 %). */
export function textWidth(html) {
  context = context || document.createElement('canvas').getContext('2d');
  context.font = FONT;
  // Subscripts and superscripts are smaller: count them at 70 %.
  const sub = [...html.matchAll(/<su[bp]>(.*?)<\/su[bp]>/g)].map((m) => m[1]).join('');
  const main = html.replace(/<su[bp]>.*?<\/su[bp]>/g, '').replace(/<[^>]+>/g, '');
  return context.measureText(main).width + 0.7 * context.measureText(sub).width;
}

/** Line segments of the figure's traces, in pixels of the plot area. */
function segmentsOf(traces, toPx) {
  const out = [];
  for (const t of traces) {
    if (!String(t.mode || '').includes('lines') || !Array.isArray(t.x)) continue;
    for (let i = 0; i + 1 < t.x.length; i++) {
      if (t.x[i] === null || t.x[i + 1] === null) continue;
      out.push([toPx([t.x[i], t.y[i]]), toPx([t.x[i + 1], t.y[i + 1]])]);
    }
  }
  return out;
}

// ---- the plot area a figure is drawn in ---------------------------------------------------------
// A figure whose axes' ranges are given (not autoranged) maps data to pixels linearly: its labels
// are placed before it is drawn. With fixed margins (polygons.js) its plot area is known before it
// is drawn: the div's size less the margins.

/**
 * The size {width, height} (px) of a figure drawn in `div` (its computed size, rounded) and its
 * plot area {w, h} (px) laid out with `margin` (fixed). A polygon's div changes height with its
 * legend's rows: its figure is drawn at the size the div has once the legend is in place.
 */
export function plotArea(div, margin) {
  const style = getComputedStyle(div);
  const [width, height] = [Math.round(parseFloat(style.width)), Math.round(parseFloat(style.height))];
  return { width, height, w: width - margin.l - margin.r, h: height - margin.t - margin.b };
}

/**
 * Ranges {x, y} that show every point of `traces` and the pole (0, 0) in a plot area `area`
 * ({w, h} px) at equal scales, at least `pad` px from its edges, centred (a figure of one point:
 * 1 unit across).
 */
export function equalRanges(traces, area, pad) {
  let [x0, x1, y0, y1] = [Infinity, -Infinity, Infinity, -Infinity];
  const take = (x, y) => {
    if (x === null || y === null || x === undefined || y === undefined) return;
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  };
  take(0, 0);
  for (const t of traces) for (let i = 0; i < (t.x?.length || 0); i++) take(t.x[i], t.y[i]);
  const span = Math.max(x1 - x0, y1 - y0);
  // Pixels per unit that fit `extent` into `px` less the pads (a figure of one point: 1 unit).
  const fit = (extent, px) => Math.max(px - 2 * pad, px / 2) / (span > 0 ? Math.max(extent, 1e-9 * span) : 1);
  const k = Math.min(fit(x1 - x0, area.w), fit(y1 - y0, area.h));
  const [cx, cy] = [(x0 + x1) / 2, (y0 + y1) / 2];
  return { x: [cx - area.w / (2 * k), cx + area.w / (2 * k)], y: [cy - area.h / (2 * k), cy + area.h / (2 * k)] };
}

/**
 * Annotations for `entries` = [{at: [x, y], text, colour}] on a figure drawn in the frame
 * `frame`: {x, y} the ranges of its linear axes, {w, h} its plot area (px).
 */
export function placeLabels(frame, entries, traces) {
  const toPx = ([x, y]) => [(frame.w * (x - frame.x[0])) / (frame.x[1] - frame.x[0]), (frame.h * (frame.y[1] - y)) / (frame.y[1] - frame.y[0])];
  const area = { x0: 0, y0: 0, x1: frame.w, y1: frame.h };
  const segments = segmentsOf(traces, toPx);
  const placed = [];
  const out = [];
  for (const e of entries) {
    const [ax, ay] = toPx(e.at);
    const w = textWidth(e.text) + 2 * PAD;
    const h = LABEL_HEIGHT + 2 * PAD;
    let best = null;
    for (const r of RADII) {
      for (const [dx, dy] of DIRECTIONS) {
        const n = Math.hypot(dx, dy);
        // The box's nearest edge r px from the anchor, in direction (dx, dy).
        const cx = ax + (dx / n) * r + (dx * w) / 2;
        const cy = ay + (dy / n) * r + (dy * h) / 2;
        const box = { x0: cx - w / 2, x1: cx + w / 2, y0: cy - h / 2, y1: cy + h / 2 };
        let cost = r;
        for (const p of placed) if (overlaps(box, p)) cost += 1e6;
        if (box.x0 < area.x0 || box.x1 > area.x1 || box.y0 < area.y0 || box.y1 > area.y1) cost += 1e3;
        for (const [a, b] of segments) if (segmentHitsBox(a, b, box)) cost += 25;
        if (!best || cost < best.cost) best = { cost, box, cx, cy, r };
      }
      if (best.cost < 1e3 && best.cost - best.r < 25) break; // clear of labels, area and lines
    }
    placed.push(best.box);
    const label = {
      name: `label:${e.text}`,
      x: e.at[0], y: e.at[1], xref: 'x', yref: 'y', showarrow: false,
      xanchor: 'center', yanchor: 'middle',
      xshift: best.cx - ax, yshift: -(best.cy - ay),
      text: e.text, font: { size: 14, color: e.colour || '#1f2933' },
      bgcolor: 'rgba(255,255,255,0.75)', borderpad: 0,
    };
    // A label pushed far from what it names is tied to it by a thin leader line.
    if (best.r >= LEADER) {
      Object.assign(label, {
        showarrow: true, arrowhead: 0, arrowwidth: 0.8, arrowcolor: e.colour || '#1f2933', standoff: 2,
        ax: best.cx - ax, ay: best.cy - ay, xshift: 0, yshift: 0,
      });
    }
    out.push(label);
  }
  return out;
}
