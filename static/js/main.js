// main.js: wiring. Owns the state of the page and decides when to ask the server.
//
// Requests are made per decision, never per frame:
//   geometry change (preset, dimension, driver, law) -> one /sweep for the whole cycle
//   pause, drag end, slider, edit (debounced)         -> one /analyze with the polygons, then
//                                                       the /solution once the instant is drawn
// The animation (requestAnimationFrame, time-based) only plays back the sweep it already has.

import { afterPaint } from './playback.js';
import * as api from './api.js';
import { Controls, POSE_PARAMETER } from './controls.js';
import { LinkageView, ZOOM_STEP } from './linkage-view.js';
import { PointReadout } from './point-readout.js';
import { CentreControls } from './instant-centres.js';
import { SpatialView } from './spatial-view.js';
import { SpatialFields, spatialTrack, sweepRequest, chainAt, extentOf, renderSpatialPlots } from './spatial-motion.js';
import { renderPolygons, clearPolygons } from './polygons.js';
import { renderPlots, moveCursor, available, quantityChoices } from './plots.js';
import { cycleOrder, allSeries, xAxes, transmissionName } from './series.js';
import { renderSolution, renderMessage } from './steps.js';
import { readHash, writeHash } from './share.js';
import { trackFromSweep, staticTrack, frameAt, valueAt, indexOfValue, componentSources, samplesFor } from './track.js';
import * as S from './scene.js';
import { fmt, show } from './units.js';
import { plotlyReady, katexReady } from './vendor.js';
import { installTabs } from './tabs.js';
import { installExport } from './export.js';
import { renderMagnitudes } from './magnitudes.js';
import { Editor } from './editor.js';
import { DynamicsPanel } from './dynamics.js';
import { GearTrains } from './gear-view.js';
import { CamApp } from './cam-view.js';
import { LinkageDesigner } from './synthesis-view.js';

// The least samples per revolution (1.5 deg apart: smooth cycle plots, the dynamics' cycle means);
// more where the drawing needs them (fetchTrack).
const SAMPLES = 241;
const CYCLE_SECONDS = 4; // one revolution at 1x (angle-driven scenes)
const DEBOUNCE_MS = 250; // analysis after the last slider/drag movement
const PLOTS_AFTER_MS = 150; // a new geometry's cycle plots wait this long (left out if a newer one came)
const QUANTITIES = ['position', 'velocity', 'acceleration'];
// An instant as drawn: the /analyze body the worked solution carries as `results`, and the
// polygons' segments (the extension `polygons`, docs/ARCHITECTURE.md).
const INSTANT = ['position', 'velocity', 'acceleration', 'poles', 'components', 'polygons'];
const FIRST_STEPS = 4; // worked-solution steps typeset before the page is given back (the rest follow)

const $ = (id) => document.getElementById(id);

class App {
  constructor() {
    this.presets = new Map();
    this.examples = [];
    this.source = null; // {type: 'preset', name, params} | {type: 'example', file} | {type: 'shared'}
    this.scene = null;
    this.track = null;
    this.u = 0;
    this.asked = null; // the instant put at u, exactly ({track, u, value}: placeAt)
    this.direction = 1;
    this.playing = !matchMedia('(prefers-reduced-motion: reduce)').matches;
    this.speed = 1;
    this.units = 'si';
    this.method = 'vector';
    this.plot = { links: [], quantity: null, axis: 'angle' };
    this.camera = { yaw: -35, pitch: 22 };
    this.driverEdits = {};
    this.analysis = null;
    this.polygons = null;
    this.analysisU = null;
    this.geometrySeq = 0;
    this.analysisSeq = 0;
    this.solutionSeq = 0;
    this.dirty = true;
    this.firstFrame = false;
    this.lastTime = null;
    this.lastHash = null;
    this.plotted = null;
  }

  async start() {
    this.controls = new Controls({
      preset: (v) => this.onSource(v),
      instant: (v, final) => this.onInstant(v, final),
      // Space and Play drive the gear train, the cam or the designed linkage while one is shown
      // (js/gear-view.js, js/cam-view.js, js/synthesis-view.js).
      play: (p) => {
        const other = [this.gearTrains, this.cams, this.designer].find((view) => view?.shown);
        return other ? other.setPlaying(!other.playing) : this.setPlaying(p);
      },
      speed: (s) => { this.speed = s; this.saveHash(); },
      units: (u) => this.onUnits(u),
      options: (o) => this.onOptions(o),
      plot: (sel) => { this.plot = { ...this.plot, ...sel }; this.drawPlots(); this.saveHash(); },
      method: (m) => { this.method = m; this.requestSolution(); this.saveHash(); },
      share: () => this.onShare(),
    });
    $('print-solution').addEventListener('click', () => this.openPrintable());
    installTabs();
    installExport(this);
    this.dynamics = new DynamicsPanel({
      section: $('dynamics'), plots: $('dynamics-plots'), hodograph: $('dynamics-hodograph'),
      info: $('dynamics-info'), message: $('dynamics-message'), balance: $('dynamics-balance'),
      arrows: $('dynamics-arrows'), onArrows: () => this.drawFrame(),
      balancedBox: $('dynamics-balanced'), balancedSvg: $('balanced-linkage'),
    });
    this.controls.setPlaying(this.playing);
    this.linkage = new LinkageView($('linkage'), {
      onDrag: (angle) => this.onDrag(angle),
      onDragEnd: () => this.scheduleAnalysis(0),
      onPointDrop: (name, at, frame) => this.onPointDrop(name, at, frame),
      onLinkPick: (link, at, frame) => this.addLinkPoint(link, at, frame),
    });
    // A point's readout and the paths traced (point-readout.js); zoom and pan: the buttons, and
    // the keys + − 0 outside a field (the wheel, pinch, drag and arrows are the view's own).
    this.addedPoints = []; // points picked on a link (addLinkPoint), removable
    this.pointReadout = new PointReadout(this.linkage, {
      select: $('readout-point'), trace: $('readout-trace'), clear: $('clear-traces'), remove: $('remove-point'), out: $('point-readout'),
    }, { removable: (name) => this.addedPoints.includes(name), remove: (name) => this.removeLinkPoint(name) });
    this.centreControls = new CentreControls(this.linkage, { toggle: $('show-centres'), triple: $('kennedy-triple') });
    $('zoom-in').addEventListener('click', () => this.linkage.zoomBy(ZOOM_STEP));
    $('zoom-out').addEventListener('click', () => this.linkage.zoomBy(1 / ZOOM_STEP));
    $('zoom-fit').addEventListener('click', () => this.linkage.fit());
    // The polygons are drawn at their divs' size (polygons.js, labels placed for it): drawn
    // again when the window takes another (a phone turned, a window resized), once it settles.
    let resized = null;
    window.addEventListener('resize', () => {
      clearTimeout(resized);
      resized = setTimeout(() => this.drawPolygons(), 150);
    });
    document.addEventListener('keydown', (ev) => {
      const zoom = { '+': ZOOM_STEP, '=': ZOOM_STEP, '-': 1 / ZOOM_STEP, '0': 0 }[ev.key];
      if (zoom === undefined || ev.ctrlKey || ev.metaKey || ev.altKey || $('linkage').hidden) return;
      if (ev.target.closest?.('input, select, textarea, [contenteditable]')) return;
      ev.preventDefault();
      if (zoom) this.linkage.zoomBy(zoom);
      else this.linkage.fit();
    });
    // Turn (default) or Edit: the toggle above the drawing, or the key E outside a field.
    $('edit-mode').addEventListener('click', () => this.setEditMode($('edit-mode').getAttribute('aria-pressed') !== 'true'));
    document.addEventListener('keydown', (ev) => {
      if (ev.key.toLowerCase() !== 'e' || ev.ctrlKey || ev.metaKey || ev.altKey) return;
      if (ev.target.closest?.('input, select, textarea, [contenteditable]') || !$('editor-panel').hidden) return;
      ev.preventDefault();
      this.setEditMode($('edit-mode').getAttribute('aria-pressed') !== 'true');
    });
    this.history = []; // earlier {scene, source}, for undo
    this.future = []; // undone ones, for redo
    $('undo').addEventListener('click', () => this.undo());
    $('redo').addEventListener('click', () => this.redo());
    document.addEventListener('keydown', (ev) => {
      if (!(ev.ctrlKey || ev.metaKey) || ev.target.closest?.('input[type="text"], textarea')) return;
      const key = ev.key.toLowerCase();
      if (key === 'z' && !ev.shiftKey) this.undo();
      else if (key === 'y' || (key === 'z' && ev.shiftKey)) this.redo();
      else return;
      ev.preventDefault();
    });
    this.paintHistory();
    this.editor = new Editor({
      onDone: async (scene) => {
        this.closeEditor();
        await this.openScene(scene, { name: 'the editor' });
      },
      onClose: () => this.closeEditor(),
    });
    $('new-mechanism').addEventListener('click', () => this.openEditor(null));
    $('editor-from-current').addEventListener('click', () => this.editor.open(S.isSpatial(this.scene) ? null : this.scene));
    this.spatial = new SpatialView($('spatial'), {
      onRotate: (yaw, pitch) => { this.camera = { yaw, pitch }; this.saveHash(); },
    });
    // Joint offsets and lengths of a spatial chain: a change is a new geometry (spatial-motion.js).
    this.spatialFields = new SpatialFields($('spatial-fields'), (scene) => {
      this.spatialEdit = true;
      this.loadScene(scene, { keepInstant: true }).catch((err) => this.status(`This chain cannot be analysed: ${err.detail || err.message}`, 'error'));
    });
    requestAnimationFrame((t) => this.tick(t));

    const [presets, examples, shared] = await Promise.allSettled([api.getPresets(), api.getExampleIndex(), readHash()]);
    if (presets.status === 'fulfilled') {
      for (const p of presets.value.presets || []) this.presets.set(p.name, p);
    } else {
      this.status(`Textbook mechanisms are not available: ${presets.reason.detail || presets.reason.message}`, 'error');
    }
    // The views draw linkages and spatial chains; a cam or gear-train example is for the API until
    // their views exist.
    const drawn = (x) => !x.kind || x.kind === 'linkage' || x.kind === 'spatial_chain';
    this.examples = examples.status === 'fulfilled' ? (examples.value.examples || []).filter(drawn) : [];
    this.controls.setPresetChoices([...this.presets.values()], this.examples);
    // Gear trains (issue 25): their own group at the end of the menu and their own panel.
    this.gearTrains = new GearTrains($('gear-train'));
    this.gearsReady = this.gearTrains.load(examples.status === 'fulfilled' ? examples.value.examples || [] : [])
      .then(() => this.gearTrains.addChoices($('preset')));
    // Cams (issue 24): their own group in the menu and their own section (js/cam-view.js).
    this.cams = new CamApp($('cam-app'));
    this.camsReady = this.cams.addChoices($('preset'));
    // Their share links, units and exports are the page's (js/share.js, units.js, export.js).
    for (const view of [this.cams, this.gearTrains]) {
      view.onChange = () => this.saveHash();
      view.setUnits(this.units);
    }
    // Design a linkage (issue 26): its own group and section; "Open in the analyser" comes back
    // here with the designed scene as a shared scene.
    this.designer = new LinkageDesigner($('synthesis-app'), {
      onOpen: (scene) => {
        this.designer.close();
        this.playing = !matchMedia('(prefers-reduced-motion: reduce)').matches;
        this.controls.setPlaying(this.playing);
        return this.openScene(scene, { name: 'the linkage designer' });
      },
    });
    this.designer.addChoices($('preset'));

    const state = shared.status === 'fulfilled' ? shared.value : null;
    if (state && !state.error) await this.restore(state);
    else {
      if (state?.error) this.status(state.error, 'error');
      await this.openDefault();
    }
    window.addEventListener('hashchange', async () => {
      if (location.hash === this.lastHash) return;
      const s = await readHash();
      if (s && !s.error) await this.restore(s);
    });
  }

  // ---- choosing a mechanism --------------------------------------------------------------------

  async openDefault() {
    if (this.presets.has('four_bar')) return this.openPreset('four_bar', {});
    if (this.presets.size) return this.openPreset(this.presets.keys().next().value, {});
    const four = this.examples.find((x) => x.file === 'S000-T1.json') || this.examples[0];
    if (four) return this.openExample(four.file);
    this.status('No mechanism could be loaded.', 'error');
  }

  async onSource(value) {
    const [type, name] = [value.slice(0, value.indexOf(':')), value.slice(value.indexOf(':') + 1)];
    if (type === 'design') {
      this.setPlaying(false, { analyse: false });
      this.cams?.close();
      this.gearTrains?.close();
      return this.designer.open();
    }
    this.designer?.close();
    if (type === 'gear' || type === 'gear-example') {
      this.setPlaying(false, { analyse: false });
      this.cams?.close();
      return this.gearTrains.open(type, name);
    }
    this.gearTrains?.close();
    if (type === 'cam') {
      this.setPlaying(false, { analyse: false });
      return this.cams.open(name);
    }
    this.cams?.close();
    this.driverEdits = {};
    // A newly chosen mechanism starts moving, as the page does on opening.
    this.playing = !matchMedia('(prefers-reduced-motion: reduce)').matches;
    this.controls.setPlaying(this.playing);
    if (type === 'preset') await this.openPreset(name, {});
    else if (type === 'example') await this.openExample(name);
  }

  async openPreset(name, params, view = null) {
    const meta = this.presets.get(name);
    this.controls.selectSource(`preset:${name}`, meta?.description || '');
    let scene;
    try {
      scene = view?.scene || await api.presetScene(meta?.scene, name, params);
    } catch (err) {
      this.status(`The preset ${name} could not be built: ${err.detail}`, 'error');
      this.reselectSource();
      return;
    }
    this.source = { type: 'preset', name, params: { ...params } };
    // A preset opens in the pose it was built in (its crank angle or its time, as the textbook
    // states the problem), as a worked example does; the server has checked the scene there, so
    // that instant is asked for beside the sweep (loadScene), and the sweep before the fields
    // are built.
    const shown = view ? this.commitOrReport(scene, view) : this.commitOrReport(scene, null, S.ownInstant(scene), true);
    this.controls.setPresetFields(meta?.parameters || [], params, (p, v) => this.onParam(p, v));
    this.setDriverFields(scene);
    await shown;
  }

  async openExample(file, view = null) {
    const entry = this.examples.find((x) => x.file === file);
    this.controls.selectSource(`example:${file}`, entry?.description || entry?.title || '');
    let scene;
    try {
      scene = view?.scene || await api.getExample(file);
    } catch (err) {
      this.status(err.detail, 'error');
      this.reselectSource();
      return;
    }
    this.source = { type: 'example', file };
    this.setExampleFields(scene);
    // A worked example opens at the book's pose (its drawn pose, its driver angle or its time),
    // not at the first sample of the sweep (a limit position for a rocking crank).
    await this.commitOrReport(scene, view, S.ownInstant(scene));
  }

  /** A scene document from elsewhere (an uploaded file, the editor): analysed at once. */
  async openScene(scene, { name = 'file' } = {}) {
    if (scene.kind === 'cam' || scene.kind === 'gear_train') return this.openFamilyScene(scene, name);
    this.cams?.close();
    this.gearTrains?.close();
    const before = this.snapshot();
    this.driverEdits = {};
    this.source = { type: 'shared' };
    this.controls.selectSource('shared', `Opened from ${name}.`);
    this.setExampleFields(scene);
    await this.commitOrReport(scene, null);
    if (this.scene === scene) this.remember(before);
  }

  // ---- editing the drawn pose: drag a joint, undo, redo ------------------------------------

  /**
   * A joint dropped at `at` (world, m): the pose shown becomes the drawn pose, with that joint
   * moved; slot axes turn with their guides. The result is a scene of its own (no longer the
   * preset's parameters), checked by the server before it replaces what is shown.
   */
  async onPointDrop(name, at, frame) {
    const scene = structuredClone(this.scene);
    for (const n of Object.keys(scene.points)) if (frame.position[n]) scene.points[n] = [...frame.position[n]];
    for (const j of scene.joints || []) {
      if (j.type === 'slider' || j.type === 'prismatic') j.axis = this.linkage.axisAt(j, j.links[0], frame);
    }
    scene.points[name] = at;
    for (const d of scene.drivers || []) delete d.angle_deg;
    const before = this.snapshot();
    try {
      await this.loadScene(scene, { keepInstant: true });
    } catch (err) {
      this.linkage.draw(frame);
      this.status(`${name} cannot go there: ${err.detail || err.message}`, 'error');
      return;
    }
    this.source = { type: 'shared' };
    this.controls.selectSource('shared', 'A mechanism edited in the drawing.');
    this.setExampleFields(scene);
    this.remember(before);
  }

  // ---- a point of a link picked in the drawing -------------------------------------------------

  /**
   * A click at `at` (world, m) on `link` in `frame`: that point of the link becomes a point of the
   * scene, fixed in the link, and is analysed by the server (the sweep for its path, the instant
   * for its readout) like a coupler point; its readout is shown and its path traced. The click is
   * carried to the drawn pose of the scene in the link's own frame: with B, C two points of the
   * link, P = B + u BC + w k×BC, the same u, w at both poses (drawing, not kinematics).
   */
  async addLinkPoint(link, at, frame) {
    const scene = structuredClone(this.scene);
    const [b, c] = (scene.links[link]?.points || []).filter((n) => scene.points[n] && frame.position[n]);
    if (!c) {
      this.status(`A point of ${link} cannot be placed: the link has fewer than two named points to fix it by.`, 'warning');
      return;
    }
    const name = freshPointName(scene);
    scene.points[name] = carried(frame.position[b], frame.position[c], at, scene.points[b], scene.points[c]);
    scene.links[link].points.push(name);
    const before = this.snapshot();
    try {
      await this.loadScene(scene, { keepInstant: true, sameMechanism: true });
    } catch (err) {
      this.status(`No point of ${link} there: ${err.detail || err.message}`, 'error');
      return;
    }
    if (this.scene !== scene) return; // a newer change won
    this.addedPoints = [...this.addedPoints, name];
    this.remember(before);
    this.pointReadout.pick(name);
    this.pointReadout.setTraced(name, true);
    this.status(`Point ${name} added to ${link}: its readout, and its path traced (Remove point takes it away).`);
  }

  /** A point added by addLinkPoint taken out of the scene again. */
  async removeLinkPoint(name) {
    const scene = structuredClone(this.scene);
    delete scene.points[name];
    for (const body of Object.values(scene.links)) body.points = body.points.filter((n) => n !== name);
    const before = this.snapshot();
    try {
      await this.loadScene(scene, { keepInstant: true, sameMechanism: true });
    } catch (err) {
      this.status(`Point ${name} cannot be removed: ${err.detail || err.message}`, 'error');
      return;
    }
    this.remember(before);
    this.pointReadout.pick('');
  }

  /** Edit mode: joints move in the drawing; Turn mode (off): a press on the driver turns it. */
  setEditMode(on) {
    $('edit-mode').setAttribute('aria-pressed', String(on));
    this.linkage.setMode(on ? 'edit' : 'turn');
    this.status(on ? 'Edit mode: drag a joint to change the geometry (E or the button to turn the crank again).' : 'Turn mode: press anywhere on the crank to turn it.');
  }

  openEditor(scene) {
    this.setPlaying(false, { analyse: false });
    $('linkage').toggleAttribute('hidden', true);
    $('spatial').toggleAttribute('hidden', true);
    // The motion controls stay: Play, the slider and Speed are there in every mode (issue 30).
    this.editor.open(scene);
  }

  closeEditor() {
    this.editor.close();
    showView(S.isSpatial(this.scene) ? 'spatial' : 'linkage');
  }

  snapshot() {
    return this.scene ? { scene: this.scene, source: structuredClone(this.source), spatial: this.spatialEdits() } : null;
  }

  remember(before) {
    if (!before) return;
    this.history.push(before);
    if (this.history.length > 50) this.history.shift();
    this.future = [];
    this.paintHistory();
  }

  async undo() {
    const state = this.history.pop();
    if (!state) return;
    this.future.push(this.snapshot());
    await this.restore({ ...state, view: { ...this.shareState().view, spatial: state.spatial, playing: false } });
    this.paintHistory();
  }

  async redo() {
    const state = this.future.pop();
    if (!state) return;
    this.history.push(this.snapshot());
    await this.restore({ ...state, view: { ...this.shareState().view, spatial: state.spatial, playing: false } });
    this.paintHistory();
  }

  paintHistory() {
    $('undo').disabled = !this.history.length;
    $('redo').disabled = !this.future.length;
  }

  /** Put the selector back on what is shown (after a mechanism could not be opened). */
  reselectSource() {
    if (this.source) this.controls.el.preset.value = this.sourceValue();
  }

  /** The selector's value for what is shown. */
  sourceValue() {
    const src = this.source;
    return src.type === 'preset' ? `preset:${src.name}` : src.type === 'example' ? `example:${src.file}` : 'shared';
  }

  /** Say which source's drawing is on screen (the selector's data-shown), once it is. */
  markShown() {
    if (this.source) this.controls.el.preset.dataset.shown = this.sourceValue();
  }

  setExampleFields(scene) {
    if (S.isSpatial(scene)) {
      this.controls.setSpatialFields(scene, (joint, field, v) => this.onJoint(joint, field, v));
      return;
    }
    const ground = S.groundLink(scene);
    const fixed = new Set(scene.links[ground]?.points || []);
    this.controls.setPointFields(scene, fixed, (p, i, v) => this.onPoint(p, i, v));
    this.setDriverFields(scene);
  }

  setDriverFields(scene) {
    if (S.isSpatial(scene)) return;
    this.controls.setDriverFields(scene, (f, v) => this.onDriver(f, v), (kind, name, text) => this.onLaw(kind, name, text));
  }

  /** Load a chosen mechanism; an error has no field to sit next to, so it goes to the status line.
   * `posed`: the server checked the scene at `instant` (loadScene). */
  async commitOrReport(scene, view, instant = null, posed = false) {
    try {
      await this.loadScene(scene, view ? { instant: view.view?.instant, spatial: view.view?.spatial, keepChoices: true } : { instant, posed });
    } catch (err) {
      this.status(`${scene.title || 'This mechanism'}: ${err.detail || err.message}`, 'error');
    }
  }

  // ---- edits: each one is validated by the server before it replaces what is shown ---------------

  /**
   * `posed`: the scene comes from the server checked at the instant shown (a preset posed there,
   * posedAtInstant), so that instant is asked for beside the sweep (loadScene).
   */
  async edit(fieldKey, valueSI, makeScene, onAccept = null, { posed = false } = {}) {
    const before = this.snapshot();
    try {
      const scene = await makeScene();
      await this.loadScene(scene, { keepInstant: true, posed });
      this.remember(before);
    } catch (err) {
      this.controls.showFieldError(fieldKey, err.detail || err.message, err.position);
      this.controls.revertField(fieldKey);
      return false;
    }
    this.controls.acceptField(fieldKey, valueSI);
    onAccept?.();
    $('linkage').dataset.edited = fieldKey; // the last edit accepted (for a reader, a test)
    return true;
  }

  onParam(name, value) {
    const params = { ...this.source.params, [name]: value };
    const posed = this.posedAtInstant(params);
    return this.edit(
      `param:${name}`,
      value,
      async () => this.withDriverEdits(await api.buildPreset(this.source.name, posed)),
      () => { this.source = { ...this.source, params }; this.saveHash(); },
      { posed: posed !== params },
    );
  }

  onPoint(name, index, value) {
    return this.edit(`point:${name}:${index}`, value, async () => {
      const scene = structuredClone(this.scene);
      scene.points[name][index] = value;
      return scene;
    });
  }

  onDriver(field, value) {
    const edits = { ...this.driverEdits, [field]: value };
    return this.edit(
      `driver:${field}`,
      value,
      async () => {
        const scene = structuredClone(this.scene);
        scene.drivers[0] = { ...scene.drivers[0], ...edits };
        return scene;
      },
      () => { this.driverEdits = edits; },
    );
  }

  onLaw(kind, name, text) {
    const key = kind === 'angle' ? 'law:angle' : `law:s:${name}`;
    return this.edit(key, text, async () => {
      const scene = structuredClone(this.scene);
      if (kind === 'angle') scene.drivers[0].angle_law = text;
      else if (Array.isArray(scene.moving_points)) scene.moving_points.find((m) => m.name === name).s_law = text;
      else scene.moving_points[name].s_law = text;
      return scene;
    });
  }

  onJoint(name, field, value) {
    return this.edit(`joint:${name}:${field}`, value, async () => {
      const scene = structuredClone(this.scene);
      scene.joints.find((j) => j.name === name)[field] = value;
      return scene;
    });
  }

  /**
   * Preset parameters with the drawn pose at the analysed instant: the slider is the one crank
   * angle, so an edit is checked (and any "cannot be assembled" said) at the angle shown.
   */
  posedAtInstant(params) {
    const meta = this.presets.get(this.source.name);
    const t = this.track;
    if (!meta?.parameters?.some((p) => p.name === POSE_PARAMETER) || !t || t.static || t.param !== 'angle') return params;
    const deg = (this.instantValue() * 180) / Math.PI;
    return { ...params, [POSE_PARAMETER]: Number((((deg % 360) + 360) % 360).toFixed(6)) };
  }

  withDriverEdits(scene) {
    if (scene.drivers?.length && Object.keys(this.driverEdits).length) {
      scene.drivers[0] = { ...scene.drivers[0], ...this.driverEdits };
    }
    return scene;
  }

  // ---- geometry: one sweep per change ---------------------------------------------------------

  /**
   * Ask the server for the whole cycle of `scene`, then replace what is shown. Throws the
   * server's error (and leaves the page as it was) when the scene is not acceptable.
   *
   * The instant to be analysed is asked for as soon as it is known to assemble, beside what is
   * left of the sweep: analyzeNow's identical request then shares its answer (api.js) instead
   * of waiting for the sweep first. `posed`: the server checked the scene at the crank angle
   * to be shown (the one kept by an edit, `keepInstant`, or `instant`: a preset built in its
   * drawn pose), so at once; a new mechanism without an instant is analysed at its track's
   * start, which its first sweep (of up to three, "Samples per revolution") has placed when the
   * crank turns fully or the track is over time.
   *
   * A new mechanism whose first sweep is too coarse for the drawing is shown from that sweep at
   * once, and its finer sweep replaces it when it comes (refineTrack: the same instant,
   * exactly); its cycle plots and dynamics wait for the finer sweep.
   */
  async loadScene(scene, { keepInstant = false, instant = null, keepChoices = keepInstant, spatial = null, sameMechanism = false, posed = false } = {}) {
    const seq = ++this.geometrySeq;
    const previous = keepInstant && this.track ? this.instantValue() : null;
    if (S.isSpatial(scene)) return this.loadSpatial(scene, seq, previous ?? instant, spatial);
    const timeDriven = S.isTimeDriven(scene);
    const ask = (param, value) => api.analyze(S.sceneAt(scene, param, value), INSTANT).catch(() => {}); // (its error is analyzeNow's)
    const at = previous ?? instant ?? null; // the crank angle or time to be shown (null: the start)
    // (an edit is posed at a crank angle only: posedAtInstant)
    if (posed && at !== null) ask(timeDriven ? 'time' : 'angle', at);
    // (a crank's turn, or a time range, starts where the first sweep starts; a rocking crank's
    // samples are the midpoints of its range's parts, which move with their number)
    let early = null; // the first sweep, shown while a finer one is asked for
    let settle;
    const final = new Promise((resolve) => { settle = resolve; });
    const placed = previous === null
      ? (first, finer) => {
          if (finer && seq === this.geometrySeq) {
            early = first;
            this.commitPlanar(scene, first, null, at ?? first.values[0], keepChoices, sameMechanism, final);
          } else if (at === null && (first.closed || first.param === 'time')) {
            ask(first.param, first.values[0]);
          }
        }
      : null;
    let track;
    let note = null;
    try {
      track = await this.fetchTrack(scene, timeDriven, placed);
    } catch (err) {
      if (early) { // (a finer sweep that failed leaves the first one shown)
        settle(early);
        return;
      }
      // Not-assemblable and friends are answers about the scene: report them to the caller.
      // A network failure, or (for time laws) a sweep over the range chosen here that fails
      // although the scene's own instant may be fine, only costs the animation: check the
      // scene with /analyze and show it still.
      const soft = err.code === 'network' || (timeDriven && err.code !== 'invalid_expression');
      if (!soft) throw err;
      const probeScene = timeDriven ? S.sceneAt(scene, 'time', scene.time ?? 0) : scene;
      try {
        await api.analyze(probeScene, ['position']);
      } catch (probe) {
        if (probe.code !== 'network') throw probe;
      }
      track = staticTrack(scene, timeDriven ? 'time' : 'angle', timeDriven ? scene.time ?? 0 : S.drawnAngle(scene, scene.drivers?.[0]?.link));
      note = timeDriven
        ? `No animation over time: ${err.detail} The instant t = ${fmt(scene.time ?? 0)} s is analysed.`
        : `No animation: ${err.detail} The drawn pose is analysed.`;
    }
    if (early) {
      if (seq === this.geometrySeq && this.track === early) this.refineTrack(track);
      settle(track);
      return;
    }
    if (seq !== this.geometrySeq) return; // a newer edit won
    this.commitPlanar(scene, track, note, at, keepChoices, sameMechanism);
  }

  /** The sweep drawn for `scene`; `placed(track, finer)` is told its first track, and whether a
   * finer one is asked for after it. */
  async fetchTrack(scene, timeDriven, placed = null) {
    const range = timeDriven ? [0, Math.max(2, 2 * (scene.time ?? 0))] : undefined;
    // Over time, also the transport/relative/Coriolis parts of the moving points, to animate them.
    const quantities = timeDriven ? [...QUANTITIES, 'components'] : QUANTITIES;
    // Samples per revolution: the fewest whose interpolation stays within half a pixel of the
    // drawing (track.samplesFor), at least SAMPLES; a sharp turn the first sweep resolved only
    // partly asks again (at most twice more).
    const sweepFollowingTheDrawing = async (target) => {
      let body = await api.sweep(target, SAMPLES, quantities, range);
      let track = trackFromSweep(body);
      for (let round = 0; round < 2; round++) {
        const n = samplesFor(track, this.linkage.pixelsPerMetre(track), { least: SAMPLES });
        if (round === 0) placed?.(track, n > track.n);
        if (n <= track.n) break;
        body = await api.sweep(target, n, quantities, range);
        track = trackFromSweep(body);
      }
      this.warnings(body.warnings);
      return track;
    };
    if (!timeDriven && scene.drivers?.length) {
      // A crank that turns fully is swept from 0 deg, so the samples (plots, CSV) fall on
      // round angles; one that cannot be assembled at 0 deg is swept from its drawn pose.
      try {
        return await sweepFollowingTheDrawing(S.sceneAt(scene, 'angle', 0));
      } catch (err) {
        if (err.code === 'network') throw err;
      }
    }
    return sweepFollowingTheDrawing(scene);
  }

  /** Show `scene` swept as `track` at `instant`; `final`: the track its plots and dynamics are
   * drawn from (when a finer sweep of it is still coming: loadScene). */
  commitPlanar(scene, track, note, instant, keepChoices, sameMechanism = false, final = null) {
    this.dynamics.leave();
    this.scene = scene;
    this.track = track;
    this.analysis = null;
    this.analysisU = null;
    // the last sweep drawn (for a reader, a test): a first one that a finer one replaces is not
    if (final) delete $('linkage').dataset.samples;
    else $('linkage').dataset.samples = String(track.n);
    showView('linkage');
    this.markShown();
    $('view-title').textContent = scene.title || 'Mechanism';

    this.setInstantRange(track);
    this.placeAt(instant ?? null);
    this.direction = 1;
    if (track.n < 2 && this.playing) {
      this.playing = false;
      this.controls.setPlaying(false);
    }

    // The traced and plotted point and links survive an edit or a shared link, not a new mechanism.
    const names = S.pointNames(scene);
    const opts = this.controls.options();
    const trace = keepChoices && (opts.trace === null || names.includes(opts.trace)) ? opts.trace : defaultTrace(scene);
    this.controls.setPointChoices(names, trace);
    const links = S.movingLinks(scene);
    const chosen = keepChoices ? this.plot.links.filter((l) => links.includes(l)) : [];
    this.plot = {
      links: chosen.length ? chosen : links.slice(0, 3),
      quantity: keepChoices ? this.plot.quantity : null,
      axis: keepChoices ? this.plot.axis : 'angle',
      trace: trace || names[names.length - 1],
    };
    this.mechanismFacts(null);
    this.controls.setLinkChoices(links, S.linkColours(scene), this.plot.links);

    this.linkage.options = { ...this.linkage.options, ...this.controls.options(), units: this.units };
    this.linkage.editable = !timeDrivenScene(scene);
    this.linkage.setScene(scene, track, { sameMechanism });
    this.addedPoints = sameMechanism ? this.addedPoints.filter((n) => names.includes(n)) : [];

    this.trackMessages(track, note);
    $('plots-title').textContent = track.param === 'time' ? 'Over time' : track.feasible ? 'Over one cycle' : 'Over the feasible range';
    // What is seen first comes first: the mechanism (this frame), then its instant (the drawing
    // and the polygons), then, PLOTS_AFTER_MS after that is painted, the cycle plots (Plotly,
    // 50 to 100 ms of the page's time) while the server writes the worked solution, and last the
    // dynamics panel (a sweep of forces, figures under the fold). The wait keeps the next edit
    // from queuing behind plots of a geometry it replaces: a value stepped past with the arrow
    // keys, the next one drawn within that time, is not plotted (plotAfterInstant).
    this.drawFrame();
    this.dirty = true;
    clearTimeout(this.analysisTimer);
    $('plots').setAttribute('aria-busy', 'true'); // the previous geometry's until drawPlots
    this.plotAfterInstant(scene, final ?? track);
    this.saveHash();
  }

  /** The instant of `scene` analysed and painted, then PLOTS_AFTER_MS later its cycle plots and
   * its dynamics panel (commitPlanar); `swept`: its track, or the promise of its finer one. */
  async plotAfterInstant(scene, swept) {
    await this.analyzeNow();
    await afterPaint();
    const track = await swept;
    await new Promise((resolve) => setTimeout(resolve, PLOTS_AFTER_MS));
    if (this.scene !== scene) return; // a newer geometry plots its own
    // (the track shown: one without a sweep that analyzeNow framed anew has no cycle to plot)
    await this.drawPlots();
    if (!(await plotlyReady()) || this.scene !== scene || this.track !== track) return;
    await this.dynamics.show(scene, this.units, track.n);
    this.drawFrame();
  }

  /** The slider's range: the track's first to last value. */
  setInstantRange(track) {
    const v = track.values;
    this.controls.setInstantRange(track.param, Math.min(v[0], v[v.length - 1]), Math.max(v[0], v[v.length - 1]), track.n > 1);
  }

  /** `note`, the range of a crank that rocks and the sweep's warnings, above the drawing. */
  trackMessages(track, note = null) {
    const v = track.values;
    const messages = [];
    if (note) messages.push(note);
    if (!track.feasible) {
      const [a, b] = [v[0], v[v.length - 1]];
      messages.push(`The crank cannot turn fully: it rocks between ${show('angle', Math.min(a, b), this.units)} and ${show('angle', Math.max(a, b), this.units)} (limit positions).`);
    }
    for (const warning of track.warnings || []) messages.push(`Note: ${warning}.`);
    this.viewMessage(messages.join(' '));
  }

  /**
   * The finer sweep of the mechanism shown replaces its first (loadScene): the same instant,
   * exactly, now on the finer track, and the analysis drawn kept.
   */
  refineTrack(track) {
    const value = this.instantValue();
    const analysed = this.analysis && this.analysisU !== null ? this.instantValue(this.analysisU) : null;
    this.track = track;
    $('linkage').dataset.samples = String(track.n);
    this.setInstantRange(track);
    this.placeAt(value);
    this.trackMessages(track);
    this.linkage.setScene(this.scene, track, { sameMechanism: true });
    if (analysed !== null) { // (one still asked for finds its index when it comes: analyzeNow)
      this.analysisU = indexOfValue(track, analysed); // (this.u when paused there: placeAt)
      this.linkage.setAnalysis(this.analysis);
    }
    this.dirty = true;
  }

  /**
   * A spatial chain swept over time, shown at `instant` (s; the start when null). `spatial`: the
   * chain as opened and the fields' joint offsets, when a share link carries an edited chain.
   */
  async loadSpatial(scene, seq, instant = null, spatial = null) {
    this.dynamics.show(scene, this.units, SAMPLES); // hides the panel: no masses in space
    const edited = this.spatialEdit;
    this.spatialEdit = false;
    const shared = sharedSpatialEdits(spatial);
    let sweep = null;
    let note = null;
    const { samples, quantities, timeRange } = sweepRequest(scene);
    try {
      sweep = await api.sweep(scene, samples, quantities, timeRange);
      this.warnings(sweep.warnings);
    } catch (err) {
      if (err.code !== 'network' && !edited) throw err;
      note = `The server cannot analyse this spatial chain: ${err.detail}`;
    }
    if (seq !== this.geometrySeq) return;
    // The fields edit the chain as it was opened (a share link of an edited chain carries it).
    if (shared) this.spatialBase = shared.base;
    else if (!edited) this.spatialBase = scene;
    this.scene = scene;
    this.track = sweep ? spatialTrack(sweep) : null;
    this.analysis = null;
    this.u = this.track && instant !== null && instant !== undefined ? indexOfValue(this.track, instant) : 0;
    showView('spatial');
    this.markShown();
    $('view-title').textContent = scene.title || 'Spatial chain';
    $('instant-readout').textContent = '';
    this.mechanismFacts(null); // Grashof and transmission angles are planar facts
    if (this.track) this.controls.setInstantRange('time', timeRange[0], timeRange[1], true);
    else this.controls.setInstantRange('angle', 0, 0, false);
    this.setPlaying(this.playing && !!this.track, { analyse: false });
    this.spatial.setOptions({ ...this.controls.options(), units: this.units });
    this.spatial.setCamera(this.camera.yaw, this.camera.pitch);
    this.spatial.setExtent(this.track ? extentOf(this.track) : null);
    this.spatial.setScene(scene);
    this.spatialFields.show(this.spatialBase, scene, shared ? shared.offsets : edited ? this.spatialFields.offsets : null);
    this.viewMessage(note || '');
    clearPolygons($('velocity-polygon'), $('acceleration-polygon'));
    renderMagnitudes($('polygon-table'), scene, null, null, this.units);
    this.polygonMessage('The polygons are drawn for planar linkages. The vectors of this spatial chain are listed under its drawing.');
    $('plots-title').textContent = 'Over time';
    this.drawPlots();
    this.dirty = true;
    this.drawFrame();
    this.requestSolution();
    this.saveHash();
  }

  /** The spatial chain at the animation's instant: drawn, and its values listed. */
  drawSpatialFrame() {
    if (!this.track) {
      this.spatial.setAnalysis(null);
      return;
    }
    const { scene, analysis } = chainAt(this.scene, this.track, this.u);
    this.spatial.setScene(scene);
    this.spatial.setAnalysis(analysis);
    this.paintSpatialInfo();
    const value = this.instantValue();
    this.controls.setInstant(value);
    $('spatial').dataset.instant = String(value);
    this.markFirstFrame();
  }

  paintSpatialInfo() {
    const ul = $('spatial-info');
    ul.replaceChildren(...this.spatial.summary().map((line) => Object.assign(document.createElement('li'), { textContent: line })));
    ul.hidden = !ul.children.length;
  }

  // ---- the analysed instant -------------------------------------------------------------------

  /**
   * Put the instant at `value` (rad or s; null: the track's start): its fractional index u, and
   * the value itself, kept exactly while u stays there (the track's interpolation at u differs
   * from it in the last digits; an angle brought into the swept turn or a time clamped to the
   * range is the track's own value). "The last digits": within 1e-9 of the value, far above the
   * interpolation's rounding (~1e-15) and far below a turn brought back (2 pi).
   */
  placeAt(value) {
    this.u = value === null ? 0 : indexOfValue(this.track, value);
    const near = value === null ? null : valueAt(this.track, this.u);
    this.asked = near !== null && Math.abs(near - value) <= 1e-9 * Math.max(1, Math.abs(value)) ? { track: this.track, u: this.u, value } : null;
  }

  /** The driver's angle (rad) or the time (s) at the fractional index u: the value put there
   * (placeAt), else the track's interpolation. */
  instantValue(u = this.u) {
    if (!this.track) return null;
    const asked = this.asked;
    return asked && asked.track === this.track && asked.u === u ? asked.value : valueAt(this.track, u);
  }

  instantScene(u = this.u) {
    const t = this.track;
    if (!t) return this.scene;
    // A static track of a crank (no sweep) analyses the drawn pose itself.
    return t.static && t.param === 'angle' ? this.scene : S.sceneAt(this.scene, t.param, this.instantValue(u));
  }

  scheduleAnalysis(delay = DEBOUNCE_MS) {
    clearTimeout(this.analysisTimer);
    this.analysisTimer = setTimeout(() => this.analyzeNow(), delay);
  }

  /**
   * One request per pause for what is drawn (/analyze with the polygons: the drawing, the
   * polygons, the cursor), then the worked solution of the same instant once that is painted.
   */
  async analyzeNow() {
    if (!this.scene) return;
    if (S.isSpatial(this.scene)) {
      if (!this.playing) this.requestSolution();
      return;
    }
    const seq = ++this.analysisSeq;
    this.solutionSeq += 1; // a solution asked for earlier must not replace this one
    const solutionSeq = this.solutionSeq;
    const track = this.track;
    const asked = this.u;
    const value = this.instantValue(asked);
    const scene = this.instantScene(asked);
    let answer = null;
    try {
      answer = await api.analyze(scene, INSTANT);
    } catch (err) {
      if (seq !== this.analysisSeq) return;
      this.analysis = null;
      this.polygons = null;
      this.linkage.setAnalysis(null);
      this.polygonMessage(err.code === 'network' ? `Polygons unavailable: ${err.detail}` : `At this instant the server reports: ${err.detail}`);
      this.solutionFailed(err);
    }
    if (seq !== this.analysisSeq) return;
    // (a finer sweep of the mechanism that replaced its first meanwhile has the same instant at
    // its own index: refineTrack)
    const u = this.track === track ? asked : indexOfValue(this.track, value);
    if (answer) {
      const { polygons: segments, ...results } = answer;
      this.analysis = results;
      this.polygons = segments;
      this.analysisU = u;
      this.warnings(results.warnings);
      if (this.track.static) {
        // Without a sweep the picture is framed on the one pose the server placed.
        const frame = frameFromAnalysis(this.analysis);
        this.track = staticTrack(this.scene, this.track.param, this.track.values[0], frame.position);
        this.linkage.setScene(this.scene, this.track);
      }
      this.linkage.setAnalysis(this.analysis);
      this.drawPolygons();
      this.mechanismFacts(this.analysis);
      // Marked analysed once the polygons of this instant are drawn (their details "pending"),
      // so that a detail marked done is never the previous instant's.
      $('linkage').dataset.analysed = String(this.instantValue(u));
      this.dirty = true; // the next frame draws this instant (its poles, vectors, readouts)
      // The plots' cursor is moved, and the worked solution asked for and typeset, once the
      // frame that shows the instant is painted (plots of a new geometry are drawn after it,
      // with their cursor: commitPlanar).
      await afterPaint();
      if (seq !== this.analysisSeq) return;
      if (this.plotted === this.track) moveCursor($('plots'), this.scene, this.track, this.instantValue(u), this.units);
      if (solutionSeq === this.solutionSeq) this.requestSolution();
    }
    this.dirty = true;
    this.saveHash();
  }

  /** The worked solution alone (another method, or a spatial chain). */
  async requestSolution() {
    if (!this.scene) return;
    const seq = ++this.solutionSeq;
    const spatial = S.isSpatial(this.scene);
    const u = this.analysisU ?? this.u;
    const target = spatial ? this.spatialInstant() : this.instantScene(u);
    // the instant solved, as #linkage[data-analysed] marks the one analysed
    const instant = spatial ? null : String(this.instantValue(u));
    try {
      const [sol] = await Promise.all([api.solution(target, this.method, 4), katexReady()]);
      if (seq !== this.solutionSeq) return;
      if (instant !== null) $('steps').dataset.instant = instant;
      this.showSolution(sol);
    } catch (err) {
      if (seq === this.solutionSeq) this.solutionFailed(err);
    }
  }

  /** A spatial chain at the sample nearest the animation's instant (the server's own pose). */
  spatialInstant() {
    return this.track ? chainAt(this.scene, this.track, Math.round(this.u)).scene : this.scene;
  }

  /** The steps a reader sees first at once, the rest in later tasks (steps.renderSolution). */
  async showSolution(solution) {
    this.solution = solution;
    const rendered = renderSolution($('steps'), $('mistakes'), solution, this.units, { first: FIRST_STEPS });
    $('steps').dataset.method = solution.method; // its first steps are in (for a reader, a test)
    const failures = await rendered;
    if (failures && this.solution === solution) this.status(`${failures} step(s) of the worked solution could not be typeset; they are shown as text.`, 'error');
  }

  solutionFailed(err) {
    this.solution = null;
    renderMessage($('steps'), err.code === 'network' ? `No worked solution: ${err.detail}` : `No worked solution for this instant: ${err.detail}`);
    $('mistakes').replaceChildren();
  }

  /** What the server noticed but answered anyway (an unknown scene key, ...), on the status line. */
  warnings(list) {
    if (list && list.length) this.status(`Note: ${list.join('; ')}`, 'warning');
  }

  /** Opens the print-friendly worked solution of the analysed instant in a new window. */
  async openPrintable() {
    if (!this.scene) return;
    const target = S.isSpatial(this.scene) ? this.scene : this.instantScene(this.analysisU ?? this.u);
    const page = window.open('', '_blank');
    try {
      const html = await api.solutionPage(target, this.method, 4);
      // about:blank shares this page's origin and base URL, so the page's /vendor/ links resolve.
      page.document.open();
      page.document.write(html);
      page.document.close();
    } catch (err) {
      page?.close();
      this.status(`No printable solution: ${err.detail}`, 'error');
    }
  }

  drawPolygons() {
    if (!this.analysis) return;
    renderPolygons($('velocity-polygon'), $('acceleration-polygon'), this.scene, this.analysis, this.polygons, this.units);
    renderMagnitudes($('polygon-table'), this.scene, this.analysis, this.polygons, this.units);
    this.polygonMessage('');
    const v = this.instantValue(this.analysisU ?? this.u);
    if (this.track && !this.track.static && v !== null) {
      const label = this.track.param === 'time' ? `t = ${fmt(v)} s` : `θ = ${show('angle', v, this.units)}`;
      $('instant-readout').textContent = `analysed instant: ${label}`;
      $('linkage').setAttribute('aria-label', `Drawing of the ${this.scene.title || 'mechanism'}; analysed instant ${label}`);
    } else {
      $('instant-readout').textContent = '';
    }
  }

  /** The cycle plots of the track shown; #plots is aria-busy from a new geometry until then. */
  async drawPlots() {
    try {
      await this.plotTrack();
    } finally {
      $('plots').removeAttribute('aria-busy');
    }
  }

  async plotTrack() {
    if (!(await plotlyReady())) {
      this.plotsMessage('Plotly could not be loaded, so the plots cannot be drawn.');
      return;
    }
    const div = $('plots');
    const t = this.track;
    if (t?.spatial) {
      window.Plotly.purge(div);
      await renderSpatialPlots(div, t, window.Plotly);
      $('plot-facts').replaceChildren();
      this.plotsMessage('');
      return;
    }
    if (!t || t.n < 2) {
      window.Plotly.purge(div);
      this.plotsMessage(t ? 'No sweep from the server, so there is no cycle to plot.' : '');
      return;
    }
    const choices = quantityChoices(allSeries(this.scene, t, cycleOrder(t), this.units));
    const preferred = this.plot.quantity
      ?? (choices.find((c) => c.value.startsWith('slider:')) || choices.find((c) => c.value === `point:${this.plot.trace}:velocity`) || choices[0])?.value;
    const quantity = this.controls.setQuantityChoices(choices, preferred);
    const axis = this.controls.setAxisChoices(xAxes(this.scene, t), this.plot.axis);
    this.plot = { ...this.plot, quantity, axis };
    const { ok, facts } = renderPlots(div, this.scene, t, { links: this.plot.links, quantity, axis, units: this.units, cursor: this.analysisU === null ? null : this.instantValue(this.analysisU) });
    this.plotted = t; // the cycle plotted (analyzeNow moves its cursor)
    $('plot-facts').replaceChildren(...facts.map((f) => Object.assign(document.createElement('li'), { textContent: f })));
    const have = available(t);
    this.plotsMessage(!ok ? 'The sweep has nothing to plot.' : !have.omega ? 'The server swept positions only: angular velocities and accelerations are not plotted.' : '');
  }

  /** Grashof class and transmission angle of each four-bar loop at the analysed instant. */
  mechanismFacts(analysis) {
    const el = $('mechanism-facts');
    const loops = analysis?.four_bar_loops || [];
    el.textContent = loops.map((l) => `${l.grashof}; transmission angle ${transmissionName(this.track, l.links)} = ${show('angle', l.transmission_angle, this.units)}`).join(' · ');
    el.hidden = !loops.length;
  }

  // ---- interaction ---------------------------------------------------------------------------

  setPlaying(playing, { analyse = true } = {}) {
    const animatable = this.track && this.track.n > 1;
    this.playing = playing && !!animatable;
    this.controls.setPlaying(this.playing);
    if (!this.playing && analyse) this.scheduleAnalysis(0);
    this.dirty = true;
    this.saveHash();
  }

  onInstant(valueSI, final) {
    if (!this.track || this.track.n < 2) return;
    if (this.playing) this.setPlaying(false, { analyse: false });
    this.placeAt(valueSI);
    this.dirty = true;
    this.scheduleAnalysis(final ? 0 : DEBOUNCE_MS);
  }

  onDrag(linkAngle) {
    if (!this.track || this.track.param !== 'angle') return;
    if (this.playing) this.setPlaying(false, { analyse: false });
    this.placeAt(linkAngle);
    this.dirty = true;
    this.scheduleAnalysis();
  }

  onUnits(units) {
    this.units = units;
    this.controls.setUnits(units);
    this.cams.setUnits(units);
    this.gearTrains.setUnits(units);
    if (!this.scene) return this.saveHash(); // only a cam or a gear train has been shown
    this.linkage.setOptions({ units });
    this.spatial.setOptions({ units });
    this.mechanismFacts(this.analysis);
    // The worked solution follows the units switch without asking the server again.
    if (this.solution) this.showSolution(this.solution);
    if (S.isSpatial(this.scene)) this.paintSpatialInfo();
    this.drawPolygons();
    this.drawPlots();
    this.dynamics.units = units;
    this.dynamics.drawCycle();
    this.dirty = true;
    this.saveHash();
  }

  onOptions(options) {
    this.linkage.setOptions(options);
    this.spatial.setOptions(options);
    this.dirty = true;
    this.saveHash();
  }

  // ---- animation -----------------------------------------------------------------------------

  tick(now) {
    const dt = this.lastTime === null ? 0 : Math.min((now - this.lastTime) / 1000, 0.1);
    this.lastTime = now;
    const t = this.track;
    if (this.playing && t && t.n > 1) {
      this.advance(t, dt);
      this.dirty = true;
    }
    if (this.dirty && t) {
      this.drawFrame();
      this.dirty = false;
    }
    requestAnimationFrame((x) => this.tick(x));
  }

  advance(t, dt) {
    const last = t.n - 1;
    // Angle scenes: one revolution per CYCLE_SECONDS at 1x. Time scenes: real time.
    const rate = t.param === 'time'
      ? (this.speed * last) / Math.max(t.values[last] - t.values[0], 1e-9)
      : (this.speed * last) / CYCLE_SECONDS;
    let u = this.u + this.direction * rate * dt;
    if (t.closed) u = ((u % last) + last) % last;
    else if (t.param === 'time') u = u > last ? 0 : u;
    else if (u > last || u < 0) {
      // A crank that cannot turn fully rocks between its limit positions.
      this.direction = -this.direction;
      u = Math.min(Math.max(u, 0), last);
    }
    this.u = u;
  }

  drawFrame() {
    if (S.isSpatial(this.scene)) return this.drawSpatialFrame();
    const exact = !this.playing && this.analysis && this.analysisU === this.u;
    const frame = exact ? frameFromAnalysis(this.analysis) : frameAt(this.track, this.u);
    this.linkage.draw(frame);
    this.dynamics.drawArrows(this.linkage, $('linkage'), frame, this.track, this.u);
    const value = this.instantValue();
    this.controls.setInstant(value);
    $('linkage').dataset.instant = String(value);
    this.markFirstFrame();
  }

  markFirstFrame() {
    if (this.firstFrame) return;
    this.firstFrame = true;
    performance.mark('first-frame');
  }

  // ---- share ---------------------------------------------------------------------------------

  /** The cam or gear-train view while one is shown (else null: the linkage view). */
  familyView() {
    return [this.cams, this.gearTrains].find((view) => view?.shown) || null;
  }

  /** A cam or gear-train scene (an uploaded file) in its own view. */
  async openFamilyScene(scene, name) {
    this.setPlaying(false, { analyse: false });
    this.designer?.close();
    const [view, other] = scene.kind === 'cam' ? [this.cams, this.gearTrains] : [this.gearTrains, this.cams];
    other.close();
    this.controls.selectSource('shared', `Opened from ${name}.`);
    return view.openScene(scene, name);
  }

  /** A share link of a cam or a gear train (its view's shareState). */
  async restoreFamily(state) {
    this.setPlaying(false, { analyse: false });
    this.designer?.close();
    const cam = state.view.family === 'cams';
    const [view, other, ready] = cam ? [this.cams, this.gearTrains, this.camsReady] : [this.gearTrains, this.cams, this.gearsReady];
    other.close();
    await ready;
    const src = state.source || {};
    const value = ['cam', 'gear', 'gear-example'].includes(src.type) ? `${src.type}:${src.name}` : 'shared';
    this.controls.selectSource(value, 'A mechanism opened from a link.');
    const ok = await view.restore(state);
    if (ok !== true) this.status(`This link could not be opened: ${ok}`, 'error');
  }

  shareState() {
    const family = this.familyView();
    if (family) return family.shareState();
    return {
      scene: this.scene,
      source: this.source,
      view: {
        instant: this.track && !this.track.static ? this.instantValue() : null,
        playing: this.playing,
        speed: this.speed,
        units: this.units,
        options: this.controls.options(),
        plot: this.plot,
        method: this.method,
        camera: this.camera,
        spatial: this.spatialEdits(),
      },
    };
  }

  /** An edited spatial chain's fields: the chain as opened and the joint offsets (else null). */
  spatialEdits() {
    const edited = S.isSpatial(this.scene) && this.spatialBase && this.spatialBase !== this.scene;
    return edited ? { base: this.spatialBase, offsets: [...this.spatialFields.offsets] } : null;
  }

  saveHash() {
    clearTimeout(this.hashTimer);
    this.hashTimer = setTimeout(async () => {
      const state = this.shareState();
      if (!state.scene) return;
      await writeHash(state);
      this.lastHash = location.hash;
    }, 300);
  }

  async onShare() {
    clearTimeout(this.hashTimer);
    const url = await writeHash(this.shareState());
    this.lastHash = location.hash;
    this.controls.showShareUrl(url);
    try {
      await navigator.clipboard.writeText(url);
      this.status('Link copied: it opens this mechanism at this instant with these settings.');
    } catch {
      this.status('Link ready: copy it from the field next to the button.');
    }
  }

  async restore(state) {
    const view = state.view || {};
    this.units = view.units === 'mm' ? 'mm' : 'si';
    this.controls.setUnits(this.units);
    this.cams.setUnits(this.units);
    this.gearTrains.setUnits(this.units);
    if (view.family === 'cams' || view.family === 'gear_trains') return this.restoreFamily(state);
    this.speed = view.speed || 1;
    this.controls.setSpeed(this.speed);
    this.method = ['loop', 'newton_euler', 'statics'].includes(view.method) ? view.method : 'vector';
    this.controls.setMethod(this.method);
    if (view.camera) this.camera = view.camera;
    if (view.plot) {
      // Links before issue 13 saved the point whose speed was plotted.
      const { links = [], quantity = null, axis = 'angle', point = null } = view.plot;
      this.plot = { links, quantity: quantity ?? (point ? `point:${point}:velocity` : null), axis };
    }
    this.driverEdits = {};
    this.playing = view.playing !== false;
    this.controls.setPlaying(this.playing);
    if (view.options) {
      this.controls.setPointChoices(S.isSpatial(state.scene) ? [] : S.pointNames(state.scene), view.options.trace);
      this.controls.setOptions(view.options);
    }
    const src = state.source || {};
    if (src.type === 'preset' && this.presets.has(src.name)) {
      await this.openPreset(src.name, src.params || {}, { scene: state.scene, view });
    } else if (src.type === 'example' && this.examples.some((x) => x.file === src.file)) {
      await this.openExample(src.file, { scene: state.scene, view });
    } else {
      this.source = { type: 'shared' };
      this.controls.selectSource('shared', 'A mechanism opened from a link.');
      this.setExampleFields(state.scene);
      await this.commitOrReport(state.scene, { view });
    }
    if (this.track) this.controls.setOptions(view.options || {});
    this.linkage.setOptions(this.controls.options());
    if (!this.playing) this.scheduleAnalysis(0);
  }

  // ---- messages ------------------------------------------------------------------------------

  status(text, level = 'info') {
    const el = $('status');
    el.textContent = text;
    el.dataset.level = level;
    clearTimeout(this.statusTimer);
    if (level === 'info') this.statusTimer = setTimeout(() => { el.textContent = ''; }, 6000);
  }

  viewMessage(text) {
    setMessage($('view-message'), text);
  }

  polygonMessage(text) {
    setMessage($('polygon-message'), text);
  }

  plotsMessage(text) {
    setMessage($('plots-message'), text);
  }
}

/** Scenes moved by time laws are not edited by dragging (their paths name points). */
function timeDrivenScene(scene) {
  return S.isTimeDriven(scene);
}

/** The spatial fields' state from a link, when it is well formed (else null: offsets start at 0). */
function sharedSpatialEdits(spatial) {
  const base = spatial?.base;
  const offsets = spatial?.offsets;
  if (!base || !S.isSpatial(base) || !Array.isArray(base.joints) || !Array.isArray(offsets)) return null;
  if (offsets.length !== base.joints.length || !offsets.every(Number.isFinite)) return null;
  return { base, offsets };
}

/** Show one of the two drawings. SVG elements have no `hidden` property: use the attribute. */
function showView(which) {
  $('linkage').toggleAttribute('hidden', which !== 'linkage');
  $('spatial').toggleAttribute('hidden', which !== 'spatial');
  $('spatial-info').toggleAttribute('hidden', which !== 'spatial');
  // A spatial chain moves in time (spatial-motion.js): its own fields replace the dimensions.
  $('spatial-fields').toggleAttribute('hidden', which !== 'spatial');
  $('dimensions').toggleAttribute('hidden', which === 'spatial');
  $('plot-choices').toggleAttribute('hidden', which === 'spatial');
  for (const el of document.querySelectorAll('.planar-only')) el.toggleAttribute('hidden', which === 'spatial');
}

/** The first of P1, P2, … that names no point of `scene`. */
function freshPointName(scene) {
  let i = 1;
  while (`P${i}` in scene.points) i += 1;
  return `P${i}`;
}

/**
 * The point that is to (b2, c2) what `p` is to (b1, c1): p = b1 + u (c1 − b1) + w k×(c1 − b1)
 * solved for u, w, then b2 + u (c2 − b2) + w k×(c2 − b2).
 */
function carried(b1, c1, p, b2, c2) {
  const d1 = [c1[0] - b1[0], c1[1] - b1[1]];
  const n = d1[0] ** 2 + d1[1] ** 2;
  const r = [p[0] - b1[0], p[1] - b1[1]];
  const u = (r[0] * d1[0] + r[1] * d1[1]) / n;
  const w = (d1[0] * r[1] - d1[1] * r[0]) / n;
  const d2 = [c2[0] - b2[0], c2[1] - b2[1]];
  return [b2[0] + u * d2[0] - w * d2[1], b2[1] + u * d2[1] + w * d2[0]];
}

function setMessage(el, text) {
  el.textContent = text;
  el.hidden = !text;
}

/** The analysed instant drawn exactly as the server placed it. */
function frameFromAnalysis(analysis) {
  const frame = { position: {}, velocity: {}, acceleration: {}, parts: {}, exact: true };
  for (const group of [analysis.points, analysis.moving_points]) {
    for (const [name, q] of Object.entries(group || {})) {
      if (q.position) frame.position[name] = q.position;
      if (q.velocity) frame.velocity[name] = q.velocity;
      if (q.acceleration) frame.acceleration[name] = q.acceleration;
    }
  }
  for (const part of componentSources(analysis)) frame.parts[part.point] = part;
  return frame;
}

/** Trace the coupler point if there is one (a point of a link that is no joint), else a moving point. */
function defaultTrace(scene) {
  const mp = S.movingPoints(scene);
  if (mp.length) return mp[0].name;
  const jointPoints = new Set((scene.joints || []).map((j) => j.point));
  const ground = S.groundLink(scene);
  for (const [name, l] of Object.entries(scene.links)) {
    if (name === ground) continue;
    const free = l.points.find((p) => !jointPoints.has(p));
    if (free) return free;
  }
  // A four-bar without a coupler point: trace the coupler's far joint.
  const coupler = S.movingLinks(scene).find((l) => !(scene.joints || []).some((j) => j.links.includes(l) && j.links.includes(ground)));
  return coupler ? scene.links[coupler].points[scene.links[coupler].points.length - 1] : null;
}

new App().start().catch((err) => {
  // A defect in the page itself: say so where a person looks.
  const el = $('status');
  el.textContent = `The page failed to start: ${err.message}`;
  el.dataset.level = 'error';
  throw err;
});
