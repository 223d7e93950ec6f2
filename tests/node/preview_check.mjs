// Opens the output preview in headless Chromium (Debian's /usr/bin/chromium through playwright-core)
// and reports what a person would see, for tests/python/test_glb_preview.py.
//   node tests/node/preview_check.mjs URL FRAME SCRATCH_DIR
// Stdout: JSON {consoleErrors, pageErrors, failedRequests, viewerError, frameCount, playedDiffers,
// framedBox, sliderFrame, influencesAtSlider, reportText, sheetLoaded}; screenshots in SCRATCH_DIR.
import fs from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';

const [url, frameText, scratch] = process.argv.slice(2);
const frame = Number(frameText);
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking', '--disable-component-update',
         '--no-first-run', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});  // playwright gives the browser a fresh user-data-dir of its own
const result = { consoleErrors: [], pageErrors: [], failedRequests: [] };
try {
  const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
  page.on('console', (message) => { if (message.type() === 'error') result.consoleErrors.push(message.text()); });
  page.on('pageerror', (error) => result.pageErrors.push(String(error)));
  page.on('requestfailed', (request) => result.failedRequests.push(`${request.failure().errorText} ${request.url()}`));
  page.on('response', (response) => { if (response.status() >= 400) result.failedRequests.push(`${response.status()} ${response.url()}`); });
  await page.goto(url);
  await page.waitForFunction(() => window.meshikViewer && (window.meshikViewer.ready || window.meshikViewer.error),
                             null, { timeout: 60000 });
  result.viewerError = await page.evaluate(() => window.meshikViewer.error);
  result.frameCount = await page.evaluate(() => window.meshikViewer.frameCount);
  result.framedBox = await page.evaluate(() => window.meshikViewer.framedBox);
  const canvas = page.locator('#stage canvas');
  await page.waitForTimeout(300);
  const first = await canvas.screenshot({ path: path.join(scratch, 'playing-1.png') });
  await page.waitForTimeout(700);
  const second = await canvas.screenshot({ path: path.join(scratch, 'playing-2.png') });
  result.playedDiffers = !first.equals(second);
  await page.locator('#frame').fill(String(frame));  // a range input: fill sets the value and fires input
  await page.waitForTimeout(200);
  result.sliderFrame = await page.evaluate(() => window.meshikViewer.currentFrame);
  result.playingAfterSlider = await page.evaluate(() => window.meshikViewer.playing);
  result.influencesAtSlider = await page.evaluate(() => window.meshikViewer.influences());
  await canvas.screenshot({ path: path.join(scratch, 'slider.png') });
  result.reportText = await page.locator('#report').textContent();
  result.sheetLoaded = await page.evaluate(() => {
    const image = document.getElementById('sheet');
    return image.complete && image.naturalWidth > 0;
  });
} finally {
  await browser.close();
}
console.log(JSON.stringify(result));
