// Where a grade's time goes in the page's grader (docs/web.md, "The badge in the page"): the
// page's worker (web/grader_worker.js) grades one file of a step several times in a row, and
// the probe prints each grade's time and what the grader's journal says it did, with times.
//   node --experimental-websocket web/test/grade_probe.mjs --site build-web/site \
//       [--step ndf] [--file labs/ndf/solution.glsl] [--runs 3] [--first FILE] [--edits 1]
// (--first: a grade of another file of the step before them, in the same worker: what a
// worker's first grade costs, or what one grade leaves to the next.)
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, word, i, all) => {
  if (word.startsWith('--')) pairs.push([word.slice(2), all[i + 1]]);
  return pairs;
}, []));
if (!args.site) throw new Error('--site is required (see the file\'s comment)');
const step = args.step ?? 'ndf';
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const file = fs.readFileSync(path.resolve(root, args.file ?? `labs/${step}/solution.glsl`), 'utf8');
const runs = Number(args.runs ?? 3);
const server = await serve(path.resolve(args.site));
const browser = await Chromium.launch(fs.mkdtempSync(path.join(os.tmpdir(), 'pbrlab-grade-')));
const page = await browser.newPage();
await page.navigate(`http://127.0.0.1:${server.address().port}/grader_worker.js`);
const files = JSON.stringify({[`${step}.glsl`]: file});
await page.evaluate(`(() => {
  window.grader = new Worker('grader_worker.js');
  window.answers = [];
  window.naming = null;  // when the grade said the file fails (its feedback started)
  grader.onmessage = (e) => {
    if (e.data.namingTheMistake) naming = performance.now();
    else answers.push({...e.data, naming});
  };
  return true;
})()`);
const grades = [];
if (args.first) {
  const first = fs.readFileSync(path.resolve(root, args.first), 'utf8');
  grades.push([step, JSON.stringify({[`${step}.glsl`]: first})]);
}
// --edits: each grade's file differs by a comment, as a student's edits do (the file's
// programs compile again); without it the same text is graded each time.
for (let run = 0; run < runs; ++run)
  grades.push([step, args.edits ? JSON.stringify({[`${step}.glsl`]: file + `\n// edit ${run}\n`}) : files]);
let seen = 0;
for (const [run, [id, files]] of grades.entries()) {
  const start = Date.now();
  const posted = await page.evaluate(
      `naming = null; grader.postMessage({step: '${id}', files: ${files}, stats: true}); performance.now()`);
  const answer = await page.until(
      () => page.evaluate(`answers[${run}] ?? null`), 600000, `grade ${run + 1}`);
  const module = JSON.parse(answer.report).modules[0];
  console.log(`grade ${run + 1} (${id}): ${module.status}, ${answer.ms.toFixed(0)} ms in the worker, ` +
              `${Date.now() - start} ms posted to answered` +
              (answer.naming ? `, said it fails ${(answer.naming - posted).toFixed(0)} ms after posted` : '') +
              `; the worker's memory ${(answer.heapBytes / 2 ** 20).toFixed(0)} MB`);
  console.log(answer.journal.slice(seen).split('\n').filter((l) => l).map((l) => '  ' + l)
                  .join('\n'));
  seen = answer.journal.length;
}
await browser.close();
server.close();
