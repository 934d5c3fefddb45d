// katex_check.mjs: typeset LaTeX strings with the vendored KaTeX, as the front end does.
//
// Reads JSON lines from stdin, each a LaTeX string (or {"latex": "..."}), and renders each with
// katex.renderToString(latex, {throwOnError: true, displayMode: true, strict: "error"}).
// Writes one JSON line per input line: {"ok": true} or {"ok": false, "error": "...",
// "latex": "..."}; exits with status 1 if any string failed, 2 on unreadable input.
// Usage: node tests/katex_check.mjs < lines.jsonl

import { createRequire } from 'node:module';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createInterface } from 'node:readline';

const require = createRequire(import.meta.url);
const here = dirname(fileURLToPath(import.meta.url));
const katex = require(join(here, '..', 'static', 'vendor', 'katex', 'katex.min.js'));

let failed = 0;
let unreadable = 0;
const lines = createInterface({ input: process.stdin, crlfDelay: Infinity });
for await (const line of lines) {
  if (!line.trim()) continue;
  let latex;
  try {
    const parsed = JSON.parse(line);
    latex = typeof parsed === 'string' ? parsed : parsed.latex;
    if (typeof latex !== 'string') throw new Error('expected a string or {"latex": string}');
  } catch (err) {
    unreadable += 1;
    process.stdout.write(JSON.stringify({ ok: false, error: `unreadable input: ${err.message}` }) + '\n');
    continue;
  }
  try {
    katex.renderToString(latex, { throwOnError: true, displayMode: true, strict: 'error' });
    process.stdout.write('{"ok":true}\n');
  } catch (err) {
    failed += 1;
    process.stdout.write(JSON.stringify({ ok: false, error: String(err.message), latex }) + '\n');
  }
}
process.exitCode = unreadable ? 2 : failed ? 1 : 0;
