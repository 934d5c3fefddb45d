// export.js: what a student takes away: the cycle and the analysed instant as CSV, the drawing,
// the polygons and the plots as PNG or SVG, and the scene as JSON (download and upload).
//
// Numbers are written in the display units chosen on the page, with the unit in every column
// header; the sweep's columns are the series the plots draw (series.js), in the plots' order
// (driver angle 0..360 deg). Nothing is recomputed here.

import { cycleOrder, xValues, xAxes, allSeries } from './series.js';
import { toDisplay, unitLabel } from './units.js';
import { slug } from './plots.js';
import { isSpatial } from './scene.js';
import { withLegend } from './polygons.js';

const $ = (id) => document.getElementById(id);

/** One CSV field: quoted when it holds a comma, a quote or a line break. */
function field(v) {
  if (v === null || v === undefined || (typeof v === 'number' && !Number.isFinite(v))) return '';
  const s = typeof v === 'number' ? String(v) : String(v);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

export function toCsv(rows) {
  return rows.map((r) => r.map(field).join(',')).join('\r\n') + '\r\n';
}

export function download(filename, blob) {
  const url = URL.createObjectURL(blob);
  const a = Object.assign(document.createElement('a'), { href: url, download: filename });
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** The sweep: x columns (driver angle, time when it is uniform) then every series. */
export function sweepCsv(scene, track, units) {
  const order = cycleOrder(track);
  const axes = xAxes(scene, track).map((axis) => xValues(scene, track, order, axis, units));
  const series = allSeries(scene, track, order, units);
  const header = [...axes.map((a) => a.title), ...series.map((s) => `${s.label} [${s.unit}]`)];
  const rows = order.index.map((_, i) => [...axes.map((a) => a.x[i]), ...series.map((s) => s.y[i])]);
  return toCsv([header, ...rows]);
}

/** The analysed instant as the server gave it: one row per point vector and per link quantity. */
export function instantCsv(analysis, instantLabel, units) {
  const rows = [['object', 'quantity', 'x', 'y', 'magnitude', 'unit']];
  rows.push(['instant', instantLabel.name, '', '', instantLabel.value, instantLabel.unit]);
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const [name, q] of Object.entries(group || {})) {
      for (const [quantity, kind] of [['position', 'length'], ['velocity', 'velocity'], ['acceleration', 'acceleration']]) {
        const v = q[quantity];
        if (!v) continue;
        const d = v.map((c) => toDisplay(kind, c, units));
        rows.push([`point ${name}`, quantity, ...d.slice(0, 2), Math.hypot(...d), unitLabel(kind, units)]);
      }
    }
  }
  for (const [name, l] of Object.entries(analysis.links || {})) {
    for (const [quantity, kind] of [['angle', 'angle'], ['omega', 'omega'], ['alpha', 'alpha']]) {
      if (typeof l[quantity] === 'number') rows.push([`link ${name}`, quantity, '', '', toDisplay(kind, l[quantity], units), unitLabel(kind, units)]);
    }
  }
  for (const j of analysis.joints || []) {
    for (const part of ['transport_velocity', 'relative_velocity', 'transport_acceleration', 'coriolis_acceleration', 'relative_acceleration']) {
      const v = j[part];
      if (!v) continue;
      const kind = part.endsWith('velocity') ? 'velocity' : 'acceleration';
      const d = v.map((c) => toDisplay(kind, c, units));
      rows.push([`joint ${j.point}`, part.replace('_', ' '), ...d.slice(0, 2), Math.hypot(...d), unitLabel(kind, units)]);
    }
  }
  return toCsv(rows);
}

/** CSS rules the drawing's labels need, inlined so the SVG file looks like the page. */
function drawingStyle() {
  const wanted = ['-label', '.view-note'];
  const rules = [];
  for (const sheet of document.styleSheets) {
    let list;
    try {
      list = sheet.cssRules;
    } catch {
      continue;
    }
    for (const r of list) if (r.selectorText && wanted.some((w) => r.selectorText.includes(w))) rules.push(r.cssText);
  }
  return rules.join('\n');
}

/** The live drawing as a standalone SVG document. */
export function drawingSvg(svg) {
  const copy = svg.cloneNode(true);
  const [, , w, h] = (svg.getAttribute('viewBox') || '0 0 1000 600').split(/\s+/).map(Number);
  copy.setAttribute('xmlns', 'http://www.w3.org/2000/svg');
  copy.setAttribute('width', String(w));
  copy.setAttribute('height', String(h));
  copy.removeAttribute('class');
  const style = document.createElementNS('http://www.w3.org/2000/svg', 'style');
  style.textContent = drawingStyle();
  copy.insertBefore(style, copy.firstChild);
  const bg = document.createElementNS('http://www.w3.org/2000/svg', 'rect');
  Object.entries({ x: 0, y: 0, width: w, height: h, fill: '#ffffff' }).forEach(([k, v]) => bg.setAttribute(k, String(v)));
  copy.insertBefore(bg, style.nextSibling);
  return { text: new XMLSerializer().serializeToString(copy), width: w, height: h };
}

/** An image loaded from `url` (a blob: or data: URL). */
async function loadImage(url, what) {
  const img = new Image();
  await new Promise((resolve, reject) => {
    img.onload = resolve;
    img.onerror = () => reject(new Error(`${what} could not be rasterised`));
    img.src = url;
  });
  return img;
}

/** Rasterise an SVG document (text) at `scale` into a PNG blob. */
async function svgToPng(text, width, height, scale = 2) {
  const url = URL.createObjectURL(new Blob([text], { type: 'image/svg+xml' }));
  try {
    const img = await loadImage(url, 'the drawing');
    const canvas = Object.assign(document.createElement('canvas'), { width: width * scale, height: height * scale });
    const ctx = canvas.getContext('2d');
    ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
    return await new Promise((resolve) => canvas.toBlob(resolve, 'image/png'));
  } finally {
    URL.revokeObjectURL(url);
  }
}

/** A Plotly chart as PNG or SVG (Plotly's own toImage). */
async function plotImage(div, format) {
  const P = globalThis.Plotly;
  if (!P || !div.data) throw new Error('this figure is not drawn yet');
  const box = div.getBoundingClientRect();
  const url = await P.toImage(div, { format, width: Math.max(box.width, 640), height: Math.max(box.height, 400), scale: format === 'png' ? 2 : 1 });
  return dataUrlBlob(url);
}

/**
 * A polygon as the student sees it: the polygon with its legend and, when it is shown, its detail
 * panel under it (polygon-detail.js), stacked in one PNG or SVG. Each panel keeps its on-screen
 * proportions, magnified alike to at least 640 px wide (so the "1 cm = …" scales hold in an SVG
 * of a panel at least that wide).
 */
async function polygonImage(main, format) {
  const P = globalThis.Plotly;
  if (!P || !main.data) throw new Error('this figure is not drawn yet');
  const detail = $(`${main.id}-detail`);
  const panels = detail && !detail.hidden && detail.data ? [main, detail] : [main];
  const box = main.getBoundingClientRect();
  const zoom = Math.max(1, 640 / box.width);
  const width = Math.round(box.width * zoom);
  const scale = format === 'png' ? 2 : 1;
  const images = [];
  for (const div of panels) {
    // The polygon with its legend (HTML under it on the page, Plotly's in the image, in as much room)
    const legend = div === main ? $(`${main.id}-legend`) : null;
    const room = legend ? legend.getBoundingClientRect().height : 0;
    const height = Math.round((div.getBoundingClientRect().height + room) * zoom);
    // The legend's room in the image: its height on the page (Plotly's, in the wider image,
    // wraps to as many rows at most).
    const figure = legend ? withLegend(div, Math.round(room)) : { data: div.data, layout: div.layout };
    images.push({ url: await P.toImage(figure, { format, width, height, scale }), height });
  }
  const total = images.reduce((sum, im) => sum + im.height, 0);
  return format === 'png' ? stackPng(images, width, total, scale) : stackSvg(images, width, total);
}

/** PNG images (data: URLs, `scale` px per CSS px) one under the other on one canvas. */
async function stackPng(images, width, height, scale) {
  const canvas = Object.assign(document.createElement('canvas'), { width: width * scale, height: height * scale });
  const ctx = canvas.getContext('2d');
  let y = 0;
  for (const { url, height: h } of images) {
    const img = await loadImage(url, 'a panel');
    ctx.drawImage(img, 0, y * scale, width * scale, h * scale);
    y += h;
  }
  return new Promise((resolve) => canvas.toBlob(resolve, 'image/png'));
}

/** SVG documents (data: URLs) nested one under the other in one SVG document. */
async function stackSvg(images, width, height) {
  const NS = 'http://www.w3.org/2000/svg';
  const root = document.createElementNS(NS, 'svg');
  Object.entries({ xmlns: NS, width, height, viewBox: `0 0 ${width} ${height}` }).forEach(([k, v]) => root.setAttribute(k, String(v)));
  let y = 0;
  for (const { url, height: h } of images) {
    const text = await dataUrlBlob(url).text();
    const panel = document.importNode(new DOMParser().parseFromString(text, 'image/svg+xml').documentElement, true);
    panel.setAttribute('y', String(y));
    root.append(panel);
    y += h;
  }
  return new Blob([new XMLSerializer().serializeToString(root)], { type: 'image/svg+xml' });
}

/** A data: URL's bytes as a Blob, decoded here (a fetch of it would break the page's CSP). */
function dataUrlBlob(url) {
  const comma = url.indexOf(',');
  const head = url.slice(5, comma); // "image/png;base64" or "image/svg+xml;charset=utf-8"
  const type = head.split(';')[0];
  const body = url.slice(comma + 1);
  if (head.endsWith(';base64')) {
    const bytes = Uint8Array.from(atob(body), (c) => c.charCodeAt(0));
    return new Blob([bytes], { type });
  }
  return new Blob([decodeURIComponent(body)], { type });
}

/** Wire the export menu to the app (main.js's App: scene, track, analysis, units). */
export function installExport(app) {
  const name = () => slug(app.scene?.title);
  const guard = (fn) => async (...args) => {
    try {
      await fn(...args);
      $('export-menu').open = false;
    } catch (err) {
      app.status(`Export failed: ${err.message}`, 'error');
    }
  };
  // A cam's or a gear train's view (js/cam-view.js, gear-view.js): its table and its scene.
  $('export-csv').addEventListener('click', guard(() => {
    const view = app.familyView();
    if (view === app.cams) return download(`${slug(view.scene?.title)}-svaj.csv`, new Blob([view.svajCsv()], { type: 'text/csv' }));
    if (view) return download(`${slug(view.scene?.title)}-speeds.csv`, new Blob([view.speedsCsv()], { type: 'text/csv' }));
    if (!app.track || app.track.n < 2) throw new Error('there is no cycle (sweep) to export for this scene');
    download(`${name()}-cycle.csv`, new Blob([sweepCsv(app.scene, app.track, app.units)], { type: 'text/csv' }));
  }));
  $('export-instant-csv').addEventListener('click', guard(() => {
    if (!app.analysis || isSpatial(app.scene)) throw new Error('no analysed instant of a planar linkage yet');
    const v = app.instantValue(app.analysisU ?? app.u);
    const label = app.track.param === 'time'
      ? { name: 'time t', value: v, unit: 's' }
      : { name: 'driver angle', value: toDisplay('angle', v, app.units), unit: unitLabel('angle', app.units) };
    download(`${name()}-instant.csv`, new Blob([instantCsv(app.analysis, label, app.units)], { type: 'text/csv' }));
  }));
  $('export-figure').addEventListener('click', guard(async () => {
    const which = $('export-figure-which').value;
    const format = $('export-figure-format').value;
    let blob;
    if (which === 'linkage') {
      const svg = isSpatial(app.scene) ? $('spatial') : $('linkage');
      const { text, width, height } = drawingSvg(svg);
      blob = format === 'svg' ? new Blob([text], { type: 'image/svg+xml' }) : await svgToPng(text, width, height);
    } else if (which.endsWith('-polygon')) {
      blob = await polygonImage($(which), format);
    } else {
      blob = await plotImage($(which), format);
    }
    download(`${name()}-${which}.${format}`, blob);
  }));
  $('export-scene').addEventListener('click', guard(() => {
    const scene = app.familyView()?.scene ?? app.scene;
    if (!scene) throw new Error('no scene loaded');
    download(`${slug(scene.title)}.json`, new Blob([JSON.stringify(scene, null, 2)], { type: 'application/json' }));
  }));
  $('import-scene').addEventListener('change', guard(async (ev) => {
    const file = ev.target.files?.[0];
    ev.target.value = '';
    if (!file) return;
    let doc;
    try {
      doc = JSON.parse(await file.text());
    } catch (err) {
      throw new Error(`${file.name} is not JSON (${err.message})`);
    }
    const scene = doc && typeof doc === 'object' && doc.scene && typeof doc.scene === 'object' ? doc.scene : doc;
    if (!scene || typeof scene !== 'object' || !scene.kind) throw new Error(`${file.name} is not a scene document (no "kind")`);
    await app.openScene(scene, { type: 'file', name: file.name });
  }));
}
