// share.js: the scene and the view in the URL hash, so a link opens exactly what was shown.
//
// Format: #s=<prefix>.<base64url>, prefix "z" for deflate-raw compressed JSON (short links,
// where the browser has CompressionStream) or "j" for plain JSON. The document is
// {v: 1, scene, source, view}; the scene travels whole, so a link keeps working even when a
// preset's defaults change later.

const KEY = 's';

function toBase64Url(bytes) {
  let bin = '';
  for (let i = 0; i < bytes.length; i += 0x8000) bin += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(bin).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64Url(text) {
  const b64 = text.replace(/-/g, '+').replace(/_/g, '/') + '==='.slice((text.length + 3) % 4);
  const bin = atob(b64);
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
}

async function pipe(bytes, stream) {
  const body = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(body).arrayBuffer());
}

export async function encodeState(state) {
  const bytes = new TextEncoder().encode(JSON.stringify({ v: 1, ...state }));
  if (typeof CompressionStream === 'function') {
    return `z.${toBase64Url(await pipe(bytes, new CompressionStream('deflate-raw')))}`;
  }
  return `j.${toBase64Url(bytes)}`;
}

export async function decodeState(token) {
  const [prefix, data] = [token.slice(0, 1), token.slice(2)];
  let bytes = fromBase64Url(data);
  if (prefix === 'z') bytes = await pipe(bytes, new DecompressionStream('deflate-raw'));
  else if (prefix !== 'j') throw new Error('unknown share format');
  const doc = JSON.parse(new TextDecoder().decode(bytes));
  if (!doc || doc.v !== 1 || typeof doc.scene !== 'object') throw new Error('not a shared scene');
  return doc;
}

/** The state in the current location's hash, or null. Never throws: a bad link opens the default. */
export async function readHash(hash = location.hash) {
  const params = new URLSearchParams(hash.replace(/^#/, ''));
  const token = params.get(KEY);
  if (!token) return null;
  try {
    return await decodeState(token);
  } catch (err) {
    return { error: `This link could not be opened (${err.message}); showing the default mechanism.` };
  }
}

/** Put the state into the address bar without adding a history entry per change. */
export async function writeHash(state) {
  const token = await encodeState(state);
  const url = `${location.pathname}${location.search}#${KEY}=${token}`;
  history.replaceState(null, '', url);
  return location.href;
}
