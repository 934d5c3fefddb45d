// point-readout.js: a point's position, velocity and acceleration at the instant, and the paths
// (coupler curves) of any points over the cycle, in the linkage drawing.
//
// A click or tap on a point of the drawing (or the "Read point" menu, for the keyboard) picks it:
// its readout shows r, v and a with their magnitudes, and "trace its path" adds its path to the
// drawing, in a colour of its own; several paths at once, each removable (untick it, or "Clear
// paths"). Hovering a point with the mouse reads it out until the pointer leaves it. Numbers are
// the server's: at the analysed instant the /analyze answer's, while the mechanism plays the
// sweep's nearest sample (named with its crank angle or time), never an interpolation. The paths
// are the sweep's positions already fetched: no request is made for a readout or a path.
//
// A click on a link's bar or plate away from its named points adds that point of the link to the
// scene (main.js addLinkPoint: the server sweeps and analyses it like a coupler point); it is then
// read and traced like any other, and "Remove point" takes it away again.

import { show, unitLabel, toDisplay, fmt, denoise } from './units.js';
import { pointName } from './notation.js';

const NONE = '';

export class PointReadout {
  /**
   * @param {import('./linkage-view.js').LinkageView} view
   * @param {{select: HTMLSelectElement, trace: HTMLInputElement, clear: HTMLButtonElement, remove: HTMLButtonElement, out: HTMLElement}} els
   * @param {{removable: (name: string) => boolean, remove: (name: string) => void}} points the
   *   points added on a link, and how one is taken away
   */
  constructor(view, els, points) {
    this.view = view;
    this.els = els;
    this.points = points;
    this.scene = null;
    this.pinned = NONE; // the picked point (a click, a tap, the menu)
    this.hover = null; // the point under the mouse, read out while it is there
    this.key = null; // what the readout shows now, so that a frame changes it only when needed
    view.callbacks.onPointPick = (name) => this.pick(name);
    view.callbacks.onPointHover = (name) => {
      this.hover = name;
      this.key = null;
      if (view.lastFrame) this.update(view.lastFrame);
    };
    view.afterDraw.push((frame) => this.update(frame));
    els.select.addEventListener('change', () => this.pick(els.select.value));
    els.trace.addEventListener('change', () => this.setTraced(this.pinned, els.trace.checked));
    els.remove.addEventListener('click', () => this.pinned && this.points.removable(this.pinned) && this.points.remove(this.pinned));
    els.clear.addEventListener('click', () => {
      this.view.setTraces([]);
      this.paintTools();
    });
  }

  /** Show `name`'s readout (NONE: no point) and ring it in the drawing. */
  pick(name) {
    this.pinned = name || NONE;
    this.els.select.value = this.pinned;
    this.key = null;
    this.paintTools();
    this.view.setPicked(this.pinned || null);
  }

  setTraced(name, on) {
    if (!name) return;
    const rest = this.view.traces.filter((n) => n !== name);
    this.view.setTraces(on ? [...rest, name] : rest);
    this.paintTools();
  }

  /** The menu of points (on a new mechanism), the trace box and the clear button's state. */
  paintTools() {
    const { select, trace, clear, remove } = this.els;
    if (this.view.scene !== this.scene) {
      this.scene = this.view.scene;
      const names = Object.keys(this.view.track?.points || {});
      if (!names.includes(this.pinned)) this.pinned = NONE;
      select.replaceChildren(new Option('none', NONE), ...names.map((n) => new Option(pointName(n), n)));
      select.value = this.pinned;
    }
    trace.disabled = !this.pinned;
    trace.checked = Boolean(this.pinned) && this.view.traces.includes(this.pinned);
    clear.disabled = !this.view.traces.length;
    remove.hidden = !(this.pinned && this.points.removable(this.pinned));
    this.els.out.dataset.traces = this.view.traces.join(' ');
  }

  /** After each frame: the readout of the hovered or picked point, when what it shows changed. */
  update(frame) {
    if (this.view.scene !== this.scene) this.paintTools();
    const name = this.hover || this.pinned;
    const track = this.view.track;
    const sample = frame.exact || !track ? null : Math.round(frame.u ?? 0);
    const key = `${name}|${frame.exact ? 'exact' : sample}|${this.view.options.units}`;
    if (key === this.key) return;
    this.key = key;
    const out = this.els.out;
    out.dataset.point = name || NONE;
    if (!name) {
      delete out.dataset.values;
      out.replaceChildren('Click or tap a point of the drawing (or choose it here) to read its position, velocity and acceleration; a click on a link away from its points adds that point.');
      delete out.dataset.instant;
      return;
    }
    const q = frame.exact ? { position: frame.position[name], velocity: frame.velocity[name], acceleration: frame.acceleration[name] } : sampleOf(track, name, sample);
    const units = this.view.options.units;
    const size = this.view.map?.size || 0;
    const when = frame.exact ? 'at the analysed instant' : `at the sample ${track.param === 'time' ? 't' : 'θ'} = ${show(track.param === 'time' ? 'time' : 'angle', track.values[sample], units, 4)} (pause for any instant)`;
    out.dataset.instant = frame.exact ? 'analysed' : `sample ${sample}`;
    // the server's numbers unrounded, SI (r, v, a), for a reader of the page's data (a test)
    out.dataset.values = JSON.stringify({ r: q?.position ?? null, v: q?.velocity ?? null, a: q?.acceleration ?? null });
    const parts = [];
    for (const [symbol, kind, key2] of [['r', 'length', 'position'], ['v', 'velocity', 'velocity'], ['a', 'acceleration', 'acceleration']]) {
      const v = q?.[key2];
      if (!v) continue;
      parts.push(vectorText(symbol, pointName(name), kind, v, units, size));
    }
    const head = document.createElement('strong');
    head.textContent = `Point ${pointName(name)}`;
    out.replaceChildren(head, ` ${when}: `, ...parts.flatMap((p, i) => (i ? ['; ', p] : [p])), parts.length ? '' : 'no values at this instant.');
  }
}

/** The sweep's sample `i` of point `name`: the server's numbers, not an interpolation. */
function sampleOf(track, name, i) {
  const q = track.points[name] || {};
  return { position: q.position?.[i], velocity: q.velocity?.[i], acceleration: q.acceleration?.[i] };
}

/**
 * "v_C = (0.5, −1.2) m/s, |v_C| = 1.3 m/s" as a span (the subscript as <sub>); components and
 * magnitude rounded by units.js (denoised on the drawing's size for a position, on the
 * magnitude for a rate).
 */
function vectorText(symbol, name, kind, v, units, size) {
  const span = document.createElement('span');
  span.className = `readout-${kind}`;
  const scale = kind === 'length' ? size : Math.hypot(v[0], v[1]);
  const c = (x) => fmt(toDisplay(kind, denoise(x, scale), units), 4);
  const label = () => {
    const f = document.createDocumentFragment();
    const sub = document.createElement('sub');
    sub.textContent = name;
    f.append(symbol, sub);
    return f;
  };
  span.append(label(), ` = (${c(v[0])}, ${c(v[1])}) ${unitLabel(kind, units)}`);
  if (kind !== 'length') span.append(', |', label(), `| = ${show(kind, Math.hypot(v[0], v[1]), units, 4)}`);
  return span;
}
