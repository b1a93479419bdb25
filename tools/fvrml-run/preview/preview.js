// The preview page's script: shows /scene.glb in web/viewer.js's view (the browser page's, with the
// scene's animation, lights and viewpoint), and follows /events, the server's stream of states: a
// new good scene is loaded (the camera and the animation's time kept), a broken one shows its
// diagnostics over the last good picture; while an animation is made, the frames so far play.
/* global FvrmlViewer */
'use strict';

const view = document.getElementById('view');
const overlay = document.getElementById('overlay');
const status = document.getElementById('status');
const scaleInput = document.getElementById('scale');
const statsText = document.getElementById('stats');
// The 3D view, its lights, viewpoint, animation and time slider: web/viewer.js, the browser page's.
const viewer = new FvrmlViewer(view, {
  play: document.getElementById('play'),
  slider: document.getElementById('time'),
  clockText: document.getElementById('clock'),
});
let shown = -1, framed = false;

function load(version, partial) {
  fetch('/scene.glb?v=' + version)
    .then((r) => { if (!r.ok) throw new Error('HTTP ' + r.status); return r.arrayBuffer(); })
    .then((glb) => {
      if (version < shown) return null;  // a later scene arrived first
      const keep = framed;  // the first scene frames the camera; later ones keep the user's
      framed = true;
      return viewer.show(glb, currentView, keep).then(() => {
        shown = version;
        document.body.dataset.shown = String(version);
        document.body.dataset.shownFrames = partial ? `${partial.frames}/${partial.of}` : 'all';
      });
    })
    .catch((e) => { status.textContent = 'cannot load the scene: ' + e; });
}

let currentView = null;

function show(state) {
  if (state.ok && state.stats && state.stats.view) currentView = state.stats.view;
  // Errors over the last good picture; a good run's warnings (a missing Inline) over its own.
  const warned = state.ok && /warning:/.test(state.diagnostics || '');
  overlay.style.display = state.ok && !warned ? 'none' : 'block';
  overlay.className = warned ? 'warn' : '';
  overlay.textContent = state.ok && !warned ? '' : state.diagnostics;
  document.body.dataset.state = state.ok ? 'ok' : 'error';
  const s = state.stats || {};
  let triangles = 0, frames = 0;
  for (const shape of s.shapes || []) triangles += shape.triangles || 0;
  for (const a of s.animations || []) {  // per frame: the animated shapes' triangles over their frames
    triangles += Math.round(a.triangles / Math.max(1, a.frames));
    if (!a.constant) frames = Math.max(frames, a.frames);  // one that never changed is a still shape
  }
  const time = frames ? `${Math.round(s.total_ms || 0)} ms for ${frames} frames (${((s.total_ms || 0) / frames).toFixed(1)} ms a frame)`
                      : `${Math.round(s.total_ms || 0)} ms`;
  statsText.textContent = `${s.backend || ''} · resolution × ${state.scale} · ${triangles.toLocaleString()} triangles · ${time}`;
  // While an animation is made, the page shows (and plays) the frames so far.
  document.body.dataset.partial = state.partial ? `${state.partial.frames}/${state.partial.of}` : '';
  if (state.partial) status.textContent = `frames so far: ${state.partial.frames} of ${state.partial.of}`;
  if (state.ok && state.version !== shown) load(state.version, state.partial);
}

// This page's name for its stream: said again when it goes away, so the server frees its slot then.
const pageId = Math.random().toString(36).slice(2, 12);
const events = new EventSource('/events?page=' + pageId);
addEventListener('pagehide', () => {
  events.close();
  navigator.sendBeacon('/closed?page=' + pageId);
});
events.addEventListener('state', (e) => { status.textContent = ''; show(JSON.parse(e.data)); });
events.addEventListener('progress', (e) => {  // while the scene runs again: frames done of N, share
  const p = JSON.parse(e.data);
  status.textContent = `running: ${p.done}/${p.jobs} ${p.what}, ${Math.floor(p.fraction * 100)}%`;
});
events.onerror = () => { status.textContent = 'disconnected: is fvrml-run --serve still running?'; };

scaleInput.onchange = () => {
  fetch('/settings?scale=' + encodeURIComponent(scaleInput.value), { method: 'POST' });
};
