// scene.js: read-only questions about a scene document (spec scene-v1), for drawing.
//
// Which link is the ground, which point is the crank's pivot, whether the scene is driven by a
// time law... Nothing here computes motion: it reads the document the server defined, and
// builds the instant-specific copy of it that /analyze and /solution are asked about.

export const isSpatial = (scene) => scene && scene.kind === 'spatial_chain';

export function groundLink(scene) {
  return Object.entries(scene.links || {}).find(([, l]) => l.ground)?.[0] ?? null;
}

export function movingLinks(scene) {
  return Object.entries(scene.links || {})
    .filter(([, l]) => !l.ground)
    .map(([name]) => name);
}

export function movingPoints(scene) {
  // The spec writes moving_points as a list; accept an object too (name -> definition).
  const mp = scene.moving_points;
  if (!mp) return [];
  return Array.isArray(mp) ? mp : Object.entries(mp).map(([name, m]) => ({ name, ...m }));
}

/** True when the motion is given as functions of time (angle_law / s_law), not by omega. */
export function isTimeDriven(scene) {
  return (scene.drivers || []).some((d) => typeof d.angle_law === 'string') || movingPoints(scene).length > 0;
}

/** The driver link, its ground pivot and the point a student grabs to turn it. */
export function driverHandle(scene) {
  const driver = (scene.drivers || [])[0];
  if (!driver) return null;
  const link = scene.links?.[driver.link];
  const ground = groundLink(scene);
  if (!link) return null;
  const pivotJoint = (scene.joints || []).find(
    (j) => j.type === 'revolute' && j.links.includes(driver.link) && j.links.includes(ground),
  );
  const pivot = pivotJoint ? pivotJoint.point : link.points[0];
  const others = link.points.filter((p) => p !== pivot);
  if (!others.length) return null;
  // The farthest point of the crank is the easiest to grab.
  const p0 = scene.points[pivot];
  const handle = others.reduce((best, p) => {
    const d = Math.hypot(scene.points[p][0] - p0[0], scene.points[p][1] - p0[1]);
    return d > best.d ? { p, d } : best;
  }, { p: others[0], d: -1 }).p;
  return { link: driver.link, pivot, handle };
}

/** The scene as asked about at one instant: driver angle (rad, absolute) or time (s). */
export function sceneAt(scene, param, value) {
  const copy = structuredClone(scene);
  if (param === 'time') {
    copy.time = value;
  } else if (copy.drivers && copy.drivers.length) {
    copy.drivers[0] = { ...copy.drivers[0], angle_deg: (value * 180) / Math.PI };
  }
  return copy;
}

/** The instant a scene itself asks for: its time (time laws), else its first driver's angle_deg
 * or drawn angle (rad, absolute). */
export function ownInstant(scene) {
  if (isTimeDriven(scene)) return scene.time ?? 0;
  const driver = scene.drivers?.[0];
  if (!driver) return null;
  if (typeof driver.angle_deg === 'number') return (driver.angle_deg * Math.PI) / 180;
  return drawnAngle(scene, driver.link);
}

/** The drawn-pose angle of a link (direction from its first to its second point). */
export function drawnAngle(scene, linkName) {
  const pts = scene.links?.[linkName]?.points;
  if (!pts || pts.length < 2) return 0;
  const [a, b] = [scene.points[pts[0]], scene.points[pts[1]]];
  return Math.atan2(b[1] - a[1], b[0] - a[0]);
}

/** Every point name worth labelling, in scene order, moving points last. */
export function pointNames(scene) {
  return [...Object.keys(scene.points || {}), ...movingPoints(scene).map((m) => m.name)];
}

/** Stable colours for links, by their order in the scene. */
const PALETTE = ['#3b6ea5', '#2a9d8f', '#c8553d', '#8e5ea2', '#d08c2c', '#5b8c5a', '#6c757d', '#b5446e'];
export function linkColours(scene) {
  const colours = {};
  movingLinks(scene).forEach((name, i) => {
    colours[name] = PALETTE[i % PALETTE.length];
  });
  return colours;
}
