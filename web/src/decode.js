// The data block of a replay file: one JSON document whose large arrays are base64 of
// little-endian Float32 / Uint32 values (written by src/web/replay_data.cpp).

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

// The replay's data from the page's script tag, arrays decoded.
export function readReplayData(elementId) {
  const element = document.getElementById(elementId);
  if (!element) throw new Error(`replay: no data block #${elementId}`);
  const data = decodeScene(JSON.parse(element.textContent));
  data.frames.time = floats(data.frames.time);
  data.frames.pos = floats(data.frames.pos);
  data.frames.quat = floats(data.frames.quat);
  return data;
}

// The model's arrays decoded in place (meshes, textures): a replay file's data block and the live
// view's greeting describe the model alike (src/web/replay_scene.cpp).
export function decodeScene(data) {
  for (const mesh of data.meshes) {
    mesh.vert = floats(mesh.vert);
    mesh.face = uints(mesh.face);
  }
  for (const texture of data.textures || []) {
    // RGB or RGBA bytes, row 0 first (as MuJoCo stores them), to RGBA
    const bytes = bytesOf(texture.data);
    const n = texture.width * texture.height;
    const rgba = new Uint8Array(4 * n);
    for (let i = 0; i < n; ++i) {
      for (let k = 0; k < 3; ++k) rgba[4 * i + k] = bytes[texture.channels * i + k];
      rgba[4 * i + 3] = texture.channels === 4 ? bytes[4 * i + 3] : 255;
    }
    texture.rgba = rgba;
  }
  return data;
}
