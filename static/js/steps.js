// steps.js: the worked solution of the analysed instant, rendered with KaTeX.
//
// The server writes the solution (issue 4: steps are data, built from the solver's numbers);
// this module only typesets it. Each step shows its title, its equation(s) in KaTeX and the
// plain-text form under it, which is also what a screen reader gets. A step whose LaTeX KaTeX
// cannot read is shown as plain text with a visible mark (class `step-error`), so a bad string
// from the server is seen and tested for, never silently dropped.

function el(tag, attrs = {}, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  return node;
}

function typeset(latex, target) {
  const katex = globalThis.katex;
  if (!katex) {
    target.textContent = latex;
    return 'KaTeX is not loaded';
  }
  try {
    katex.render(latex, target, { displayMode: true, throwOnError: true, strict: 'ignore', trust: false, output: 'htmlAndMathml' });
    return null;
  } catch (err) {
    target.textContent = latex;
    return err.message;
  }
}

/** Render {steps, mistakes} into the two containers. Returns the number of LaTeX failures. */
export function renderSolution(stepsEl, mistakesEl, solution) {
  stepsEl.replaceChildren();
  let failures = 0;
  const list = el('ol', { class: 'step-list' });
  for (const step of solution.steps || []) {
    const item = el('li', { class: 'step' });
    if (step.title) item.appendChild(el('h3', { class: 'step-title' }, step.title));
    if (step.latex) {
      const math = el('div', { class: 'step-math' });
      const error = typeset(step.latex, math);
      if (error) {
        failures += 1;
        math.classList.add('step-error');
        math.title = `KaTeX could not read this step: ${error}`;
      }
      item.appendChild(math);
    }
    if (step.text) item.appendChild(el('p', { class: 'step-text' }, step.text));
    if (step.figure && step.figure.svg) {
      // A free-body diagram (dynamics-v1): the server's SVG, every name in it escaped there.
      const figure = el('div', { class: 'step-figure' });
      figure.innerHTML = step.figure.svg;
      item.appendChild(figure);
    }
    list.appendChild(item);
  }
  stepsEl.appendChild(list);

  mistakesEl.replaceChildren();
  const mistakes = solution.mistakes || [];
  if (mistakes.length) {
    const ul = el('ul', { class: 'mistake-list' });
    for (const m of mistakes) {
      const li = el('li');
      li.appendChild(el('strong', {}, m.title || ''));
      if (m.text) li.appendChild(el('p', {}, m.text));
      ul.appendChild(li);
    }
    mistakesEl.appendChild(ul);
  } else {
    mistakesEl.appendChild(el('p', { class: 'muted' }, 'No typical mistakes listed for this mechanism.'));
  }
  return failures;
}

export function renderMessage(stepsEl, text) {
  stepsEl.replaceChildren(el('p', { class: 'panel-message' }, text));
}
