// instant-centres.js: the instant-centre layer of the linkage drawing and Kennedy's lines.
//
// Every instant centre I_jk of the analysed instant, between any two links (the ground 1, the
// moving links 2, 3, … as notation.js numbers them), as the server's /analyze answer gives it
// (`instant_centres`: links, position, or direction_at_infinity for two links in relative
// translation); nothing is computed here. For a chosen triple of links, Kennedy's line: the
// three centres I_ij, I_jk, I_ik lie on one straight line (Kennedy's theorem), drawn through
// them and across the picture. Names are placed by drawing-labels.js, clear of each other, of
// the joints, of the poles and of the other centres. Shown, like the poles, at the analysed
// instant only (paused).

import { svgEl, setAttrs } from './svg.js';
import { COLOURS } from './theme.js';
import { linkNumbers, instantCentre } from './notation.js';
import { groundLink, movingLinks } from './scene.js';
import { show, fmt } from './units.js';
import { measureLabel, aroundPoint, boxAt, markerBox, placeAll } from './drawing-labels.js';

const KENNEDY = '#1f2933'; // ink: Kennedy's lines are construction lines
const REACH = 4000; // viewBox px a Kennedy line runs either way (the picture clips it)

/** Link name -> number, the ground included (1). */
function numbers(scene) {
  return { [groundLink(scene)]: 1, ...linkNumbers(scene) };
}

/** "I₂₄" for the centre of links a and b, the smaller number first. */
export function centreName(scene, [a, b]) {
  const n = numbers(scene);
  return instantCentre(Math.min(n[a], n[b]), Math.max(n[a], n[b]));
}

/** Every triple of links as "a,b,c" (by number), for the Kennedy menu. */
export function linkTriples(scene) {
  const n = numbers(scene);
  const links = [groundLink(scene), ...movingLinks(scene)].sort((a, b) => n[a] - n[b]);
  const out = [];
  for (let i = 0; i < links.length; i++) {
    for (let j = i + 1; j < links.length; j++) {
      for (let k = j + 1; k < links.length; k++) out.push([links[i], links[j], links[k]]);
    }
  }
  return out;
}

/**
 * Draw the centres of `analysis` into `layer` with `view`'s map (view.px, view.inView), the
 * triple `kennedy` (link names, or null) with its line; `avoid` are the boxes already taken
 * (joints, poles and their names). Returns the lines for the drawing's notes (centres outside
 * the picture or at infinity) and the boxes the centres and their names now take. With `poles`
 * (the velocity poles drawn by the view) a centre with the ground, I_1k, is left to the poles
 * where they mark it (everywhere but at a fixed pivot), so that none is drawn or listed twice.
 */
export function drawCentres(view, layer, analysis, kennedy, avoid, poles = false) {
  const scene = view.scene;
  const notes = [];
  const marks = [];
  const labels = [];
  const units = view.options.units;
  const at = (c) => show('length', c, units, 3, view.map.size);
  const inTriple = (links) => kennedy && links.every((l) => kennedy.includes(l));
  const centres = analysis.instant_centres || [];
  const byPair = new Map();
  const ground = groundLink(scene);
  for (const c of centres) {
    const name = centreName(scene, c.links);
    byPair.set([...c.links].sort().join('|'), c);
    if (poles && c.links.includes(ground) && !(c.position && view.isGroundPoint(c.position))) continue;
    if (!c.position) {
      const d = c.direction_at_infinity;
      notes.push(`${name} at infinity${d ? `, direction (${fmt(d[0], 3, 1)}, ${fmt(d[1], 3, 1)})` : ''}`);
      continue;
    }
    if (!view.inView(c.position)) {
      notes.push(`${name} (${at(c.position[0])}, ${at(c.position[1])})`);
      continue;
    }
    const [x, y] = view.px(c.position);
    const chosen = inTriple(c.links);
    const g = svgEl('g', { class: `centre${chosen ? ' kennedy-centre' : ''}`, 'data-links': c.links.join(' '), transform: `translate(${x.toFixed(2)},${y.toFixed(2)})` }, layer);
    svgEl('circle', { r: chosen ? 5 : 3.5, fill: chosen ? KENNEDY : '#ffffff', stroke: chosen ? KENNEDY : COLOURS.ink, 'stroke-width': 1.6 }, g);
    const t = svgEl('text', { class: 'centre-label', 'text-anchor': 'middle', 'dominant-baseline': 'central', fill: chosen ? KENNEDY : COLOURS.ink }, g);
    t.textContent = name;
    svgEl('title', {}, g).textContent = `${name}: instant centre of links ${c.links.join(' and ')}`;
    marks.push(markerBox([x, y], 6));
    labels.push({ node: t, at: [x, y], size: measureLabel(t), last: -1 });
  }
  if (kennedy) drawKennedyLine(view, layer, kennedy, byPair, notes);
  for (const label of labels) label.candidates = aroundPoint(label.at, label.size);
  const chosen = placeAll(labels, [...avoid, ...marks], [], { x0: 0, y0: 0, x1: view.svg.viewBox.baseVal.width, y1: view.map.height });
  labels.forEach((label, i) => {
    const c = label.candidates[chosen[i]].at;
    setAttrs(label.node, { x: (c[0] - label.at[0]).toFixed(1), y: (c[1] - label.at[1]).toFixed(1) });
    marks.push(boxAt(c, label.size));
  });
  return { notes: notes.length ? [`Instant centres outside the picture: ${notes.join(', ')}`] : [], marks };
}

/** Kennedy's line of the triple: through its finite centres (along the direction of one at infinity). */
function drawKennedyLine(view, layer, [a, b, c], byPair, notes) {
  const pairs = [[a, b], [b, c], [a, c]].map((p) => byPair.get([...p].sort().join('|')));
  if (pairs.some((p) => !p)) return;
  const finite = pairs.filter((p) => p.position).map((p) => view.px(p.position));
  const infinite = pairs.find((p) => !p.position && p.direction_at_infinity);
  let from;
  let dir;
  if (finite.length >= 2) {
    // The two centres farthest apart fix the line best.
    let best = [finite[0], finite[1]];
    for (let i = 0; i < finite.length; i++) {
      for (let j = i + 1; j < finite.length; j++) {
        if (dist(finite[i], finite[j]) > dist(best[0], best[1])) best = [finite[i], finite[j]];
      }
    }
    from = best[0];
    dir = [best[1][0] - best[0][0], best[1][1] - best[0][1]];
  } else if (finite.length === 1 && infinite) {
    from = finite[0];
    dir = [infinite.direction_at_infinity[0], -infinite.direction_at_infinity[1]];
  } else return;
  const n = Math.hypot(dir[0], dir[1]);
  if (!(n > 0)) {
    notes.push(`Kennedy: ${pairs.map((p) => centreName(view.scene, p.links)).join(', ')} coincide`);
    return;
  }
  const u = [dir[0] / n, dir[1] / n];
  const line = svgEl('line', {
    x1: from[0] - u[0] * REACH, y1: from[1] - u[1] * REACH, x2: from[0] + u[0] * REACH, y2: from[1] + u[1] * REACH,
    stroke: KENNEDY, 'stroke-width': 1.6, 'stroke-dasharray': '8 4 2 4', class: 'kennedy-line',
  }, layer);
  svgEl('title', {}, line).textContent = `Kennedy's line of links ${a}, ${b}, ${c}: ${pairs.map((p) => centreName(view.scene, p.links)).join(', ')} on one straight line`;
  layer.prepend(line);
}

const dist = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1]);

/**
 * The layer's controls: "all instant centres" and the triple of Kennedy's line (its menu filled
 * for each new mechanism). Sets the view's options showCentres and kennedy (link names).
 */
export class CentreControls {
  constructor(view, { toggle, triple }) {
    this.view = view;
    this.els = { toggle, triple };
    this.scene = null;
    const apply = () => {
      triple.disabled = !toggle.checked;
      const chosen = toggle.checked && triple.value ? triple.value.split(',') : null;
      view.setOptions({ showCentres: toggle.checked, kennedy: chosen });
    };
    toggle.addEventListener('change', apply);
    triple.addEventListener('change', apply);
    view.afterDraw.push(() => {
      if (view.scene === this.scene) return;
      this.scene = view.scene;
      const keep = triple.value;
      const n = numbers(this.scene);
      const options = linkTriples(this.scene).map((t) => new Option(`${t.map((l) => n[l]).join(', ')}: ${t.join(', ')}`, t.join(',')));
      triple.replaceChildren(new Option('no Kennedy line', ''), ...options);
      triple.value = options.some((o) => o.value === keep) ? keep : '';
      if (triple.value !== keep) view.options.kennedy = null;
    });
  }
}
