// The browser page (index.html): .wrl and .fs files by drag and drop or a file picker, fvrml-run
// on them in a worker (worker.js), the shape in the 3D view (viewer.js), every diagnostic with
// file:line:col and its source line, and the results saved as .glb and .wrl.
/* global FvrmlViewer, createFvrmlRun, fvrmlWorkerMain */
'use strict';

const $ = (id) => document.getElementById(id);
const viewer = new FvrmlViewer($('view'), { play: $('play'), slider: $('time'), clockText: $('clock') });
let files = [];        // [{path, data}] as the user gave them (gzip inflated)
let lastGlb = null;    // the shown scene's .glb, for saving
let running = Promise.resolve();
let generation = 0;    // runs started: only the latest shows its answer

// The worker: fvrml-web.js's factory and worker.js's function as one script in a Blob. Where no
// worker can start, the same function runs here, on the page's thread.
// runner(job, replace): fvrml-run's answer for `job`. `replace`: a scene run, which cancels the
// runs still going: a wasm run cannot be stopped midway (the build has no threads, so the emitted
// code polls no cancel flag), so their worker is ended, a fresh one started, and each of them
// answers {cancelled: true}. On the page's own thread runs go one after another.
const runner = (() => {
  const source = 'var _scriptDir = undefined;\nvar createFvrmlRun = ' + createFvrmlRun.toString() + ';\n' +
    fvrmlWorkerMain.toString() + '\nfvrmlWorkerMain(self);\n';
  let next = 0;
  const waiting = new Map();
  try {
    const url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
    let worker = null;
    const start = () => {
      worker = new Worker(url);
      worker.onmessage = (e) => { waiting.get(e.data.id)(e.data.answer); waiting.delete(e.data.id); };
    };
    start();
    document.body.dataset.worker = 'yes';
    return (job, replace) => new Promise((resolve) => {
      if (replace && waiting.size) {
        worker.terminate();
        for (const answer of waiting.values()) answer({ cancelled: true });
        waiting.clear();
        start();
      }
      const id = next++;
      waiting.set(id, resolve);
      worker.postMessage({ id, job });
    });
  } catch (e) {
    document.body.dataset.worker = 'no';
    const here = { postMessage: (m) => here.answer(m) };
    fvrmlWorkerMain(here);
    let queue = Promise.resolve();
    return (job) => (queue = queue.then(() => new Promise((resolve) => {
      here.answer = (m) => resolve(m.answer);
      here.onmessage({ data: { id: 0, job } });
    })));
  }
})();

// A .wrl.gz (or any gzip) is inflated here: the toolchain reads plain text.
async function inflated(bytes) {
  if (bytes.length < 2 || bytes[0] !== 0x1f || bytes[1] !== 0x8b) return bytes;
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

const isScene = (path) => /\.(wrl|wrz|fs)(\.gz)?$/i.test(path);

// The file to run: the one chosen, else the first scene no other file names (an Inline's target).
function mainFile() {
  const chosen = $('main').value;
  if (chosen && files.some((f) => f.path === chosen)) return chosen;
  const texts = files.map((f) => new TextDecoder().decode(f.data.subarray(0, 1 << 20)));
  const scenes = files.filter((f) => isScene(f.path));
  const named = (f) => texts.some((t, i) => files[i] !== f && t.includes(f.path.split('/').pop()));
  return (scenes.find((f) => !named(f)) || scenes[0] || {}).path;
}

async function addFiles(list) {
  const added = [];
  for (const file of list) {
    const path = (file.webkitRelativePath || file.name).replace(/\.gz$/i, '');
    added.push({ path, data: await inflated(new Uint8Array(await file.arrayBuffer())) });
  }
  // New files replace those of the same name; a new scene starts a new set.
  const fresh = added.some((f) => isScene(f.path)) && !$('keep').checked;
  files = (fresh ? [] : files.filter((f) => !added.some((a) => a.path === f.path))).concat(added);
  const select = $('main');
  select.innerHTML = '';
  for (const f of files.filter((g) => isScene(g.path))) select.add(new Option(f.path, f.path));
  select.value = mainFile() || '';
  await runScene(fresh);
}

// Diagnostics as the command line prints them; errors in red, warnings (a missing Inline) in amber.
function showLog(log, ok) {
  const box = $('diagnostics');
  const text = log.split('\n').filter((l) => !/^wrote /.test(l)).join('\n').trim();
  box.textContent = text;
  box.className = ok ? (/warning:/.test(text) ? 'warn' : 'note') : 'error';
  box.style.display = text ? 'block' : 'none';
}

// A new run replaces the one still going (a scene dropped by mistake, a script fixed while the
// broken one still meshes): the older's answer comes back cancelled and changes nothing.
function runScene(fresh) {
  const mine = ++generation;
  running = (async () => {
    const main = mainFile();
    if (!main) return;
    document.body.dataset.state = 'running';
    $('status').textContent = 'running ' + main + ' …';
    const t0 = performance.now();
    const answer = await runner({ files, main, format: 'glb', args: ['--backend', $('backend').value] }, true);
    if (answer.cancelled || mine !== generation) return;
    const ms = performance.now() - t0;
    showLog(answer.log, answer.code === 0);
    if (answer.code !== 0) {
      $('status').textContent = main + ': failed (exit status ' + answer.code + ')';
      document.body.dataset.state = 'error';
      return;
    }
    lastGlb = answer.output;
    const view = answer.stats && answer.stats.view;
    const shown = await viewer.show(answer.output.buffer, view, !fresh);
    if (mine !== generation) return;
    // Per frame: still shapes' triangles, and animated ones' over their frames (as the preview counts).
    let triangles = 0;
    const stats = answer.stats || {};
    for (const s of stats.shapes || []) triangles += s.triangles || 0;
    for (const a of stats.animations || []) triangles += Math.round(a.triangles / Math.max(1, a.frames));
    $('status').textContent = `${main}: ${triangles.toLocaleString()} triangles, ${Math.round(ms)} ms` +
      (shown.animated ? `, animated (${shown.duration.toFixed(2)} s)` : '');
    $('saveGlb').disabled = $('saveWrl').disabled = false;
    document.body.dataset.state = 'ok';
    document.body.dataset.animated = shown.animated ? 'yes' : 'no';
  })();
  return running;
}

function save(bytes, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([bytes]));
  a.download = name;
  a.click();
}
const baseName = () => (mainFile() || 'scene').split('/').pop().replace(/\.(wrl|wrz|fs)$/i, '');
$('saveGlb').onclick = () => lastGlb && save(lastGlb, baseName() + '.glb');
$('saveWrl').onclick = async () => {  // VRML97 is its own run: fvrml-run -o scene.wrl
  const answer = await runner({ files, main: mainFile(), format: 'wrl', args: ['--backend', $('backend').value] });
  if (answer.cancelled) return;  // a new scene came first
  if (answer.code === 0) save(answer.output, baseName() + '-fvrml.wrl');
  else showLog(answer.log, false);
};

$('pick').onchange = async (e) => {
  await addFiles(Array.from(e.target.files));
  e.target.value = '';  // the same file chosen again is a change too
};
$('main').onchange = () => runScene(true);
$('backend').onchange = () => runScene(false);
$('rerun').onclick = () => runScene(false);
$('source').onkeydown = (e) => {  // FScript pasted or typed: run as a .fs on Ctrl+Enter
  if (e.key === 'Enter' && (e.ctrlKey || e.metaKey)) $('runSource').click();
};
$('runSource').onclick = () => {
  files = [{ path: 'pasted.fs', data: new TextEncoder().encode($('source').value) }];
  $('main').innerHTML = '';
  $('main').add(new Option('pasted.fs', 'pasted.fs'));
  runScene(true);
};
addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dropping'); });
addEventListener('dragleave', () => document.body.classList.remove('dropping'));
addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dropping');
  addFiles(e.dataTransfer.files);
});
$('status').textContent = 'drop .wrl or .fs files here, or open them';
document.body.dataset.state = 'ready';
// For tests and scripts: the page's own entry points.
window.fvrmlPage = { addFiles, runScene, get files() { return files; }, get glb() { return lastGlb; } };
