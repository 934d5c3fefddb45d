// theme.js: the colours of the physical quantities, shared by the linkage view, the polygons,
// the plots and the legend, so that "red" means acceleration everywhere on the page.

export const COLOURS = {
  ink: '#1f2933',
  muted: '#6b7280',
  ground: '#6b7280',
  velocity: '#2b6cb0',
  acceleration: '#c53030',
  normal: '#dd6b20',
  tangential: '#2f855a',
  transport: '#718096',
  relative: '#d69e2e',
  coriolis: '#805ad5',
  trace: '#b5446e',
  pole: '#1f2933',
};

export const LEGEND = [
  { key: 'velocity', label: 'velocity v' },
  { key: 'acceleration', label: 'acceleration a' },
  { key: 'normal', label: 'normal part aⁿ = −ω²r' },
  { key: 'tangential', label: 'tangential part aᵗ = α × r' },
  { key: 'transport', label: 'transport (point of the guide)', dash: true },
  { key: 'relative', label: 'relative (along the slot)' },
  { key: 'coriolis', label: 'Coriolis 2 ω × v_rel' },
  { key: 'trace', label: 'path of the traced point', dash: true },
  { key: 'groove', label: 'groove (slot cut in its link)', groove: true },
];
