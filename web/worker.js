// The page's worker: runs fvrml-run (the browser build, fvrml-web.js) on the files the user gave,
// in memory, and sends back what the command line would show and write. Defined here as one
// function the page turns into a worker from a Blob (a page opened from file:// may not start a
// worker from a file), with fvrml-web.js's factory before it; a fresh instance per run, as each run
// of the command line is a fresh process.
/* exported fvrmlWorkerMain */
/* global createFvrmlRun */
'use strict';

function fvrmlWorkerMain(scope) {
  // One run: job = {files: [{path, data}], main, format, args}; answers {code, log, stats, output}.
  async function run(job) {
    let log = '';
    const say = (text) => { log += text + '\n'; };
    const fvrml = await createFvrmlRun({ print: say, printErr: say, noInitialRun: true });
    const FS = fvrml.FS;
    const made = new Set(['/work', '/out']);
    FS.mkdir('/work');
    FS.mkdir('/out');
    for (const f of job.files) {
      const parts = f.path.split('/').filter((p) => p && p !== '.' && p !== '..');
      let dir = '/work';
      for (const p of parts.slice(0, -1)) {
        dir += '/' + p;
        if (!made.has(dir)) FS.mkdir(dir), made.add(dir);
      }
      FS.writeFile(dir + '/' + parts[parts.length - 1], f.data);
    }
    FS.chdir('/work');
    const out = '/out/scene.' + job.format;
    let code;
    try {
      code = fvrml.callMain([job.main, '-o', out, '--stats-file', '/out/stats.json', ...(job.args || [])]);
    } catch (e) {
      say('error: the run stopped: ' + e);
      code = 1;
    }
    const read = (path, encoding) => {
      try { return FS.readFile(path, encoding ? { encoding } : undefined); } catch (e) { return null; }
    };
    const statsText = read('/out/stats.json', 'utf8');
    return { code, log, stats: statsText ? JSON.parse(statsText) : null, output: code === 0 ? read(out) : null };
  }

  scope.onmessage = async (e) => {
    const { id, job } = e.data;
    let answer;
    try {
      answer = await run(job);
    } catch (err) {
      answer = { code: 1, log: 'error: ' + err, stats: null, output: null };
    }
    scope.postMessage({ id, answer }, answer.output ? [answer.output.buffer] : []);
  };
}
