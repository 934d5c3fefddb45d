// boxes.js: the two tests of label placement on screen boxes {x0, y0, x1, y1} (pixels), shared by
// the polygons' labels (labels.js) and the drawing's names (drawing-labels.js).

/** True when the open boxes a and b share an area. */
export const overlaps = (a, b) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;

/** True when the segment a-b passes through the box (Liang–Barsky clipping). */
export function segmentHitsBox([x1, y1], [x2, y2], b) {
  let t0 = 0;
  let t1 = 1;
  const dx = x2 - x1;
  const dy = y2 - y1;
  for (const [p, q] of [[-dx, x1 - b.x0], [dx, b.x1 - x1], [-dy, y1 - b.y0], [dy, b.y1 - y1]]) {
    if (p === 0) {
      if (q < 0) return false;
      continue;
    }
    const r = q / p;
    if (p < 0) t0 = Math.max(t0, r);
    else t1 = Math.min(t1, r);
    if (t0 > t1) return false;
  }
  return true;
}
