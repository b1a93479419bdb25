// What the Chromium tests share (tests/wasm/page_browser.mjs, tests/clients/preview_browser.mjs):
// Debian's Chromium, headless with software WebGL, driven by playwright-core; named checks that
// count their failures; the canvas's drawn pixels and a digest of them. Copied beside node_modules
// with the test that imports it (their shell scripts do).
import { chromium } from 'playwright-core';

export function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
  });
}

let failures = 0;
export async function check(name, fn) {
  try {
    await fn();
    console.log('ok   ' + name);
  } catch (e) {
    failures++;
    console.log('FAIL ' + name + ': ' + e.message);
  }
}
export const failed = () => failures > 0;

// The WebGL canvas's pixels that are not the white background, and a digest of them (read through
// a 2D copy: a WebGL canvas has no pixels of its own to read).
export function picture(page) {
  return page.evaluate(() => {
    const c = document.querySelector('canvas'), copy = document.createElement('canvas');
    copy.width = c.width, copy.height = c.height;
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let drawn = 0, digest = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) drawn++;
      digest = (digest * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) >>> 0;
    }
    return { drawn, total: d.length / 4, digest };
  });
}
