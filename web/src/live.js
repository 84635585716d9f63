// The live view (`mjarm view --web`, the passive viewer's web form; docs/viewer.md "In a
// browser"): the replay page's scene built from the server's greeting (the model as a replay file
// describes it), its bodies posed from the binary frames streamed over the WebSocket, the
// viewer's sliders and modes in a panel, each move sent back. Playback has no meaning here: no
// scrub, speed or plots. Its state is exposed to tests as window.mjarmLive.
import {decodeScene} from './decode.js';
import {buildOverlays} from './overlays.js';
import {buildScene, poseBodies} from './scene.js';
import {LIVE_STYLE, STYLE} from './style.js';
import {createView, element} from './view.js';

function layout() {
  element('style', {textContent: STYLE + LIVE_STYLE}, document.head);
  const root = element('div', {id: 'mjarm-root'}, document.body);
  const main = element('div', {id: 'mjarm-main'}, root);
  const view = element('div', {id: 'mjarm-view'}, main);
  const title = element('div', {id: 'mjarm-title', textContent: 'mjarm live view'}, view);
  const panel = element('div', {id: 'mjarm-panel'}, main);
  const link = element('div', {id: 'mjarm-link', textContent: 'connecting…'}, panel);
  const sliders = element('div', {id: 'mjarm-sliders'}, panel);
  const modeLabel = element('label', {textContent: 'mode '}, panel);
  const mode = element('select', {id: 'mjarm-mode'}, modeLabel);
  const reset = element('button', {id: 'mjarm-reset', textContent: 'reset'}, panel);
  const status = element('div', {id: 'mjarm-status'}, panel);
  element('p', {textContent: 'Drag to turn the view, right-drag to pan, scroll to zoom.'}, panel);
  const bar = element('div', {id: 'mjarm-bar'}, root);
  const camera = element('select', {title: 'camera'}, bar);
  const label = element('label', {title: 'the tool frame and the target frame'}, bar);
  const frames = element('input', {type: 'checkbox', checked: true}, label);
  label.append(' frames');
  const time = element('span', {id: 'mjarm-time'}, bar);
  return {view, title, link, sliders, modeLabel, mode, reset, status, camera, frames, time};
}

// The viewer's panel from the greeting: a slider per value, the modes, reset; `send` takes each
// move. A greeting without sliders (the passive viewer: watched, not steered) shows none.
function buildPanel(greeting, ui, send, sendNow) {
  ui.sliders.textContent = '';
  for (const s of greeting.sliders) {
    const label = element('label', {}, ui.sliders);
    const shown = element('span', {className: 'value', textContent: s.value.toFixed(3)});
    const input = element('input', {
      type: 'range',
      id: `slider-${s.name}`,
      min: s.lower,
      max: s.upper,
      step: (s.upper - s.lower) / 1000,
      value: s.value
    });
    input.oninput = () => {
      shown.textContent = Number(input.value).toFixed(3);
      send(s.name, Number(input.value));
    };
    label.append(s.name, shown, input);
  }
  const steered = greeting.sliders.length > 0;
  // display, not the hidden attribute: the panel's style shows every label as a block
  ui.modeLabel.style.display = steered ? '' : 'none';
  ui.reset.style.display = steered ? '' : 'none';
  ui.mode.textContent = '';
  for (const m of greeting.modes)
    element('option', {value: m, textContent: m, selected: m === greeting.mode}, ui.mode);
  ui.mode.onchange = () => send('mode', ui.mode.value);
  ui.reset.onclick = () => sendNow({reset: true});
}

const vector = (f, at) => Array.from(f.subarray(at, at + 3), (v) => v.toFixed(3)).join(' ');

export async function startLive() {
  const ui = layout();
  const live = window.mjarmLive = {
    ready: false,
    connected: false,
    greeting: null,  // the greeting without the model's arrays
    frames: 0,       // frames received
    renders: 0,
  };
  const socket = new WebSocket(
      `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws${location.search}`);
  socket.binaryType = 'arraybuffer';
  // slider moves leave at most 30 times a second each: the newest value of each name
  const pending = new Map();
  const send = (name, value) => pending.set(name, value);
  const sendNow = (message) => {
    if (socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(message));
  };
  setInterval(() => {
    for (const [name, value] of pending) sendNow({set: name, value});
    pending.clear();
  }, 33);

  let view = null;  // the 3D view, once the greeting built it
  socket.onopen = () => {
    live.connected = true;
    ui.link.textContent = 'connected';
    ui.link.className = '';
  };
  socket.onclose = () => {
    live.connected = false;
    ui.link.textContent = 'disconnected (reload to connect again)';
    ui.link.className = 'down';
  };
  let building = false;  // the greeting's textures are being inflated: frames wait for the view
  socket.onmessage = async (event) => {
    if (typeof event.data === 'string') {
      const greeting = JSON.parse(event.data);
      try {
        if (!view && !building) {
          building = true;
          view = buildView(await decodeScene(greeting), ui, live);
        }
      } catch (error) {
        document.body.textContent = `mjarm live view: ${error.message}`;
        throw error;
      }
      buildPanel(greeting, ui, send, sendNow);
      live.greeting = {
        model: greeting.model,
        frame: greeting.frame,
        sliders: greeting.sliders,
        mode: greeting.mode,
        modes: greeting.modes,
        drawnGeoms: greeting.geoms.length,
      };
      return;
    }
    if (!view) return;  // the server sends the greeting first
    view.receive(new Float32Array(event.data));
  };
}

// The scene of the greeting `data`, drawn again whenever a frame came or the orbit moved.
function buildView(data, ui, live) {
  ui.title.textContent = `${data.model} — live`;
  const layout = data.frame;
  const nb = data.bodies.length;
  if (layout.bodies !== nb)
    throw new Error(`the frames hold ${layout.bodies} bodies, the model ${nb}`);
  // the newest frame as a replay of one frame (scene.js poses from it), the overlays' poses
  // refilled from it
  data.frames = {
    time: new Float32Array(1),
    pos: new Float32Array(3 * nb),
    quat: new Float32Array(4 * nb)
  };
  const panel = layout.tool !== undefined;
  data.overlays = panel ? {tool: new Float32Array(7), target: new Float32Array(7)} : {};
  const {scene, bodies, meshCount, skipped, headlight} = buildScene(data);
  const overlays = buildOverlays(data, scene);
  overlays.groups.path.visible = false;  // a path of one frame: none
  overlays.groups.frames.visible = ui.frames.checked = panel;
  ui.frames.disabled = !panel;
  ui.frames.onchange = () => {
    overlays.groups.frames.visible = ui.frames.checked;
    dirty = true;
  };
  const view = createView(data, scene, bodies, headlight, ui.view, ui.camera);
  ui.camera.onchange = () => {
    view.setCamera(Number(ui.camera.value));
    dirty = true;
  };
  let dirty = true, drawn = null, newest = null;

  function draw() {
    poseBodies(data, bodies, data.frames.time[0]);
    overlays.update(0);
    view.renderer.render(scene, view.camera());
    ++live.renders;
    drawn = newest;
    const f = newest;
    ui.time.textContent = `t ${f[layout.time].toFixed(3)} s`;
    ui.status.textContent = panel ?
        `end effector ${vector(f, layout.tool)}\ntarget       ${vector(f, layout.target)}\n` +
            `gripper ${f[layout.gripper].toFixed(2)}` :
        '';
  }

  function loop() {
    // nothing to pose before the first frame (the passive form's loop may not have synced yet)
    if (newest && (dirty || view.orbited)) {
      dirty = view.orbited = false;
      draw();
    }
    requestAnimationFrame(loop);
  }
  window.addEventListener('resize', () => {
    view.resize();
    dirty = true;
  });
  view.resize();
  requestAnimationFrame(loop);

  Object.assign(live, {
    ready: true,
    meshCount,
    skippedGeoms: skipped,
    bodies: data.bodies.map((b) => b.name),
    // the newest frame received, and the frame the view shows now, as numbers
    last: () => (newest ? Array.from(newest) : null),
    drawn: () => (drawn ? Array.from(drawn) : null),
    // every body's pose as the view holds it: [x y z], [w x y z]
    bodyPoses: () =>
        bodies.map((b) => ({
                     name: b.name,
                     pos: b.position.toArray(),
                     quat: [b.quaternion.w, b.quaternion.x, b.quaternion.y, b.quaternion.z]
                   })),
    // the tool and target frames as drawn (null without the viewer's panel)
    overlayPositions: () => ({
      tool: overlays.axes.tool?.position.toArray() ?? null,
      target: overlays.axes.target?.position.toArray() ?? null
    }),
    setCamera: (name) => {
      view.setCamera(name === null ? -1 : data.cameras.findIndex((c) => c.name === name));
      dirty = true;
      return view.cameraIndex;
    },
  });

  return {
    receive(f) {
      if (f.length !== layout.floats) {
        console.error(
            `mjarm live view: a frame of ${f.length} floats, the greeting said ${layout.floats}`);
        return;
      }
      newest = f;
      data.frames.time[0] = f[layout.time];
      data.frames.pos.set(f.subarray(layout.pos, layout.pos + 3 * nb));
      data.frames.quat.set(f.subarray(layout.quat, layout.quat + 4 * nb));
      if (panel) {
        data.overlays.tool.set(f.subarray(layout.tool, layout.tool + 7));
        data.overlays.target.set(f.subarray(layout.target, layout.target + 7));
      }
      ++live.frames;
      dirty = true;
    },
  };
}
