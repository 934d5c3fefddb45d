// dynamics.js: forces and energy over one cycle (dynamics-v1), for scenes with masses or loads.
//
// One /sweep with the quantities `forces` and `energy` per mechanism (not per frame): stacked
// plots over the driver angle of the driving torque with its mean, the driver's power, the
// magnitude of every joint force, the kinetic energy and the equivalent inertia; the polar
// diagram of the frame force (the tip of the shaking force over the cycle from O, with magnitude
// circles, angle spokes and the current instant's vector); the cycle's figures. For a four-bar,
// "Compare balanced" asks /balance for counterweights as heavy as the crank and the rocker and
// adds the balanced mechanism's frame force to the polar diagram.

import * as api from './api.js';
import { toDisplay, unitLabel, fmt } from './units.js';
import { svgEl, setAttrs, arrowMarker } from './svg.js';
import { LinkageView } from './linkage-view.js';
import { trackFromSweep, frameAt } from './track.js';
import { toCsv, download } from './export.js';
import { pointName } from './notation.js';

const ARROW_PX = 70; // the largest joint force of the cycle, on the drawing
const CONFIG = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ['select2d', 'lasso2d', 'toImage'] };
const FIELDS = ['masses', 'point_masses', 'forces', 'torques'];

/** Whether the scene has masses or loads (only then is the dynamics panel shown). */
export function hasDynamics(scene) {
  if (!scene || scene.kind !== 'linkage') return false;
  return FIELDS.some((k) => scene[k] && Object.keys(scene[k]).length > 0);
}

const norm = (v) => Math.hypot(v[0], v[1]);
const SPOKES = Array.from({ length: 12 }, (_, i) => (i * Math.PI) / 6); // every 30 degrees

/** Magnitude circles at a round step (1, 2 or 5 times a power of ten), three to six of them,
 * the outermost at or beyond ``largest``. */
export function polarGrid(largest) {
  const raw = largest / 4;
  const decade = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((m) => m * decade).find((v) => v >= raw);
  const count = Math.max(1, Math.ceil(largest / step - 1e-9));
  const rings = Array.from({ length: count }, (_, i) => (i + 1) * step);
  return { rings, radius: rings[rings.length - 1] };
}

/** Circles of the given radii about O as one line broken by nulls. */
function circles(radii) {
  const x = [];
  const y = [];
  for (const r of radii) {
    for (let i = 0; i <= 96; i += 1) {
      x.push(r * Math.cos((i * Math.PI) / 48));
      y.push(r * Math.sin((i * Math.PI) / 48));
    }
    x.push(null);
    y.push(null);
  }
  return { x, y };
}

/** Spokes from O to ``radius`` every 30 degrees, one line broken by nulls. */
function spokes(radius) {
  return {
    x: SPOKES.flatMap((a) => [0, radius * Math.cos(a), null]),
    y: SPOKES.flatMap((a) => [0, radius * Math.sin(a), null]),
  };
}

function grounded(scene) {
  const ground = Object.entries(scene.links).find(([, l]) => l.ground)?.[0];
  return scene.joints
    .filter((j) => j.type === 'revolute' && j.links.includes(ground))
    .map((j) => j.links.find((l) => l !== ground));
}

/** Counterweights as heavy as each grounded link (1 kg where it has no mass). */
export function counterweights(scene) {
  return grounded(scene).map((link) => ({ link, mass: scene.masses?.[link]?.mass || 1 }));
}

/** The scene with Coulomb friction ``slider`` at every slider and prismatic joint and a friction
 * circle (``pin`` times ``radius``) at every revolute joint; unchanged where both are 0. */
export function withFriction(scene, slider, pin, radius) {
  if (!(slider > 0) && !(pin > 0)) return scene;
  const joints = scene.joints.map((joint) => {
    const { friction, ...rest } = joint;
    if (joint.type === 'revolute') return pin > 0 ? { ...rest, friction: { coefficient: pin, pin_radius: radius } } : rest;
    return slider > 0 ? { ...rest, friction: { coefficient: slider } } : rest;
  });
  return { ...scene, joints };
}

function isFourBar(scene) {
  const moving = Object.values(scene.links).filter((l) => !l.ground).length;
  return moving === 3 && scene.joints.length === 4 && scene.joints.every((j) => j.type === 'revolute');
}

/**
 * The cycle as the plots draw it, one row per sample: the driver angle (display units), the
 * driving torque M [N m], the power M ω [W], every joint force F_x, F_y, |F| [N], the kinetic
 * energy T [J] and the equivalent inertia [kg m²]; the server's numbers, unrounded.
 */
export function cycleCsv(sweep, units) {
  const driver = sweep.drivers[0];
  const columns = [[`driver angle [${unitLabel('angle', units)}]`, sweep.driver_angle.map((a) => toDisplay('angle', a, units))]];
  if (driver) columns.push([`torque M (${driver.link}) [N m]`, driver.torque], ['power M ω [W]', driver.power]);
  for (const joint of sweep.joints) {
    columns.push(
      [`F_x at ${joint.point} [N]`, joint.force.map((f) => f[0])],
      [`F_y at ${joint.point} [N]`, joint.force.map((f) => f[1])],
      [`|F| at ${joint.point} [N]`, joint.force.map(norm)],
    );
  }
  columns.push(['kinetic energy T [J]', sweep.energy.kinetic], ['equivalent inertia [kg m²]', sweep.energy.equivalent_inertia]);
  const rows = sweep.driver_angle.map((_, i) => columns.map(([, values]) => values[i]));
  return toCsv([columns.map(([title]) => title), ...rows]);
}

export class DynamicsPanel {
  constructor({ section, plots, hodograph, info, message, balance, arrows, onArrows, balancedBox, balancedSvg }) {
    Object.assign(this, { section, plots, hodograph, info, message, balance, arrows, balancedBox });
    this.balancedView = new LinkageView(balancedSvg, { onDrag: () => {}, onDragEnd: () => {} });
    this.seq = 0;
    this.scene = null;
    this.sweep = null;
    this.balanced = null;
    balance.addEventListener('change', () => this.drawHodograph());
    arrows.addEventListener('change', () => onArrows());
    // statics and friction (docs/DYNAMICS.md): the same sweep asked again with them
    const field = (id) => section.querySelector(`#${id}`);
    this.statics = field('dynamics-statics');
    this.friction = ['dynamics-mu-slider', 'dynamics-mu-pin', 'dynamics-pin-radius'].map(field);
    this.fluctuation = field('dynamics-k');
    field('dynamics-csv').addEventListener('click', () => {
      // the series drawn (a newer sweep may be on its way)
      if (this.plotted) download('cycle-dynamics.csv', new Blob([cycleCsv(this.plotted, this.units)], { type: 'text/csv' }));
    });
    for (const input of [this.statics, this.fluctuation, ...this.friction]) {
      input.addEventListener('change', () => {
        if (this.original) this.show(this.original, this.units, this.samples);
      });
    }
  }

  /** The scene as asked: with the friction of the panel's fields (a bad value: none). */
  asked(scene) {
    const [slider, pin, radius] = this.friction.map((input) => Number(input.value));
    const ok = (x) => Number.isFinite(x) && x >= 0;
    if (!ok(slider) || !ok(pin) || !(radius > 0)) return scene;
    return withFriction(scene, slider, pin, radius);
  }

  /**
   * Another geometry is shown (a preset, an edit): the sweep of forces drawn is no longer its own,
   * so the instant's arrow, the joint forces on the drawing and the balanced mechanism stop
   * following the animation (an arrow moved on another mechanism's sweep, a Plotly relayout
   * of 25-50 ms at every frame drawn while the next mechanism opened) until ``show`` draws
   * the new one; a sweep still asked for is dropped.
   */
  leave() {
    this.seq += 1;
    this.sweep = null;
    this.balanced = null;
    clearTimeout(this.instantTimer);
  }

  /** The sweep (``samples`` as the animation's, so that its frames index both). */
  async show(original, units, samples) {
    const seq = ++this.seq;
    this.units = units;
    this.samples = samples;
    this.original = original;
    this.section.hidden = !hasDynamics(original);
    if (this.section.hidden) return;
    delete this.section.dataset.asked;
    const scene = this.asked(original);
    const statics = this.statics.checked;
    this.scene = scene;
    this.sweep = null;
    this.balanced = null;
    this.instant = 0;
    this.balance.parentElement.hidden = !isFourBar(scene);
    this.message.hidden = true;
    let sweep;
    try {
      sweep = await api.sweep(scene, samples, ['forces', 'energy'], undefined, statics, this.k());
    } catch (err) {
      if (seq !== this.seq) return;
      this.message.textContent = err.detail;
      this.message.hidden = false;
      return;
    }
    if (seq !== this.seq) return;
    this.sweep = sweep;
    this.drawCycle();
    // what the plots show, for a reader (and a test) to wait on
    this.section.dataset.asked = `${statics ? 'statics' : 'dynamics'}${scene === original ? '' : '+friction'}`;
    if (isFourBar(scene)) {
      try {
        const answer = await api.balance(scene, counterweights(scene));
        const balancedSweep = await api.sweep(answer.scene, samples, ['position', 'forces']);
        if (seq !== this.seq) return;
        this.balanced = { answer, sweep: balancedSweep, track: trackFromSweep(balancedSweep), shown: false };
      } catch (err) {
        this.balanced = { error: err.detail };
      }
    }
    this.drawHodograph();
  }

  /** The coefficient of speed fluctuation k of the panel's field, or null where it is not in (0, 1]. */
  k() {
    const k = Number(this.fluctuation.value);
    return k > 0 && k <= 1 ? k : null;
  }

  /** The cycle's efficiency and self-locking, in words (with friction only). */
  frictionWords(c) {
    if (!('efficiency' in c)) return '';
    const eta = c.efficiency === null ? 'no efficiency (not a driven machine, or it locks)' : `efficiency ${fmt(c.efficiency)}`;
    const locking = c.self_locking ? ` ${c.self_locking.reason}.` : ' No self-locking.';
    return ` With friction: ${eta}.${locking}`;
  }

  drawCycle() {
    const P = globalThis.Plotly;
    const s = this.sweep;
    if (!P || !s) return;
    const x = s.driver_angle.map((a) => toDisplay('angle', a, this.units));
    const xTitle = `driver angle [${unitLabel('angle', this.units)}]`;
    const driver = s.drivers[0];
    const traces = [];
    if (driver) {
      traces.push({ x, y: driver.torque, name: `torque M (${driver.link})`, yaxis: 'y', line: { color: '#c0392b' } });
      if (driver.torque_frictionless) {
        traces.push({ x, y: driver.torque_frictionless, name: 'torque without friction', yaxis: 'y', line: { dash: 'dot', color: '#7f8c8d' } });
      }
      if (s.cycle) {
        traces.push({ x: [x[0], x[x.length - 1]], y: [s.cycle.mean_torque, s.cycle.mean_torque], name: 'mean torque', yaxis: 'y', line: { dash: 'dash', color: '#c0392b' } });
      }
      traces.push({ x, y: driver.power, name: 'power M ω', yaxis: 'y2', line: { color: '#8e44ad' } });
    }
    for (const joint of s.joints) {
      traces.push({ x, y: joint.force.map(norm), name: `|F| at ${pointName(joint.point)}`, yaxis: 'y3' });
    }
    traces.push({ x, y: s.energy.kinetic, name: 'kinetic energy T', yaxis: 'y4', line: { color: '#27ae60' } });
    traces.push({ x, y: s.energy.equivalent_inertia, name: 'equivalent inertia', yaxis: 'y5', line: { color: '#2c3e50' } });
    const axis = (title, domain) => ({ title: { text: title, font: { size: 11 } }, domain, zeroline: true });
    const layout = {
      // the top margin holds Plotly's toolbar (25 px, shown while the pointer is over the
      // figure), which lay on the torque curve with 16 px
      margin: { l: 70, r: 16, t: 32, b: 44 },
      // a phone's column stacks the legend one entry a row (~210 px): the figure grows by as much,
      // so that the axes keep their height and the legend (placed in their fractions) its place
      height: matchMedia('(max-width: 760px)').matches ? 876 : 656,
      showlegend: true,
      // the legend's top under the x axis' title (which ends about 75 px under the axes)
      legend: { orientation: 'h', y: -0.15, yanchor: 'top' },
      xaxis: { title: { text: xTitle }, anchor: 'y5' },
      yaxis: axis('torque [N m]', [0.82, 1]),
      yaxis2: axis('power [W]', [0.62, 0.79]),
      yaxis3: axis('joint force [N]', [0.42, 0.59]),
      yaxis4: axis('T [J]', [0.22, 0.39]),
      yaxis5: axis('I_eq [kg m²]', [0, 0.19]),
    };
    P.react(this.plots, traces, layout, CONFIG);
    this.plotted = s;
    const c = s.cycle;
    this.info.textContent = c
      ? `Period ${fmt(c.period)} s, mean torque ${fmt(c.mean_torque)} N m, mean power ${fmt(c.mean_power)} W, ` +
        `work per cycle ${Object.entries(c.work).map(([k, v]) => `${k} ${fmt(v)} J`).join(', ') || '(no loads)'}, ` +
        `energy fluctuation ${fmt(c.energy_fluctuation)} J` +
        (c.flywheel_inertia === null || c.flywheel_inertia === undefined ? '.' : `, flywheel inertia ${fmt(c.flywheel_inertia)} kg m² for k = ${fmt(c.speed_fluctuation)}.`) +
        this.frictionWords(c)
      : 'The driver does not turn fully at constant speed: no cycle figures.';
  }

  /**
   * The polar diagram of the frame force, drawn as textbooks draw it on Plotly's cartesian axes
   * (the vendored plotly-basic has no polar axes): the tip of the force vector over the cycle
   * from the marked origin O, equal scales, magnitude circles labelled in N and angle spokes
   * every 30 degrees labelled, and the current instant's vector as an arrow from O
   * (``markInstant``). With "Compare balanced" the balanced mechanism's curve is added.
   */
  drawHodograph() {
    const P = globalThis.Plotly;
    const s = this.sweep;
    if (!P || !s) return;
    const curves = [{ forces: s.frame_force, name: 'frame force (tip of F over the cycle)', color: '#c0392b' }];
    let note = '';
    if (this.balance.checked && this.balanced?.sweep) {
      curves.push({ forces: this.balanced.sweep.frame_force, name: 'balanced', color: '#27ae60' });
      note = this.balanced.answer.counterweights.map((w) => `${w.link}: ${fmt(w.mass)} kg at ${fmt(w.distance)} m from ${w.pivot}`).join('; ');
    } else if (this.balance.checked && this.balanced?.error) {
      note = this.balanced.error;
    }
    const largest = Math.max(...curves.flatMap((c) => c.forces.map(norm)), 1e-300);
    const { rings, radius } = polarGrid(largest);
    const grid = { mode: 'lines', hoverinfo: 'skip', showlegend: false, line: { color: '#b8c2cc', width: 1 } };
    const traces = [
      { ...grid, name: 'magnitude circles', ...circles(rings) },
      { ...grid, name: 'angle spokes', ...spokes(radius) },
      {
        name: 'magnitude labels', mode: 'text', hoverinfo: 'skip', showlegend: false,
        x: rings.map((r) => r * Math.cos(Math.PI / 12)), y: rings.map((r) => r * Math.sin(Math.PI / 12)),
        text: rings.map((r) => `${fmt(r, 3)} N`), textfont: { size: 11, color: '#6b7785' },
      },
      {
        name: 'angle labels', mode: 'text', hoverinfo: 'skip', showlegend: false,
        x: SPOKES.map((a) => 1.12 * radius * Math.cos(a)), y: SPOKES.map((a) => 1.12 * radius * Math.sin(a)),
        text: SPOKES.map((a) => `${Math.round((a * 180) / Math.PI)}°`), textfont: { size: 11, color: '#6b7785' },
      },
      ...curves.map((c) => ({
        name: c.name, mode: 'lines', line: { color: c.color, width: 2 },
        x: c.forces.map((f) => f[0]), y: c.forces.map((f) => f[1]),
        hovertemplate: '|F| %{customdata:.4g} N<br>Fx %{x:.4g} N, Fy %{y:.4g} N<extra></extra>',
        customdata: c.forces.map(norm),
      })),
      { name: 'origin O', mode: 'markers+text', x: [0], y: [0], text: ['O'], textposition: 'bottom left', marker: { color: '#2c3e50', size: 7 }, hoverinfo: 'skip', showlegend: false },
    ];
    const axis = { range: [-1.25 * radius, 1.25 * radius], showgrid: false, zeroline: false, showticklabels: false, fixedrange: true };
    const layout = {
      // two short lines: one long one was cut at both ends in the panel's column
      title: { text: 'Polar diagram of the frame force<br>(shaking force): F on the frame, from O', font: { size: 13 } },
      margin: { l: 16, r: 16, t: 56, b: 16 },
      height: 380,
      xaxis: axis,
      yaxis: { ...axis, scaleanchor: 'x', scaleratio: 1 },
      showlegend: true,
      legend: { orientation: 'h', y: -0.02 },
      annotations: [this.instantArrow(this.instant ?? 0)],
    };
    P.react(this.hodograph, traces, layout, CONFIG);
    this.hodograph.dataset.note = note;
    const side = this.balance.checked && this.balanced?.track;
    this.balancedBox.hidden = !side;
    if (side && !this.balanced.shown) {
      this.balancedView.setScene(this.balanced.answer.scene, this.balanced.track);
      this.balancedView.draw(frameAt(this.balanced.track, 0));
      this.balanced.shown = true;
    }
    this.balance.title = note;
  }

  /** The arrow from O to the frame force at sample ``k`` (a Plotly annotation). */
  instantArrow(k) {
    const F = this.sweep.frame_force[k];
    return {
      name: 'current frame force', x: F[0], y: F[1], ax: 0, ay: 0, xref: 'x', yref: 'y', axref: 'x', ayref: 'y',
      showarrow: true, arrowhead: 2, arrowsize: 1.3, arrowwidth: 2.5, arrowcolor: '#2c3e50', text: '',
      hovertext: `F = (${fmt(F[0], 4)}, ${fmt(F[1], 4)}) N, |F| = ${fmt(norm(F), 4)} N`,
    };
  }

  /** Move the current instant's arrow to the sample nearest ``u`` (when it changes; a relayout
   * at most every 80 ms while the mechanism moves). */
  markInstant(track, u) {
    const s = this.sweep;
    if (!s || this.section.hidden || !track || track.param !== 'angle' || s.samples !== track.n) return;
    const k = Math.min(Math.max(Math.round(u), 0), s.samples - 1);
    const now = performance.now();
    if (k === this.instant || !this.hodograph.layout) return;
    clearTimeout(this.instantTimer);
    if (now - (this.instantDrawn ?? 0) < 80) {
      this.instantTimer = setTimeout(() => this.markInstant(track, u), 80); // the last one is drawn
      return;
    }
    this.instant = k;
    this.instantDrawn = now;
    const arrow = this.instantArrow(k);
    globalThis.Plotly?.relayout(this.hodograph, {
      'annotations[0].x': arrow.x, 'annotations[0].y': arrow.y, 'annotations[0].hovertext': arrow.hovertext,
    });
  }

  /**
   * Arrows of the joint forces on the animated linkage at fractional sample ``u`` (each the force
   * the joint's first link exerts on its second), when "Show joint forces" is on and the
   * animation is the same sweep over the driver angle.
   */
  drawArrows(view, svg, frame, track, u) {
    this.markInstant(track, u);
    const b = this.balanced;
    if (b?.shown && !this.balancedBox.hidden && track && b.track.n === track.n) {
      this.balancedView.draw(frameAt(b.track, u)); // the balanced mechanism in step
    }
    let g = svg.querySelector('g.layer-forces');
    const s = this.sweep;
    const on = this.arrows.checked && !this.section.hidden && s && track && track.param === 'angle' && s.samples === track.n;
    if (!on) {
      if (g) g.setAttribute('visibility', 'hidden');
      return;
    }
    if (!g) {
      g = svgEl('g', { class: 'layer-forces' }, svg);
      this.head = arrowMarker(svgEl('defs', {}, g), 'force-head', '#c0392b');
      this.arrowNodes = null;
    }
    g.setAttribute('visibility', 'visible');
    if (!this.arrowNodes || this.arrowNodes.length !== s.joints.length || this.arrowNodes.sweep !== s) {
      for (const node of g.querySelectorAll('line, text')) node.remove();
      this.arrowNodes = s.joints.map((j) => ({
        joint: j,
        line: svgEl('line', { class: 'force-arrow', stroke: '#c0392b', 'stroke-width': 2.5, 'marker-end': this.head }, g),
        label: svgEl('text', { class: 'force-label', fill: '#c0392b' }, g),
      }));
      this.arrowNodes.sweep = s;
      this.largest = Math.max(...s.joints.flatMap((j) => j.force.map(norm)), 1e-300);
    }
    const max = s.samples - 1;
    const clamped = Math.min(Math.max(u, 0), max);
    const i = Math.min(Math.floor(clamped), Math.max(max - 1, 0));
    const f = clamped - i;
    for (const a of this.arrowNodes) {
      const p = frame.position[a.joint.point];
      const F0 = a.joint.force[i];
      const F1 = a.joint.force[Math.min(i + 1, max)];
      const F = [F0[0] + (F1[0] - F0[0]) * f, F0[1] + (F1[1] - F0[1]) * f];
      const size = norm(F);
      if (!p || size < 1e-9 * this.largest) {
        a.line.setAttribute('visibility', 'hidden');
        a.label.setAttribute('visibility', 'hidden');
        continue;
      }
      const [x, y] = view.px(p);
      const length = (ARROW_PX * size) / this.largest;
      const x2 = x + (F[0] / size) * length;
      const y2 = y - (F[1] / size) * length;
      setAttrs(a.line, { x1: x, y1: y, x2, y2, visibility: null });
      setAttrs(a.label, { x: x2 + 4, y: y2 - 4, visibility: null });
      a.label.textContent = `F ${pointName(a.joint.point)} ${fmt(size, 3)} N`;
    }
  }
}
