// The page as a student uses it (issue 45), in headless Chromium:
//   watchdog  no file locks the student out: a frame or a grade that never comes back (loops
//             in GLSL, and hangs that need none: ?testHang, the page's test hook) is noticed,
//             the page recovers, and the next visit does not run the file until it is edited;
//   view      the student's picture by default once their file exists, the solution's a click
//             away, the view chosen kept per step across reloads;
//   newest    a file just written is graded before anything else, a visit regrades only the
//             files changed since their saved reports, a badge never shows an older file's
//             grade; the first estimator grade in a fresh page, measured;
//   story     the rows under the picture and the badge never disagree without a reason on
//             screen; a grade's message is its first sentence, the details folded;
//   laptop    at 1280x800 and 1366x768 nothing is cut: the steps fold into a line, the
//             editor wraps.
// Screenshots and figures.json go to --out.
//
// node --experimental-websocket web/test/page_test.mjs --site build-web/site --out DIR
//      [--pbrlab build/pbrlab] [--parts watchdog,view,newest,story,laptop]
// (--pbrlab: a loop that ends in the page is graded by the desktop too, the verdicts compared.)
import {execFileSync} from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';
import {labPage} from './lab_page.mjs';

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, word, i, all) => {
  if (word.startsWith('--')) pairs.push([word.slice(2), all[i + 1]]);
  return pairs;
}, []));
for (const required of ['site', 'out'])
  if (!args[required]) throw new Error(`--${required} is required (see the file's comment)`);
const parts = (args.parts ?? 'watchdog,view,newest,story,laptop').split(',');
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const out = path.resolve(args.out);
fs.rmSync(out, {recursive: true, force: true});
fs.mkdirSync(out, {recursive: true});

const failures = [];
const figures = {};
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures.push(what);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const read = (file) => fs.readFileSync(path.join(root, file), 'utf8');
const solution = read('labs/ndf/solution.glsl');
const missingPi = read('labs/ndf/mistakes/missing_pi.glsl');
// The solution with `loop` at the top of its body and `use` added to what it returns (so that
// no compiler drops the loop as dead code).
const withLoop = (loop, use = '') => solution
    .replace('// BEGIN SOLUTION', '// BEGIN SOLUTION\n    ' + loop)
    .replace('return a2 / (PI * d * d);', `return a2 / (PI * d * d)${use};`);

const server = await serve(path.resolve(args.site));
const base = `http://127.0.0.1:${server.address().port}/index.html`;
let profileCount = 0;
// A browser with a fresh profile (a student's first visit), or `profile` again (the next).
async function launch(profile = path.join(out, `profile-${++profileCount}`), size = {}) {
  const browser = await Chromium.launch(profile, size);
  return {browser, profile};
}
async function open(browser, query, size = {}) {
  const page = await browser.newPage(size);
  await page.navigate(`${base}?${query}`);
  const lab = labPage(page);
  await page.until(async () => (await lab.status()).step, 60000, 'the GUI to start');
  return {page, ...lab};
}
const shot = async (page, name) => {
  await page.screenshot(path.join(out, name));
  console.log(`     screenshot ${name}`);
};
// The status once `test` holds of it.
const statusWhen = (lab, test, ms, what) => lab.page.until(async () => {
  const s = await lab.status();
  return test(s) ? s : null;
}, ms, what);
const editorText = (page) => page.evaluate(`document.getElementById('source').value`);
const notice = (page) => page.evaluate(
    `document.getElementById('notice').hidden ? '' : document.getElementById('notice-text').textContent`);

// ---- watchdog ----
// After a hang and its recovery (the page reloaded itself, or the student opened it again):
// the page answers, says which file did not finish and why, does not run it (nor grade it),
// and runs it again once edited.
async function checkNotRun(lab, label, hook = '') {
  const {page} = lab;
  const s = await statusWhen(lab, (s) => s.step === 'ndf' && s.settled, 60000,
                             `${label}: ndf to settle after the hang`);
  const said = await notice(page);
  check(/^ndf\.glsl did not finish last time \(\d+ s\): a loop that never ends\? Edit it to run it again\.$/.test(said),
        `${label}: the page says which file did not finish and why ("${said}")`);
  check(/did not finish last time/.test(s.errorLog) && s.rows.length === 1,
        `${label}: the GUI does not run it: the picture is the solution's (${s.error} ` +
        `${s.errorLog.split('\n')[0]}; ${s.rows.length} row)`);
  const graded = await page.evaluate(`pbrlabPage.gradeTimes.filter((g) => g.step === 'ndf').length`);
  check(graded === 0 && /did not finish last time/.test(s.gradeMessage),
        `${label}: nor is it graded (${graded} grades; badge ${s.badge}: ${s.gradeMessage})`);
  await shot(page, `${label}-not-run.png`);
  // Edited (the hook's word gone, or a loop that ends): it runs, and is graded.
  await lab.typeFile(solution + `\n// edited after the hang ${hook}\n`);
  const ran = await statusWhen(lab, (s) => s.step === 'ndf' && s.settled && s.rows.length === 2 &&
                                            s.badge === 'passes', 120000,
                               `${label}: the edited file to run and pass`);
  check(ran.rows[0].ok && (await notice(page)) === '',
        `${label}: edited, the file runs and is graded again (${ran.rows[0].text}; badge ${ran.badge})`);
}

async function watchdog() {
  // 1. The GUI's frame never comes back (the page's thread stopped where it runs the file,
  // after the page noted it), then the student closes the tab and opens the site again; the
  // hook is still on in the new tab, so a page that ran the file would stop again.
  {
    const {browser} = await launch();
    let lab = await open(browser, 'step=ndf&testHang=frame');
    await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
    await lab.typeFile(solution + '\n// PBRLAB_TEST_HANG\n');
    const stopped = await lab.page.until(async () => !(await lab.page.answers(3000)), 30000,
                                         'the page to stop (the test hook)').catch(() => false);
    check(stopped, 'frame hang: the page stops where the GUI runs the file (the test hook)');
    await sleep(3000);  // the student waits a little, then closes the tab
    await lab.page.close();
    lab = await open(browser, 'step=ndf&testHang=frame');
    check(await lab.page.answers(5000), 'frame hang: the site opens again after the tab was closed');
    check(await editorText(lab.page) === solution + '\n// PBRLAB_TEST_HANG\n',
          'frame hang: the file is kept as typed');
    await checkNotRun(lab, 'frame-hang');
    // A reload after all this: the file, edited, runs (the hung note is gone for good).
    await browser.close();
  }
  // 2. A grade that never comes back (the worker stopped: the test hook), under a 10 s limit:
  // the page answers throughout, the badge says the file did not finish, naming it, and the
  // grader is restarted for the next file.
  {
    const {browser} = await launch();
    const lab = await open(browser, 'step=ndf&testHang=grade&gradeLimit=10');
    await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
    await lab.typeFile(solution + '\n// PBRLAB_TEST_HANG\n');
    const start = Date.now();
    let answered = true;
    const s = await lab.page.until(async () => {
      answered = answered && await lab.page.answers(2000);
      const s = await lab.status();
      return s.badge === 'fails' ? s : null;
    }, 60000, 'the hung grade to be reported');
    figures.gradeHangReportedMs = Date.now() - start;
    check(answered, 'grade hang: the page answers while the grader is stuck');
    check(/^ndf\.glsl did not finish in 10 s \(the time limit\): a loop that never ends\?/.test(s.gradeMessage),
          `grade hang: the badge says the file did not finish, naming it, after ` +
          `${figures.gradeHangReportedMs} ms (${s.gradeMessage})`);
    await shot(lab.page, 'grade-hang.png');
    await lab.typeFile(solution);
    const again = await statusWhen(lab, (s) => s.badge === 'passes', 60000,
                                   'the next file to be graded by a new worker');
    check(again.badge === 'passes', 'grade hang: the grader restarted grades the next file');
    await browser.close();
  }
  // 3. Loops in GLSL that never end: the issue's and two more. With the loops bounded (the
  // preprocessor's guard), the page answers and the badge fails, naming the loop. Without,
  // the GPU never finishes the draw: the page stops, and a GPU's watchdog (simulated: the
  // headless browser's software GPU has none) resets it; the page reloads itself, or the
  // student closes the tab and opens the site again; either way the file is not run again
  // until edited.
  const loops = [
    ['the issue\'s', 'int i = 0; while (i >= 0) { i = (i + 1) & 0x3fffffff; }',
     ' + 1e-30 * float(i)', 'reload'],
    ['a float at its fixed point', 'float x = 1.0; int k = 0; while (x > 0.0) { x = x * 0.5 + 1e-30; k++; }',
     ' + 1e-30 * float(k)', 'close'],
    ['a power of 3 that never reaches 0', 'uint n = 1u; uint k = 0u; do { n = n * 3u; k++; } while (n != 0u);',
     ' + 1e-30 * float(k)', 'reload'],
  ];
  figures.loops = [];
  for (const [name, loop, use, after] of loops) {
    const label = `loop-${figures.loops.length + 1}`;
    // (Chromium blocks WebGL for a site whose pages caused GPU resets: a simulated watchdog
    // that resets it more than once would end there, which says nothing of the page.)
    const {browser, profile} = await launch(undefined,
                                            {flags: ['--disable-domain-blocking-for-3d-apis']});
    let lab = await open(browser, 'step=ndf');
    await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
    await lab.typeFile(withLoop(loop, use));
    await lab.page.evaluate(`pbrlabPage.flush()`);  // written now, not 0.3 s after the typing
    const start = Date.now();
    let stopped = false;
    let s = null;
    while (Date.now() - start < 90000) {
      if (!(await lab.page.answers(15000))) {
        stopped = true;
        break;
      }
      s = await lab.status();
      if (s.step === 'ndf' && s.settled && !['...', 'missing'].includes(s.badge)) break;
      await sleep(500);
    }
    figures.loops.push({name, stopped, ms: Date.now() - start});
    if (!stopped) {
      // Bounded: a verdict in bounded time, the desktop's (`pbrlab check` on the same file).
      let native = 'not checked (no --pbrlab)';
      if (args.pbrlab) {
        const dir = fs.mkdtempSync(path.join(out, 'loop-'));
        fs.writeFileSync(path.join(dir, 'ndf.glsl'), withLoop(loop, use));
        try {
          execFileSync(args.pbrlab, ['check', 'ndf', '--submission', dir, '--json',
                                     path.join(dir, 'r.json')], {stdio: 'ignore'});
        } catch {}  // exit 1: it failed, which the report says
        const report = JSON.parse(fs.readFileSync(path.join(dir, 'r.json'), 'utf8')).modules[0];
        native = `${report.status}: ${report.message}`;
      }
      // The same verdict and the same message (the guard's budget and the loop's line are the
      // desktop's: tests/test_loop_guard.cpp grades the page's GLSL ES natively too).
      const verdict = {passes: 'passed', fails: 'failed'}[s?.badge];
      check(s?.settled && verdict && (!args.pbrlab || native === `${verdict}: ${s.gradeMessage}`),
            `${label} (${name}): the page answers and grades it as the desktop does ` +
            `(${s?.badge}: ${s?.gradeMessage?.slice(0, 160)}; desktop ${native.slice(0, 170)})`);
      await shot(lab.page, `${label}-bounded.png`);
      await browser.close();
      continue;
    }
    check(true, `${label} (${name}): the page stopped in the draw after ${Date.now() - start} ms`);
    let resets = 0;
    if (after === 'close') {
      // The student closes the stuck tab; the GPU's watchdog resets the GPU meanwhile.
      await lab.page.close();
      await browser.crashGpu();
      ++resets;
      lab = await open(browser, 'step=ndf');
    } else {
      // The GPU's watchdog resets the GPU whenever a draw runs too long (here: the page has
      // not answered for 10 s): the page loses its context and reloads itself; lost twice
      // within a minute, it asks the student to reload, who does.
      const loads = lab.page.loads;
      await browser.crashGpu();
      ++resets;
      const deadline = Date.now() + 240000;
      for (;;) {
        if (Date.now() > deadline) throw new Error(`${label}: the page did not come back`);
        await sleep(2000);
        if (!(await lab.page.answers(10000))) {
          await browser.crashGpu();
          ++resets;
          continue;
        }
        const said = await lab.page.evaluate(
            `(typeof pbrlabPage === 'object' && pbrlabPage.running ? JSON.parse(pbrlabPage.status()).step : '') +
             '|' + (document.getElementById('notice-text')?.textContent ?? '')`, 10000)
            .catch(() => '|');  // (stopped meanwhile: the next round resets the GPU)
        if (lab.page.loads > loads && (said.split('|')[0] || /twice/.test(said))) break;
      }
      const said = await notice(lab.page);
      if (/twice within a minute/.test(said)) {
        check(/^The page lost its GPU while running ndf\.glsl/.test(said),
              `${label}: lost twice, the page asks for a reload, naming the file ("${said}")`);
        await shot(lab.page, `${label}-lost-twice.png`);
        await lab.page.reload();
        await lab.page.until(async () => (await lab.status()).step, 60000, 'the GUI to start again');
      }
    }
    figures.loops.at(-1).gpuResets = resets;
    await checkNotRun(lab, label);
    await browser.close();
    // The browser closed and opened again: the edited file stays run, nothing is refused.
    const again = await launch(profile);
    lab = await open(again.browser, 'step=ndf');
    s = await statusWhen(lab, (s) => s.settled && s.rows.length === 2, 120000, 'ndf to settle');
    check(s.rows[0].ok && (await notice(lab.page)) === '',
          `${label}: the next visit runs the edited file (${s.rows[0].text})`);
    await again.browser.close();
  }
}

// ---- view ----
async function view() {
  const {browser} = await launch();
  let lab = await open(browser, 'step=ndf');
  let s = await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
  check(s.view === 'solution', `no file yet: the solution's picture (${s.view})`);
  await lab.typeFile(missingPi);
  s = await statusWhen(lab, (s) => s.view === 'student', 20000,
                       'the student\'s picture once their file exists').catch(() => lab.status());
  check(s.view === 'student', `the student's file written: their picture (${s.view})`);
  s = await statusWhen(lab, (s) => s.settled && s.rows.length === 2, 60000, 'ndf to settle');
  await shot(lab.page, 'view-student-default.png');
  await lab.page.reload();
  await lab.page.until(async () => (await lab.status()).step, 60000, 'the GUI to start again');
  s = await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
  check(s.view === 'student', `after a reload: still the student's picture (${s.view})`);
  // One click: the button beside the view chooser.
  const [x, y, w, h] = s.layout.viewToggle;
  await lab.page.click(x + w / 2, y + h / 2);
  s = await statusWhen(lab, (s) => s.view === 'solution', 5000, 'one click to the solution')
      .catch(() => lab.status());
  check(s.view === 'solution', `one click shows the solution's picture (${s.view})`);
  await lab.page.reload();
  await lab.page.until(async () => (await lab.status()).step, 60000, 'the GUI to start again');
  s = await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
  check(s.step === 'ndf' && s.view === 'solution',
        `after a reload: the step and the view chosen for it are kept (${s.step}, ${s.view})`);
  // Another step keeps its own: no file, the solution's; its file written, the student's.
  await lab.page.evaluate(`pbrlabPage.console('step fresnel')`);
  s = await statusWhen(lab, (s) => s.step === 'fresnel' && s.settled, 60000, 'fresnel to settle');
  check(s.view === 'solution', `fresnel, no file: the solution's picture (${s.view})`);
  await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'fresnel'`), 10000, 'the editor');
  await lab.typeFile(read('labs/fresnel/solution.glsl'));
  s = await statusWhen(lab, (s) => s.view === 'student', 20000, 'fresnel\'s student view')
      .catch(() => lab.status());
  check(s.view === 'student', `fresnel's file written: the student's picture (${s.view})`);
  await lab.page.evaluate(`pbrlabPage.console('step ndf')`);
  s = await statusWhen(lab, (s) => s.step === 'ndf' && s.settled, 60000, 'ndf to settle');
  check(s.view === 'solution', `back on ndf: the view chosen for it (${s.view})`);
  await browser.close();
}

// ---- newest ----
// Files written into the workspace as an earlier visit (or another tab) left them: in
// /work and saved, not graded by this page.
const writeQuietly = (page, files) => page.evaluate(`new Promise((resolve) => {
  for (const [name, text] of Object.entries(${JSON.stringify(files)})) FS.writeFile('/work/' + name, text);
  FS.syncfs(false, () => resolve(true));
})`);
const gradesOf = (page) => page.evaluate(`pbrlabPage.gradeTimes`);

async function newest() {
  const {browser} = await launch();
  let lab = await open(browser, 'step=ndf');
  await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
  // The estimator's first grade in a fresh page (its worker's first: nothing drawn or summed
  // before), the student's file typed on its step.
  await lab.page.evaluate(`pbrlabPage.console('step prefilter')`);
  await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'prefilter'`), 60000, 'prefilter');
  let start = Date.now();
  await lab.typeFile(read('labs/prefilter/solution.glsl'));
  let s = await statusWhen(lab, (s) => s.step === 'prefilter' && s.badge === 'passes', 240000,
                           'prefilter\'s first badge');
  figures.firstPrefilterBadgeMs = Date.now() - start;
  // The grade that computed the converged integrals (a fresh browser has none); a later grade
  // in the same worker reads them from its memory, whatever the page sent it first.
  const prefilterGrades = (await gradesOf(lab.page)).filter((g) => g.step === 'prefilter');
  const first = prefilterGrades.find((g) => g.converged?.computed > 0);
  figures.firstPrefilterGradeMs = Math.round(first?.ms ?? -1);
  figures.firstPrefilterConvergedComputed = first?.converged.computed ?? 0;
  check(first !== undefined,
        `the first prefilter grade in a fresh page computes the converged integrals ` +
        `(${figures.firstPrefilterConvergedComputed} of them, ${figures.firstPrefilterGradeMs} ms ` +
        `in the worker; the badge ${figures.firstPrefilterBadgeMs} ms after typing; grades: ` +
        `${prefilterGrades.map((g) => `${Math.round(g.ms)} ms`).join(', ')})`);

  // A fix while the other steps are graded: the visit's badges grade prefilter, mc_specular
  // and irradiance (changed since their reports: none saved), and the student, on ndf with
  // a file that does not compile, types the fix at once.
  await lab.page.evaluate(`pbrlabPage.console('step ndf')`);
  await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'ndf'`), 60000, 'ndf');
  await lab.typeFile(solution.replace('return', 'retrun'));
  await statusWhen(lab, (s) => s.step === 'ndf' && s.badge === 'compile error', 60000,
                   'ndf\'s compile error');
  await writeQuietly(lab.page, {
    'prefilter.glsl': read('labs/prefilter/solution.glsl') + '\n// another version\n',
    'mc_specular.glsl': read('labs/mc_specular/solution.glsl'),
    'irradiance.glsl': read('labs/irradiance/solution.glsl')});
  await lab.page.reload();
  await lab.page.until(async () => (await lab.status()).step === 'ndf', 60000, 'the GUI again');
  await lab.page.until(() => lab.page.evaluate(
      `Object.values(pbrlabPage.graders).some((g) => g.job && g.job.step !== 'ndf')`), 60000,
      'another step\'s grade to start');
  await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'ndf'`), 10000, 'the editor');
  const typedAt = await lab.page.evaluate('performance.now()');
  start = Date.now();
  await lab.typeFile(solution);
  await lab.page.evaluate(`pbrlabPage.flush()`);
  await sleep(100);  // the GUI's next frame has seen the file
  const seen = new Set();
  s = await lab.page.until(async () => {
    const s = await lab.status();
    seen.add(s.badge);
    return s.badge === 'passes' ? s : null;
  }, 120000, 'the fix\'s badge');
  figures.fixBadgeMs = Date.now() - start;
  const grades = await gradesOf(lab.page);
  const fix = grades.find((g) => g.step === 'ndf' && g.sentAt > typedAt);
  const others = grades.filter((g) => g.step !== 'ndf');
  const pending = await lab.page.evaluate(`[...Object.values(pbrlabPage.graders).map((g) => g.job?.step),
                                              ...pbrlabPage.queue.map((j) => j.step)].filter((s) => s)`);
  check(fix && figures.fixBadgeMs < 15000 && (pending.length > 0 ||
                                              others.some((g) => g.answeredAt > fix.answeredAt)),
        `a fix is graded before the visit's other grades: its badge in ${figures.fixBadgeMs} ms, ` +
        `graded by "${fix?.worker}" while ${pending.join(', ') || 'nothing'} waited or ran ` +
        `(others answered: ${others.map((g) => g.step).join(', ')})`);
  check(!seen.has('compile error'),
        `the badge never showed the older file's grade while the fix waited (seen: ${[...seen].join(', ')})`);
  await shot(lab.page, 'newest-fix.png');
  await lab.page.until(
      `Object.values(pbrlabPage.graders).every((g) => !g.job) && pbrlabPage.queue.length === 0`,
      300000, 'every grade to finish');
  // prefilter's grade in this second page (another version of its file): the converged
  // integrals its first grade computed come from IndexedDB (web/grader_worker.js), none is
  // computed again. Checked by what the worker did, not by the times (a slower machine
  // shifts them); the times are figures.
  const again = (await gradesOf(lab.page)).find((g) => g.step === 'prefilter');
  figures.secondPagePrefilterGradeMs = Math.round(again?.ms ?? -1);
  check(again?.converged?.computed === 0 &&
            again.converged.restored >= figures.firstPrefilterConvergedComputed,
        `the next page's first prefilter grade reads the converged integrals from IndexedDB ` +
        `(computed ${again?.converged?.computed}, the worker restored ` +
        `${again?.converged?.restored} files; ${figures.secondPagePrefilterGradeMs} ms in the ` +
        `worker, the first page's ${figures.firstPrefilterGradeMs} ms)`);
  // The next visit: nothing changed, nothing graded; the badges are the saved reports.
  await lab.page.reload();
  await lab.page.until(async () => (await lab.status()).step === 'ndf', 60000, 'the GUI again');
  s = await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
  await sleep(3000);
  let after = await gradesOf(lab.page);
  check(after.length === 0 && s.badge === 'passes',
        `a visit with nothing changed grades nothing (${after.map((g) => g.step).join(', ') || 'none'}), ` +
        `the badges from the saved reports (ndf ${s.badge})`);
  // One file changed since: that one alone is graded.
  await writeQuietly(lab.page, {'irradiance.glsl': read('labs/irradiance/solution.glsl') + '\n// changed\n'});
  await lab.page.reload();
  await lab.page.until(async () => (await lab.status()).step === 'ndf', 60000, 'the GUI again');
  await lab.page.until(() => lab.page.evaluate(
      `pbrlabPage.gradeTimes.length > 0 && Object.values(pbrlabPage.graders).every((g) => !g.job)`),
      240000, 'the changed file\'s grade');
  await sleep(2000);
  after = await gradesOf(lab.page);
  check(after.length === 1 && after[0].step === 'irradiance',
        `a visit after one file changed grades that one (${after.map((g) => g.step).join(', ')})`);
  await browser.close();
}

// ---- story ----
async function story() {
  const {browser} = await launch();
  const lab = await open(browser, 'step=prefilter');
  await statusWhen(lab, (s) => s.settled, 120000, 'prefilter to settle');
  await lab.typeFile(read('labs/prefilter/solution.glsl'));
  let s = await statusWhen(lab, (s) => s.settled && s.rows.length === 2 && s.badge === 'passes',
                           240000, 'prefilter\'s solution graded');
  const outside = s.rows.filter((r) => !r.ok).length;
  check(outside === 0 || /solution's own picture is outside the band on this GPU.*the badge is the grade/.test(s.bandNote),
        `prefilter: rows outside the band (${outside}) beside a badge that passes say why on ` +
        `screen ("${s.bandNote}")`);
  await shot(lab.page, 'story-prefilter-rows.png');
  await lab.page.evaluate(`pbrlabPage.console('step ndf')`);
  await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'ndf'`), 60000, 'ndf');
  await lab.typeFile(missingPi);
  s = await statusWhen(lab, (s) => s.step === 'ndf' && s.settled && s.badge === 'fails', 120000,
                       'ndf without its pi graded');
  check(/^grade: [^\n]{10,160}[.?!]$/.test(s.grade) && !/ It matches /.test(s.grade) &&
            s.gradeDetails.length > 40 && s.gradeMessage.startsWith(s.grade.slice(7)),
        `a grade's message is one short first line ("${s.grade}"), the details folded ` +
        `(${s.gradeDetails.length} characters)`);
  await shot(lab.page, 'story-grade-folded.png');
  await browser.close();
}

// ---- laptop ----
async function laptop() {
  for (const [width, height] of [[1280, 800], [1366, 768]]) {
    const {browser} = await launch(undefined, {width, height});
    const lab = await open(browser, 'step=ndf', {width, height});
    await statusWhen(lab, (s) => s.settled, 60000, 'ndf to settle');
    await lab.typeFile(missingPi);
    const s = await statusWhen(lab, (s) => s.settled && s.badge === 'fails' && s.rows.length === 2,
                               120000, 'ndf graded');
    const l = s.layout;
    check(l.compact && l.steps === 0 && l.view >= 500 && l.pictureSide >= 400,
          `${width}x${height}: the steps fold into a line; the picture's window ${l.view} ` +
          `pixels wide, the picture ${l.pictureSide}`);
    // The editor: no line runs off its edge (they wrap), its buttons all in view.
    const editor = await lab.page.evaluate(`(() => {
      const e = document.getElementById('source');
      const buttons = [...document.querySelectorAll('#editor header button, #editor header label')]
          .map((b) => b.getBoundingClientRect());
      const header = document.querySelector('#editor header').getBoundingClientRect();
      return {scroll: e.scrollWidth, client: e.clientWidth,
              buttonsInView: buttons.every((r) => r.right <= header.right + 0.5 && r.bottom <= header.bottom + 0.5),
              wraps: getComputedStyle(e).whiteSpace, width: e.getBoundingClientRect().width};
    })()`);
    check(editor.scroll <= editor.client && editor.wraps === 'pre-wrap' && editor.buttonsInView,
          `${width}x${height}: the editor (${editor.width} pixels) wraps its lines ` +
          `(${editor.scroll} <= ${editor.client}) and shows its buttons`);
    await shot(lab.page, `laptop-${width}x${height}.png`);
    // The step with the longest file name: the editor's buttons stay on one line.
    await lab.page.evaluate(`pbrlabPage.console('step mc_specular')`);
    await lab.page.until(() => lab.page.evaluate(`pbrlabPage.step === 'mc_specular'`), 60000,
                         'the editor on mc_specular');
    const heights = await lab.page.evaluate(
        `[...document.querySelectorAll('#editor header button, #editor header label')]
             .map((b) => b.getBoundingClientRect().height)`);
    check(heights.every((h) => h < 24), `${width}x${height}: mc_specular.glsl's buttons on one ` +
          `line each (heights ${heights.join(', ')})`);
    // Its name whole (the header gives the buttons a second line rather than cut the name).
    const name = await lab.page.evaluate(`(() => {
      const f = document.getElementById('file');
      return {text: f.textContent, scroll: f.scrollWidth, client: f.clientWidth};
    })()`);
    check(name.text === 'mc_specular.glsl' && name.scroll <= name.client,
          `${width}x${height}: the file's name is whole ("${name.text}", ${name.scroll} <= ` +
          `${name.client} pixels)`);
    await browser.close();
  }
}

const all = {watchdog, view, newest, story, laptop};
for (const part of parts) {
  try {
    await all[part]();
  } catch (e) {
    check(false, `${part}: ${e.message ?? e}`);
  }
}
fs.writeFileSync(path.join(out, 'figures.json'), JSON.stringify(figures, null, 2));
server.close();
console.log(`figures: ${path.join(out, 'figures.json')}`);
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
process.exit(0);
