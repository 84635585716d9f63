// The replay page in a real browser (docs/replay.md "Tested in a browser"): a pick is recorded,
// written as a replay file, and opened by headless Chromium from file:// — no server, no
// network. Checked: no console error or exception; as many meshes as the model has drawn geoms;
// at several times the page puts every free object where state.csv says; a screenshot that is not
// blank; the arm's silhouette against mjarm's own EGL rendering from the same camera. Usage: node replay_browser_test.mjs MJARM_CLI WORK_DIR (MJARM_WEB_MODULES: the build
// tree's web/node_modules, for ws; CHROMIUM: the browser, default `chromium` on PATH).
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { Browser, Checks, cliAndWorkFolder, findChromium, openPage } from './devtools.mjs';
import { decodePng } from './png.mjs';

const { cli, work } = cliAndWorkFolder('replay_browser_test.mjs');

const checks = new Checks();
const check = checks.check.bind(checks);

function csvRows(path) {
  const [header, ...lines] = readFileSync(path, 'utf8').trim().split('\n');
  return { columns: header.split(','), rows: lines.map((l) => l.split(',').map(Number)) };
}

const chromium = findChromium('replay browser test');
const recording = join(work, 'rec');
execFileSync(cli, ['run', 'pick-place', '--record', recording], { stdio: ['ignore', 'ignore', 'inherit'] });
const html = join(work, 'run.html');
const report = JSON.parse(execFileSync(cli, ['replay-html', recording, '-o', html, '--json'], { encoding: 'utf8' }));
const state = csvRows(join(recording, 'state.csv'));
console.log(`replay: ${report.bytes} bytes, ${report.frames} frames, ${report.drawn_geoms} geoms drawn`);
check(statSync(html).size === report.bytes, 'the file has the size the command reports');

// frames as fast as the page draws them: headless Chromium otherwise holds each frame to the next
// tick of its 60 Hz clock, so a frame that misses one by a little waits a whole tick (docs/replay.md
// "Size and speed": 15 frames per second without these switches, 13–75 with them, under load)
const browser = await Browser.start(chromium, { args: ['--disable-gpu-vsync', '--disable-frame-rate-limit'] });
try {
  const page = await openPage(browser, pathToFileURL(html).href);
  let ready = false;
  for (let i = 0; i < 600 && !ready; ++i) {
    ready = await page.evaluate('Boolean(window.mjarmReplay && window.mjarmReplay.ready)');
    if (!ready) await new Promise((r) => setTimeout(r, 50));
  }
  check(ready, 'the page is ready', `${page.loadMs} ms to its load event`);
  const info = await page.evaluate(`(() => { const r = window.mjarmReplay; return {
      meshCount: r.meshCount, skipped: r.skippedGeoms, frames: r.frameCount, cameras: r.cameras,
      free: r.freeJoints, times: r.frameTimes() }; })()`);
  check(info.meshCount === report.drawn_geoms, 'one mesh per drawn geom',
        `${info.meshCount} meshes, ${report.drawn_geoms} drawn geoms`);
  check(info.skipped.length === 0, 'no geom left undrawn', info.skipped.join(' '));
  check(info.frames === report.frames, 'every frame is in the page', `${info.frames} of ${report.frames}`);
  check(info.free.length > 0, 'the recording has a free object', info.free.map((f) => f.body).join(' '));

  // at frame times the page shows recorded states: the free objects' qpos is their world pose
  const tColumn = state.columns.indexOf('t');
  let worst = 0, compared = 0;
  for (const fraction of [0, 0.2, 0.45, 0.6, 0.8, 1]) {
    const t = info.times[Math.round(fraction * (info.times.length - 1))];
    await page.evaluate(`window.mjarmReplay.seek(${t})`);
    const row = state.rows.reduce((best, r) => (Math.abs(r[tColumn] - t) < Math.abs(best[tColumn] - t) ? r : best));
    for (const { joint, body } of info.free) {
      const pose = await page.evaluate(`window.mjarmReplay.bodyPose(${JSON.stringify(body)})`);
      for (let k = 0; k < 3; ++k) {
        const recorded = row[state.columns.indexOf(`q.${joint}.${k}`)];
        worst = Math.max(worst, Math.abs(pose.pos[k] - recorded));
        ++compared;
      }
    }
  }
  check(compared > 0 && worst < 1e-5, 'seeking puts the free objects where state.csv says',
        `largest difference ${worst.toExponential(2)} m over ${compared} coordinates`);
  // the overlays: contacts where the object lies on the table, every non-phase event marked
  // (a tenth into the run: the arm approaches, the object has settled on the table)
  const tRest = info.times[Math.round(0.1 * (info.times.length - 1))];
  await page.evaluate(`window.mjarmReplay.seek(${tRest})`);
  const contacts = await page.evaluate('window.mjarmReplay.contactCount()');
  check(contacts > 0, 'contacts are drawn where the object lies on the table', `${contacts} at t = ${tRest.toFixed(3)} s`);
  const events = readFileSync(join(recording, 'events.csv'), 'utf8').trim().split('\n').slice(1)
    .filter((line) => line.split(',')[1] !== 'phase').length;
  const marks = await page.evaluate('window.mjarmReplay.eventMarks()');
  check(marks === events && events > 0, 'every grasp and result event is marked on the timeline', `${marks} of ${events}`);

  // between frames the page interpolates: a time between two frames lies between their poses
  const mid = 0.5 * (info.times[10] + info.times[11]);
  const between = await page.evaluate(`window.mjarmReplay.seek(${mid})`);
  check(Math.abs(between - mid) < 1e-9, 'a seek between frames keeps its time');

  // playback moves the time on; the rate of frames drawn is printed, not judged. Played for 20
  // drawn frames and paused by the page itself at the 20th (each frame drawn flat out costs the
  // software rasteriser a core, and the protocol's calls wait behind the frames): enough for the
  // time to move and for a rate, at a fraction of a second of drawing
  const played = await page.evaluate(`new Promise((done) => {
      const r = window.mjarmReplay, first = r.renders();
      let start = null;
      r.seek(${info.times[0]});
      r.play();
      const tick = (clock) => {
        const drawn = r.renders() - first;
        if (start === null && drawn > 0) start = { clock, drawn };
        if (drawn < 20) return requestAnimationFrame(tick);
        r.pause();
        done({ t: r.time(), drawn: drawn - start.drawn, ms: clock - start.clock });
      };
      requestAnimationFrame(tick);
    })`);
  check(played.t > info.times[0], 'playing moves the replay time on', `t = ${played.t.toFixed(3)} s after 20 frames`);
  console.log(`playback: ${((1000 * played.drawn) / played.ms).toFixed(1)} frames drawn per second (${played.drawn} frames in ${played.ms.toFixed(0)} ms)`);
  const cost = await page.evaluate('window.mjarmReplay.drawCost(12)');
  const gl = await page.evaluate('window.mjarmReplay.softwareGl');
  console.log(`drawing one frame: ${cost.toFixed(2)} ms (${(1000 / cost).toFixed(0)} per second at most; software GL: ${gl})`);

  // a screenshot from the model's first camera in mid-run, not blank
  const camera = info.cameras[0];
  await page.evaluate(`window.mjarmReplay.setCamera(${JSON.stringify(camera)}); window.mjarmReplay.seek(${info.times[Math.round(info.times.length / 2)]})`);
  const shot = await page.send('Page.captureScreenshot', { format: 'png' });
  const png = Buffer.from(shot.data, 'base64');
  writeFileSync(join(work, 'screenshot.png'), png);
  const image = decodePng(png);
  const colours = new Set();
  for (let i = 0; i < image.width * image.height; i += 7) {
    colours.add((image.rgba[4 * i] << 16) | (image.rgba[4 * i + 1] << 8) | image.rgba[4 * i + 2]);
  }
  check(colours.size > 50, 'the screenshot is not blank', `${colours.size} colours in ${image.width}×${image.height} (${join(work, 'screenshot.png')})`);

  // a click in the middle of the first plot moves the replay to the middle of its time axis
  const box = await page.evaluate(`(() => { const r = document.querySelector('#mjarm-plots .u-over').getBoundingClientRect();
    return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; })()`);
  for (const type of ['mouseMoved', 'mousePressed', 'mouseReleased']) {
    await page.send('Input.dispatchMouseEvent', { type, x: box.x, y: box.y, button: 'left', clickCount: 1 });
  }
  const clicked = await page.evaluate('window.mjarmReplay.time()');
  const middle = 0.5 * (info.times[0] + info.times[info.times.length - 1]);
  check(Math.abs(clicked - middle) < 0.05 * (info.times[info.times.length - 1] - info.times[0]),
        'a click on a plot moves the replay there', `t = ${clicked.toFixed(3)} s, the plot's middle ${middle.toFixed(3)} s`);

  // the arm's silhouette against mjarm's own EGL rendering of the same state from the same
  // camera (`mjarm render --only-subtree`): the moving arm, the subtree of the body its first
  // controlled joint moves
  const summary = JSON.parse(readFileSync(join(recording, 'summary.json'), 'utf8'));
  const joints = await page.evaluate('window.mjarmReplay.joints');
  const arm = joints.find((j) => j.name === summary.controllers[0].joints[0]).body;
  const tArm = info.times[Math.round(0.55 * (info.times.length - 1))];
  const armRow = state.rows.reduce((best, r) => (Math.abs(r[tColumn] - tArm) < Math.abs(best[tColumn] - tArm) ? r : best));
  const q = state.columns.map((c, i) => (c.startsWith('q.') ? armRow[i] : null)).filter((v) => v !== null);
  const rect = await page.evaluate('window.mjarmReplay.setViewSize(640, 480)');
  for (const view of info.cameras) {
    const eglPath = join(work, `silhouette_${view}_egl.png`);
    execFileSync(cli, ['render', join(recording, 'model.mjb'), '--q', ...q.map(String), '--allow-outside-range',
                       '--camera', view, '--size', '640x480', '--only-subtree', arm, '--out', eglPath],
                 // Mesa's software rasteriser allocates from JIT code LeakSanitizer cannot
                 // attribute: a sanitized build renders without leak checking (tests/CMakeLists.txt)
                 { stdio: ['ignore', 'ignore', 'inherit'],
                   env: { ...process.env, ASAN_OPTIONS: `${process.env.ASAN_OPTIONS || ''}:detect_leaks=0` } });
    const egl = decodePng(readFileSync(eglPath));
    await page.evaluate(`window.mjarmReplay.setCamera(${JSON.stringify(view)}); window.mjarmReplay.seek(${tArm}); window.mjarmReplay.silhouette(${JSON.stringify(arm)})`);
    const clip = await page.send('Page.captureScreenshot', { format: 'png', clip: { ...rect, scale: 1 } });
    writeFileSync(join(work, `silhouette_${view}_page.png`), Buffer.from(clip.data, 'base64'));
    const web = decodePng(Buffer.from(clip.data, 'base64'));
    if (web.width !== egl.width || web.height !== egl.height) {
      check(false, `camera ${view}: the two pictures have one size`, `page ${web.width}×${web.height}, EGL ${egl.width}×${egl.height}`);
      continue;
    }
    // EGL: what differs from the background (the commonest colour of the border: the arm may
    // cover a corner); the page: white on black
    const counts = new Map();
    for (let x = 0; x < egl.width; ++x) {
      for (const y of [0, egl.height - 1]) {
        const i = 4 * (y * egl.width + x);
        const key = (egl.rgba[i] << 16) | (egl.rgba[i + 1] << 8) | egl.rgba[i + 2];
        counts.set(key, (counts.get(key) || 0) + 1);
      }
    }
    const commonest = [...counts.entries()].sort((p, r) => r[1] - p[1])[0][0];
    const bg = [(commonest >> 16) & 255, (commonest >> 8) & 255, commonest & 255];
    let both = 0, either = 0, inEgl = 0, inWeb = 0;
    for (let i = 0; i < egl.width * egl.height; ++i) {
      const a = Math.max(...[0, 1, 2].map((k) => Math.abs(egl.rgba[4 * i + k] - bg[k]))) > 30;
      const b = web.rgba[4 * i] + web.rgba[4 * i + 1] + web.rgba[4 * i + 2] > 3 * 128;
      both += a && b ? 1 : 0;
      either += a || b ? 1 : 0;
      inEgl += a ? 1 : 0;
      inWeb += b ? 1 : 0;
    }
    const overlap = either > 0 ? both / either : 0;
    check(inEgl > 0.01 * egl.width * egl.height, `camera ${view}: the arm (${arm} and below) fills part of the EGL picture`,
          `${inEgl} pixels`);
    check(overlap >= 0.9, `camera ${view}: the arm's silhouette matches mjarm's EGL rendering (intersection over union ≥ 0.9)`,
          `${overlap.toFixed(3)} (page ${inWeb} pixels, EGL ${inEgl})`);
  }
  await page.evaluate('window.mjarmReplay.silhouette(null); window.mjarmReplay.setViewSize(null, null)');
  checks.pageIsClean(page, (url) => /^(file|data|blob|about):/.test(url), 'its own file');
} catch (error) {
  check(false, 'the page test ran to its end', error.stack);
} finally {
  browser.stop();
}
checks.end();
