// A printable exercise sheet (POST /api/v1/exercises/export, format html): typeset every
// formula with KaTeX. A file, not an inline script, so the sheet runs under the server's CSP.
if (window.katex) {
  for (const el of document.querySelectorAll('[data-tex]')) {
    try { window.katex.render(el.dataset.tex, el, { throwOnError: false, displayMode: true }); }
    catch (e) { /* the plain TeX stays visible */ }
  }
}
