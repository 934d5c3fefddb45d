// magnitudes.js: the table beside the polygons: the magnitude of every vector the polygons draw,
// as the server gave it (points: |v|, |a|; links: ω, α; the image segments' relative parts
// v_CB, aⁿ_CB, aᵗ_CB from /solution's `polygons`; sliders and moving points: transport, relative
// and Coriolis parts), in the display units, named as in the polygons.

import { componentSources } from './track.js';
import { toDisplay, unitLabel, fmt } from './units.js';
import { linkNumbers, imageName, pointName } from './notation.js';

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

const mag = (v) => (v ? Math.hypot(v[0], v[1]) : null);

function row(cells, head = false) {
  const tr = el('tr');
  cells.forEach((c, i) => {
    const cell = el(head || i === 0 ? 'th' : 'td', head ? { scope: 'col' } : i === 0 ? { scope: 'row' } : {});
    cell.append(...(Array.isArray(c) ? c : [c]));
    tr.appendChild(cell);
  });
  return tr;
}

/** The polygons' label `symbol` with sub- and superscripts as nodes: [v, sub CB] etc. */
function symbol(main, sub, sup = '') {
  const nodes = [main];
  if (sup) nodes.push(el('sup', {}, sup));
  nodes.push(el('sub', {}, sub));
  return nodes;
}

export function renderMagnitudes(table, scene, analysis, polygons, units) {
  table.replaceChildren();
  if (!analysis) return;
  const u = (kind) => unitLabel(kind, units);
  const val = (kind, v) => (v === null || v === undefined ? '—' : fmt(toDisplay(kind, v, units), 4));
  const points = el('tbody');
  points.appendChild(row(['point (image)', `|v| [${u('velocity')}]`, `|a| [${u('acceleration')}]`], true));
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const [name, q] of Object.entries(group || {})) {
      points.appendChild(row([`${pointName(name)} (${imageName(name)})`, val('velocity', mag(q.velocity)), val('acceleration', mag(q.acceleration))]));
    }
  }
  const links = el('tbody');
  links.appendChild(row(['link', `ω [${u('omega')}]`, `α [${u('alpha')}]`], true));
  const numbers = linkNumbers(scene);
  for (const [name, l] of Object.entries(analysis.links || {})) {
    links.appendChild(row([`${name} (${numbers[name] ?? '?'})`, val('omega', l.omega), val('alpha', l.alpha)]));
  }
  table.append(points, links);
  // The image segments B -> C as the polygons label them: v_CB = ω × r_BC, aⁿ_CB, aᵗ_CB.
  const segments = polygons?.segments || [];
  if (segments.length) {
    const body = el('tbody');
    body.appendChild(row(['point rel. base', `|ω|·r [${u('velocity')}]`, `aⁿ = ω²r [${u('acceleration')}]`, `aᵗ = |α|·r [${u('acceleration')}]`], true));
    for (const seg of segments) {
      const tag = `${pointName(seg.point)}${pointName(seg.base)}`;
      body.appendChild(row([[`${pointName(seg.point)} rel. ${pointName(seg.base)} (`, ...symbol('v', tag), ', ', ...symbol('a', tag, 'n'), ', ', ...symbol('a', tag, 't'), ')'],
        val('velocity', mag(seg.velocity)), val('acceleration', mag(seg.normal)), val('acceleration', mag(seg.tangential))]));
    }
    table.appendChild(body);
  }
  const parts = componentSources(analysis);
  if (parts.length) {
    const body = el('tbody');
    body.appendChild(row(['part at', `|v| [${u('velocity')}]`, `|a| [${u('acceleration')}]`], true));
    for (const j of parts) {
      const p = pointName(j.point);
      body.appendChild(row([[`${p} transport (`, ...symbol('v', `${p},tr`), ', ', ...symbol('a', `${p},tr`), ')'], val('velocity', mag(j.transport_velocity)), val('acceleration', mag(j.transport_acceleration))]));
      body.appendChild(row([[`${p} relative (`, ...symbol('v', `${p},rel`), ', ', ...symbol('a', `${p},rel`), ')'], val('velocity', mag(j.relative_velocity)), val('acceleration', mag(j.relative_acceleration))]));
      body.appendChild(row([[`${p} Coriolis (`, ...symbol('a', `${p},Cor`), ')'], '', val('acceleration', mag(j.coriolis_acceleration))]));
    }
    table.appendChild(body);
  }
}
