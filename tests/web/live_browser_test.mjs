// The live view in a real browser (docs/viewer.md "In a browser"): `mjarm view panda --web` is
// started (and always stopped, by its process id), its page — the replay page's three.js scene in
// live mode — opened by headless Chromium; checked: the scene is built from the greeting (one mesh
// per drawn geom, no playback controls), frames arrive and every body is drawn at its streamed
// pose, a slider moved in the page moves the target and the arm follows (in the frames and in the
// drawn scene), the screenshot is not blank, no console error and no request beyond its own
// server; with --token the page without the token, or with another, is refused and with it
// served. Usage: node live_browser_test.mjs MJARM_CLI [WORK_DIR] (MJARM_WEB_MODULES: the build
// tree's web/node_modules, for ws; CHROMIUM: the browser, default `chromium` on PATH).
import { spawn } from 'node:child_process';
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { Browser, Checks, findChromium, openPage } from './devtools.mjs';
import { decodePng } from './png.mjs';

const [cli, work = '.'] = process.argv.slice(2);
if (!cli) {
  console.error('usage: node live_browser_test.mjs MJARM_CLI');
  process.exit(2);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

const checks = new Checks();
const check = checks.check.bind(checks);

// `mjarm view panda --web …` running, and the address it printed on stderr
async function startViewer(extra) {
  const child = spawn(cli, ['view', 'panda', '--web', '--duration', '300', ...extra],
                      { stdio: ['ignore', 'ignore', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  for (let i = 0; i < 1200 && !/live at (http:\S+)/.test(stderr); ++i) {
    if (child.exitCode !== null) break;
    await sleep(50);
  }
  const found = /live at (http:\S+)/.exec(stderr);
  if (!found) {
    stopViewer(child);
    throw new Error(`the viewer printed no address: ${stderr}`);
  }
  return { child, url: found[1] };
}

function stopViewer(child) {
  if (child.exitCode === null) {
    try { process.kill(child.pid, 'SIGKILL'); } catch { /* already gone */ }
  }
}

async function until(page, expression, tries = 1200) {
  for (let i = 0; i < tries; ++i) {
    if (await page.evaluate(expression)) return true;
    await sleep(50);
  }
  return false;
}

const chromium = findChromium('live browser test');
const browser = await Browser.start(chromium);
const viewers = [];
try {
  const open = await startViewer([]);
  viewers.push(open.child);
  const page = await openPage(browser, open.url);
  const live = 'window.mjarmLive';
  check(await until(page, `${live}.ready && ${live}.connected && ${live}.frames > 2 && ${live}.renders > 0`),
        'the page connects, builds the scene from the greeting, and frames arrive');
  const info = await page.evaluate(`(() => { const l = ${live}; return { greeting: l.greeting,
      meshCount: l.meshCount, skipped: l.skippedGeoms, bodies: l.bodies,
      sliders: document.querySelectorAll('#mjarm-sliders input').length,
      modes: Array.from(document.querySelectorAll('#mjarm-mode option'), (o) => o.value),
      shown: ['mjarm-mode', 'mjarm-reset'].every((id) => document.getElementById(id).offsetParent !== null),
      playback: ['mjarm-scrub', 'mjarm-plots', 'mjarm-phases'].filter((id) => document.getElementById(id)) }; })()`);
  const layout = info.greeting.frame;
  check(info.greeting.model === 'panda', 'the greeting names the model', info.greeting.model);
  check(info.meshCount > 0 && info.meshCount === info.greeting.drawnGeoms, 'one mesh per drawn geom of the model',
        `${info.meshCount} meshes, ${info.greeting.drawnGeoms} drawn geoms`);
  check(info.skipped.length === 0, 'no geom left undrawn', info.skipped.join(' '));
  check(info.playback.length === 0, 'no scrub, plots or timeline live', info.playback.join(' '));
  check(info.sliders === 7, 'the panel has the viewer\'s seven sliders', `${info.sliders}`);
  check(info.shown && ['kinematic', 'position', 'torque'].every((m) => info.modes.includes(m)),
        'the panel shows the modes and reset',
        info.modes.join(' '));

  // every body drawn at the pose of the frame the view shows, the tool frame where the frame has it
  const shownPoses = async () => page.evaluate(`({ poses: ${live}.bodyPoses(), frame: ${live}.drawn(),
      overlay: ${live}.overlayPositions() })`);
  const poseError = (shown) => {
    let worst = shown.poses.length === layout.bodies ? 0 : Infinity;
    shown.poses.forEach((body, b) => {
      for (let k = 0; k < 3; ++k) worst = Math.max(worst, Math.abs(body.pos[k] - shown.frame[layout.pos + 3 * b + k]));
      for (let k = 0; k < 4; ++k) worst = Math.max(worst, Math.abs(body.quat[k] - shown.frame[layout.quat + 4 * b + k]));
    });
    for (let k = 0; k < 3; ++k) {
      worst = Math.max(worst, Math.abs(shown.overlay.tool[k] - shown.frame[layout.tool + k]),
                       Math.abs(shown.overlay.target[k] - shown.frame[layout.target + k]));
    }
    return worst;
  };
  const before = await shownPoses();
  check(poseError(before) < 1e-6, 'every body (and the tool and target frames) drawn at its streamed pose',
        `largest difference ${poseError(before).toExponential(2)} over ${before.poses.length} bodies`);

  // the x slider, moved in the page: the target moves in the frames, the arm follows
  const x0 = (await page.evaluate(`${live}.last()`))[layout.target];
  const x1 = x0 + 0.05;
  await page.evaluate(`(() => { const s = document.getElementById('slider-x');
      s.value = ${x1}; s.dispatchEvent(new Event('input')); return s.value; })()`);
  const set = await page.evaluate('Number(document.getElementById("slider-x").value)');
  check(await until(page, `Math.abs(${live}.last()[${layout.target}] - ${set}) < 1e-5`),
        'moving the x slider moves the target in the frames', `${x0.toFixed(4)} → ${set.toFixed(4)}`);
  check(await until(page, `Math.abs(${live}.drawn()[${layout.tool}] - ${set}) < 1e-3`),
        'the end effector follows to within 1 mm, in the frame the view shows');
  const after = await shownPoses();
  check(poseError(after) < 1e-6, 'after the move, every body is drawn at its streamed pose',
        `largest difference ${poseError(after).toExponential(2)}`);
  // the body nearest the tool at the start (the hand) moved along x with it
  const near = before.poses.map((p, b) => [b, Math.hypot(...[0, 1, 2].map((k) => p.pos[k] - before.frame[layout.tool + k]))])
                     .sort((a, b) => a[1] - b[1])[0][0];
  const moved = after.poses[near].pos[0] - before.poses[near].pos[0];
  check(Math.abs(moved - (set - x0)) < 2e-3, 'the arm is drawn where it went',
        `${info.bodies[near]} moved ${moved.toFixed(4)} m in x (the target ${(set - x0).toFixed(4)} m)`);

  // a screenshot of the live scene, not blank
  mkdirSync(work, { recursive: true });
  const shot = await page.send('Page.captureScreenshot', { format: 'png' });
  const png = Buffer.from(shot.data, 'base64');
  writeFileSync(join(work, 'live_view.png'), png);
  const image = decodePng(png);
  const colours = new Set();
  for (let i = 0; i < image.width * image.height; i += 7) {
    colours.add((image.rgba[4 * i] << 16) | (image.rgba[4 * i + 1] << 8) | image.rgba[4 * i + 2]);
  }
  check(colours.size > 50, 'the screenshot is not blank', `${colours.size} colours in ${image.width}×${image.height}`);
  const server = open.url.replace(/\/[^/]*$/, '');
  checks.pageIsClean(page, (url) => url.startsWith(server), 'its own server');

  const locked = await startViewer(['--token']);
  viewers.push(locked.child);
  const bare = locked.url.split('?')[0];
  const refused = await openPage(browser, bare);
  const text = await refused.evaluate('document.body.innerText');
  check(/access token/.test(text), 'without the token the page is refused', text.trim());
  const wrong = await openPage(browser, `${bare}?token=${'0'.repeat(32)}`);
  check(/access token/.test(await wrong.evaluate('document.body.innerText')),
        'with another token the page is refused');
  const served = await openPage(browser, locked.url);
  check(await until(served, 'window.mjarmLive.ready && window.mjarmLive.connected && window.mjarmLive.frames > 0'),
        'with the token the page is served, builds its scene and streams');
} catch (error) {
  check(false, 'the live test ran to its end', error.stack);
} finally {
  browser.stop();
  for (const child of viewers) stopViewer(child);
}
checks.end();
