// The page's grader in a Web Worker (docs/web.md, "The badge in the page"): grader.js is the
// site's second program (core/host/web_grader.cpp), which grades a step as `pbrlab check`
// does in its own WebGL 2 context on an OffscreenCanvas. Each message {step, files} carries
// every file of the page's workspace (name -> text); they replace this worker's /work, and
// the answer {step, report} is the report `pbrlab check --json` writes; with {stats: true}
// also {journal}, what every grade so far compiled and checked, with times (--stats), and
// {heapBytes}, the program's memory (its in-memory files included). Before
// it, a grade whose file fails says {namingTheMistake: true} as its feedback starts.
let started;
const ready = new Promise((resolve) => { started = resolve; });
var Module = {
  print: (text) => console.log('grader: ' + text),
  printErr: (text) => console.warn('grader: ' + text),
  onRuntimeInitialized: () => started(),
};
// The site's data (the page's package: the browser fetched it for the page already).
importScripts('lab-data.js', 'grader.js');

onmessage = async (event) => {
  await ready;
  const {step, files, stats} = event.data;
  const start = performance.now();
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
  const answer = {step, report, ms: performance.now() - start};
  if (stats) {
    const address = Module.ccall('pbrlab_journal', 'number', [], []);
    answer.journal = UTF8ToString(address);
    Module._free(address);
    answer.heapBytes = HEAP8.length;  // the program's memory, its in-memory files included
  }
  postMessage(answer);
};
