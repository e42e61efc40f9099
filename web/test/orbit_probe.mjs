// Where a frame's time goes while the mouse orbits the camera in the page (docs/web.md,
// "Orbiting"): three drags of the picture; for each, the frames drawn, the GUI's frame (the
// main loop's callback) and the time between frames, with the live picture's side and draw
// time under it; three drags grabbed again while the last release's evaluation may run (the
// time the page takes to answer); then a sampling profile of one more drag, the calls that
// wait on the GPU process (WebGL's getParameter, getError, readPixels, ...) with their
// callers.
//   node --experimental-websocket web/test/orbit_probe.mjs --site build-web/site [--step ndf]
//        [--wait 6000]
// (Function names in the wasm need the site linked with --profiling-funcs.)
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';
import {labPage} from './lab_page.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, word, i, all) => {
  if (word.startsWith('--')) pairs.push([word.slice(2), all[i + 1]]);
  return pairs;
}, []));
if (!args.site) throw new Error('--site is required (see the file\'s comment)');
const step = args.step ?? 'ndf';
const server = await serve(path.resolve(args.site));
const profileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'pbrlab-orbit-'));
const browser = await Chromium.launch(profileDir);
const page = await browser.newPage();
const {settledOn, status} = labPage(page);
await page.navigate(`http://127.0.0.1:${server.address().port}/index.html?step=${step}&view=solution`);
await page.until(() => settledOn(step), 120000, `${step} to settle`);
// --wait MS: the first drag after the grader has loaded and graded (it warms up once the first
// picture has settled, on the same cores), as a student's first drag usually is.
if (args.wait) {
  await new Promise((resolve) => setTimeout(resolve, Number(args.wait)));
  await page.until(() => settledOn(step), 120000, `${step} to settle`);
}
// The GUI's frames only (emscripten's main loop), not the page's frame counter's ticks.
await page.evaluate(`(() => {
  window.probe = {busy: [], gaps: [], last: 0};
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (cb) => cb.name === 'tick' ? raf(cb) : raf((t) => {
    const s = performance.now();
    if (probe.last) probe.gaps.push(s - probe.last);
    probe.last = s;
    cb(t);
    probe.busy.push(performance.now() - s);
  });
  return true;
})()`);
const view = await page.evaluate(`pbrlabPage.viewCentre()`);
const move = (type, x, y, buttons) => page.send('Input.dispatchMouseEvent',
    {type, x, y, button: 'left', buttons, clickCount: type === 'mouseMoved' ? 0 : 1});
const median = (a) => a.slice().sort((x, y) => x - y)[Math.floor(a.length / 2)]?.toFixed(1);
for (let run = 0; run < 3; ++run) {
  await page.evaluate(`probe.busy = []; probe.gaps = []; probe.last = 0; true`);
  const atPress = await status();
  await page.evaluate(`pbrlabPage.countFrames(true)`);
  const start = Date.now();
  const sides = [];
  await move('mousePressed', view.x, view.y, 1);
  for (let i = 1; i <= 60; ++i) {
    await move('mouseMoved', view.x + 200 * i / 60, view.y + 40 * i / 60, 1);
    if (i % 6 === 0) {
      const s = await status();
      sides.push(`${s.liveSide} px ${s.liveMs?.toFixed(1)} ms`);
    }
  }
  await move('mouseReleased', view.x + 200, view.y + 40, 0);
  const frames = await page.evaluate(`pbrlabPage.countFrames(false)`);
  const ms = Date.now() - start;
  const p = JSON.parse(await page.evaluate(`JSON.stringify(probe)`));
  console.log(`drag ${run}: ${frames} frames in ${ms} ms = ${(frames / ms * 1000).toFixed(1)} per ` +
              `second; the GUI's frame: median ${median(p.busy)} ms, between frames ` +
              `${median(p.gaps)} ms`);
  console.log(`  live picture (every 6th move): ${sides.join(', ')}`);
  const atRelease = await status();
  console.log(`  evaluations finished during the drag: ${atRelease.evaluations - atPress.evaluations}, ` +
              `given way to the press: ${atRelease.evaluationsYielded - atPress.evaluationsYielded}; ` +
              `the window's last frame drew ${(100 * atRelease.redraw.lastFraction).toFixed(1)}% of it`);
  console.log(`  the first 16 frames' intervals: ${p.gaps.slice(0, 16).map((g) => g.toFixed(0)).join(' ')} ms`);
}
// Grabbed again while the last release's evaluation may run (it starts about 0.25 s after the
// release and takes 1.1-1.4 s for ndf): from the press to the fifth move the page has taken
// (each dispatch returns once the page has handled the event), then the evaluation after the
// release settles.
for (const delay of [350, 600, 850]) {
  await page.until(() => settledOn(step), 120000, `${step} to settle`);
  const before = (await status()).evaluations;
  await page.drag(view, {x: view.x + 60, y: view.y}, 10);
  await new Promise((resolve) => setTimeout(resolve, delay));
  const start = Date.now();
  await move('mousePressed', view.x + 60, view.y, 1);
  for (let i = 1; i <= 5; ++i) await move('mouseMoved', view.x + 60 - 8 * i, view.y, 1);
  const grabbed = Date.now() - start;
  await move('mouseReleased', view.x + 20, view.y, 0);
  const settled = await page.until(() => settledOn(step), 120000, `${step} to settle`);
  console.log(`grabbed again ${delay} ms after a release: the fifth move taken after ${grabbed} ms; ` +
              `${settled.evaluations - before} evaluations finished since that release`);
}
await page.send('Profiler.enable');
await page.send('Profiler.setSamplingInterval', {interval: 200});
await page.send('Profiler.start');
await page.drag(view, {x: view.x + 200, y: view.y + 40}, 60);
const {profile} = await page.send('Profiler.stop');
const byId = new Map(profile.nodes.map((n) => [n.id, n]));
const parent = new Map();
for (const n of profile.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
const samples = new Map();
for (const s of profile.samples) samples.set(s, (samples.get(s) ?? 0) + 1);
const total = profile.samples.length;
const own = new Map(), waits = new Map();
const waiting = new Set(['getParameter', 'getError', 'readPixels', 'finish', 'checkFramebufferStatus',
                         'getProgramParameter', 'getShaderParameter', 'getUniformLocation']);
for (const [id, count] of samples) {
  const frame = byId.get(id).callFrame;
  own.set(frame.functionName || '(anonymous)', (own.get(frame.functionName || '(anonymous)') ?? 0) + count);
  if (!waiting.has(frame.functionName)) continue;
  const chain = [frame.functionName];
  for (let p = parent.get(id), k = 0; p && k < 6; p = parent.get(p), ++k)
    chain.push(byId.get(p).callFrame.functionName);
  waits.set(chain.join(' < '), (waits.get(chain.join(' < ')) ?? 0) + count);
}
const percent = (c) => (100 * c / total).toFixed(1).padStart(5) + '%';
console.log('the calls that wait on the GPU process, with their callers:');
for (const [chain, c] of [...waits].sort((a, b) => b[1] - a[1]).slice(0, 8)) console.log(`${percent(c)}  ${chain}`);
console.log('the main thread\'s own time:');
for (const [name, c] of [...own].sort((a, b) => b[1] - a[1]).slice(0, 8)) console.log(`${percent(c)}  ${name}`);
await browser.close();
server.close();
fs.rmSync(profileDir, {recursive: true, force: true});
