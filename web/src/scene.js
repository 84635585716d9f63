// The model drawn with three.js from its exported geoms: MuJoCo's coordinates kept (z up), each
// body a group posed per frame, each drawn geom a mesh in its body at the geom's local pose.
import * as THREE from 'three';

const ZUP_FROM_YUP =
    new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), Math.PI / 2);

// Notes where three's texture u (its longitude, continuous across its seam) stands from MuJoCo's
// longitude (from +x, counter-clockwise about z), once the geometry is turned z up.
function longitudes(geometry, shift) {
  geometry.userData.uvShift = shift;
  return geometry;
}

function primitiveGeometry(geom, data) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case 'plane': {
      // MuJoCo draws a plane of size 0 as infinite: here, as wide as the model's extent allows
      const wide = Math.max(data.extent * 4, 2);
      return new THREE.PlaneGeometry(2 * (a > 0 ? a : wide), 2 * (b > 0 ? b : wide));
    }
    // three's sphere has its poles on y, MuJoCo's on z (its texture's colatitude runs from +z)
    case 'sphere':
      return longitudes(new THREE.SphereGeometry(a, 32, 16).applyQuaternion(ZUP_FROM_YUP), 0.5);
    case 'ellipsoid':
      return longitudes(
          new THREE.SphereGeometry(1, 32, 16).applyQuaternion(ZUP_FROM_YUP).scale(a, b, c), 0.5);
    case 'capsule':
      // three's capsule and cylinder run along y, MuJoCo's along z
      return longitudes(
          new THREE.CapsuleGeometry(a, 2 * b, 8, 24).applyQuaternion(ZUP_FROM_YUP), 0.5);
    case 'cylinder':
      return longitudes(
          new THREE.CylinderGeometry(a, a, 2 * b, 32).applyQuaternion(ZUP_FROM_YUP), -0.25);
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
      // per face corner, in the order toNonIndexed keeps
      if (mesh.texcoord) flat.setAttribute('uv', new THREE.BufferAttribute(mesh.texcoord, 2));
      return flat;
    }
    case 'hfield':
      return geom.hfield >= 0 ? hfieldGeometry(data.hfields[geom.hfield]) : null;
    default:
      return null;
  }
}

// A height field as MuJoCo draws it (mjr_uploadHField): the grid's vertex (row r, column c) at
// x = sx (2c/(ncol−1) − 1), y = sy (2r/(nrow−1) − 1), z = elevation · sz; sides down to the base
// at −base; a flat bottom; every triangle its own normal.
function hfieldGeometry(hfield) {
  const {nrow, ncol, data} = hfield;
  const [sx, sy, sz, base] = hfield.size;
  const x = (c) => sx * ((2 * c) / (ncol - 1) - 1);
  const y = (r) => sy * ((2 * r) / (nrow - 1) - 1);
  const z = (r, c) => data[r * ncol + c] * sz;
  const v = [];
  const quad = (a, b, c, d) => v.push(...a, ...b, ...c, ...a, ...c, ...d);  // counter-clockwise
  for (let r = 0; r + 1 < nrow; ++r) {
    for (let c = 0; c + 1 < ncol; ++c) {
      quad(
          [x(c), y(r), z(r, c)], [x(c + 1), y(r), z(r, c + 1)],
          [x(c + 1), y(r + 1), z(r + 1, c + 1)], [x(c), y(r + 1), z(r + 1, c)]);
    }
  }
  for (let r = 0; r + 1 < nrow; ++r) {
    quad(
        [-sx, y(r + 1), -base], [-sx, y(r), -base], [-sx, y(r), z(r, 0)],
        [-sx, y(r + 1), z(r + 1, 0)]);
    quad(
        [sx, y(r), -base], [sx, y(r + 1), -base], [sx, y(r + 1), z(r + 1, ncol - 1)],
        [sx, y(r), z(r, ncol - 1)]);
  }
  for (let c = 0; c + 1 < ncol; ++c) {
    quad(
        [x(c), -sy, -base], [x(c + 1), -sy, -base], [x(c + 1), -sy, z(0, c + 1)],
        [x(c), -sy, z(0, c)]);
    quad(
        [x(c + 1), sy, -base], [x(c), sy, -base], [x(c), sy, z(nrow - 1, c)],
        [x(c + 1), sy, z(nrow - 1, c + 1)]);
  }
  quad([-sx, -sy, -base], [-sx, sy, -base], [sx, sy, -base], [sx, -sy, -base]);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(v), 3));
  geometry.computeVertexNormals();
  return geometry;
}

// The size MuJoCo's renderer scales a primitive by (mjv_initGeom): a sphere (r, r, r), a capsule
// or a cylinder (r, r, half-length); planes, meshes and height fields are drawn at their own size
const PRIMITIVES = new Set(['sphere', 'capsule', 'ellipsoid', 'cylinder', 'box']);
function drawnSize(geom) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case 'sphere':
      return [a, a, a];
    case 'capsule':
    case 'cylinder':
      return [a, a, b];
    default:
      return [a, b, c];
  }
}

// A 2D texture's coordinates as MuJoCo 4 draws them, each with the material's scale: texrepeat,
// times the geom's first two sizes when texuniform (measured against mjarm's EGL rendering, see
// docs/replay.md). A plane's (and a height field's) from the position, s = ½·rx·x − ½,
// t = −½·ry·y − ½ (render_gl3.c's planar mapping); a mesh's own coordinates; a box's per face, the
// face's first in-plane axis (x, else y) across and its second (y, else z) down, 0 … 1 over the
// face; a sphere's or an ellipsoid's longitude (from +x) and colatitude (from +z) over 2π and π; a
// cylinder's longitude and height (0 at the top) on its side and x, y over its caps.
function mujocoUv(geometry, geom) {
  const size = drawnSize(geom);
  const [rx, ry] = geom.texrepeat;
  const pos = geometry.getAttribute('position');
  const own = geometry.getAttribute('uv');
  const normal = geometry.getAttribute('normal');
  const uv = new Float32Array(2 * pos.count);
  let su = rx, sv = ry;  // the material's scale of (u, v) in 0 … 1
  if (geom.texuniform) {
    su *= size[0] > 0 ? size[0] : 1;
    sv *= size[1] > 0 ? size[1] : 1;
  }
  for (let i = 0; i < pos.count; ++i) {
    const x = pos.getX(i), y = pos.getY(i), z = pos.getZ(i);
    let u = 0, v = 0;
    switch (geom.type) {
      case 'mesh':
        if (own) {
          u = su * own.getX(i);
          v = sv * own.getY(i);
        }
        break;
      case 'box': {
        const nx = Math.abs(normal.getX(i)), nz = Math.abs(normal.getZ(i));
        const [a, b] = nz > 0.5 ? [x / size[0], y / size[1]] :
            nx > 0.5            ? [y / size[1], z / size[2]] :
                                  [x / size[0], z / size[2]];
        u = su * 0.5 * (a + 1);
        v = sv * 0.5 * (1 - b);
        break;
      }
      case 'sphere':
      case 'ellipsoid':
      case 'capsule': {
        // three's own longitude (continuous across its seam) turned to MuJoCo's: the geometry is
        // three's turned from y up to z up (capsule) or taken as it is with its poles on ±z
        u = su * (own.getX(i) + geometry.userData.uvShift);
        v = sv * (1 - own.getY(i));
        break;
      }
      case 'cylinder': {
        if (Math.abs(normal.getZ(i)) > 0.5) {  // a cap
          u = su * 0.5 * (x / size[0] + 1);
          v = sv * 0.5 * (1 + y / size[1]);
        } else {
          u = su * (own.getX(i) + geometry.userData.uvShift);
          v = sv * 0.5 * (1 - z / size[2]);
        }
        break;
      }
      default: {  // plane, height field: planar (a height field's over its size, texuniform or not)
        const perMetre = geom.texuniform && geom.type === 'plane';
        u = (0.5 * rx * x) / (perMetre || !(size[0] > 0) ? 1 : size[0]) - 0.5;
        v = (-0.5 * ry * y) / (perMetre || !(size[1] > 0) ? 1 : size[1]) - 0.5;
      }
    }
    uv[2 * i] = u;
    uv[2 * i + 1] = v;
  }
  geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
}

// A cube texture's lookup direction as MuJoCo generates it: the vertex's position in the geom's
// unit object (a primitive's position over its size; a mesh's, plane's or height field's own),
// times the size when texuniform.
function mujocoCubeDirection(geometry, geom) {
  const size = drawnSize(geom).map((s) => (s > 0 ? s : 1));
  const primitive = PRIMITIVES.has(geom.type);
  const pos = geometry.getAttribute('position');
  const dir = new Float32Array(3 * pos.count);
  for (let i = 0; i < pos.count; ++i) {
    for (let k = 0; k < 3; ++k) {
      const p = pos.getComponent(i, k);
      const object = primitive ? p / size[k] : p;
      dir[3 * i + k] = geom.texuniform ? object * size[k] : object;
    }
  }
  geometry.setAttribute('mjcube', new THREE.BufferAttribute(dir, 3));
}

// The model's textures for three.js, each uploaded once: a 2D texture repeated, a cube (or a
// skybox's) as six faces — MuJoCo's order +x −x +y −y +z −z, stacked, or one face repeated —
// uploaded as OpenGL takes them (no flip).
function makeTextures(data) {
  // both kinds are sampled alike: trilinear, mipmapped, sRGB
  const sampled = (texture) => {
    texture.magFilter = THREE.LinearFilter;
    texture.minFilter = THREE.LinearMipmapLinearFilter;
    texture.generateMipmaps = true;
    texture.colorSpace = THREE.SRGBColorSpace;
    texture.needsUpdate = true;
    return texture;
  };
  return data.textures.map((t) => {
    if (t.type === '2d') {
      const texture = new THREE.DataTexture(t.rgba, t.width, t.height, THREE.RGBAFormat);
      texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
      return sampled(texture);
    }
    const w = t.width, single = t.height === t.width;
    const faces = [];
    for (let i = 0; i < 6; ++i) {
      const pixels = single ? t.rgba : t.rgba.subarray(4 * w * w * i, 4 * w * w * (i + 1));
      faces.push(new THREE.DataTexture(pixels, w, w, THREE.RGBAFormat));
    }
    const cube = new THREE.CubeTexture(faces);
    cube.format = THREE.RGBAFormat;
    return sampled(cube);
  });
}

// A material drawing a cube texture as MuJoCo does: looked up by the direction mujocoCubeDirection
// gives each vertex, modulating the colour.
function useCubeTexture(material, cube) {
  material.onBeforeCompile = (shader) => {
    shader.uniforms.mjCube = {value: cube};
    shader.vertexShader =
        shader.vertexShader
            .replace(
                '#include <common>',
                '#include <common>\nattribute vec3 mjcube;\nvarying vec3 vMjCube;')
            .replace('#include <begin_vertex>', '#include <begin_vertex>\nvMjCube = mjcube;');
    shader.fragmentShader =
        shader.fragmentShader
            .replace(
                '#include <common>',
                '#include <common>\nuniform samplerCube mjCube;\nvarying vec3 vMjCube;')
            .replace('#include <map_fragment>', 'diffuseColor *= textureCube(mjCube, vMjCube);');
  };
  material.customProgramCacheKey = () => 'mjarm-cube-texture';
}

// The skybox as MuJoCo draws it (mjr_render): unlit, behind everything, the texture looked up by
// the view direction (x, y, z) as (x, z, −y) — MuJoCo's cube is turned 90° about x, so its +y face
// is the sky above.
function skyboxMesh(cube) {
  const cubeRaw = cube.clone();
  cubeRaw.colorSpace = THREE.NoColorSpace;  // MuJoCo writes the texels as they are
  cubeRaw.needsUpdate = true;
  const material = new THREE.ShaderMaterial({
    uniforms: {sky: {value: cubeRaw}},
    vertexShader: `varying vec3 vDirection;
      void main() {
        vDirection = position;
        vec4 p = projectionMatrix * vec4(mat3(viewMatrix) * position, 1.0);
        gl_Position = vec4(p.xy, 0.9999 * p.w, p.w);
      }`,
    fragmentShader: `uniform samplerCube sky;
      varying vec3 vDirection;
      void main() {
        gl_FragColor = vec4(textureCube(sky, vec3(vDirection.x, vDirection.z, -vDirection.y)).rgb, 1.0);
      }`,
    side: THREE.BackSide,
    depthTest: false,
    depthWrite: false,
  });
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(2, 2, 2), material);
  mesh.name = 'skybox';
  mesh.frustumCulled = false;
  mesh.renderOrder = -1;  // drawn first, under everything
  return mesh;
}

function material(geom, textures, geometry) {
  const [r, g, b, alpha] = geom.rgba;
  const texture = geom.texture >= 0 ? textures[geom.texture] : null;
  const flat = texture && !texture.isCubeTexture;
  if (flat) mujocoUv(geometry, geom);
  const result = new THREE.MeshPhongMaterial({
    map: flat ? texture : null,
    color: new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace),
    emissive: new THREE.Color().setRGB(
        r * geom.emission, g * geom.emission, b * geom.emission, THREE.SRGBColorSpace),
    specular: new THREE.Color(geom.specular, geom.specular, geom.specular),
    shininess: Math.max(1, geom.shininess * 128),
    transparent: alpha < 1,
    opacity: alpha,
    side: geom.type === 'plane' ? THREE.DoubleSide : THREE.FrontSide,
  });
  if (texture && texture.isCubeTexture) {
    mujocoCubeDirection(geometry, geom);
    useCubeTexture(result, texture);
  }
  return result;
}

// The scene: the body groups (index = MuJoCo body id), the number of drawn meshes, the skybox
// (null without one).
export function buildScene(data) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0.12, 0.14, 0.17);
  scene.add(new THREE.AmbientLight(0xffffff, 0.9));
  const textures = makeTextures(data);
  let sky = null;
  if (data.skybox >= 0 && textures[data.skybox].isCubeTexture) {
    sky = skyboxMesh(textures[data.skybox]);
    scene.add(sky);
  }
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
    const mesh = new THREE.Mesh(geometry, material(geom, textures, geometry));
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
  return {scene, bodies, meshCount, skipped, headlight, sky};
}

// The frames either side of time t and the weight of the later one, in `at` (one object for
// every call: posing a frame allocates nothing).
const at = {
  k: 0,
  next: 0,
  w: 0
};
function frameAt(time, t) {
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
  at.k = k;
  at.next = next;
  at.w = span > 0 ? Math.min(Math.max((t - time[k]) / span, 0), 1) : 0;
  return at;
}

const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();

// Poses `object` as element `i` of `count` in frame-major pos (x y z) and quat (w x y z) arrays,
// between frames k and next with weight w: positions mixed linearly, orientations by slerp.
function poseBetween(object, pos, quat, count, i, {k, next, w}) {
  const p0 = (k * count + i) * 3, p1 = (next * count + i) * 3;
  const q0 = (k * count + i) * 4, q1 = (next * count + i) * 4;
  object.position.set(
      pos[p0] + w * (pos[p1] - pos[p0]), pos[p0 + 1] + w * (pos[p1 + 1] - pos[p0 + 1]),
      pos[p0 + 2] + w * (pos[p1 + 2] - pos[p0 + 2]));
  qa.set(quat[q0 + 1], quat[q0 + 2], quat[q0 + 3], quat[q0]);
  qb.set(quat[q1 + 1], quat[q1 + 2], quat[q1 + 3], quat[q1]);
  object.quaternion.slerpQuaternions(qa, qb, w);
}

// Poses `object` where the model's moving camera number `track` (cameras[c].track) is at time t:
// its pose per frame as MuJoCo computed it (src/web/replay_cameras.cpp), interpolated.
export function poseTrackedCamera(data, track, t, object) {
  const poses = data.camera_poses;
  poseBetween(
      object, poses.pos, poses.quat, poses.cameras.length, track, frameAt(data.frames.time, t));
}

// Poses every body at time t: the frames either side, positions mixed linearly, orientations
// by spherical interpolation (the recording is decimated: docs/replay.md).
export function poseBodies(data, bodies, t) {
  const between = frameAt(data.frames.time, t);
  const {pos, quat} = data.frames;
  const nb = bodies.length;
  for (let b = 0; b < nb; ++b) poseBetween(bodies[b], pos, quat, nb, b, between);
  return between.k;
}
