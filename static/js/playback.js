// playback.js: animation frames. The animation loop of a family's view (the cam, the gear
// train, the designer): one requestAnimationFrame loop per view, running while the view is shown,
// that hands the view the time since the last frame (the linkage view's own loop is main.js's,
// which also redraws on demand); and afterPaint, to do secondary work once a frame is painted.

/** Resolves after the next frame has been painted (a task queued from its animation frame). */
export function afterPaint() {
  return new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));
}

/** The longest step a frame may take (s): a tab in the background does not make the motion jump. */
export const MAX_STEP = 0.1;

export class Playback {
  /**
   * @param {() => boolean} shown whether the view is shown (the loop stops when it is not)
   * @param {(dt: number, now: number) => void} step called every frame: dt the seconds since the
   *   last frame (0 on the first, at most MAX_STEP), now the frame's time (ms)
   */
  constructor(shown, step) {
    this.shown = shown;
    this.step = step;
    this.running = false;
  }

  /** Runs the loop from the next frame, unless it is running. */
  start() {
    if (this.running) return;
    this.running = true;
    let last = null;
    const frame = (now) => {
      if (!this.shown()) {
        this.running = false;
        return;
      }
      const dt = last === null ? 0 : Math.min((now - last) / 1000, MAX_STEP);
      last = now;
      this.step(dt, now);
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  }
}
