// The page's grader in a Web Worker (docs/web.md, "The badge in the page"): grader.js is the
// site's second program (core/host/web/grader.cpp), which grades a step as `pbrlab check`
// does in its own WebGL 2 context on an OffscreenCanvas. Each message {step, files} carries
// every file of the page's workspace (name -> text), and where the worker keeps what it
// computed once (store: the page's IndexedDB name; version: the site's); the files replace
// this worker's /work, and
// the answer {step, report} is the report `pbrlab check --json` writes; with {stats: true}
// also {journal}, what every grade so far compiled and checked, with times (--stats), and
// {heapBytes}, the program's memory (its in-memory files included). Before
// it, a grade whose file fails says {namingTheMistake: true} as its feedback starts; a grade
// during which the worker's WebGL context was lost (the GPU reset) answers {contextLost: true}
// instead of its report, which would judge the file by a lost context's zeros. Started as
// grader_worker.js?testHang=grade (the site's tests only), a grade of files holding the word
// PBRLAB_TEST_HANG never ends, as a draw that never finishes would not (shell.html's watchdog).
const testHang = new URLSearchParams(self.location.search).get('testHang') === 'grade';
let started;
const ready = new Promise((resolve) => { started = resolve; });
var Module = {
  print: (text) => console.log('grader: ' + text),
  printErr: (text) => console.warn('grader: ' + text),
  onRuntimeInitialized: () => started(),
};
// The site's data (the page's package: the browser fetched it for the page already).
importScripts('lab-data.js', 'grader.js');

// The converged integrals of the estimators' checks are seconds of work per environment
// (prefilter's first grade: about 17 of its 30 s, single-threaded here), and the same for
// every student's file: they are kept in IndexedDB under the site's version (a site built
// anew computes them anew: core/web/build_ids.cpp keys them by "this page's program"), so
// only the first grade of a step in a browser computes them, not the first of every page.
const convergedDir = '/home/web_user/.cache/pbrlab/converged';
const kept = new Set();  // the files of convergedDir that IndexedDB holds
let cacheDb = null;      // (null: a site without a version, or a browser without storage)
let cacheVersion = '';
let restoredCount = 0;   // the files restoreCache read back
function openCache(store, version) {
  return new Promise((resolve) => {
    if (!store || !version || version === 'unversioned' || typeof indexedDB === 'undefined')
      return resolve(null);
    const open = indexedDB.open(store + 'grader-cache', 1);
    open.onupgradeneeded = () => open.result.createObjectStore('converged');
    open.onsuccess = () => resolve(open.result);
    open.onerror = () => resolve(null);
  });
}
function transaction(mode, act) {
  return new Promise((resolve) => {
    const tx = cacheDb.transaction('converged', mode);
    const results = [];
    act(tx.objectStore('converged'), results);
    tx.oncomplete = () => resolve(results);
    tx.onerror = tx.onabort = () => resolve(results);
  });
}
// Once per worker: the files of this site's version into the program's cache folder; those
// of other versions are dropped.
async function restoreCache(store, version) {
  cacheDb = await openCache(store, version);
  if (!cacheDb) return;
  cacheVersion = version;
  const entries = await transaction('readonly', (s, results) => {
    const cursor = s.openCursor();
    cursor.onsuccess = () => {
      if (!cursor.result) return;
      results.push([cursor.result.key, cursor.result.value]);
      cursor.result.continue();
    };
  });
  FS.mkdirTree(convergedDir);
  const stale = [];
  for (const [key, bytes] of entries) {
    const [entryVersion, name] = key.split('/');
    if (entryVersion !== version) {
      stale.push(key);
      continue;
    }
    FS.writeFile(`${convergedDir}/${name}`, bytes);
    kept.add(name);
  }
  restoredCount = kept.size;
  if (stale.length) await transaction('readwrite', (s) => stale.forEach((key) => s.delete(key)));
}
const convergedFiles = () => FS.analyzePath(convergedDir).exists
    ? FS.readdir(convergedDir).filter((n) => n.endsWith('.bin')) : [];
// After a grade: what it computed, kept.
function keepCache() {
  if (!cacheDb) return;
  const added = convergedFiles().filter((n) => !kept.has(n));
  if (!added.length) return;
  transaction('readwrite', (s) => {
    for (const name of added) {
      s.put(FS.readFile(`${convergedDir}/${name}`), `${cacheVersion}/${name}`);
      kept.add(name);
    }
  });
}
let restored = null;

onmessage = async (event) => {
  await ready;
  const {step, files, stats, store, version} = event.data;
  restored ??= restoreCache(store, version);
  await restored;
  if (testHang && Object.values(files).some((text) => text.includes('PBRLAB_TEST_HANG')))
    for (;;) {}
  const start = performance.now();
  const before = new Set(convergedFiles());
  let report;
  try {
    if (FS.analyzePath('/work').exists) {
      for (const name of FS.readdir('/work'))
        if (name !== '.' && name !== '..') FS.unlink('/work/' + name);
    } else {
      FS.mkdir('/work');
    }
    for (const [name, text] of Object.entries(files)) FS.writeFile('/work/' + name, text);
    const address = Module.ccall('pbrlab_grade', 'number', ['string'], [step]);
    report = UTF8ToString(address);
    Module._free(address);
  } catch (e) {  // what went wrong costs this grade only
    report = JSON.stringify({modules: [{id: step, status: 'failed',
                                        message: 'the grader stopped: ' + e}]});
  }
  if (typeof GL !== 'undefined' && GL.currentContext && GL.currentContext.GLctx.isContextLost()) {
    postMessage({step, contextLost: true});
    return;
  }
  // What the cache did for this grade (the site's tests check it, not the times): the
  // converged integrals this grade computed (files it added), and how many this worker read
  // back from IndexedDB when it started.
  const converged = {computed: convergedFiles().filter((n) => !before.has(n)).length,
                     restored: restoredCount};
  keepCache();
  const answer = {step, report, ms: performance.now() - start, converged};
  if (stats) {
    const address = Module.ccall('pbrlab_journal', 'number', [], []);
    answer.journal = UTF8ToString(address);
    Module._free(address);
    answer.heapBytes = HEAP8.length;  // the program's memory, its in-memory files included
  }
  postMessage(answer);
};
