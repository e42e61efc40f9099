// Where a frame's time goes while orbiting: node --experimental-websocket orbit_probe.mjs SITE STEP
import path from 'node:path';
import {Chromium, serve} from './chromium.mjs';
import {labPage} from './lab_page.mjs';

const [site, step = 'ndf'] = process.argv.slice(2);
const server = await serve(path.resolve(site));
const browser = await Chromium.launch('/tmp/op/profile');
const page = await browser.newPage();
const {settledOn} = labPage(page);
await page.navigate(`http://127.0.0.1:${server.address().port}/index.html?step=${step}&view=solution`);
await page.until(() => settledOn(step), 120000, 'settle');
await page.evaluate(`(() => {
  window.probe = {busy: [], gaps: [], last: 0};
  const raf = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (cb) => raf((t) => {
    const s = performance.now();
    if (probe.last) probe.gaps.push(s - probe.last);
    probe.last = s;
    cb(t);
    probe.busy.push(performance.now() - s);
  });
  return true;
})()`);
const view = await page.evaluate(`pbrlabPage.viewCentre()`);
for (let run = 0; run < 2; ++run) {
  await page.evaluate(`probe.busy = []; probe.gaps = []; probe.last = 0; true`);
  await page.evaluate(`pbrlabPage.countFrames(true)`);
  const start = Date.now();
  await page.drag(view, {x: view.x + 200, y: view.y + 40}, 60);
  const frames = await page.evaluate(`pbrlabPage.countFrames(false)`);
  const ms = Date.now() - start;
  const p = JSON.parse(await page.evaluate(`JSON.stringify(probe)`));
  const med = (a) => a.slice().sort((x, y) => x - y)[Math.floor(a.length / 2)]?.toFixed(1);
  console.log(`run ${run}: ${frames} frames in ${ms} ms = ${(frames / ms * 1000).toFixed(1)} fps; ` +
              `main-loop callback median ${med(p.busy)} ms (n ${p.busy.length}), gap between callbacks median ${med(p.gaps)} ms`);
  console.log('  status: ' + JSON.stringify((await labPage(page).status()).rows));
}
await browser.close();
server.close();
