// notation.js: names of poles and images that cannot collide with the names of points.
//
// Textbook notation, the same in the drawing, the polygons and the magnitudes table:
//   - links are numbered, the ground 1 and the moving links 2, 3, … in the scene's order;
//   - the velocity pole of link k (its instant centre with the ground) is I₁ₖ, its acceleration
//     pole Γ₁ₖ (Latin capitals name points; I and Γ with two indices never do);
//   - the poles of the polygons are O_v and O_a, and the image of point B is b (lowercase), so
//     "O_v ≡ a, d" reads: the images of A and D sit at the pole;
//   - a point named by a Greek letter spelled out ('Gamma', 'omega1') is written as the letter
//     (Γ, ω1), as the worked solution's LaTeX and figures write it; its image is the small
//     letter (γ).

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

const GREEK = {
  alpha: 'α', beta: 'β', gamma: 'γ', delta: 'δ', epsilon: 'ε', zeta: 'ζ', eta: 'η', theta: 'θ',
  iota: 'ι', kappa: 'κ', lambda: 'λ', mu: 'μ', nu: 'ν', xi: 'ξ', pi: 'π', rho: 'ρ', sigma: 'σ',
  tau: 'τ', upsilon: 'υ', phi: 'φ', chi: 'χ', psi: 'ψ', omega: 'ω', Gamma: 'Γ', Delta: 'Δ',
  Theta: 'Θ', Lambda: 'Λ', Xi: 'Ξ', Pi: 'Π', Sigma: 'Σ', Upsilon: 'Υ', Phi: 'Φ', Psi: 'Ψ',
  Omega: 'Ω',
};

/** A point's name as the views write it: a Greek letter spelled out, with at most two digits
 * after it ('Gamma', 'omega1'), as the letter (Γ, ω1); any other name as it is. */
export function pointName(point) {
  const found = /^([A-Za-z]+)([0-9]{0,2})$/.exec(point);
  return found && Object.hasOwn(GREEK, found[1]) ? GREEK[found[1]] + found[2] : point;
}

/** A text for people (a preset's description) with each point name that is a capital Greek
 * letter spelled out ('Gamma', 'Omega2') written as the letter, as `pointName` writes it. */
export function greekPointNames(text) {
  return text.replace(/\b[A-Z][a-z]+[0-9]{0,2}\b/g, (word) => pointName(word));
}

/** The image of a point in a polygon: its name in lowercase (the image of Γ is γ). */
export const imageName = (point) => pointName(point.toLowerCase());

/** The poles of the velocity and acceleration polygons (Plotly text, HTML subscripts). */
export const POLYGON_POLE = { velocity: 'O<sub>v</sub>', acceleration: 'O<sub>a</sub>' };
