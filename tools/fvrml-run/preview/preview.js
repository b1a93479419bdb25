// The preview page's script: shows /scene.glb with three.js, plays its animation (our glTF's STEP
// animation of frame nodes), and follows /events, the server's stream of states: a new good scene
// is loaded (the camera and the animation's time kept), a broken one shows its diagnostics over the
// last good picture; while an animation is made, the frames so far play.
import * as THREE from '/three/build/three.module.js';
import { GLTFLoader } from '/three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from '/three/examples/jsm/controls/OrbitControls.js';

const view = document.getElementById('view');
const overlay = document.getElementById('overlay');
const status = document.getElementById('status');
const playButton = document.getElementById('play');
const slider = document.getElementById('time');
const clockText = document.getElementById('clock');
const scaleInput = document.getElementById('scale');
const statsText = document.getElementById('stats');

const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setClearColor(0xffffff);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
camera.position.set(3, 2, 4);
scene.add(camera);  // the headlight rides on it
const controls = new OrbitControls(camera, renderer.domElement);
let lights = [];

// The scene's lights (VRML97 DirectionalLights and the headlight), or a key light and a soft fill
// when it has none, as our pictures do; its background colour.
function light(view) {
  for (const l of lights) l.parent.remove(l);
  lights = [];
  const add = (object, parent) => { parent.add(object); lights.push(object); };
  if (!view || view.lights.length === 0) {
    add(new THREE.HemisphereLight(0xffffff, 0x444444, 0.6), scene);
    const key = new THREE.DirectionalLight(0xffffff, 0.8);
    key.position.set(3, 5, 4);
    add(key, scene);
  } else {
    for (const l of view.lights) {
      const d = new THREE.DirectionalLight(new THREE.Color(...l.colour), l.intensity);
      d.position.set(-l.direction[0], -l.direction[1], -l.direction[2]);  // toward the light
      add(d, scene);
      if (l.ambient > 0) add(new THREE.AmbientLight(new THREE.Color(...l.colour), l.ambient * l.intensity), scene);
    }
  }
  if (!view || view.headlight) {
    const head = new THREE.DirectionalLight(0xffffff, view && view.lights.length ? 1 : 0.5);
    head.position.set(0, 0, 1);  // from the eye, in the camera's frame
    add(head, camera);
  }
  if (view) renderer.setClearColor(new THREE.Color(...view.background));
}

// The scene's Viewpoint as the start camera (VRML97: position, then orientation as axis and angle).
function viewpoint(view) {
  if (!view || !view.camera) return false;
  const c = view.camera;
  camera.position.set(...c.position);
  const axis = new THREE.Vector3(c.orientation[0], c.orientation[1], c.orientation[2]);
  camera.quaternion.setFromAxisAngle(axis.lengthSq() > 0 ? axis.normalize() : new THREE.Vector3(0, 0, 1), c.orientation[3]);
  camera.fov = THREE.Math.radToDeg(c.fieldOfView);
  camera.updateProjectionMatrix();
  // Orbit about the point the viewpoint looks at, as far ahead as the origin is.
  const ahead = new THREE.Vector3(0, 0, -1).applyQuaternion(camera.quaternion);
  controls.target.copy(camera.position).addScaledVector(ahead, Math.max(1, camera.position.length()));
  controls.update();
  return true;
}

let content = null, mixer = null, action = null, duration = 0, playing = true, framed = false, shown = -1;
let framesOf = [];  // the nodes the animation switches
const clock = new THREE.Clock();

function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

// The first scene frames the camera on its bounds; later ones keep the user's camera.
function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  if (box.isEmpty()) return;
  const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length();
  controls.target.copy(centre);
  camera.position.copy(centre).add(new THREE.Vector3(0.6, 0.45, 0.8).multiplyScalar(size));
  camera.near = size / 1000;
  camera.far = size * 100;
  camera.updateProjectionMatrix();
  controls.update();
  framed = true;
}

function load(version, partial) {
  new GLTFLoader().load('/scene.glb?v=' + version, (gltf) => {
    if (version < shown) return;  // a later scene arrived first
    const time = mixer ? mixer.time : 0;  // the animation goes on where it was
    if (content) scene.remove(content);
    content = gltf.scene;
    content.traverse((o) => { if (o.isMesh && o.material) o.material.side = THREE.DoubleSide; });
    scene.add(content);
    mixer = null, action = null, duration = 0;
    framesOf = [];
    if (gltf.animations.length) {
      // The frames are switched by scaling them to 0: hidden instead, so three.js draws (and
      // inverts the matrices of) only the frame shown.
      for (const track of gltf.animations[0].tracks) {
        const node = content.getObjectByName(track.name.split('.')[0]);
        if (node) framesOf.push(node);
      }
      mixer = new THREE.AnimationMixer(content);
      action = mixer.clipAction(gltf.animations[0]);
      action.play();
      duration = gltf.animations[0].duration;
      action.paused = false;  // a paused action ignores setTime
      mixer.setTime(duration > 0 ? time % duration : 0);
      action.paused = !playing;
    }
    slider.disabled = playButton.disabled = !mixer;
    light(currentView);
    if (!framed) {
      if (viewpoint(currentView)) framed = true;
      else frame(content);
    }
    draw();  // now, not at the next animation frame: a headless screenshot never gets one
    shown = version;
    document.body.dataset.shown = String(version);
    document.body.dataset.shownFrames = partial ? `${partial.frames}/${partial.of}` : 'all';
  }, undefined, (e) => { status.textContent = 'cannot load the scene: ' + e; });
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

playButton.onclick = () => {
  playing = !playing;
  playButton.textContent = playing ? 'Pause' : 'Play';
  if (action) action.paused = !playing;
};
slider.oninput = () => {
  if (!mixer) return;
  action.paused = false;  // a paused action ignores setTime
  mixer.setTime(Number(slider.value) * duration);
  action.paused = !playing;
  clockText.textContent = (Number(slider.value) * duration).toFixed(2) + ' s';
};
scaleInput.onchange = () => {
  fetch('/settings?scale=' + encodeURIComponent(scaleInput.value), { method: 'POST' });
};

function draw() {
  const dt = clock.getDelta();
  if (mixer && playing) mixer.update(dt);
  for (const node of framesOf) node.visible = node.scale.x !== 0;
  if (mixer && duration > 0) {
    const t = mixer.time % duration;
    if (playing) slider.value = String(t / duration);
    clockText.textContent = t.toFixed(2) + ' s';
  }
  controls.update();
  renderer.render(scene, camera);
}
renderer.setAnimationLoop(draw);
