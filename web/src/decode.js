// The data block of a replay file: one JSON document whose large arrays are base64 of
// little-endian Float32 / Uint32 values, and textures deflated (written by src/web/replay_*.cpp).

function bytesOf(base64) {
  const text = atob(base64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
  return bytes;
}

export function floats(base64) {
  const bytes = bytesOf(base64 || '');
  return new Float32Array(bytes.buffer, 0, bytes.length / 4);
}

export function uints(base64) {
  const bytes = bytesOf(base64 || '');
  return new Uint32Array(bytes.buffer, 0, bytes.length / 4);
}

// zlib-deflated bytes (src/web/replay_textures.cpp) inflated by the browser
async function inflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// A texture's pixels as RGBA bytes, row 0 first (as MuJoCo stores them): inflated, each row's
// difference from the row above undone, grey and RGB expanded
async function texturePixels(texture) {
  const bytes = await inflate(bytesOf(texture.data));
  const {width, height, channels} = texture;
  const row = width * channels;
  if (bytes.length !== row * height) {
    throw new Error(`replay: a texture inflates to ${bytes.length} bytes, not ${row * height}`);
  }
  for (let i = row; i < bytes.length; ++i) bytes[i] = (bytes[i] + bytes[i - row]) & 255;
  const n = width * height;
  const rgba = new Uint8Array(4 * n);
  for (let i = 0; i < n; ++i) {
    for (let k = 0; k < 3; ++k) rgba[4 * i + k] = bytes[channels * i + (channels === 1 ? 0 : k)];
    rgba[4 * i + 3] = channels === 4 ? bytes[4 * i + 3] : 255;
  }
  return rgba;
}

// The replay's data from the page's script tag, arrays decoded.
export async function readReplayData(elementId) {
  const element = document.getElementById(elementId);
  if (!element) throw new Error(`replay: no data block #${elementId}`);
  const data = await decodeScene(JSON.parse(element.textContent));
  data.frames.time = floats(data.frames.time);
  data.frames.pos = floats(data.frames.pos);
  data.frames.quat = floats(data.frames.quat);
  return data;
}

// The model's arrays decoded in place (meshes, textures): a replay file's data block and the live
// view's greeting describe the model alike (src/web/replay_scene.cpp).
export async function decodeScene(data) {
  for (const mesh of data.meshes) {
    mesh.vert = floats(mesh.vert);
    mesh.face = uints(mesh.face);
    if (mesh.texcoord) mesh.texcoord = floats(mesh.texcoord);
  }
  for (const hfield of data.hfields || []) hfield.data = floats(hfield.data);
  const poses = data.camera_poses;
  if (poses && poses.cameras.length > 0) {
    poses.pos = floats(poses.pos);
    poses.quat = floats(poses.quat);
  }
  data.textures = data.textures || [];
  await Promise.all(data.textures.map(async (texture) => {
    texture.rgba = await texturePixels(texture);
  }));
  return data;
}
