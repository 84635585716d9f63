// The replay page's scene in a real browser (docs/replay.md "Tested in a browser"): a run of the
// scene test model (tests/web/replay_scene_model.xml: skybox, textures, a height field, a cart
// with tracking cameras) is written by hand, made into a replay with `mjarm replay-html --model`,
// and opened by headless Chromium. Checked: no console error; every drawn geom a mesh (the
// height field too), the skybox and the textures there; the tracking, aimed and riding cameras
// posed where MuJoCo poses them (computed here by hand from the cart's recorded position); the
// sky as mjarm's own EGL rendering draws it from the same camera. Usage: node
// replay_scene_browser_test.mjs MJARM_CLI WORK_DIR (MJARM_WEB_MODULES as replay_browser_test.mjs).
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { Browser, Checks, cliAndWorkFolder, findChromium, openPage } from './devtools.mjs';
import { decodePng } from './png.mjs';

const { cli, work } = cliAndWorkFolder('replay_scene_browser_test.mjs');
const model = join(dirname(fileURLToPath(import.meta.url)), 'replay_scene_model.xml');
const checks = new Checks();
const check = checks.check.bind(checks);

// the run: the cart at q = 0.5 sin(3t) for 1 s of 2 ms rows (the recorder's file names)
const recording = join(work, 'rec');
mkdirSync(recording);
const cart = (t) => 0.5 * Math.sin(3 * t);
const times = Array.from({ length: 501 }, (_, i) => 0.002 * i);
writeFileSync(join(recording, 'state.csv'), `t,q.cart_x\n${times.map((t) => `${t},${cart(t)}`).join('\n')}\n`);
writeFileSync(join(recording, 'task.csv'), `t\n${times.join('\n')}\n`);
writeFileSync(join(recording, 'events.csv'), 't,kind,message\n0,phase,slide\n');
writeFileSync(join(recording, 'summary.json'), '{"model": "replay_scene", "status": "ok"}');
const html = join(work, 'scene.html');
const report = JSON.parse(execFileSync(cli, ['replay-html', recording, '--model', model, '-o', html, '--json'],
                                       { encoding: 'utf8' }));
console.log(`replay: ${report.bytes} bytes, ${report.frames} frames, ${report.drawn_geoms} geoms drawn`);

const chromium = findChromium('replay scene browser test');
const browser = await Browser.start(chromium);
try {
  const page = await openPage(browser, pathToFileURL(html).href);
  // the page is ready once its textures are inflated, or has failed (its message in the body):
  // waited for frame by frame in the page
  const ready = await page.evaluate(`new Promise((done) => {
      const wait = () => {
        if (window.mjarmReplay?.ready) done(true);
        else if (document.body.textContent.startsWith('mjarm replay:')) done(false);
        else requestAnimationFrame(wait);
      };
      wait(); })`);
  check(ready, 'the page is ready', `${page.loadMs} ms to its load event`);
  const info = await page.evaluate(`(() => { const r = window.mjarmReplay; return {
      meshCount: r.meshCount, skipped: r.skippedGeoms, hfields: r.hfieldCount, skybox: r.skybox,
      textures: r.textureCount, times: r.frameTimes(), cameras: r.cameras }; })()`);
  check(info.meshCount === report.drawn_geoms, 'one mesh per drawn geom, the height field too',
        `${info.meshCount} meshes, ${report.drawn_geoms} drawn geoms`);
  check(info.skipped.length === 0, 'no geom left undrawn', info.skipped.join(' '));
  check(info.hfields === 1, 'the height field is drawn', `${info.hfields}`);
  check(info.skybox, 'the skybox is drawn');
  check(info.textures === 3, 'every texture once: the sky, the grid (six geoms), the dice', `${info.textures}`);

  // the cameras at frame times: MuJoCo's poses, by hand from the cart's position (x = q, 0, 0.2)
  let worstFollow = 0, worstRider = 0, worstAim = 0;
  for (const fraction of [0, 0.17, 0.5, 0.83, 1]) {
    const t = info.times[Math.round(fraction * (info.times.length - 1))];
    const x = cart(times.reduce((best, s) => (Math.abs(s - t) < Math.abs(best - t) ? s : best)));
    const pose = async (name) => page.evaluate(`(() => { const r = window.mjarmReplay;
        r.setCamera(${JSON.stringify(name)}); r.seek(${t}); return r.cameraPose(); })()`);
    const follow = await pose('follow');  // track: its offset from the cart kept
    [x, -1.8, 1.2].forEach((v, k) => { worstFollow = Math.max(worstFollow, Math.abs(follow.pos[k] - v)); });
    const rider = await pose('rider');  // fixed in the cart
    [x, -0.2, 0.5].forEach((v, k) => { worstRider = Math.max(worstRider, Math.abs(rider.pos[k] - v)); });
    const aim = await pose('aim');  // targetbody: its −z axis towards the cart
    const [w, qx, qy, qz] = aim.quat;
    const view = [-2 * (qx * qz + w * qy), -2 * (qy * qz - w * qx), -(1 - 2 * (qx * qx + qy * qy))];
    const to = [x - aim.pos[0], -aim.pos[1], 0.2 - aim.pos[2]];
    const norm = Math.hypot(...to);
    to.forEach((v, k) => { worstAim = Math.max(worstAim, Math.abs(view[k] - v / norm)); });
  }
  check(worstFollow < 1e-6, 'the tracking camera follows the cart at its offset', `largest difference ${worstFollow.toExponential(2)} m`);
  check(worstRider < 1e-6, 'the camera in the cart rides it', `largest difference ${worstRider.toExponential(2)} m`);
  check(worstAim < 1e-6, 'the aimed camera looks at the cart', `largest difference ${worstAim.toExponential(2)}`);

  // pictures to look at, and the sky against mjarm's EGL rendering from the horizon camera: the
  // top tenth of the picture is sky in both
  const rect = await page.evaluate('window.mjarmReplay.showPlots(false); window.mjarmReplay.setViewSize(640, 480)');
  const tMid = info.times[Math.round(0.3 * (info.times.length - 1))];
  for (const view of ['follow', 'horizon', 'aim']) {
    await page.evaluate(`window.mjarmReplay.setCamera(${JSON.stringify(view)}); window.mjarmReplay.seek(${tMid})`);
    const shot = await page.send('Page.captureScreenshot', { format: 'png', clip: { ...rect, scale: 1 } });
    writeFileSync(join(work, `scene_${view}_page.png`), Buffer.from(shot.data, 'base64'));
  }
  const egl = join(work, 'scene_horizon_egl.png');
  const q = cart(times.reduce((best, s) => (Math.abs(s - tMid) < Math.abs(best - tMid) ? s : best)));
  execFileSync(cli, ['render', model, '--q', String(q), '--camera', 'horizon', '--size', '640x480', '--out', egl],
               { stdio: ['ignore', 'ignore', 'inherit'],
                 env: { ...process.env, ASAN_OPTIONS: `${process.env.ASAN_OPTIONS || ''}:detect_leaks=0` } });
  const a = decodePng(readFileSync(egl));
  const b = decodePng(readFileSync(join(work, 'scene_horizon_page.png')));
  let difference = 0, n = 0;
  for (let y = 0; y < Math.floor(a.height / 10); ++y) {
    for (let x = 0; x < a.width; ++x) {
      for (let k = 0; k < 3; ++k) difference += Math.abs(a.rgba[4 * (y * a.width + x) + k] - b.rgba[4 * (y * b.width + x) + k]);
      n += 3;
    }
  }
  check(a.width === b.width && n > 0 && difference / n < 6, 'the sky is drawn as MuJoCo draws it (top tenth of the horizon camera)',
        `mean difference ${(difference / n).toFixed(2)} of 255 (${egl})`);
  await page.evaluate('window.mjarmReplay.setViewSize(null, null)');
  checks.pageIsClean(page, (url) => /^(file|data|blob|about):/.test(url), 'its own file');
} catch (error) {
  check(false, 'the page test ran to its end', error.stack);
} finally {
  browser.stop();
}
checks.end();
