// vendor.js: the vendored libraries (KaTeX, Plotly), loaded on first use.
//
// Parsing a megabyte of Plotly takes a few hundred milliseconds of main thread on a slow
// machine; loading it only when the first plot is drawn lets the mechanism and its polygons
// appear first. index.html preloads both files, so the download still starts at once. A library
// that fails to load resolves to null and the view concerned says so.

const SOURCES = {
  Plotly: 'vendor/plotly/plotly-basic.min.js',
  katex: 'vendor/katex/katex.min.js',
};

const pending = new Map();

function load(globalName) {
  if (globalThis[globalName]) return Promise.resolve(globalThis[globalName]);
  if (!pending.has(globalName)) {
    pending.set(globalName, new Promise((resolve) => {
      const script = document.createElement('script');
      script.src = SOURCES[globalName];
      script.async = true;
      script.addEventListener('load', () => resolve(globalThis[globalName] || null), { once: true });
      script.addEventListener('error', () => resolve(null), { once: true });
      document.head.appendChild(script);
    }));
  }
  return pending.get(globalName);
}

export const plotlyReady = () => load('Plotly');
export const katexReady = () => load('katex');
