// api.js: the only place that talks to the server.
//
// Every call goes to the same origin under /api/v1. Failures are turned into one error type,
// ApiError {code, detail, position, status, title}, whatever went wrong: an RFC 9457
// problem+json answer from the server, another HTTP error, or the network (code 'network').
// The views show `detail` next to the field or panel concerned.

const BASE = '/api/v1';

export class ApiError extends Error {
  constructor({ code, detail, position = null, status = 0, title = '' }) {
    super(detail);
    this.name = 'ApiError';
    this.code = code;
    this.detail = detail;
    this.position = position;
    this.status = status;
    this.title = title;
  }
}

async function problemFrom(response, path) {
  const type = response.headers.get('content-type') || '';
  let body = null;
  if (type.includes('json')) {
    try {
      body = await response.json();
    } catch {
      body = null;
    }
  }
  if (body && typeof body === 'object' && (body.code || body.detail)) {
    // FastAPI's own validation errors may carry `detail` as a list of {loc, msg}; flatten it
    // so a student reads one sentence instead of a JSON dump.
    let detail = body.detail;
    if (Array.isArray(detail)) {
      detail = detail.map((d) => (d.loc ? `${d.loc.join('.')}: ${d.msg}` : d.msg || String(d))).join('; ');
    }
    return new ApiError({
      code: body.code || 'http_' + response.status,
      detail: String(detail || body.title || response.statusText),
      position: body.position ?? null,
      status: response.status,
      title: body.title || '',
    });
  }
  return new ApiError({
    code: 'http_' + response.status,
    detail: `The server answered HTTP ${response.status} ${response.statusText} for ${path}.`,
    status: response.status,
  });
}

/**
 * JSON text of a request body, a BigInt written as its exact digits (a JSON number above 2^53
 * loses digits in a JavaScript Number: an exercise seed goes up to 2^63 - 1).
 */
export function jsonBody(value) {
  const marked = JSON.stringify(value, (key, v) => (typeof v === 'bigint' ? `\u0000bigint:${v}` : v));
  return marked.replace(/"\\u0000bigint:(-?\d+)"/g, '$1');
}

// The server's answers are functions of the request (the same scene, samples, method ... give the
// same numbers), so an answer already fetched is reused rather than asked again: a return to a
// preset, to an instant or to a method seen before costs no request. The newest ANSWERS_KEPT
// answers are kept (a sweep is ~0.5 MB of objects); a request still under way is shared; a
// failure is never kept. Each caller gets its own copy (callers edit scenes they were given).
const ANSWERS_KEPT = 16;
const REUSED = /^\/(presets\/[^/?]+|sweep|solution|analyze|balance)$/;
const answers = new Map(); // method + path + body text -> promise of the parsed JSON

async function call(method, path, body) {
  const text = body === undefined ? undefined : jsonBody(body);
  if (method !== 'POST' || !REUSED.test(path)) return ask(method, path, text);
  const key = `${path} ${text}`;
  let answer = answers.get(key);
  if (answer) answers.delete(key); // re-inserted below as the newest
  else {
    answer = ask(method, path, text);
    answer.catch(() => answers.get(key) === answer && answers.delete(key));
  }
  answers.set(key, answer);
  while (answers.size > ANSWERS_KEPT) answers.delete(answers.keys().next().value);
  return structuredClone(await answer);
}

/** One request; `text` the JSON body. */
async function ask(method, path, text) {
  let response;
  try {
    response = await fetch(BASE + path, {
      method,
      headers: text === undefined ? {} : { 'Content-Type': 'application/json' },
      body: text,
    });
  } catch (err) {
    throw new ApiError({ code: 'network', detail: `The server cannot be reached (${err.message}).` });
  }
  if (!response.ok) throw await problemFrom(response, path);
  return response.json();
}

export const getPresets = () => call('GET', '/presets');
/** The presets of one family (`gear_trains`, `cams`; docs/GEARS.md). */
export const getPresetFamily = (family) => call('GET', `/presets?family=${encodeURIComponent(family)}`);
export const buildPreset = (name, params) => call('POST', `/presets/${encodeURIComponent(name)}`, params);
/** A preset's scene: at its defaults (no `params`) the one its listing carries (`listed`, GET
 * /presets: no request, a copy the caller may change), else built by the server. */
export const presetScene = (listed, name, params = {}) =>
  (listed && !Object.keys(params).length ? Promise.resolve(structuredClone(listed)) : buildPreset(name, params));
export const analyze = (scene, quantities) =>
  call('POST', '/analyze', quantities ? { scene, quantities } : { scene });
export const sweep = (scene, samples, quantities, timeRange, statics = false, speedFluctuation = null) =>
  call('POST', '/sweep', {
    scene, samples, quantities,
    ...(timeRange ? { time_range: timeRange } : {}),
    ...(statics ? { statics: true } : {}),
    ...(speedFluctuation ? { speed_fluctuation: speedFluctuation } : {}),
  });
export const solution = (scene, method, digits = 4) => call('POST', '/solution', { scene, method, digits });
export const balance = (scene, counterweights) => call('POST', '/balance', { scene, counterweights });
/** A cam's worked solution at cam angle `angleDeg` (docs/CAMS.md). */
export const camSolution = (scene, angleDeg, digits = 4) => call('POST', '/solution', { scene, angle_deg: angleDeg, digits });

/** A four-bar for two or three coupler positions, a function or a time ratio (docs/SYNTHESIS.md). */
export const synthesis = (task) => call('POST', '/synthesis', task);

/** The printable worked solution: a whole HTML page (text, not JSON). */
export async function solutionPage(scene, method, digits = 4) {
  const response = await fetch(BASE + '/solution.html', {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ scene, method, digits }),
  });
  if (!response.ok) throw await problemFrom(response, '/solution.html');
  return response.text();
}

/** The seed example scenes, served from server/examples at /examples (not part of the API). */
export async function getExample(file) {
  const response = await fetch(`examples/${encodeURIComponent(file)}`);
  if (!response.ok) {
    throw new ApiError({ code: 'http_' + response.status, detail: `Example ${file} could not be loaded (HTTP ${response.status}).`, status: response.status });
  }
  return response.json();
}

export async function getExampleIndex() {
  const response = await fetch('examples/index.json');
  if (!response.ok) return { examples: [] };
  return response.json();
}

// --- exercises (exercises-v1) -----------------------------------------------------------------
export const exerciseTypes = () => call('GET', '/exercises/types');
export const generateExercises = (request) => call('POST', '/exercises', request);
export const getExercise = (id) => call('GET', `/exercises/${encodeURIComponent(id)}`);
export const checkAnswers = (id, answers) => call('POST', '/exercises/check', { id, answers });

/** An export as a file: {blob, filename} (Moodle XML, HTML sheet, CSV or JSON). */
export async function exportExercises(request) {
  let response;
  try {
    response = await fetch(BASE + '/exercises/export', {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: jsonBody(request),
    });
  } catch (err) {
    throw new ApiError({ code: 'network', detail: `The server cannot be reached (${err.message}).` });
  }
  if (!response.ok) throw await problemFrom(response, '/exercises/export');
  const disposition = response.headers.get('content-disposition') || '';
  const match = /filename="([^"]+)"/.exec(disposition);
  return { blob: await response.blob(), filename: match ? match[1] : 'exercises' };
}
