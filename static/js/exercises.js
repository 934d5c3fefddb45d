// exercises.js: the instructor page and the student mode (exercises.html).
//
// Instructor (exercises.html): choose a type, a difficulty, a count and a seed; the server
// generates the exercises (nothing is stored: the id type:difficulty:seed:index is the whole
// exercise); the preview shows each statement with its figure and, folded, its key; each export
// downloads as a file. Student (exercises.html#id=<id>, the share link): the statement, a field
// per asked quantity, a check that grades and names a typical mistake, and the worked solution
// revealed one step at a time; exercises.html#student (the app's link) starts with a type
// chooser. "Exam set" asks for opaque ids (a random seed, the set's password): their student
// mode shows the statement only, with no check and no solution. The server computes everything;
// this page only shows it.

import {
  checkAnswers,
  exerciseTypes,
  exportExercises,
  generateExercises,
  getExercise,
} from './api.js';
import { katexReady } from './vendor.js';
import { mathBlock } from './steps.js';
import { fmt } from './units.js';

const $ = (id) => document.getElementById(id);

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

function status(message, error = false) {
  const box = $('status');
  box.textContent = message;
  if (error) box.dataset.level = 'error';
  else delete box.dataset.level;
}

/** A statement's data one to a line where its rows do not fit (a phone): each row breaks after
 * every datum (the server separates them with ",\;"). */
const oneDatumALine = (latex) => latex.replaceAll(',\\;', ',\\\\');

/** A statement's or a step's equations as a block (steps.mathBlock: narrowed where too wide,
 * else scrolling in a group the keyboard reaches); KaTeX loaded first. */
async function equations(latex, label, narrow) {
  await katexReady();
  const [math, error] = mathBlock(latex, label, narrow);
  if (error) math.classList.add('step-error');
  return math;
}

async function typeset(latex, target, display = true) {
  const katex = await katexReady();
  target.textContent = latex;
  if (!katex) return;
  try {
    katex.render(latex, target, { displayMode: display, throwOnError: true, strict: 'ignore', trust: false });
  } catch {
    target.textContent = latex;
    target.classList.add('step-error');
  }
}

/** The figure: SVG written by the server from the scene (names escaped there). */
function figure(target, svg) {
  const doc = new DOMParser().parseFromString(svg, 'image/svg+xml');
  const root = doc.documentElement;
  target.replaceChildren(root.nodeName === 'svg' ? document.importNode(root, true) : el('p', {}, 'figure unavailable'));
}

const shareLink = (id) => `${location.origin}${location.pathname}#id=${encodeURIComponent(id)}`;

// --- instructor ---------------------------------------------------------------------------------

function request() {
  return {
    type: $('ex-type').value,
    difficulty: $('ex-difficulty').value,
    count: Number($('ex-count').value),
    seed: seedValue(),
    exam: $('ex-exam').checked,
  };
}

/** The seed as typed, exact: a BigInt of its digits (sent as a JSON number of those digits,
 * api.jsonBody), or the text itself, which the server refuses with its reason. */
function seedValue() {
  const text = $('ex-seed').value.trim();
  return /^[0-9]{1,19}$/.test(text) ? BigInt(text) : text;
}

// An exam set's seed is its password (whoever has it gets the key from the server, which
// refuses one below 2^32): a random one from 2^32 to 2^63 - 1, handled as digits (BigInt).
const MIN_EXAM_SEED = 2n ** 32n;

function examSeed() {
  const [high, low] = crypto.getRandomValues(new Uint32Array(2));
  return (BigInt((high & 0x7fffffff) || 1) << 32n) | BigInt(low);
}

function examChanged() {
  const seed = seedValue();
  if ($('ex-exam').checked && (typeof seed !== 'bigint' || seed < MIN_EXAM_SEED)) {
    $('ex-seed').value = String(examSeed());
  }
}

function card(exercise) {
  const box = el('article', { class: 'panel card', 'data-id': exercise.id });
  box.appendChild(el('h3', {}, `${exercise.index + 1}. ${exercise.title}`));
  box.appendChild(el('p', { class: 'muted small mono' }, exercise.id));
  if (exercise.exam) {
    box.appendChild(el('p', { class: 'muted small' }, 'Exam: students see only the statement; keep the seed and this key private.'));
  }
  box.appendChild(el('p', {}, exercise.statement.text));
  // on a phone the data go one to a line and the figure scales to the column (css)
  const tex = el('div', { class: 'tex' });
  equations(exercise.statement.latex, 'Data', oneDatumALine).then((math) => tex.replaceChildren(math));
  box.appendChild(tex);
  const fig = el('figure');
  figure(fig, exercise.statement.figure_svg);
  box.appendChild(fig);
  const key = el('details');
  key.appendChild(el('summary', {}, 'Answer key'));
  const table = el('table');
  for (const asked of exercise.asked) {
    const row = el('tr');
    row.appendChild(el('td', {}, asked.label));
    row.appendChild(el('td', { class: 'mono key-value', 'data-key': asked.key }, fmt(exercise.answers[asked.key], 6)));
    row.appendChild(el('td', {}, asked.unit));
    row.appendChild(el('td', {}, `± ${asked.tolerance * 100} %`));
    table.appendChild(row);
  }
  key.appendChild(table);
  box.appendChild(key);
  const open = el('a', { href: `#id=${encodeURIComponent(exercise.id)}`, class: 'student-link' }, 'Open in student mode');
  box.appendChild(open);
  return box;
}

async function preview(event) {
  event?.preventDefault();
  status('Generating…');
  try {
    const { exercises } = await generateExercises(request());
    $('preview').replaceChildren(...exercises.map(card));
    status(`${exercises.length} exercise(s): ${request().type}, ${request().difficulty}, seed ${request().seed}.`);
  } catch (err) {
    $('preview').replaceChildren();
    status(err.detail || String(err), true);
  }
}

/** The export's own fields: the tolerance (the field in %, sent relative) and, when a class list
 * is chosen, its text (one exercise per student, named on the sheets). */
async function exportFields() {
  const fields = { tolerance: Number($('ex-tolerance').value) / 100 };
  const file = $('ex-students').files[0];
  if (file) fields.students_csv = await file.text();
  return fields;
}

async function download(button) {
  const body = {
    ...request(),
    ...(await exportFields()),
    format: button.dataset.format,
    with_solutions: button.dataset.solutions === 'true',
  };
  status('Preparing the download…');
  try {
    const { blob, filename } = await exportExercises(body);
    const link = el('a', { href: URL.createObjectURL(blob), download: filename });
    document.body.appendChild(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
    status(`Downloaded ${filename}.`);
  } catch (err) {
    status(err.detail || String(err), true);
  }
}

async function instructor() {
  $('instructor').hidden = false;
  $('student').hidden = true;
  if (!$('ex-type').options.length) {
    const { types } = await exerciseTypes();
    for (const t of types) $('ex-type').appendChild(el('option', { value: t.name }, t.title));
    const describe = () => {
      const t = types.find((x) => x.name === $('ex-type').value);
      $('ex-type-description').textContent = t ? t.description : '';
    };
    $('ex-type').addEventListener('change', describe);
    describe();
    $('generate-form').addEventListener('submit', preview);
    $('ex-exam').addEventListener('change', examChanged);
    for (const button of document.querySelectorAll('.downloads button')) {
      button.addEventListener('click', () => download(button));
    }
  }
  await preview();
}

// --- student ------------------------------------------------------------------------------------

let current = null;
let shown = 0;

function parseNumber(text) {
  const cleaned = text.trim().replace(',', '.').replace(/\s+/g, '');
  if (cleaned === '') return null;
  const value = Number(cleaned);
  return Number.isFinite(value) ? value : NaN;
}

function answerRow(asked) {
  const row = el('tr', { 'data-key': asked.key });
  const label = el('td');
  const symbol = el('span', { class: 'symbol' });
  typeset(asked.symbol, symbol, false);
  label.append(symbol, ' ', asked.label);
  const field = el('input', { type: 'text', inputmode: 'decimal', name: asked.key, 'aria-label': `${asked.label} in ${asked.unit}` });
  const input = el('td');
  input.appendChild(field);
  row.append(label, input, el('td', {}, asked.unit), el('td', { class: 'result', 'aria-live': 'polite' }));
  return row;
}

async function check(event) {
  event.preventDefault();
  if (current.exam) return;
  const answers = {};
  for (const field of document.querySelectorAll('#answer-rows input')) {
    const value = parseNumber(field.value);
    if (Number.isNaN(value)) {
      status(`"${field.value}" is not a number.`, true);
      field.focus();
      return;
    }
    if (value !== null) answers[field.name] = value;
  }
  try {
    const result = await checkAnswers(current.id, answers);
    for (const r of result.results) {
      const cell = document.querySelector(`#answer-rows tr[data-key="${CSS.escape(r.key)}"] .result`);
      cell.className = `result ${r.verdict}`;
      cell.replaceChildren(el('span', {}, { correct: '✓ correct', incorrect: '✗ not right', missing: '— missing' }[r.verdict]));
      if (r.diagnosis) cell.appendChild(el('span', { class: 'diagnosis' }, r.diagnosis));
    }
    const correct = result.results.filter((r) => r.verdict === 'correct').length;
    $('score').textContent = `${correct} of ${result.results.length} correct`;
    status('Checked.');
  } catch (err) {
    status(err.detail || String(err), true);
  }
}

function nextStep() {
  const steps = current.solution.steps;
  if (shown >= steps.length) return;
  const step = steps[shown];
  const item = el('li', { class: 'step' });
  item.appendChild(el('h3', { class: 'step-title' }, step.title));
  // a long line is broken, else scrolls sideways inside its block: the keyboard reaches it
  const math = el('div');
  equations(step.latex, `Equations of step ${shown + 1}`).then((block) => math.replaceWith(block));
  item.append(math, el('p', { class: 'step-text' }, step.text));
  $('st-steps').appendChild(item);
  shown += 1;
  $('step-count').textContent = `step ${shown} of ${steps.length}`;
  $('next-step').disabled = shown >= steps.length;
}

async function student(id) {
  $('instructor').hidden = true;
  $('student').hidden = false;
  status('Loading the exercise…');
  try {
    current = await getExercise(id);
  } catch (err) {
    status(err.detail || String(err), true);
    return;
  }
  shown = 0;
  $('st-title').textContent = current.title;
  $('st-id').textContent = current.id;
  $('st-text').textContent = current.statement.text;
  $('st-latex').replaceChildren(await equations(current.statement.latex, 'The data', oneDatumALine));
  figure($('st-figure'), current.statement.figure_svg);
  $('answer-rows').replaceChildren(...current.asked.map(answerRow));
  $('score').textContent = '';
  $('st-steps').replaceChildren();
  // an exam exercise comes without solution, and the server checks none of its answers
  const exam = current.exam === true;
  $('check').hidden = exam;
  $('st-exam').hidden = !exam;
  $('st-solution').hidden = exam;
  $('next-step').disabled = exam;
  $('step-count').textContent = exam ? '' : `${current.solution.steps.length} steps`;
  $('st-share-url').hidden = true;
  document.title = `${current.title}: exercise`;
  status('');
}

// --- student entry: a type chooser (exercises.html#student, the app's Exercises link) ----------

/** The chooser's types, once: a new exercise is type:difficulty:seed:0 with a fresh seed. */
async function chooser() {
  if ($('st-type').options.length) return;
  const { types } = await exerciseTypes();
  for (const t of types) $('st-type').appendChild(el('option', { value: t.name }, t.title));
  const describe = () => {
    const t = types.find((x) => x.name === $('st-type').value);
    $('st-type-description').textContent = t ? t.description : '';
  };
  $('st-type').addEventListener('change', describe);
  describe();
}

/** The chooser set to the exercise shown (its id's type and difficulty), so that "New exercise"
 * gives another of the same kind, not the menu's first type. */
function chooseKindOf(id) {
  const [type, difficulty] = id.split(':');
  for (const [select, value] of [[$('st-type'), type], [$('st-difficulty'), difficulty]]) {
    if (![...select.options].some((o) => o.value === value) || select.value === value) continue;
    select.value = value;
    select.dispatchEvent(new Event('change'));
  }
}

function studentHome() {
  $('instructor').hidden = true;
  $('student').hidden = false;
  $('st-exercise').hidden = true;
  $('st-solution').hidden = true;
  chooser().catch((err) => status(err.detail || String(err), true));
}

$('st-chooser').addEventListener('submit', (event) => {
  event.preventDefault();
  const seed = Math.floor(Math.random() * 1_000_000);
  location.hash = `#id=${encodeURIComponent(`${$('st-type').value}:${$('st-difficulty').value}:${seed}:0`)}`;
});

function route() {
  const match = /^#id=(.+)$/.exec(location.hash);
  if (match) {
    $('st-exercise').hidden = false;
    $('st-solution').hidden = false;
    const id = decodeURIComponent(match[1]);
    chooser().then(() => chooseKindOf(id)).catch((err) => status(err.detail || String(err), true));
    student(id);
  } else if (location.hash === '#student') studentHome();
  else instructor().catch((err) => status(err.detail || String(err), true));
}

$('answer-form').addEventListener('submit', check);
$('next-step').addEventListener('click', nextStep);
$('st-share').addEventListener('click', () => {
  const box = $('st-share-url');
  box.value = shareLink(current.id);
  box.hidden = false;
  box.select();
});
window.addEventListener('hashchange', route);
route();
