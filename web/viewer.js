// The 3D view of the browser page and of fvrml-run --serve's preview (one copy for both; a
// classic script: a page opened from file:// may load no ES module): shows a glTF binary made by
// fvrml-run with three.js, plays its animation (our glTF's STEP animation of frame nodes) under a
// play button and a time slider, with the scene's viewpoint, lights and background (fvrml-run's
// view: --stats-file, or the preview's stats).
/* global THREE */
'use strict';

function FvrmlViewer(container, controlsOf) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  renderer.setClearColor(0xffffff);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
  camera.position.set(3, 2, 4);
  scene.add(camera);  // the headlight rides on it
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  const clock = new THREE.Clock();
  const { play, slider, clockText } = controlsOf;
  let lights = [], content = null, mixer = null, action = null, duration = 0, playing = true, framesOf = [];

  // The scene's lights, or a key light and a soft fill when it has none; its background colour.
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
    renderer.setClearColor(view ? new THREE.Color(...view.background) : new THREE.Color(0xffffff));
  }

  // The scene's Viewpoint (VRML97: position, then orientation as axis and angle), else a frame of
  // the shape's bounds.
  function viewpoint(view) {
    if (!view || !view.camera) return false;
    const c = view.camera;
    camera.position.set(...c.position);
    const axis = new THREE.Vector3(c.orientation[0], c.orientation[1], c.orientation[2]);
    camera.quaternion.setFromAxisAngle(axis.lengthSq() > 0 ? axis.normalize() : new THREE.Vector3(0, 0, 1), c.orientation[3]);
    camera.fov = THREE.Math.radToDeg(c.fieldOfView);
    camera.updateProjectionMatrix();
    const ahead = new THREE.Vector3(0, 0, -1).applyQuaternion(camera.quaternion);
    controls.target.copy(camera.position).addScaledVector(ahead, Math.max(1, camera.position.length()));
    controls.update();
    return true;
  }
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
  }

  function resize() {
    const w = container.clientWidth, h = container.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  resize();

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

  play.onclick = () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    if (action) action.paused = !playing;
    draw();
  };
  slider.oninput = () => {
    if (!mixer) return;
    action.paused = false;  // a paused action ignores setTime
    mixer.setTime(Number(slider.value) * duration);
    action.paused = !playing;
    clockText.textContent = (Number(slider.value) * duration).toFixed(2) + ' s';
    draw();
  };

  // Shows a .glb (an ArrayBuffer); `keepCamera` keeps the user's camera and the animation's time
  // (a new version of the same scene).
  this.show = (glb, view, keepCamera) => new Promise((resolve, reject) => {
    new THREE.GLTFLoader().parse(glb, '', (gltf) => {
      const time = keepCamera && mixer ? mixer.time : 0;  // the animation goes on where it was
      if (content) scene.remove(content);
      content = gltf.scene;
      content.traverse((o) => { if (o.isMesh && o.material) o.material.side = THREE.DoubleSide; });
      scene.add(content);
      mixer = null, action = null, duration = 0, framesOf = [];
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
        mixer.setTime(duration > 0 ? time % duration : 0);
        action.paused = !playing;
      }
      slider.disabled = play.disabled = !mixer;
      light(view);
      if (!keepCamera && !viewpoint(view)) frame(content);
      draw();  // now, not at the next animation frame: a headless screenshot never gets one
      resolve({ animated: !!mixer, duration });
    }, reject);
  });
  this.clear = () => {
    if (content) scene.remove(content);
    content = null, mixer = null, action = null, framesOf = [];
    slider.disabled = play.disabled = true;
    draw();
  };
}
