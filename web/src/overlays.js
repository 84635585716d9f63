// What the page draws over the scene, each toggled from the bar: the tool and target frames, the
// planned path (the target's positions over the run) with the tool's trace, and the contacts —
// points and force arrows (recomputed from the recorded state: src/web/replay_overlays.cpp).
import * as THREE from 'three';

import {floats, uints} from './decode.js';

const MAX_ARROWS = 64;

function poseAt(array, frame, object) {
  const o = frame * 7;
  object.position.set(array[o], array[o + 1], array[o + 2]);
  object.quaternion.set(array[o + 4], array[o + 5], array[o + 6], array[o + 3]);
}

function pathLine(array, count, colour) {
  const points = new Float32Array(count * 3);
  for (let f = 0; f < count; ++f) points.set(array.subarray(f * 7, f * 7 + 3), f * 3);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
  return new THREE.Line(geometry, new THREE.LineBasicMaterial({color: colour}));
}

export function buildOverlays(data, scene) {
  const o = data.overlays || {};
  const frames = data.frames.time.length;
  const size = Math.max(0.05, 0.08 * data.extent);
  const groups = {frames: new THREE.Group(), path: new THREE.Group(), contacts: new THREE.Group()};
  for (const g of Object.values(groups)) scene.add(g);
  // base64 in a replay file; the live view hands arrays it refills with every frame
  const poses = (v) => (typeof v === 'string' ? floats(v) : v);
  const tool = o.tool ? poses(o.tool) : null;
  const target = o.target ? poses(o.target) : null;
  const toolAxes = new THREE.AxesHelper(size);
  const targetAxes = new THREE.AxesHelper(size * 0.7);
  targetAxes.material.transparent = true;
  targetAxes.material.opacity = 0.55;
  if (tool) groups.frames.add(toolAxes);
  if (target) groups.frames.add(targetAxes);
  if (target) groups.path.add(pathLine(target, frames, 0xff9900));
  if (tool) groups.path.add(pathLine(tool, frames, 0x33ccff));
  for (const g of Object.values(groups))
    g.traverse((c) => {
      c.renderOrder = 10;
      if (c.material) c.material.depthTest = false;
    });

  const offsets = o.contacts ? uints(o.contacts.offsets) : new Uint32Array(frames + 1);
  const points = o.contacts ? floats(o.contacts.points) : new Float32Array(0);
  const dots = new THREE.InstancedMesh(
      new THREE.SphereGeometry(size * 0.08, 10, 6),
      new THREE.MeshBasicMaterial({color: 0xff2266, depthTest: false}), MAX_ARROWS);
  dots.renderOrder = 11;
  groups.contacts.add(dots);
  const arrows = [];
  for (let i = 0; i < MAX_ARROWS; ++i) {
    const arrow =
        new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, 0xff2266);
    arrow.traverse((c) => {
      if (c.material) c.material.depthTest = false;
      c.renderOrder = 11;
    });
    arrow.visible = false;
    groups.contacts.add(arrow);
    arrows.push(arrow);
  }
  // 1 N of contact force is drawn this long: the largest force of the run spans a tenth of the
  // model
  let largest = 1e-9;
  for (let i = 0; i < points.length; i += 6)
    largest = Math.max(largest, Math.hypot(points[i + 3], points[i + 4], points[i + 5]));
  const metresPerNewton = (0.1 * data.extent) / largest;
  const matrix = new THREE.Matrix4();
  const direction = new THREE.Vector3();

  return {
    groups,
    axes: {tool: tool ? toolAxes : null, target: target ? targetAxes : null},
    contactCount: 0,
    available: {
      frames: Boolean(tool || target),
      path: Boolean(tool || target),
      contacts: Boolean(o.contacts)
    },
    update(frame) {
      if (tool) poseAt(tool, frame, toolAxes);
      if (target) poseAt(target, frame, targetAxes);
      const first = offsets[frame], last = Math.min(offsets[frame + 1], first + MAX_ARROWS);
      this.contactCount = offsets[frame + 1] - first;
      dots.count = last - first;
      for (let i = 0; i < MAX_ARROWS; ++i) {
        const c = first + i;
        const arrow = arrows[i];
        arrow.visible = c < last;
        if (!arrow.visible) continue;
        const p = points.subarray(c * 6, c * 6 + 6);
        matrix.makeTranslation(p[0], p[1], p[2]);
        dots.setMatrixAt(i, matrix);
        direction.set(p[3], p[4], p[5]);
        const length = direction.length() * metresPerNewton;
        arrow.visible = length > 1e-6;
        if (!arrow.visible) continue;
        arrow.position.set(p[0], p[1], p[2]);
        arrow.setDirection(direction.normalize());
        arrow.setLength(
            length, Math.min(0.3 * length, size * 0.25), Math.min(0.15 * length, size * 0.12));
      }
      dots.instanceMatrix.needsUpdate = true;
    },
  };
}
