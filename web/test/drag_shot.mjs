// What the picture looks like while the mouse orbits the camera (docs/web.md, "Orbiting"): a
// screenshot of the page in the middle of a drag of ndf's picture, at the live side, and one
// once it has settled.
//   node --experimental-websocket web/test/drag_shot.mjs --site build-web/site --out DIR
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';
import {labPage} from './lab_page.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, word, i, all) => {
  if (word.startsWith('--')) pairs.push([word.slice(2), all[i + 1]]);
  return pairs;
}, []));
if (!args.site || !args.out) throw new Error('--site and --out are required (see the file\'s comment)');
fs.mkdirSync(args.out, {recursive: true});
const server = await serve(path.resolve(args.site));
const profileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'pbrlab-shot-'));
const browser = await Chromium.launch(profileDir);
const page = await browser.newPage();
const {settledOn, status} = labPage(page);
await page.navigate(`http://127.0.0.1:${server.address().port}/index.html?step=ndf&view=solution`);
await page.until(() => settledOn('ndf'), 120000, 'ndf to settle');
const view = await page.evaluate(`pbrlabPage.viewCentre()`);
let side = 0;
await page.drag(view, {x: view.x + 200, y: view.y + 40}, 60, async (i) => {
  if (i !== 40) return;
  side = (await status()).liveSide;
  await page.screenshot(path.join(args.out, 'dragging.png'));
});
await page.until(() => settledOn('ndf'), 120000, 'ndf to settle after the drag');
await page.screenshot(path.join(args.out, 'settled.png'));
console.log(`the live picture was ${side} pixels mid-drag; ${args.out}/dragging.png, settled.png`);
await browser.close();
server.close();
fs.rmSync(profileDir, {recursive: true, force: true});
