// The model drawn with three.js from its exported geoms: MuJoCo's coordinates kept (z up), each
// body a group posed per frame, each drawn geom a mesh in its body at the geom's local pose.
import * as THREE from 'three';

const ZUP_FROM_YUP =
    new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), Math.PI / 2);

function primitiveGeometry(geom, data) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case 'plane': {
      // MuJoCo draws a plane of size 0 as infinite: here, as wide as the model's extent allows
      const wide = Math.max(data.extent * 4, 2);
      return new THREE.PlaneGeometry(2 * (a > 0 ? a : wide), 2 * (b > 0 ? b : wide));
    }
    case 'sphere':
      return new THREE.SphereGeometry(a, 32, 16);
    case 'ellipsoid':
      return new THREE.SphereGeometry(1, 32, 16).scale(a, b, c);
    case 'capsule':
      // three's capsule and cylinder run along y, MuJoCo's along z
      return new THREE.CapsuleGeometry(a, 2 * b, 8, 24).applyQuaternion(ZUP_FROM_YUP);
    case 'cylinder':
      return new THREE.CylinderGeometry(a, a, 2 * b, 32).applyQuaternion(ZUP_FROM_YUP);
    case 'box':
      return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    case 'mesh': {
      const mesh = data.meshes[geom.mesh];
      const geometry = new THREE.BufferGeometry();
      // faces unshared so that every triangle keeps its own normal, as MuJoCo shades a mesh
      geometry.setAttribute('position', new THREE.BufferAttribute(mesh.vert, 3));
      geometry.setIndex(new THREE.BufferAttribute(mesh.face, 1));
      const flat = geometry.toNonIndexed();
      flat.computeVertexNormals();
      return flat;
    }
    default:
      return null;
  }
}

// A plane's texture, repeated as MuJoCo does: texrepeat times over the plane, or per metre when
// the material is texuniform (the texture modulated by the colour, as MuJoCo draws it).
function planeTexture(geom, data, geometry) {
  if (geom.texture < 0) return null;
  const t = data.textures[geom.texture];
  const texture = new THREE.DataTexture(t.rgba, t.width, t.height, THREE.RGBAFormat);
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.magFilter = THREE.LinearFilter;
  texture.minFilter = THREE.LinearMipmapLinearFilter;
  texture.generateMipmaps = true;
  const {width, height} = geometry.parameters;
  const [u, v] = geom.texrepeat;
  texture.repeat.set(geom.texuniform ? u * width : u, geom.texuniform ? v * height : v);
  texture.needsUpdate = true;
  return texture;
}

function material(geom, data, geometry) {
  const [r, g, b, alpha] = geom.rgba;
  return new THREE.MeshPhongMaterial({
    map: geom.type === 'plane' ? planeTexture(geom, data, geometry) : null,
    color: new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace),
    emissive: new THREE.Color().setRGB(
        r * geom.emission, g * geom.emission, b * geom.emission, THREE.SRGBColorSpace),
    specular: new THREE.Color(geom.specular, geom.specular, geom.specular),
    shininess: Math.max(1, geom.shininess * 128),
    transparent: alpha < 1,
    opacity: alpha,
    side: geom.type === 'plane' ? THREE.DoubleSide : THREE.FrontSide,
  });
}

// The scene: the body groups (index = MuJoCo body id) and the number of drawn meshes.
export function buildScene(data) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0.12, 0.14, 0.17);
  scene.add(new THREE.AmbientLight(0xffffff, 0.9));
  const bodies = data.bodies.map((body) => {
    const group = new THREE.Group();
    group.name = body.name;
    scene.add(group);
    return group;
  });
  let meshCount = 0;
  const skipped = [];
  for (const geom of data.geoms) {
    const geometry = primitiveGeometry(geom, data);
    if (!geometry) {
      skipped.push(geom.type);
      continue;
    }
    const mesh = new THREE.Mesh(geometry, material(geom, data, geometry));
    mesh.name = geom.name;
    mesh.position.fromArray(geom.pos);
    mesh.quaternion.set(geom.quat[1], geom.quat[2], geom.quat[3], geom.quat[0]);
    mesh.userData.mjarmGeom = true;
    bodies[geom.body].add(mesh);
    ++meshCount;
  }
  const headlight = new THREE.DirectionalLight(0xffffff, 1.6);
  const fill = new THREE.DirectionalLight(0xffffff, 0.6);
  fill.position.set(1, -1, 2);
  scene.add(fill);
  return {scene, bodies, meshCount, skipped, headlight};
}

// Poses every body at time t: the frames either side, positions mixed linearly, orientations
// by spherical interpolation (the recording is decimated: docs/replay.md).
export function poseBodies(data, bodies, t) {
  const {time, pos, quat} = data.frames;
  const n = time.length;
  let k = 0;
  if (t >= time[n - 1]) {
    k = n - 1;
  } else if (t > time[0]) {
    let lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (time[mid] <= t)
        lo = mid;
      else
        hi = mid;
    }
    k = lo;
  }
  const next = Math.min(k + 1, n - 1);
  const span = time[next] - time[k];
  const w = span > 0 ? Math.min(Math.max((t - time[k]) / span, 0), 1) : 0;
  const nb = bodies.length;
  const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
  for (let b = 0; b < nb; ++b) {
    const p0 = (k * nb + b) * 3, p1 = (next * nb + b) * 3;
    const q0 = (k * nb + b) * 4, q1 = (next * nb + b) * 4;
    bodies[b].position.set(
        pos[p0] + w * (pos[p1] - pos[p0]), pos[p0 + 1] + w * (pos[p1 + 1] - pos[p0 + 1]),
        pos[p0 + 2] + w * (pos[p1 + 2] - pos[p0 + 2]));
    qa.set(quat[q0 + 1], quat[q0 + 2], quat[q0 + 3], quat[q0]);
    qb.set(quat[q1 + 1], quat[q1 + 2], quat[q1 + 3], quat[q1]);
    bodies[b].quaternion.slerpQuaternions(qa, qb, w);
  }
  return k;
}
