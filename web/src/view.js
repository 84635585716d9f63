// The 3D view the replay page and the live view share: the renderer (lighter on software GL),
// MuJoCo's free camera with orbit controls, and the model's cameras as presets.
import * as THREE from 'three';
import {OrbitControls} from 'three/addons/controls/OrbitControls.js';

import {poseTrackedCamera} from './scene.js';

export function element(tag, attributes = {}, parent = null) {
  const e = document.createElement(tag);
  Object.assign(e, attributes);
  if (parent) parent.appendChild(e);
  return e;
}

// True when WebGL runs on a software rasteriser.
function softwareGl() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return false;
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}

// The renderer in `container`, the free camera and the presets listed in the `cameraSelect`
// element; `bodies` are the scene's body groups (index = body id), `headlight` rides the camera.
export function createView(data, scene, bodies, headlight, container, cameraSelect) {
  // multisampling costs software GL (SwiftShader, llvmpipe: no GPU) more than a frame's budget
  const software = softwareGl();
  const renderer = new THREE.WebGLRenderer({antialias: !software});
  // at most 2 device pixels per CSS pixel: software GL fills every one of them
  const fullRatio = Math.min(window.devicePixelRatio || 1, 2);
  renderer.setPixelRatio(fullRatio);
  container.appendChild(renderer.domElement);
  const free =
      new THREE.PerspectiveCamera(45, 1, Math.max(data.extent * 0.01, 0.001), data.extent * 100);
  free.up.set(0, 0, 1);
  // MuJoCo's free camera: looking at the model's centre from 1.5 extents, azimuth 90°, elevation
  // −45°
  const centre = new THREE.Vector3().fromArray(data.center);
  const distance = 1.5 * data.extent;
  free.position.set(
      centre.x, centre.y - distance * Math.cos(Math.PI / 4),
      centre.z + distance * Math.sin(Math.PI / 4));
  free.lookAt(centre);
  free.add(headlight);
  scene.add(free);
  const controls = new OrbitControls(free, renderer.domElement);
  controls.target.copy(centre);
  controls.update();
  const presets = new THREE.PerspectiveCamera(45, 1, free.near, free.far);
  presets.add(headlight.clone());
  scene.add(presets);
  element('option', {value: -1, textContent: 'free camera'}, cameraSelect);
  data.cameras.forEach((c, i) => element('option', {value: i, textContent: c.name}, cameraSelect));

  const view = {
    renderer,
    software,
    fullRatio,
    free,
    cameraIndex: -1,
    orbited: false,  // the orbit moved the free camera since the last draw
    // the camera to draw with at time t: the free one, or the chosen preset at its body's pose
    // (a tracking or targeting camera at its pose of the frame, as MuJoCo computed it; the live
    // view has no such poses and draws it fixed to its body)
    camera(t) {
      if (view.cameraIndex < 0) return free;
      const c = data.cameras[view.cameraIndex];
      presets.fov = c.fovy;
      presets.updateProjectionMatrix();
      if (c.track >= 0 && data.camera_poses) {
        poseTrackedCamera(data, c.track, t, presets);
        return presets;
      }
      const parent = bodies[c.body];
      parent.updateMatrixWorld();
      const local = new THREE.Matrix4().compose(
          new THREE.Vector3().fromArray(c.pos),
          new THREE.Quaternion(c.quat[1], c.quat[2], c.quat[3], c.quat[0]),
          new THREE.Vector3(1, 1, 1));
      const world = parent.matrixWorld.clone().multiply(local);
      world.decompose(presets.position, presets.quaternion, presets.scale);
      return presets;
    },
    setCamera(index) {
      view.cameraIndex = index;
      cameraSelect.value = index;
      controls.enabled = index < 0;
    },
    resize() {
      const w = container.clientWidth, h = container.clientHeight;
      renderer.setSize(w, h, false);
      for (const cam of [free, presets]) {
        cam.aspect = w / Math.max(h, 1);
        cam.updateProjectionMatrix();
      }
    },
  };
  controls.addEventListener('change', () => {
    view.orbited = true;
  });
  return view;
}
