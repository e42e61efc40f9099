// A headless Chromium driven over its DevTools protocol, with nothing but Node's own modules
// (node --experimental-websocket on Node 20): the browser the site's tests run in. Chromium is
// Debian's; WebGL 2 comes from SwiftShader (ANGLE), so no GPU and no display are needed.
import {spawn} from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';

const kTypes = {
  '.html': 'text/html', '.js': 'text/javascript', '.wasm': 'application/wasm',
  '.data': 'application/octet-stream', '.json': 'application/json', '.png': 'image/png',
};

// Serves `dir` on 127.0.0.1 (a page's wasm and data cannot be fetched from file://).
export function serve(dir) {
  const server = http.createServer((request, response) => {
    const name = decodeURIComponent(new URL(request.url, 'http://x').pathname);
    const file = path.join(dir, path.normalize(name === '/' ? '/index.html' : name));
    if (!file.startsWith(path.resolve(dir)) || !fs.existsSync(file) ||
        fs.statSync(file).isDirectory()) {
      response.writeHead(404).end();
      return;
    }
    // Last-Modified, as a static server sends it: a reload may take the files from the
    // browser's cache (what a student's second visit does).
    response.writeHead(200, {
      'Content-Type': kTypes[path.extname(file)] ?? 'application/octet-stream',
      'Last-Modified': fs.statSync(file).mtime.toUTCString(),
      'Cache-Control': 'max-age=3600',
    });
    fs.createReadStream(file).pipe(response);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

export class Chromium {
  // A fresh profile in `profileDir` (kept between pages: IndexedDB lives there).
  // `flags`: more of Chromium's switches.
  static async launch(profileDir, {width = 1280, height = 720, flags = []} = {}) {
    fs.mkdirSync(profileDir, {recursive: true});
    const portFile = path.join(profileDir, 'DevToolsActivePort');
    fs.rmSync(portFile, {force: true});
    const args = ['--headless', '--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader',
                  '--enable-unsafe-swiftshader', '--disable-background-networking',
                  '--disable-component-update', '--disable-sync', '--disable-quic',
                  '--no-first-run', '--mute-audio', `--user-data-dir=${profileDir}`,
                  '--remote-debugging-port=0', `--window-size=${width},${height}`, ...flags,
                  'about:blank'];
    const child = spawn(chromiumBinary(), args, {stdio: ['ignore', 'ignore', 'pipe']});
    // A script that throws exits without close(): the browser goes with it, or it would go on
    // drawing its page beside whatever runs next (one such browser took 35-45% of the cores).
    process.on('exit', () => child.kill());
    let stderr = '';
    child.stderr.on('data', (d) => { stderr = (stderr + d).slice(-4000); });
    for (let i = 0; i < 200 && !fs.existsSync(portFile); ++i) await sleep(50);
    if (!fs.existsSync(portFile)) {
      child.kill();
      throw new Error('chromium did not start:\n' + stderr);
    }
    const [port, wsPath] = fs.readFileSync(portFile, 'utf8').trim().split('\n');
    const browser = new Chromium(child, new WebSocket(`ws://127.0.0.1:${port}${wsPath}`));
    browser.profileDir = profileDir;
    await new Promise((resolve, reject) => {
      browser.ws.onopen = resolve;
      browser.ws.onerror = () => reject(new Error('no DevTools connection to chromium'));
    });
    return browser;
  }

  constructor(process, ws) {
    this.process = process;
    this.ws = ws;
    this.nextId = 1;
    this.waiting = new Map();
    this.listeners = [];
    ws.onmessage = (event) => {
      const message = JSON.parse(event.data);
      if (message.id && this.waiting.has(message.id)) {
        const {resolve, reject} = this.waiting.get(message.id);
        this.waiting.delete(message.id);
        if (message.error) reject(new Error(JSON.stringify(message.error)));
        else resolve(message.result);
      } else if (message.method) {
        for (const listener of this.listeners) listener(message);
      }
    };
  }

  send(method, params = {}, sessionId = undefined) {
    const id = this.nextId++;
    this.ws.send(JSON.stringify({id, method, params, sessionId}));
    return new Promise((resolve, reject) => this.waiting.set(id, {resolve, reject}));
  }

  // A new tab, its console kept in page.console.
  async newPage({width = 1280, height = 720} = {}) {
    const {targetId} = await this.send('Target.createTarget', {url: 'about:blank'});
    const {sessionId} = await this.send('Target.attachToTarget', {targetId, flatten: true});
    const page = new Page(this, sessionId);
    page.targetId = targetId;
    await page.send('Page.enable');
    await page.send('Runtime.enable');
    await page.send('Emulation.setDeviceMetricsOverride',
                    {width, height, deviceScaleFactor: 1, mobile: false});
    return page;
  }

  // What a GPU's watchdog does to a draw that never finishes (Chromium's software GPU in a
  // headless browser has none): the GPU process goes, every WebGL context is lost, and the
  // browser starts a new one. Killed, as a watchdog kills it: Browser.crashGpuProcess asks the
  // GPU process's own thread, which a draw that never finishes keeps waiting.
  async crashGpu() {
    const gpu = fs.readdirSync('/proc').filter((pid) => /^\d+$/.test(pid)).find((pid) => {
      try {
        // (Chromium writes its arguments over argv as one line: split at spaces.)
        const args = fs.readFileSync(`/proc/${pid}/cmdline`, 'utf8').split(/[\0 ]/);
        return args.includes('--type=gpu-process') &&
               args.includes(`--user-data-dir=${this.profileDir}`);
      } catch {
        return false;  // gone meanwhile
      }
    });
    if (gpu) process.kill(Number(gpu), 'SIGKILL');
    else await Promise.race([this.send('Browser.crashGpuProcess'), sleep(5000)]).catch(() => {});
  }

  // (A GPU process stuck in a draw can keep the browser from exiting: killed after 10 s.)
  async close() {
    await Promise.race([this.send('Browser.close'), sleep(10000)]).catch(() => {});
    this.ws.close();
    await new Promise((resolve) => {
      if (this.process.exitCode !== null || this.process.signalCode !== null) return resolve();
      this.process.on('exit', resolve);
      setTimeout(() => this.process.kill('SIGKILL'), 10000);
    });
  }
}

function chromiumBinary() { return process.env.CHROMIUM ?? "chromium"; }

export class Page {
  constructor(browser, sessionId) {
    this.browser = browser;
    this.sessionId = sessionId;
    this.console = [];
    this.loads = 0;
    browser.listeners.push((message) => {
      if (message.sessionId !== sessionId) return;
      if (message.method === 'Runtime.consoleAPICalled')
        this.console.push(message.params.args.map((a) => a.value ?? a.description).join(' '));
      else if (message.method === 'Runtime.exceptionThrown')
        this.console.push('exception: ' + message.params.exceptionDetails.exception?.description);
      else if (message.method === 'Page.loadEventFired')
        ++this.loads;
    });
  }

  send(method, params = {}) { return this.browser.send(method, params, this.sessionId); }

  async navigate(url) {
    const before = this.loads;
    await this.send('Page.navigate', {url});
    await this.until(() => this.loads > before, 60000, 'the page to load');
  }

  async reload() {
    const before = this.loads;
    await this.send('Page.reload', {ignoreCache: false});
    await this.until(() => this.loads > before, 60000, 'the page to reload');
  }

  // The expression's value (awaited when it is a promise); throws the page's exception, or
  // after `timeoutMs` when the page does not answer (a page stopped in a draw never does).
  async evaluate(expression, timeoutMs = 120000) {
    let timer;
    const r = await Promise.race([
      this.send('Runtime.evaluate', {expression, awaitPromise: true, returnByValue: true}),
      new Promise((resolve, reject) => {
        timer = setTimeout(() => reject(new Error(
            `the page did not answer in ${timeoutMs} ms: ${expression.slice(0, 80)}`)), timeoutMs);
      })]).finally(() => clearTimeout(timer));
    if (r.exceptionDetails)
      throw new Error(`${expression}: ${r.exceptionDetails.exception?.description ??
                      r.exceptionDetails.text}`);
    return r.result.value;
  }

  // Polls `test` (a function, or an expression evaluated in the page) until it is true.
  async until(test, timeoutMs, what) {
    const start = Date.now();
    for (;;) {
      const value = typeof test === 'function' ? await test() : await this.evaluate(test);
      if (value) return value;
      if (Date.now() - start > timeoutMs)
        throw new Error(`waited ${timeoutMs} ms for ${what}; the page's console:\n` +
                        this.console.slice(-20).join('\n'));
      await sleep(50);
    }
  }

  // Whether the page's thread answers within `ms` (a page stopped in a draw or a loop does not).
  async answers(ms) {
    const answer = this.send('Runtime.evaluate', {expression: '1', returnByValue: true})
        .then(() => true, () => false);
    return Promise.race([answer, sleep(ms).then(() => false)]);
  }

  // The tab closed by force, as the browser's "Page unresponsive: exit page" does (its thread
  // may not answer).
  async close() {
    await Promise.race([this.browser.send('Target.closeTarget', {targetId: this.targetId}),
                        sleep(5000)]).catch(() => {});
  }

  // The page's size (the window's, as a laptop's screen gives it).
  async resize(width, height) {
    await this.send('Emulation.setDeviceMetricsOverride',
                    {width, height, deviceScaleFactor: 1, mobile: false});
  }

  // A click of the left button at (x, y).
  async click(x, y) {
    for (const type of ['mousePressed', 'mouseReleased'])
      await this.send('Input.dispatchMouseEvent',
                      {type, x, y, button: 'left', buttons: type === 'mousePressed' ? 1 : 0,
                       clickCount: 1});
  }

  async screenshot(file) {
    const {data} = await this.send('Page.captureScreenshot', {format: 'png'});
    fs.writeFileSync(file, Buffer.from(data, 'base64'));
  }

  // Typing, as a keyboard would (one input event for the text).
  async type(text) { await this.send('Input.insertText', {text}); }

  // A drag of the left button in `steps` moves; `afterMove(i)`, if given, runs after each.
  async drag(from, to, steps, afterMove = null) {
    const move = (type, x, y, buttons) => this.send('Input.dispatchMouseEvent',
        {type, x, y, button: 'left', buttons, clickCount: type === 'mouseMoved' ? 0 : 1});
    await move('mousePressed', from.x, from.y, 1);
    for (let i = 1; i <= steps; ++i) {
      await move('mouseMoved', from.x + (to.x - from.x) * i / steps,
                 from.y + (to.y - from.y) * i / steps, 1);
      if (afterMove) await afterMove(i);
    }
    await move('mouseReleased', to.x, to.y, 0);
  }
}
