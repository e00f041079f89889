// Module.springlab: the page's hook on the viewer (page_hooks.cpp), for tests and the
// course site. Linked into every springlab-web-<lab>.js after Emscripten's own code.
var springlabFirstFrame;  // ms since the page's time origin, after the first frame ran
Module['postMainLoop'] = function () {
  if (springlabFirstFrame === undefined) springlabFirstFrame = performance.now();
};
Module['springlab'] = {
  // Whether the viewer runs (main has opened its scene).
  ready: function () { return runtimeInitialized && UTF8ToString(Module['_springlab_state']()) !== 'null'; },
  // Step `frames` viewer frames (each its substeps of dt), paused or not; returns the
  // milliseconds the physics took.
  step: function (frames) {
    var start = performance.now();
    if (Module['_springlab_step'](frames) !== 0) throw new Error('springlab: the viewer is not running');
    return performance.now() - start;
  },
  // Time, energies, observables, positions and velocities, as `springlab sim --out F.json`
  // writes a frame; `problem` names a missing exercise or why the run stopped.
  state: function () { return JSON.parse(UTF8ToString(Module['_springlab_state']())); },
  observables: function () { return Module['springlab'].state().observables; },
  positions: function () { return Module['springlab'].state().pos; },
  // When the first frame was drawn, in ms since the page started loading (undefined before).
  firstFrameMs: function () { return springlabFirstFrame; },
  pause: function (paused) { Module['_springlab_set_paused'](paused ? 1 : 0); },
  resize: function (width, height) { Module['_springlab_resize'](width, height); }
};
