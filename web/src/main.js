// The page of a replay file (`mjarm replay-html`, docs/replay.md): the recorded run drawn with
// three.js, played back, and its state exposed to tests as window.mjarmReplay. The same script is
// the live view's page (`mjarm view --web`: live.js) when the page holds the live block instead.
import * as THREE from 'three';

import {readReplayData} from './decode.js';
import {startLive} from './live.js';
import {buildOverlays} from './overlays.js';
import {buildPlots} from './plots.js';
import {buildScene, poseBodies} from './scene.js';
import {STYLE} from './style.js';
import {createView, element} from './view.js';

function layout() {
  element('style', {textContent: STYLE}, document.head);
  const root = element('div', {id: 'mjarm-root'}, document.body);
  const main = element('div', {id: 'mjarm-main'}, root);
  const view = element('div', {id: 'mjarm-view'}, main);
  const title = element('div', {id: 'mjarm-title'}, view);
  // what the file says of itself: a decimated run, meshes drawn as boxes (docs/replay.md)
  const notes = element('div', {id: 'mjarm-notes'}, view);
  const plots = element('div', {id: 'mjarm-plots'}, main);
  const phases = element('div', {id: 'mjarm-phases'}, root);
  const bar = element('div', {id: 'mjarm-bar'}, root);
  const play = element('button', {textContent: 'play', title: 'play / pause (space)'}, bar);
  const back = element('button', {textContent: '◀|', title: 'previous frame (←)'}, bar);
  const step = element('button', {textContent: '|▶', title: 'next frame (→)'}, bar);
  const speed = element('select', {title: 'playback speed'}, bar);
  for (const s of [0.1, 0.25, 0.5, 1, 2, 4])
    element('option', {value: s, textContent: `${s}×`, selected: s === 1}, speed);
  const scrub = element(
      'input', {id: 'mjarm-scrub', type: 'range', min: 0, max: 1, step: 'any', value: 0}, bar);
  const time = element('span', {id: 'mjarm-time'}, bar);
  const camera = element('select', {title: 'camera'}, bar);
  const plotToggle = element('button', {textContent: 'plots', title: 'show / hide the plots'}, bar);
  const toggles = {};
  for (const [name, title] of [
           ['frames', 'the tool frame and the target frame'],
           ['path', 'the planned path (the target over the run) and the tool\'s trace'],
           ['contacts', 'contact points and force arrows'],
  ]) {
    const label = element('label', {title}, bar);
    toggles[name] = element('input', {type: 'checkbox', checked: true}, label);
    label.append(` ${name}`);
  }
  return {
    view,
    title,
    notes,
    plots,
    phases,
    play,
    back,
    step,
    speed,
    scrub,
    time,
    camera,
    plotToggle,
    toggles
  };
}

async function start() {
  const data = await readReplayData('mjarm-replay-data');
  const ui = layout();
  const {scene, bodies, meshCount, skipped, headlight, sky} = buildScene(data);
  const background = scene.background;
  const overlays = buildOverlays(data, scene);
  const view = createView(data, scene, bodies, headlight, ui.view, ui.camera);
  const {renderer, software, fullRatio, free} = view;

  const frames = data.frames.time;
  const t0 = frames[0], t1 = frames[frames.length - 1];
  let t = t0, playing = false, speed = 1, lastClock = null, frame = 0, renders = 0;
  ui.scrub.min = t0;
  ui.scrub.max = t1;
  ui.title.textContent =
      `${data.title} — ${data.model} — ${frames.length} frames at ${data.rate} Hz`;
  const notes = [data.decimation ?? '', ...(data.warnings ?? [])].filter((n) => n !== '');
  for (const note of notes) element('div', {textContent: note}, ui.notes);
  // grasp and other events as marks under the phases, their message on hover
  for (const event of data.events.filter((e) => e.kind !== 'phase')) {
    element(
        'i', {
          className: `mjarm-event mjarm-${event.kind}`,
          title: `${event.kind} at ${event.t.toFixed(3)} s: ${event.message}`,
          style: `left:${(100 * (event.t - t0)) / Math.max(t1 - t0, 1e-9)}%`
        },
        ui.phases);
  }
  for (const event of data.events.filter((e) => e.kind === 'phase')) {
    element(
        'span', {
          textContent: event.message,
          title: `${event.message} at ${event.t.toFixed(3)} s`,
          style: `left:${(100 * (event.t - t0)) / Math.max(t1 - t0, 1e-9)}%`
        },
        ui.phases);
  }
  const plots = buildPlots(data, ui.plots, (time) => seek(time));

  const resize = view.resize;

  let lastPanel = 0;
  function draw() {
    frame = poseBodies(data, bodies, t);
    overlays.update(frame);
    renderer.render(scene, view.camera(t));
    ++renders;
    // the bar and the plots' cursors at most 15 times a second while playing: each change of the
    // page is painted again, which software GL pays for as much as the 3D view
    const now = performance.now();
    if (!playing || now - lastPanel > 66) {
      lastPanel = now;
      ui.scrub.value = t;
      ui.time.textContent = `${t.toFixed(3)} / ${t1.toFixed(3)} s  #${frame}`;
      plots.cursor(t);
    }
  }

  function seek(time) {
    t = Math.min(Math.max(time, t0), t1);
    draw();
    return t;
  }

  function setPlaying(on) {
    playing = on && t < t1;
    lastClock = null;
    ui.play.textContent = playing ? 'pause' : 'play';
    // software GL fills pixels slowly: while playing it draws a quarter of them (half in each
    // direction); paused, seeking or stepping, the view is sharp again
    if (software) {
      renderer.setPixelRatio(playing ? playRatio : fullRatio);
      resize();
      draw();
    }
  }

  // software GL: while playing, the resolution steps down (to a quarter in each direction at
  // most) as long as frames come slower than 60 per second
  let playRatio = 0.5 * fullRatio, slowFrames = 0;
  function adaptResolution(interval) {
    slowFrames = interval > 1000 / 55 ? slowFrames + 1 : 0;
    if (slowFrames < 10 || playRatio <= 0.25 * fullRatio) return;
    slowFrames = 0;
    playRatio = Math.max(0.25 * fullRatio, 0.8 * playRatio);
    renderer.setPixelRatio(playRatio);
    resize();
  }

  function loop(clock) {
    if (playing) {
      if (lastClock !== null) {
        t += ((clock - lastClock) / 1000) * speed;
        if (software) adaptResolution(clock - lastClock);
      }
      lastClock = clock;
      if (t >= t1) {
        t = t1;
        setPlaying(false);
      }
      draw();
    } else if (view.orbited && view.cameraIndex < 0) {
      view.orbited = false;
      renderer.render(scene, free);
    }
    requestAnimationFrame(loop);
  }

  ui.play.onclick = () => setPlaying(!playing);
  ui.step.onclick = () => {
    setPlaying(false);
    seek(frames[Math.min(frame + 1, frames.length - 1)]);
  };
  ui.back.onclick = () => {
    setPlaying(false);
    seek(frames[Math.max(frame - (t > frames[frame] ? 0 : 1), 0)]);
  };
  ui.speed.onchange = () => {
    speed = Number(ui.speed.value);
  };
  ui.scrub.oninput = () => seek(Number(ui.scrub.value));
  ui.camera.onchange = () => {
    view.setCamera(Number(ui.camera.value));
    draw();
  };
  for (const [name, box] of Object.entries(ui.toggles)) {
    box.disabled = !overlays.available[name];
    box.checked = overlays.available[name];
    overlays.groups[name].visible = box.checked;
    box.onchange = () => {
      overlays.groups[name].visible = box.checked;
      draw();
    };
  }
  ui.plotToggle.onclick = () => {
    ui.plots.classList.toggle('hidden');
    resize();
    draw();
  };
  window.addEventListener('keydown', (e) => {
    if (e.key === ' ') {
      setPlaying(!playing);
      e.preventDefault();
    }
    if (e.key === 'ArrowRight') ui.step.onclick();
    if (e.key === 'ArrowLeft') ui.back.onclick();
  });
  window.addEventListener('resize', () => {
    resize();
    draw();
  });
  resize();
  seek(t0);
  requestAnimationFrame(loop);

  // what tests read back (tests/web): the state of the page, and a way to drive it
  window.mjarmReplay = {
    ready: true,
    meshCount,
    skybox: sky !== null,
    textureCount: data.textures.length,
    hfieldCount: data.geoms.filter((g) => g.type === 'hfield').length,
    // the pose of the camera drawn now (the free camera or the chosen preset)
    cameraPose: () => {
      const cam = view.camera(t);
      cam.updateMatrixWorld();
      const q = cam.quaternion;
      return {pos: cam.position.toArray(), quat: [q.w, q.x, q.y, q.z]};
    },
    skippedGeoms: skipped,
    notes,
    softwareGl: software,
    // milliseconds to pose and draw one frame, the GPU (or software GL) waited for: n frames
    // across the run (a figure for docs/replay.md; the browser's compositing is not counted)
    drawCost: (n) => {
      const gl = renderer.getContext();
      const pixel = new Uint8Array(4);
      const start = performance.now();
      for (let i = 0; i < n; ++i) {
        seek(t0 + ((t1 - t0) * i) / Math.max(n - 1, 1));
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);  // waits for the frame
      }
      return (performance.now() - start) / n;
    },
    frameCount: frames.length,
    startTime: t0,
    endTime: t1,
    cameras: data.cameras.map((c) => c.name),
    bodies: data.bodies.map((b) => b.name),
    freeJoints: data.free_joints,
    contactCount: () => overlays.contactCount,
    setOverlay: (name, on) => {
      ui.toggles[name].checked = on;
      overlays.groups[name].visible = on;
      draw();
    },
    eventMarks: () => ui.phases.querySelectorAll('.mjarm-event').length,
    joints: data.joints.map((j) => ({name: j.name, body: data.bodies[j.body].name})),
    frameTimes: () => Array.from(frames),
    time: () => t,
    frame: () => frame,
    renders: () => renders,
    seek,
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    playing: () => playing,
    setSpeed: (s) => {
      speed = s;
    },
    setCamera: (name) => {
      view.setCamera(name === null ? -1 : data.cameras.findIndex((c) => c.name === name));
      draw();
      return view.cameraIndex;
    },
    // the 3D view at a size of CSS pixels (null: back to the layout's), for pictures to compare
    setViewSize: (width, height) => {
      ui.view.style.flex = width ? 'none' : '';
      ui.view.style.width = width ? `${width}px` : '';
      ui.view.style.height = height ? `${height}px` : '';
      resize();
      draw();
      const r = ui.view.getBoundingClientRect();
      return {x: r.left, y: r.top, width: r.width, height: r.height};
    },
    // only the subtree of body `root` (it and its descendants) in flat white on black (null:
    // the scene again), for a silhouette to compare with mjarm's own rendering (tests/web)
    silhouette: (root) => {
      const top = data.bodies.findIndex((b) => b.name === root);
      const inside = (id) => {
        while (id > 0 && id !== top) id = data.bodies[id].parent;
        return id === top;
      };
      const white = new THREE.MeshBasicMaterial({color: 0xffffff});
      scene.background = root === null ? background : new THREE.Color(0, 0, 0);
      if (sky) sky.visible = root === null;
      ui.title.style.display = root === null ? '' : 'none';
      ui.notes.style.display = ui.title.style.display;
      for (const [name, group] of Object.entries(overlays.groups))
        group.visible = root === null && ui.toggles[name].checked;
      bodies.forEach((body, id) => {
        for (const mesh of body.children) {
          if (!mesh.userData.mjarmGeom) continue;
          mesh.userData.material ??= mesh.material;
          mesh.material = root === null ? mesh.userData.material : white;
          mesh.visible = root === null || inside(id);
        }
      });
      draw();
      return top;
    },
    showPlots: (on) => {
      ui.plots.classList.toggle('hidden', !on);
      resize();
      draw();
    },
    bodyPose: (name) => {
      const b = bodies.find((g) => g.name === name);
      if (!b) return null;
      return {
        pos: b.position.toArray(),
        quat: [b.quaternion.w, b.quaternion.x, b.quaternion.y, b.quaternion.z]
      };
    },
  };
}

const live = document.getElementById('mjarm-live') !== null;
(live ? startLive() : start()).catch((error) => {
  document.body.textContent = `mjarm ${live ? 'live view' : 'replay'}: ${error.message}`;
  throw error;
});
