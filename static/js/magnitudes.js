// magnitudes.js: the table beside the polygons: the magnitude of every vector the polygons draw,
// as the server gave it (points: |v|, |a|; links: ω, α; sliders and moving points: transport,
// relative and Coriolis parts), in the display units, named as in the polygons.

import { componentSources } from './track.js';
import { toDisplay, unitLabel, fmt } from './units.js';
import { linkNumbers, imageName } from './notation.js';

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

const mag = (v) => (v ? Math.hypot(v[0], v[1]) : null);

function row(cells, head = false) {
  const tr = el('tr');
  cells.forEach((c, i) => tr.appendChild(el(head || i === 0 ? 'th' : 'td', head ? { scope: 'col' } : i === 0 ? { scope: 'row' } : {}, c)));
  return tr;
}

export function renderMagnitudes(table, scene, analysis, units) {
  table.replaceChildren();
  if (!analysis) return;
  const u = (kind) => unitLabel(kind, units);
  const val = (kind, v) => (v === null || v === undefined ? '—' : fmt(toDisplay(kind, v, units), 4));
  const points = el('tbody');
  points.appendChild(row(['point (image)', `|v| [${u('velocity')}]`, `|a| [${u('acceleration')}]`], true));
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const [name, q] of Object.entries(group || {})) {
      points.appendChild(row([`${name} (${imageName(name)})`, val('velocity', mag(q.velocity)), val('acceleration', mag(q.acceleration))]));
    }
  }
  const links = el('tbody');
  links.appendChild(row(['link', `ω [${u('omega')}]`, `α [${u('alpha')}]`], true));
  const numbers = linkNumbers(scene);
  for (const [name, l] of Object.entries(analysis.links || {})) {
    links.appendChild(row([`${name} (${numbers[name] ?? '?'})`, val('omega', l.omega), val('alpha', l.alpha)]));
  }
  table.append(points, links);
  const parts = componentSources(analysis);
  if (parts.length) {
    const body = el('tbody');
    body.appendChild(row(['part at', `|v| [${u('velocity')}]`, `|a| [${u('acceleration')}]`], true));
    for (const j of parts) {
      body.appendChild(row([`${j.point} transport`, val('velocity', mag(j.transport_velocity)), val('acceleration', mag(j.transport_acceleration))]));
      body.appendChild(row([`${j.point} relative`, val('velocity', mag(j.relative_velocity)), val('acceleration', mag(j.relative_acceleration))]));
      body.appendChild(row([`${j.point} Coriolis`, '', val('acceleration', mag(j.coriolis_acceleration))]));
    }
    table.appendChild(body);
  }
}
