// number_format_check.mjs: call the app's number formatting (static/js/units.js) as the page does.
//
// Reads one JSON array from stdin, each item [name, args] with name one of units.js's exports
// (fmt, typed, show, denoise), and writes one JSON array of their results in the same order.
// Usage: node tests/number_format_check.mjs < calls.json

import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const source = readFileSync(join(here, '..', 'static', 'js', 'units.js'), 'utf8');
const units = await import(`data:text/javascript;base64,${Buffer.from(source).toString('base64')}`);

const chunks = [];
for await (const chunk of process.stdin) chunks.push(chunk);
const calls = JSON.parse(Buffer.concat(chunks).toString('utf8'));
process.stdout.write(JSON.stringify(calls.map(([name, args]) => units[name](...args))));
