// svg.js: tiny helpers for building SVG by hand (no framework, no build step).

export const SVG_NS = 'http://www.w3.org/2000/svg';

/** Create an SVG element with attributes and append it to `parent` (when given). */
export function svgEl(tag, attrs = {}, parent = null) {
  const node = document.createElementNS(SVG_NS, tag);
  setAttrs(node, attrs);
  if (parent) parent.appendChild(node);
  return node;
}

export function setAttrs(node, attrs) {
  for (const [k, v] of Object.entries(attrs)) {
    if (v === null || v === undefined) node.removeAttribute(k);
    else node.setAttribute(k, typeof v === 'number' ? round(v) : v);
  }
}

/** Two decimals are plenty on a 1000-unit viewBox and keep the DOM small. */
export const round = (v) => String(Math.round(v * 100) / 100);

export function clear(node) {
  while (node.firstChild) node.removeChild(node.firstChild);
}

/** Arrowhead markers, one per colour (SVG 1.1 markers cannot inherit the stroke colour). */
export function arrowMarker(defs, id, colour, size = 9) {
  const marker = svgEl('marker', {
    id,
    viewBox: '0 0 10 10',
    refX: 9,
    refY: 5,
    markerWidth: size,
    markerHeight: size,
    markerUnits: 'userSpaceOnUse',
    orient: 'auto-start-reverse',
  }, defs);
  svgEl('path', { d: 'M0,0 L10,5 L0,10 z', fill: colour }, marker);
  return `url(#${id})`;
}

/** Diagonal hatching for the ground. */
export function hatchPattern(defs, id, colour = '#6b7280') {
  const p = svgEl('pattern', { id, width: 7, height: 7, patternUnits: 'userSpaceOnUse', patternTransform: 'rotate(45)' }, defs);
  svgEl('line', { x1: 0, y1: 0, x2: 0, y2: 7, stroke: colour, 'stroke-width': 1.4 }, p);
  return `url(#${id})`;
}

/**
 * Names in a drawing stay readable however small the drawing is drawn: the CSS variable --px on
 * `svg` is kept at its viewBox units per screen pixel (app.css makes its names at least 11 screen
 * px with it), and `changed` is called when that changes (a label measured in viewBox units must
 * be measured again). Returns a function that updates it now, `changed` called or not (`notify`:
 * a new viewBox whose names are about to be built need not be told).
 */
export function watchTextScale(svg, changed = () => {}) {
  const update = (notify = true) => {
    const width = svg.getBoundingClientRect().width;
    const box = svg.viewBox.baseVal;
    if (!width || !box || !box.width) return;
    const px = (Math.ceil((1000 * box.width) / width) / 1000).toFixed(3); // up: never under
    if (svg.style.getPropertyValue('--px') === px) return;
    svg.style.setProperty('--px', px);
    if (notify) changed();
  };
  new ResizeObserver(() => update()).observe(svg);
  return update;
}
