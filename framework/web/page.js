// Starts the program of the scene's lab (springlab-web-<lab>.js) on the scene the URL names.
// scenes.js (written by tools/web_build.sh) lists the scenes this build can run:
//   SPRINGLAB_SCENES = [{file, name, lab}], SPRINGLAB_DEFAULT_SCENE = "rope.json"
(function () {
  'use strict';
  var params = new URLSearchParams(window.location.search);
  var status = document.getElementById('status');
  var canvas = document.getElementById('canvas');
  var select = document.getElementById('scene');
  if (params.has('embed')) document.body.classList.add('embed');

  // The scene menu: every scene of the build; choosing one reloads the page on it.
  var file = params.get('scene') || window.SPRINGLAB_DEFAULT_SCENE;
  var scene = null;
  window.SPRINGLAB_SCENES.forEach(function (s) {
    var option = document.createElement('option');
    option.value = s.file;
    option.textContent = s.name + ' (' + s.file + ')';
    select.appendChild(option);
    if (s.file === file) scene = s;
  });
  select.value = file;
  select.addEventListener('change', function () {
    params.set('scene', select.value);
    window.location.search = params.toString();
  });
  if (!scene) {
    status.textContent = 'no scene "' + file + '" in this build';
    console.error('springlab: no scene "' + file + '" in this build (scenes.js)');
    return;
  }

  // The program's arguments (framework/web/main.cpp) and its output on the console.
  var args = ['--scene', scene.file, '--width', String(canvas.clientWidth), '--height', String(canvas.clientHeight)];
  if (params.has('paused')) args.push('--paused');
  if (params.has('embed')) args.push('--compact');
  window.Module = {
    canvas: canvas,
    arguments: args,
    print: function (text) { console.log(text); },
    printErr: function (text) { console.error(text); },
    setStatus: function (text) { status.textContent = text; },
    postRun: [function () {
      status.textContent = '';
      canvas.focus();
    }]
  };
  canvas.addEventListener('contextmenu', function (e) { e.preventDefault(); });
  window.addEventListener('resize', function () {
    if (window.Module.springlab) window.Module.springlab.resize(canvas.clientWidth, canvas.clientHeight);
  });
  var program = document.createElement('script');
  program.src = 'springlab-web-' + scene.lab + '.js';
  document.body.appendChild(program);
})();
