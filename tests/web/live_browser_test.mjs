// The live view in a real browser (docs/viewer.md "In a browser"): `mjarm view panda --web` is
// started (and always stopped, by its process id), its page opened by headless Chromium; checked:
// no console error, frames arrive, a slider moved in the page moves the target and the arm
// follows; with --token the page without the token, or with another, is refused and with it
// served. Usage: node live_browser_test.mjs MJARM_CLI (MJARM_WEB_MODULES: the build tree's
// web/node_modules, for ws; CHROMIUM: the browser, default `chromium` on PATH).
import { spawn } from 'node:child_process';
import { Browser, Checks, findChromium, openPage } from './devtools.mjs';

const [cli] = process.argv.slice(2);
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
  check(await until(page, 'window.mjarmLive.connected && window.mjarmLive.frames > 2'),
        'the page connects and frames arrive');
  const greeting = await page.evaluate('window.mjarmLive.greeting');
  check(greeting && greeting.model === 'panda', 'the greeting names the model', greeting?.model);
  const sliders = await page.evaluate('document.querySelectorAll("#sliders input").length');
  check(sliders === 7, 'the page has the panel\'s seven sliders', `${sliders}`);
  const x0 = await page.evaluate('window.mjarmLive.last[4]');
  const x1 = x0 + 0.05;
  await page.evaluate(`(() => { const s = document.getElementById('slider-x');
      s.value = ${x1}; s.dispatchEvent(new Event('input')); return s.value; })()`);
  const set = await page.evaluate('Number(document.getElementById("slider-x").value)');
  check(await until(page, `Math.abs(window.mjarmLive.last[4] - ${set}) < 1e-5`),
        'moving the x slider moves the target in the frames', `${x0.toFixed(4)} → ${set.toFixed(4)}`);
  check(await until(page, `Math.abs(window.mjarmLive.last[1] - ${set}) < 1e-3`),
        'the end effector follows to within 1 mm');
  check(page.problems.length === 0, 'no console error or exception', page.problems.join('\n'));
  const remote = page.requests.filter((url) => !url.startsWith(open.url.replace(/\/[^/]*$/, '')));
  check(remote.length === 0, 'the page requests nothing but its own server', remote.join(' '));

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
  check(await until(served, 'window.mjarmLive.connected && window.mjarmLive.frames > 0'),
        'with the token the page is served and streams');
} catch (error) {
  check(false, 'the live test ran to its end', error.stack);
} finally {
  browser.stop();
  for (const child of viewers) stopViewer(child);
}
checks.end();
