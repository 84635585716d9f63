// A headless Chromium driven through its DevTools protocol, for the replay page's test: started
// with a profile of its own and a debugging port the browser picks (read from DevToolsActivePort),
// always stopped by its process id.
import { execFileSync, spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, existsSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(`${process.env.MJARM_WEB_MODULES}/`);
const WebSocket = require('ws');

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export class Browser {
  // `args`: more of Chromium's switches (the replay test's unthrottled frames)
  static async start(executable, { width = 1280, height = 800, args: extra = [] } = {}) {
    const profile = mkdtempSync(join(tmpdir(), 'mjarm-chromium-'));
    // software GL (SwiftShader through ANGLE): no GPU on the machines that run the suite
    const args = ['--headless', '--no-sandbox', '--no-first-run', '--no-default-browser-check',
      '--disable-extensions', '--disable-background-networking', '--disable-component-update',
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      `--window-size=${width},${height}`, '--remote-debugging-port=0', `--user-data-dir=${profile}`,
      ...extra, 'about:blank'];
    // a process group of its own: its renderer and GPU processes go with it
    const child = spawn(executable, args, { detached: true, stdio: ['ignore', 'ignore', 'pipe'] });
    let stderr = '';
    child.stderr.on('data', (d) => { stderr += d; });
    const browser = new Browser(child, profile);
    const portFile = join(profile, 'DevToolsActivePort');
    for (let i = 0; i < 300 && !existsSync(portFile); ++i) {
      if (child.exitCode !== null) break;
      await sleep(100);
    }
    if (!existsSync(portFile)) {
      browser.stop();
      throw new Error(`chromium did not start (no DevToolsActivePort): ${stderr.slice(-2000)}`);
    }
    let lines = [];
    for (let i = 0; i < 50 && lines.length < 2; ++i) {
      lines = readFileSync(portFile, 'utf8').split('\n').filter(Boolean);
      if (lines.length < 2) await sleep(100);
    }
    await browser.connect(`ws://127.0.0.1:${lines[0]}${lines[1]}`);
    return browser;
  }

  constructor(child, profile) {
    this.child = child;
    this.profile = profile;
    this.nextId = 1;
    this.pending = new Map();
    this.listeners = [];
  }

  connect(url) {
    return new Promise((resolve, reject) => {
      this.socket = new WebSocket(url, { perMessageDeflate: false, maxPayload: 256 * 1024 * 1024 });
      this.socket.on('open', resolve);
      this.socket.on('error', reject);
      this.socket.on('message', (text) => {
        const message = JSON.parse(text);
        if (message.id && this.pending.has(message.id)) {
          const { resolve: done, reject: fail, method } = this.pending.get(message.id);
          this.pending.delete(message.id);
          if (message.error) fail(new Error(`${method}: ${message.error.message}`));
          else done(message.result);
        } else if (message.method) {
          for (const listener of this.listeners) listener(message);
        }
      });
    });
  }

  send(method, params = {}, sessionId = undefined) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, method });
      this.socket.send(JSON.stringify({ id, method, params, sessionId }));
    });
  }

  on(listener) { this.listeners.push(listener); }

  // Ends the browser's process group by the id of the process this object started.
  stop() {
    try { this.socket?.close(); } catch { /* closing anyway */ }
    if (this.child.exitCode === null) {
      try { process.kill(-this.child.pid, 'SIGKILL'); } catch { /* already gone */ }
    }
    rmSync(this.profile, { recursive: true, force: true });
  }
}

// A page of the browser, its console errors and exceptions collected.
export async function openPage(browser, url) {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  const page = {
    problems: [],
    requests: [],
    loaded: false,
    send: (method, params) => browser.send(method, params, sessionId),
    async evaluate(expression) {
      const result = await this.send('Runtime.evaluate', { expression, returnByValue: true, awaitPromise: true });
      if (result.exceptionDetails) {
        throw new Error(`page: ${expression}: ${result.exceptionDetails.exception?.description || result.exceptionDetails.text}`);
      }
      return result.result.value;
    },
  };
  browser.on((message) => {
    if (message.sessionId !== sessionId) return;
    const p = message.params;
    if (message.method === 'Runtime.exceptionThrown') {
      page.problems.push(`exception: ${p.exceptionDetails.exception?.description || p.exceptionDetails.text}`);
    } else if (message.method === 'Runtime.consoleAPICalled' && (p.type === 'error' || p.type === 'assert')) {
      page.problems.push(`console.${p.type}: ${p.args.map((a) => a.value ?? a.description).join(' ')}`);
    } else if (message.method === 'Log.entryAdded' && p.entry.level === 'error') {
      page.problems.push(`log: ${p.entry.text} ${p.entry.url || ''}`);
    } else if (message.method === 'Network.requestWillBeSent') {
      page.requests.push(p.request.url);
    } else if (message.method === 'Page.loadEventFired') {
      page.loaded = true;
    }
  });
  for (const domain of ['Runtime', 'Log', 'Page', 'Network']) await page.send(`${domain}.enable`);
  const started = Date.now();
  await page.send('Page.navigate', { url });
  while (!page.loaded) {
    if (Date.now() - started > 60000) throw new Error(`page ${url} did not load in 60 s`);
    await sleep(20);
  }
  page.loadMs = Date.now() - started;
  return page;
}

// The browser to drive: $CHROMIUM or `chromium` on PATH; a missing one ends the test (exit 1)
// saying what installs it.
// A replay test's command line, `node SCRIPT MJARM_CLI WORK_DIR`: the CLI and the work folder,
// emptied; a usage line and exit 2 when either is missing
export function cliAndWorkFolder(script) {
  const [cli, workArgument] = process.argv.slice(2);
  if (!cli || !workArgument) {
    console.error(`usage: node ${script} MJARM_CLI WORK_DIR`);
    process.exit(2);
  }
  const work = resolve(workArgument);
  rmSync(work, { recursive: true, force: true });
  mkdirSync(work, { recursive: true });
  return { cli, work };
}

export function findChromium(test) {
  const named = process.env.CHROMIUM || 'chromium';
  try {
    return execFileSync('sh', ['-c', `command -v ${named}`], { encoding: 'utf8' }).trim();
  } catch {
    console.error(`${test}: no '${named}' on PATH: Debian's chromium package runs this ` +
                  'test (scripts/setup.sh all installs it)');
    process.exit(1);
  }
}

// A test's checks: each printed as it is made; end() prints the counts and exits 1 on a failure.
export class Checks {
  constructor() { this.passed = 0; this.failed = 0; }
  check(ok, what, detail = '') {
    if (ok) ++this.passed; else ++this.failed;
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}${detail ? `: ${detail}` : ''}`);
  }
  // No console error or exception on @p page, and no request but those @p own accepts (its file,
  // its server: @p source names it).
  pageIsClean(page, own, source) {
    this.check(page.problems.length === 0, 'no console error or exception', page.problems.join('\n'));
    const remote = page.requests.filter((url) => !own(url));
    this.check(remote.length === 0, `the page requests nothing but ${source}`, remote.join(' '));
  }
  end() {
    console.log(`${this.passed} passed, ${this.failed} failed`);
    process.exit(this.failed === 0 ? 0 : 1);
  }
}
