// The browser page (web/, the browser build's site) in headless Chromium from file://: its worker
// starts; a course file opened with the file picker, and another dropped on the page, show their
// shapes (pixels, not only the DOM); a broken script shows its error at the right line with the
// source line; a run started while another still meshes replaces it; the animation's slider
// changes the picture; the .glb saved from the page is the Khronos validator's clean file.
// usage: node page_browser.mjs SITE_DIR COURSE_FILE DROPPED_FILE OUT_DIR   (beside node_modules)
import { launch, check, failed, picture as pictureOf } from './chromium.mjs';
import fs from 'node:fs';
import path from 'node:path';
import assert from 'node:assert/strict';

const [site, course, dropped, out] = process.argv.slice(2);
const browser = await launch();
try {
  const page = await browser.newPage({ viewport: { width: 900, height: 600 }, acceptDownloads: true });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  const picture = () => pictureOf(page);
  const settled = async () => {
    await page.waitForFunction(() => ['ok', 'error'].includes(document.body.dataset.state), null, { timeout: 120000 });
    return page.evaluate(() => document.body.dataset.state);
  };
  const run = async (act) => {
    await page.evaluate(() => { document.body.dataset.state = 'asked'; });
    await act();
    return settled();
  };

  await page.goto('file://' + path.resolve(site, 'index.html'));
  await check('the page loads from file:// and starts its worker', async () => {
    assert.equal(await page.evaluate(() => document.body.dataset.worker), 'yes');
    assert.deepEqual(errors, []);
  });
  await check('a course file opened with the file picker shows its shape', async () => {
    assert.equal(await run(() => page.setInputFiles('#pick', course)), 'ok', await page.textContent('#diagnostics'));
    const p = await picture();
    assert.ok(p.drawn > p.total / 100, `${p.drawn} of ${p.total} pixels drawn`);
  });
  await check('a file dropped on the page shows its shape', async () => {
    const before = await picture();
    const text = fs.readFileSync(dropped, 'utf8'), name = path.basename(dropped);
    const state = await run(() => page.evaluate(([t, n]) => {
      const data = new DataTransfer();
      data.items.add(new File([t], n));
      window.dispatchEvent(new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
    }, [text, name]));
    assert.equal(state, 'ok', await page.textContent('#diagnostics'));
    const p = await picture();
    assert.ok(p.drawn > p.total / 100 && p.digest !== before.digest, `${p.drawn} pixels drawn, digest ${p.digest}`);
  });
  await check('a broken script shows its error at its line with the source line', async () => {
    const broken = 'function FRep(x, y, z, t) {\n  var r = x * x + y * y;\n  return 1 - r - z * * z;\n}\n';
    const state = await run(() => page.evaluate((t) => {
      document.getElementById('source').value = t;
      document.getElementById('runSource').click();
    }, broken));
    assert.equal(state, 'error');
    const shown = await page.textContent('#diagnostics');
    assert.match(shown, /pasted\.fs:3:\d+: error: /);
    assert.ok(shown.includes('  return 1 - r - z * * z;'), shown);
    assert.ok(await page.isVisible('#diagnostics'));
  });
  await check('a run started while another still meshes replaces it', async () => {
    // Minutes of work (three million loop turns a point) followed by a ball: the ball shows at once.
    const slow = 'function FRep(x, y, z, t) {\n  var s = 0;\n  for (var i = 0; i < 3000000; i++) s = s + x;\n' +
      '  return 0.5 - x * x - y * y - z * z + 0 * s;\n}\n';
    const ball = 'function FRep(x, y, z, t) { return 0.3 - x * x - y * y - z * z; }\n';
    const paste = (t) => page.evaluate((text) => {
      document.getElementById('source').value = text;
      document.getElementById('runSource').click();
    }, t);
    const before = await picture();
    await paste(slow);
    await page.waitForFunction(() => document.body.dataset.state === 'running');
    const t0 = Date.now();
    assert.equal(await run(() => paste(ball)), 'ok', await page.textContent('#diagnostics'));
    assert.ok(Date.now() - t0 < 60000, `the ball took ${Date.now() - t0} ms`);
    assert.match(await page.textContent('#status'), /^pasted\.fs: [0-9,]+ triangles/);
    const p = await picture();
    assert.ok(p.drawn > p.total / 100 && p.digest !== before.digest, `${p.drawn} pixels drawn`);
  });
  await check("the animation's slider changes the picture", async () => {
    assert.equal(await run(() => page.setInputFiles('#pick', course)), 'ok');
    assert.equal(await page.evaluate(() => document.body.dataset.animated), 'yes');
    await page.click('#play');  // pause
    const at = async (v) => {
      await page.evaluate((x) => {
        const s = document.getElementById('time');
        s.value = String(x);
        s.dispatchEvent(new Event('input'));
      }, v);
      return picture();
    };
    const a = await at(0.05), b = await at(0.55), c = await at(0.05);
    assert.notEqual(a.digest, b.digest);
    assert.equal(a.digest, c.digest);
  });
  await check('the .glb saved from the page passes the Khronos validator', async () => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#saveGlb')]);
    const file = path.join(out, 'saved.glb');
    await download.saveAs(file);
    assert.ok(download.suggestedFilename().endsWith('.glb'));
    const { createRequire } = await import('node:module');
    const validator = createRequire(import.meta.url)('gltf-validator');
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 100 });
    assert.equal(report.issues.numErrors, 0);
    assert.equal(report.issues.numWarnings, 0);
    assert.ok(report.info.totalTriangleCount > 1000);
  });
  await check('the .wrl saved from the page is VRML97', async () => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#saveWrl')]);
    const file = path.join(out, 'saved.wrl');
    await download.saveAs(file);
    assert.ok(fs.readFileSync(file, 'utf8').startsWith('#VRML V2.0 utf8'));
  });
  await check('no script error on the page', async () => assert.deepEqual(errors, []));
} finally {
  await browser.close();
}
process.exit(failed() ? 1 : 0);
