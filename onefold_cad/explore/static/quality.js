// onefold explore: adaptive drag frames. While the user drags a slider or orbits
// the view, and only when a full-quality frame of the 3D view is slow to draw
// here (software WebGL, a weak GPU), the frames are drawn at a reduced pixel
// ratio: the same scene, materials and camera, the canvas's size on the page
// unchanged, a quarter of the pixels to shade. As soon as the drag ends (the
// slider's `change` event, the orbit's release, or SETTLE_MS after both the
// last input and the drawing of its frame) the view is drawn once more at full
// quality. On a fast GPU every frame is full quality.
//
// How slow a full frame is comes from the GPU itself: a WebGL2 fence after each
// frame, polled without blocking (the time from the render call until the fence
// is signalled: the GPU's drawing of the frame, and whatever it had queued).

//: A full frame slower than this (ms, median of the last RECENT full frames)
//: makes drag frames reduced.
export const SLOW_MS = 16;
//: The drag frames' pixel ratio, as a fraction of the full frames'.
export const DRAG_SCALE = 0.5;
//: Without input for this long (ms) after its last frame was drawn, a slider drag has ended.
export const SETTLE_MS = 200;
const RECENT = 3;

// True when the full frames `ms` (their GPU times, most recent last) call for
// reduced drag frames: the median of the last RECENT is over `slowMs`; false
// until one is measured.
export function slowFrames(ms, slowMs = SLOW_MS) {
  const last = ms.slice(-RECENT).sort((a, b) => a - b);
  if (!last.length) return false;
  return last[Math.floor(last.length / 2)] > slowMs;
}

// renderer: the three.js WebGLRenderer (its pixel ratio is the full frames');
// draw: renders the scene with it; busy: true while an update of the design is
// on its way (it will draw the next frame itself); onSettled: called after the
// full frame that ends a run of reduced ones has been drawn.
export function createQuality({ renderer, draw, busy, onSettled }) {
  const gl = renderer.getContext();
  const fullRatio = renderer.getPixelRatio();
  const fullMs = []; // GPU times of recent full frames (ms)
  let drawing = 0; // frames handed over, not yet drawn by the GPU
  let sliding = false; // a slider is being dragged
  let orbiting = false; // the view is being orbited
  let settleTimer = null;
  let inputAt = 0; // the time of the slider's last input (ms)
  let drawnAt = 0; // the time the GPU last finished every frame handed over
  let last = 'full'; // the quality of the frame on the canvas

  // The GPU time of the frame just handed over: a fence, polled (a full
  // frame's time is kept; `drawing` counts the frames not yet drawn).
  function measure(full) {
    if (typeof gl.fenceSync !== 'function') return;
    const sync = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!sync) return; // no flush: the frame's own end hands the commands over
    drawing += 1;
    const t0 = performance.now();
    const poll = () => {
      if (gl.getSyncParameter(sync, gl.SYNC_STATUS) !== gl.SIGNALED) {
        setTimeout(poll, 2);
        return;
      }
      gl.deleteSync(sync);
      drawing -= 1;
      if (drawing === 0) drawnAt = performance.now();
      if (!full) return;
      fullMs.push(performance.now() - t0);
      if (fullMs.length > RECENT) fullMs.shift();
      renderer.domElement.dataset.fullFrameMs = fullMs.map(Math.round).join(' ');
    };
    setTimeout(poll, 0);
  }

  // Draw the scene at the quality of the moment; returns 'drag' or 'full'.
  function render() {
    const reduced = (sliding || orbiting) && slowFrames(fullMs);
    const ratio = reduced ? fullRatio * DRAG_SCALE : fullRatio;
    if (renderer.getPixelRatio() !== ratio) renderer.setPixelRatio(ratio);
    draw();
    const was = last;
    last = reduced ? 'drag' : 'full';
    renderer.domElement.dataset.quality = last;
    measure(!reduced);
    if (!reduced && was === 'drag') requestAnimationFrame(() => onSettled());
    return last;
  }

  // The drag is over: the next frame is full; draw it now unless an update
  // on its way will (it draws with the state it brings).
  function settle() {
    if (sliding || orbiting || last !== 'drag' || busy()) return;
    render();
  }

  function slide() {
    sliding = true;
    inputAt = performance.now();
    clearTimeout(settleTimer);
    settleTimer = setTimeout(quiet, SETTLE_MS);
  }

  // The drag has ended SETTLE_MS after its last input and after the frame of
  // that input was drawn (a slow server or GPU does not end it).
  function quiet() {
    const idle = !busy() && drawing === 0;
    const wait = idle ? SETTLE_MS - (performance.now() - Math.max(inputAt, drawnAt)) : 16;
    if (wait > 0) settleTimer = setTimeout(quiet, wait);
    else endSlide();
  }

  function endSlide() {
    clearTimeout(settleTimer);
    sliding = false;
    settle();
  }

  function orbit(on) {
    orbiting = on;
    settle();
  }

  return {
    render,
    slide,
    endSlide,
    orbit,
    settle,
    fullFrameMs: () => [...fullMs],
    quality: () => last,
  };
}
