// An assignment's site in a real browser (docs/web.md, "A site for an assignment"): the site
// built from `pbrlab kit --assignment A --site-steps` must
//   1. carry no line of a withheld step's reference solution (nor its planted mistakes) in any
//      file the browser downloads, where the complete site carries every one of those lines;
//   2. start the editor from the kit's starter file, show the CPU reference as the solution,
//      and put the starter's picture outside the band and a correct file within it;
//   3. show, as the solution picture, the CPU reference, which matches the desktop's render.
//
// node --experimental-websocket web/test/assignment_test.mjs --site B/assignment-site \
//      --full-site B/site --steps-dir B/assignment-steps --pbrlab build/pbrlab --out DIR
import {execFileSync} from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';
import {labPage} from './lab_page.mjs';
import {comparePictures, decodePng} from './png.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, word, i, all) => {
  if (word.startsWith('--')) pairs.push([word.slice(2), all[i + 1]]);
  return pairs;
}, []));
for (const required of ['site', 'full-site', 'steps-dir', 'pbrlab', 'out'])
  if (!args[required]) throw new Error(`--${required} is required (see the file's comment)`);
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const out = path.resolve(args.out);
fs.rmSync(out, {recursive: true, force: true});
fs.mkdirSync(out, {recursive: true});

const failures = [];
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}

// 1. What the browser downloads. A withheld step's folder holds starter.glsl.
const withheld = fs.readdirSync(args['steps-dir'])
    .filter((id) => fs.existsSync(path.join(args['steps-dir'], id, 'starter.glsl')));
check(withheld.length > 0, `the assignment withholds solutions (${withheld.join(', ')})`);
const siteText = (dir) => fs.readdirSync(dir).map((f) => fs.readFileSync(path.join(dir, f), 'latin1'))
    .join('\n');
const site = siteText(args.site), full = siteText(args['full-site']);
// The lines of code of a file (the solution's, or a planted mistake's) that would give the
// answer away: not in what every site and kit gives out (the starter, the step's handout, the
// host's shaders: shaders/ibl/lut_quadrature.frag has "float a = roughness * roughness;", and
// specular's handout shows its return line). Short lines ("}", "return x;") say nothing.
const textOf = (dir) => fs.readdirSync(dir, {recursive: true})
    .filter((f) => fs.statSync(path.join(dir, f)).isFile())
    .map((f) => fs.readFileSync(path.join(dir, f), 'utf8')).join('\n');
const hostShaders = textOf(path.join(root, 'shaders'));
const answerLines = (file, givenOut) => fs.readFileSync(file, 'utf8').split('\n')
    .map((l) => l.trim())
    .filter((l) => l.length >= 16 && !l.startsWith('//') && !givenOut.includes(l));
for (const id of withheld) {
  const starter = fs.readFileSync(path.join(args['steps-dir'], id, 'starter.glsl'), 'utf8');
  const handout = path.join(args['steps-dir'], id, 'README.md');
  const givenOut = starter + hostShaders + (fs.existsSync(handout) ? fs.readFileSync(handout) : '');
  const files = [path.join(root, 'labs', id, 'solution.glsl')];
  const mistakes = path.join(root, 'labs', id, 'mistakes');
  if (fs.existsSync(mistakes))
    for (const f of fs.readdirSync(mistakes)) files.push(path.join(mistakes, f));
  const lines = [...new Set(files.flatMap((f) => answerLines(f, givenOut)))];
  const inFull = lines.filter((l) => full.includes(l));
  const inSite = lines.filter((l) => site.includes(l));
  // The complete site carries them: the search would find them.
  check(lines.length > 0 && inFull.length === lines.length,
        `${id}: the complete site carries all ${lines.length} lines of its solution and ` +
        `mistakes (${inFull.length} found)`);
  check(inSite.length === 0, `${id}: the assignment's site carries none of them` +
        (inSite.length ? ` (found: ${inSite.slice(0, 3).join(' | ')})` : ''));
  check(!site.includes(`labs/${id}/solution.glsl`) && !site.includes(`labs/${id}/mistakes`),
        `${id}: no solution.glsl or mistakes/ in the site's file list`);
}

// 2 and 3. The page.
const server = await serve(path.resolve(args.site));
const base = `http://127.0.0.1:${server.address().port}/index.html`;
const browser = await Chromium.launch(path.join(out, 'profile'));
const page = await browser.newPage();
const {status, settledOn, typeFile, studentRows, readFile} = labPage(page);
const badge = (id, wanted) => page.until(async () => {
  const s = await status();
  return s.step === id && s.badge === wanted ? s : null;
}, 240000, `the badge of ${id} to say ${wanted}`);
try {
  const id = withheld.includes('ndf') ? 'ndf' : withheld[0];
  await page.navigate(`${base}?step=${id}&view=student`);
  await page.until(() => page.evaluate(`pbrlabPage.step === '${id}'`), 60000, `the editor on ${id}`);
  const starter = fs.readFileSync(path.join(args['steps-dir'], id, 'starter.glsl'), 'utf8');
  check(await page.evaluate(`document.getElementById('source').value`) === starter,
        `${id}: the editor starts from the kit's starter file`);
  let s = await page.until(() => settledOn(id), 120000, `${id} to settle`);
  check(s.rows.some((r) => /not in this site/.test(r.text)),
        `${id}: the solution row says the solution is not in the site ` +
        `(${s.rows.map((r) => r.text).join(' | ')})`);
  await page.screenshot(path.join(out, `${id}-starter.png`));

  await page.evaluate(`pbrlabPage.console('view solution')`);
  await page.until(() => settledOn(id), 60000, `${id} to settle`);
  const problem = await page.evaluate(`pbrlabPage.saveSolutionPicture('/tmp/${id}.png')`);
  check(problem === '', `${id}: the page saved its solution picture ${problem}`);
  if (!problem) {
    const bytes = await readFile(`/tmp/${id}.png`);
    fs.writeFileSync(path.join(out, `${id}-web.png`), bytes);
    const nativeFile = path.join(out, `${id}-native.png`);
    execFileSync(args.pbrlab, ['render', id, '--out', nativeFile], {stdio: 'ignore'});
    const c = comparePictures(decodePng(fs.readFileSync(nativeFile)), decodePng(bytes));
    check(c.passes, `${id}: the solution picture, the page's CPU reference, matches the ` +
          `desktop's render of the solution (${c.describe})`);
  }
  await page.screenshot(path.join(out, `${id}-solution-view.png`));

  await page.evaluate(`pbrlabPage.console('view student')`);
  const mistakes = path.join(root, 'labs', id, 'mistakes');
  const mistake = fs.readdirSync(mistakes).sort()[0];
  await typeFile(fs.readFileSync(path.join(mistakes, mistake), 'utf8'));
  s = await page.until(async () => {
    const s = await studentRows(id);
    return !s.rows[0].ok ? s : null;
  }, 120000, `${id}'s mistake ${mistake} to fall outside the band`);
  check(!s.rows[0].ok, `${id}: the planted mistake ${mistake} typed in the editor is outside ` +
        `the band (${s.rows[0].text})`);
  s = await badge(id, 'fails');
  check(true, `${id}: the page's grader fails the mistake without the solution in the site ` +
        `(${s.gradeMessage.slice(0, 160)})`);
  await page.screenshot(path.join(out, `${id}-mistake.png`));
  await typeFile(fs.readFileSync(path.join(root, 'labs', id, 'solution.glsl'), 'utf8'));
  s = await page.until(async () => {
    const s = await studentRows(id);
    return s.rows[0].ok ? s : null;
  }, 120000, `the correct ${id} to be within the band`);
  check(s.rows[0].ok, `${id}: a correct file typed in the editor is within the band ` +
        `(${s.rows[0].text})`);
  s = await badge(id, 'passes');
  check(true, `${id}: the page's grader passes the correct file without the solution in the site`);
  await page.screenshot(path.join(out, `${id}-correct.png`));
} catch (e) {
  check(false, String(e.message ?? e));
}
fs.writeFileSync(path.join(out, 'console.txt'), page.console.join('\n'));
await browser.close();
server.close();
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
