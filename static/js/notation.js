// notation.js: names of poles and images that cannot collide with the names of points.
//
// Textbook notation, the same in the drawing, the polygons and the magnitudes table:
//   - links are numbered, the ground 1 and the moving links 2, 3, … in the scene's order;
//   - the velocity pole of link k (its instant centre with the ground) is I₁ₖ, its acceleration
//     pole Γ₁ₖ (Latin capitals name points; I and Γ with two indices never do);
//   - the poles of the polygons are O_v and O_a, and the image of point B is b (lowercase), so
//     "O_v ≡ a, d" reads: the images of A and D sit at the pole.

import { movingLinks } from './scene.js';

const SUB = '₀₁₂₃₄₅₆₇₈₉';
const subscript = (n) => String(n).split('').map((d) => SUB[Number(d)]).join('');

/** Link name -> number (ground 1, moving links 2, 3, …). */
export function linkNumbers(scene) {
  const out = {};
  movingLinks(scene).forEach((name, i) => {
    out[name] = i + 2;
  });
  return out;
}

/** I₁₃ for the instant centre of links 1 and 3 (a comma between two-digit indices). */
export function instantCentre(i, j) {
  return `I${subscript(i)}${i > 9 || j > 9 ? ',' : ''}${subscript(j)}`;
}

export function velocityPoleName(scene, link) {
  return instantCentre(1, linkNumbers(scene)[link] ?? 0);
}

export function accelerationPoleName(scene, link) {
  const k = linkNumbers(scene)[link] ?? 0;
  return `Γ${subscript(1)}${k > 9 ? ',' : ''}${subscript(k)}`;
}

/** The image of a point in a polygon: its name in lowercase. */
export const imageName = (point) => point.toLowerCase();

/** The poles of the velocity and acceleration polygons (Plotly text, HTML subscripts). */
export const POLYGON_POLE = { velocity: 'O<sub>v</sub>', acceleration: 'O<sub>a</sub>' };
