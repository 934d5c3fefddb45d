// The printable worked solution (/api/v1/solution.html): typeset each step with KaTeX and wire
// the Print button. A file, not an inline script, so the page runs under the server's CSP.
document.querySelectorAll('.math[data-latex]').forEach(function (el) {
  if (!window.katex) { el.classList.remove('pending'); el.classList.add('error'); return; }
  try {
    katex.render(el.getAttribute('data-latex'), el,
                 {displayMode: true, throwOnError: true, strict: 'ignore', trust: false});
    el.classList.remove('pending');
  } catch (err) {
    el.classList.remove('pending');
    el.classList.add('error');
    el.title = 'KaTeX could not read this step: ' + err.message;
  }
});
document.querySelectorAll('button.print').forEach(function (b) {
  b.addEventListener('click', function () { window.print(); });
});
