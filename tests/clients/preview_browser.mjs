// The preview page in headless Chromium (Debian chromium, driven by playwright-core): the first
// picture appears, the time slider moves the morph, an edit on disk shows within 2 s, a broken edit
// shows its diagnostics over the last good picture, a fixed one clears them, a missing Inline's
// warning shows over the scene drawn without it, the scene is drawn with no animation frame (a
// headless screenshot), quick reloads each get the scene, an animation plays the
// frames made so far before the last exists, and paths outside the page are 404. usage: node preview_browser.mjs URL SCENE_FILE   (fvrml-run --serve already runs)
import { launch, check, failed, picture as pictureOf } from './chromium.mjs';
import fs from 'node:fs';
import assert from 'node:assert/strict';

const [url, scene] = process.argv.slice(2);
const browser = await launch();
try {
  const page = await browser.newPage({ viewport: { width: 640, height: 480 } });
  // In every page: the WebGL canvas's RGBA bytes, read through a 2D copy.
  const withPixels = () => {
    window.canvasPixels = () => {
      const c = document.querySelector('canvas'), copy = document.createElement('canvas');
      copy.width = c.width, copy.height = c.height;
      const g = copy.getContext('2d');
      g.drawImage(c, 0, 0);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
  };
  await page.addInitScript(withPixels);
  const picture = () => pictureOf(page);
  const shown = () => page.evaluate(() => Number(document.body.dataset.shown ?? -1));
  const until = (fn, ms, arg = null) => page.waitForFunction(fn, arg, { timeout: ms, polling: 50 });
  const write = (text) => { fs.writeFileSync(scene + '.tmp', text); fs.renameSync(scene + '.tmp', scene); };
  const original = fs.readFileSync(scene, 'utf8');

  await page.goto(url);
  await check('the first picture appears', async () => {
    await until(() => document.body.dataset.shown !== undefined, 30000);
    await page.waitForTimeout(500);
    const p = await picture();
    assert.ok(p.drawn > p.total / 100, `${p.drawn} of ${p.total} pixels drawn`);
  });
  await check('the time slider moves the morph', async () => {
    await page.click('#play');  // pause, then set the time by hand
    const set = async (v) => {
      await page.$eval('#time', (el, value) => { el.value = value; el.dispatchEvent(new Event('input')); }, v);
      await page.waitForTimeout(300);
      return picture();
    };
    const a = await set('0.05'), b = await set('0.55');
    assert.notEqual(a.digest, b.digest, 'the pictures at 5% and 55% of the cycle are the same');
  });
  await check('an edit on disk shows within 2 s', async () => {
    const before = await shown(), p0 = await picture();
    const t0 = Date.now();
    write(original.replace(/diffuseColor "[^"]*"/, 'diffuseColor "r=0;g=0;b=1;"'));
    await until((v) => Number(document.body.dataset.shown) > v, 2000, before).catch(() => {});
    const after = await shown();
    assert.ok(after > before, `still version ${after} after ${Date.now() - t0} ms`);
    await page.waitForTimeout(300);
    assert.notEqual((await picture()).digest, p0.digest, 'the picture did not change');
  });
  await check('a broken edit shows the diagnostics over the last good picture', async () => {
    write(original.replace('#VRML V2.0 utf8\n', '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "1 - x*" } }\n'));
    await until(() => document.body.dataset.state === 'error', 2000);
    const text = await page.$eval('#overlay', (el) => (getComputedStyle(el).display === 'none' ? '' : el.textContent));
    assert.match(text, /:2:\d+: error: .*\n.*\n\s*\^/, text);
    const p = await picture();
    assert.ok(p.drawn > p.total / 100, 'the last good shape is gone');
  });
  await check('a fixed edit clears them', async () => {
    write(original);
    await until(() => document.body.dataset.state === 'ok', 2000);
    const display = await page.$eval('#overlay', (el) => getComputedStyle(el).display);
    assert.equal(display, 'none');
  });
  await check('a missing Inline: its warning over the scene, which is still drawn', async () => {
    const before = await shown();
    write(original + '\nInline { url "nothere.wrl" }\n');
    // Wait for this save's run (its warning), not for the end of the run before it, whose last
    // frames can arrive after the save.
    await until((v) => Number(document.body.dataset.shown) > v && document.body.dataset.state === 'ok' &&
                document.body.dataset.shownFrames === 'all' &&
                document.getElementById('overlay').textContent.includes('nothere.wrl'), 10000, before);
    const text = await page.$eval('#overlay', (el) => (getComputedStyle(el).display === 'none' ? '' : el.textContent));
    assert.match(text, /warning: Inline 'nothere.wrl': cannot read .*nothere.wrl/, text);
    const p = await picture();
    assert.ok(p.drawn > p.total / 100, `${p.drawn} of ${p.total} pixels drawn`);
    write(original);
    await until(() => getComputedStyle(document.getElementById('overlay')).display === 'none', 5000);
  });
  await check('an animation plays its frames so far before the last one is made', async () => {
    // The benchmark gyroid at half resolution: about 0.1 s a frame, 24 frames.
    await page.request.post(url + 'settings?scale=0.5');
    await until(() => document.body.dataset.state === 'ok' && document.body.dataset.shownFrames === 'all', 20000);
    const gyroid = fs.readFileSync(`${process.env.FS_SOURCE_DIR}/bench/scenes/gyroid-sphere256.wrl`, 'utf8');
    write(gyroid);
    await until(() => /^\d+\/24$/.test(document.body.dataset.shownFrames || ''), 30000);
    const p = await picture();
    assert.ok(p.drawn > p.total / 100, `${p.drawn} of ${p.total} pixels drawn from the frames so far`);
    await until(() => document.body.dataset.shownFrames === 'all', 120000);
    write(original);
    await page.request.post(url + 'settings?scale=1');
  });
  await check("standard geometry and an Inline's contents are shown, as in VRML97 and pictures", async () => {
    const before = await shown();
    fs.writeFileSync(scene.replace(/[^/]*$/, 'part.wrl'),
      '#VRML V2.0 utf8\nTransform { translation 0.6 0 0 children Shape { appearance Appearance { material Material { diffuseColor 0 0 1 } } geometry Sphere { radius 0.3 } } }\n');
    write('#VRML V2.0 utf8\nShape { appearance Appearance { material Material { diffuseColor 1 0 0 } } geometry Box { size 0.5 0.5 0.5 } }\n' +
          'Inline { url "part.wrl" }\n');
    const colours = () => {
      const d = window.canvasPixels();
      let red = 0, blue = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] > 120 && d[i + 1] < 60 && d[i + 2] < 60) red++;
        if (d[i + 2] > 120 && d[i] < 60 && d[i + 1] < 60) blue++;
      }
      return { red, blue };
    };
    // Until the new scene is shown with both (a run already under way may show first).
    await until((v) => Number(document.body.dataset.shown) > v && document.body.dataset.state === 'ok', 10000, before);
    await until(`(${colours})().red > 500 && (${colours})().blue > 500`, 10000).catch(() => {});
    const counts = await page.evaluate(colours);
    write(original);
    assert.ok(counts.red > 500 && counts.blue > 500, `red ${counts.red}, blue ${counts.blue} pixels`);
  });
  await check('the scene is drawn without animation frames (what a headless screenshot gives)', async () => {
    const still = await browser.newPage({ viewport: { width: 320, height: 240 } });
    await still.addInitScript(() => { window.requestAnimationFrame = () => 0; });
    await still.addInitScript(withPixels);
    await still.goto(url);
    await still.waitForFunction(() => document.body.dataset.shown !== undefined, null, { timeout: 30000, polling: 50 });
    const drawn = await still.evaluate(() => {
      const d = window.canvasPixels();
      // A rendered frame: the white background and the shape. One never rendered is all black.
      let shape = 0, white = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] >= 250 && d[i + 1] >= 250 && d[i + 2] >= 250) white++;
        else if (d[i + 3] > 0) shape++;
      }
      return { shape: shape / (d.length / 4), white: white / (d.length / 4) };
    });
    await still.close();
    assert.ok(drawn.white > 0.1 && drawn.shape > 0.01, `background ${(drawn.white * 100).toFixed(1)}%, shape ${(drawn.shape * 100).toFixed(1)}%`);
  });
  await check('six quick reloads each get the scene (a closed page frees its stream)', async () => {
    for (let i = 0; i < 6; i++) await page.reload();
    await until(() => document.body.dataset.state === 'ok', 5000);
  });
  await check('paths outside the page are 404', async () => {
    for (const path of ['/../../etc/passwd', '/%2e%2e/%2e%2e/etc/passwd', '/three/../../../../etc/passwd', '/etc/passwd']) {
      const r = await page.request.get(url.replace(/\/$/, '') + path);
      assert.equal(r.status(), 404, path);
    }
  });
} finally {
  await browser.close();
}
process.exit(failed() ? 1 : 0);
