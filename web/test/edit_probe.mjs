// What a student's edit costs in the page (docs/web.md, "The badge in the page"): ndf's
// editor typed over with a correct and a wrong file in turn, and for each edit the time to
// the status under the picture, to the badge, and the grade the badge took (sent, its time in
// the worker, answered), from the edit; then the medians and ranges.
//   node --experimental-websocket web/test/edit_probe.mjs --site build-web/site [--edits 10]
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
const edits = Number(args.edits ?? 10);
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const files = [fs.readFileSync(path.join(root, 'labs/ndf/solution.glsl'), 'utf8'),
               fs.readFileSync(path.join(root, 'labs/ndf/mistakes/missing_pi.glsl'), 'utf8')];
const server = await serve(path.resolve(args.site));
const browser = await Chromium.launch(fs.mkdtempSync(path.join(os.tmpdir(), 'pbrlab-edit-')));
const page = await browser.newPage();
const {settledOn, status, typeFile} = labPage(page);
await page.navigate(`http://127.0.0.1:${server.address().port}/index.html?step=ndf&view=student`);
await page.until(() => settledOn('ndf'), 120000, 'ndf to settle');
// The grader's first grade (the file in the editor, once the picture has settled) done.
await page.until(() => page.evaluate(`pbrlabPage.gradeTimes.length > 0 && Object.values(pbrlabPage.graders).every((g) => !g.job)`),
                 120000, 'the grader to warm up');
// --idle-grades N: first N grades of new files with the window idle (posted to the page's grader
// without writing them: no evaluation beside them), for what a grade costs beside the page alone.
for (let i = 0; i < Number(args['idle-grades'] ?? 0); ++i) {
  const posted = JSON.stringify({'ndf.glsl': files[i % 2] + `// idle ${i + 1}\n`});
  const before = await page.evaluate('pbrlabPage.gradeTimes.length');
  await page.evaluate(`pbrlabPage.request('ndf', ${posted}); true`);
  const grade = await page.until(
      () => page.evaluate(`pbrlabPage.gradeTimes[${before}] ?? null`), 60000, 'an idle grade');
  console.log(`idle grade ${i + 1}: ${Math.round(grade.ms)} ms in the worker`);
}
const rows = [];
for (let edit = 0; edit < edits; ++edit) {
  const ok = edit % 2 === 0;
  await new Promise((resolve) => setTimeout(resolve, 1000));
  const start = Date.now();
  const typedAt = await page.evaluate('performance.now()');
  await typeFile(files[edit % 2] + `// edit ${edit + 1}\n`);  // a new file: graded anew
  const seen = {};
  await page.until(async () => {
    const s = await status();
    if (seen.status === undefined && s.rows?.length === 2 && s.rows[0].ok === ok)
      seen.status = Date.now() - start;
    if (seen.badge === undefined && s.badge === (ok ? 'passes' : 'fails'))
      seen.badge = Date.now() - start;
    return seen.status !== undefined && seen.badge !== undefined && s.settled;
  }, 120000, `edit ${edit + 1}`);
  const grade = (await page.evaluate(`pbrlabPage.gradeTimes`)).find((g) => g.sentAt > typedAt);
  rows.push({...seen, sent: Math.round(grade.sentAt - typedAt), worker: Math.round(grade.ms),
             answered: Math.round(grade.answeredAt - typedAt)});
  console.log(`edit ${edit + 1} (${ok ? 'correct' : 'wrong'}): status ${seen.status} ms, ` +
              `badge ${seen.badge} ms; grade sent ${rows.at(-1).sent}, ` +
              `${rows.at(-1).worker} ms in the worker, answered ${rows.at(-1).answered}`);
}
for (const key of ['status', 'badge', 'worker']) {
  const v = rows.map((r) => r[key]).sort((a, b) => a - b);
  console.log(`${key}: ${v[0]}-${v.at(-1)} ms, median ${v[Math.floor(v.length / 2)]} ms`);
}
await browser.close();
server.close();
