// tabs.js: buttons with role="tab" show the panel their aria-controls names and hide the others
// of the same tablist. A Plotly chart drawn while hidden has no size: it is resized when shown.

export function installTabs(root = document) {
  for (const list of root.querySelectorAll('[role="tablist"]')) {
    const tabs = [...list.querySelectorAll('[role="tab"]')];
    const select = (tab) => {
      for (const t of tabs) {
        const on = t === tab;
        t.setAttribute('aria-selected', String(on));
        t.tabIndex = on ? 0 : -1;
        document.getElementById(t.getAttribute('aria-controls'))?.toggleAttribute('hidden', !on);
      }
      const panel = document.getElementById(tab.getAttribute('aria-controls'));
      for (const plot of panel?.querySelectorAll('.js-plotly-plot') || []) globalThis.Plotly?.Plots.resize(plot);
    };
    list.addEventListener('click', (ev) => {
      const tab = ev.target.closest('[role="tab"]');
      if (tab && list.contains(tab)) select(tab);
    });
    // Arrow keys move between tabs (WAI-ARIA tabs pattern).
    list.addEventListener('keydown', (ev) => {
      const i = tabs.indexOf(document.activeElement);
      if (i < 0 || (ev.key !== 'ArrowRight' && ev.key !== 'ArrowLeft')) return;
      const next = tabs[(i + (ev.key === 'ArrowRight' ? 1 : tabs.length - 1)) % tabs.length];
      next.focus();
      select(next);
      ev.preventDefault();
    });
    for (const t of tabs) t.tabIndex = t.getAttribute('aria-selected') === 'true' ? 0 : -1;
  }
}
