// drawing-labels.js: the names in the linkage drawing placed so that no two overlap and none
// sits on a joint.
//
// Every frame, each label is given candidate centres (a point's name around the point, a link's
// name along the normal of the bar at its middle, then further along it) and takes the one of
// least cost: overlapping a label already placed or a joint marker costs most, then leaving the
// picture, then crossing a bar, then distance from what it names. The position a label had in
// the previous frame is kept unless another is clearly better, so names do not flicker while the
// mechanism plays. Sizes are measured once per label (canvas text metrics of the label's own
// computed font), so a frame never asks the browser for a layout.

import { overlaps, segmentHitsBox } from './boxes.js';

const PAD = 2; // px of white halo around each label (the labels' paint-order stroke)
const BLOCKED = 1e6; // on another label or on a joint marker
const OUTSIDE = 1e3; // beyond the picture's edge
const ON_BAR = 40; // crossing a bar of the drawing
const KEEP = 12; // px: a label moves only for a position at least this much better
const DIRECTIONS = [[1, -1], [-1, -1], [1, 1], [-1, 1], [1, 0], [-1, 0], [0, -1], [0, 1]];
const POINT_RADII = [4, 10, 18, 28, 40, 56, 76, 100];
const LINK_RADII = [6, 14, 24, 36, 52, 72, 96];
const ALONG = [0.5, 0.35, 0.65, 0.22, 0.78];

let context = null;

/** Width and height (px, with the halo) of an SVG text element in its computed font. */
export function measureLabel(node) {
  const style = getComputedStyle(node);
  const size = parseFloat(style.fontSize) || 16;
  context = context || document.createElement('canvas').getContext('2d');
  context.font = `${style.fontStyle} ${style.fontWeight} ${size}px ${style.fontFamily}`;
  return { w: context.measureText(node.textContent).width + 2 * PAD, h: size * 1.25 + 2 * PAD };
}

/** The box {x0, y0, x1, y1} of a label of size {w, h} centred at (cx, cy). */
export const boxAt = ([cx, cy], { w, h }) => ({ x0: cx - w / 2, x1: cx + w / 2, y0: cy - h / 2, y1: cy + h / 2 });

/** Centres around a point: the box's nearest edge r px from it, in eight directions. */
export function aroundPoint([x, y], { w, h }) {
  const out = [];
  for (const r of POINT_RADII) {
    for (const [dx, dy] of DIRECTIONS) {
      const n = Math.hypot(dx, dy);
      out.push({ at: [x + (dx / n) * r + (dx * w) / 2, y + (dy / n) * r + (dy * h) / 2], r });
    }
  }
  return out;
}

/**
 * Centres beside a bar a-b: at fractions of its length, on either side along its unit normal n,
 * the box clear of the bar's axis by r px (its half-extent along n is |n_x| w/2 + |n_y| h/2).
 */
export function besideBar(a, b, { w, h }, halfWidth) {
  const len = Math.hypot(b[0] - a[0], b[1] - a[1]) || 1;
  const n = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
  const half = Math.abs(n[0]) * (w / 2) + Math.abs(n[1]) * (h / 2);
  const out = [];
  for (const r of LINK_RADII) {
    for (const f of ALONG) {
      const m = [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])];
      const d = halfWidth + r + half;
      // Below the bar first (screen y down), as books letter a link under its line.
      const side = n[1] >= 0 ? 1 : -1;
      for (const s of [side, -side]) out.push({ at: [m[0] + s * n[0] * d, m[1] + s * n[1] * d], r: r + Math.abs(f - 0.5) * len * 0.5 });
    }
  }
  return out;
}

/** The box {x0, y0, x1, y1} of a marker of radius r centred at (x, y). */
export const markerBox = ([x, y], r) => ({ x0: x - r, x1: x + r, y0: y - r, y1: y + r });

/**
 * Choose a centre for each label, in order: labels = [{size, candidates, last}] (last: the index
 * chosen in the previous frame, or -1); markers = boxes never to cover (joints, pivots, blocks,
 * poles); bars = [[a, b]] (segments, avoided); area = the picture's box. Returns the chosen
 * indices.
 */
export function placeAll(labels, markers, bars, area) {
  const placed = [...markers];
  const chosen = [];
  for (const label of labels) {
    const cost = (c) => {
      const box = boxAt(c.at, label.size);
      let total = c.r;
      for (const p of placed) if (overlaps(box, p)) total += BLOCKED;
      if (box.x0 < area.x0 || box.x1 > area.x1 || box.y0 < area.y0 || box.y1 > area.y1) total += OUTSIDE;
      for (const [a, b] of bars) if (segmentHitsBox(a, b, box)) total += ON_BAR;
      return total;
    };
    let best = -1;
    let bestCost = Infinity;
    label.candidates.forEach((c, i) => {
      const v = cost(c);
      if (v < bestCost) [best, bestCost] = [i, v];
    });
    const last = label.candidates[label.last];
    if (last && cost(last) <= bestCost + KEEP) best = label.last;
    placed.push(boxAt(label.candidates[best].at, label.size));
    chosen.push(best);
  }
  return chosen;
}
