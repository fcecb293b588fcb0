// The studio's page in headless Chromium (Debian's `chromium`, driven by
// puppeteer-core): it lists the scene, runs Make LOD, draws the scene on its
// WebGL canvas, and draws fewer triangles as the "view from distance" slider
// moves out.
// With a bunny mesh (ASCII PLY), a one-shape scene of it is opened too: both
// files are listed with their counts, and Make LOD on it with the error range
// changed gives the levels and ranges `lodforge lod` writes with that option.
// Usage: node browser_test.mjs LODFORGE_EXE SCENE [BUNNY.ply [CHROMIUM]]
// Exit 0 pass, 1 fail, 77 skipped (Chromium cannot start).
import { execFileSync, spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { gzipSync } from 'node:zlib';
import { join } from 'node:path';
import { launchChromium } from '../tools/launch_chromium.mjs';

const [exe, scenePath, bunnyPly = '', chromium = '/usr/bin/chromium'] = process.argv.slice(2);
const fail = (msg) => { console.error(`FAIL: ${msg}`); process.exitCode = 1; };

// A VRML 1.0 scene of one IndexedFaceSet: the triangles of an ASCII PLY.
function sceneOfPly(ply, out) {
  const lines = readFileSync(ply, 'latin1').split('\n');
  let v = 0, f = 0, at = 0;
  for (; at < lines.length; ++at) {
    const w = lines[at].trim().split(/\s+/);
    if (w[0] === 'element' && w[1] === 'vertex') v = Number(w[2]);
    if (w[0] === 'element' && w[1] === 'face') f = Number(w[2]);
    if (w[0] === 'end_header') break;
  }
  const points = lines.slice(at + 1, at + 1 + v).map((l) => l.trim().split(/\s+/).slice(0, 3).join(' '));
  const faces = lines.slice(at + 1 + v, at + 1 + v + f).map((l) => `${l.trim().split(/\s+/).slice(1, 4).join(' ')} -1`);
  writeFileSync(out, `#VRML V1.0 ascii\nSeparator {\nCoordinate3 { point [\n${points.join(',\n')}] }\n` +
    `IndexedFaceSet { coordIndex [\n${faces.join(',\n')}] }\n}\n`);
  return f;
}
const work = mkdtempSync(join(tmpdir(), 'lodforge-studio-'));
const bunny = bunnyPly && existsSync(bunnyPly) ? join(work, 'bunny.wrl') : '';
const bunnyTriangles = bunny ? sceneOfPly(bunnyPly, bunny) : 0;

const server = spawn(exe, ['studio', scenePath, ...(bunny ? [bunny] : []), '--port', '0'], { stdio: ['ignore', 'ignore', 'pipe'] });
const url = await new Promise((resolve, reject) => {
  let text = '';
  server.stderr.on('data', (d) => {
    text += d;
    const m = text.match(/http:\/\/127\.0\.0\.1:\d+\//);
    if (m) resolve(m[0]);
  });
  server.on('exit', (code) => reject(new Error(`lodforge studio ended (${code}): ${text}`)));
  setTimeout(() => reject(new Error(`no URL from lodforge studio: ${text}`)), 20000);
});

let browser;
try {
  browser = await launchChromium(chromium);
} catch (e) {
  console.log(`SKIP: ${e.message}`);
  server.kill();
  process.exit(77);
}

try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 900 });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(url, { waitUntil: 'load', timeout: 180000 });
  await page.waitForFunction(() => window.studio && window.studio.lods && document.querySelector('#files tbody tr'), { timeout: 180000 });
  const listed = await page.$eval('#files tbody', (t) => t.textContent);
  if (!listed.includes(scenePath.split('/').pop())) fail(`the file list lacks the scene: ${listed}`);

  if (bunny) {  // both files, each with its shape and triangle counts
    const rows = await page.$$eval('#files tbody tr', (r) => r.map((x) => [...x.cells].map((c) => c.textContent)));
    const row = (name) => rows.find((r) => r[0] === name) || [];
    if (!row('bunny.wrl')[2]?.includes('IndexedFaceSet 1') || row('bunny.wrl')[3] !== String(bunnyTriangles))
      fail(`the bunny's row: ${row('bunny.wrl')}`);
    const example = row(scenePath.split('/').pop());
    if (!(Number(example[3]) > 0) || !example[2]) fail(`the example's row: ${example}`);
  }

  await page.click('#make-lod');
  await page.waitForFunction(() => window.studio.result && !window.studio.running && window.studio.lods.length > 0, { timeout: 300000 });
  const rows = await page.$$eval('#stats tbody tr', (r) => r.length);
  if (rows === 0) fail('no statistics rows after Make LOD');

  // Pixels of one frame that differ from the background (read in the task that drew them).
  const covered = await page.evaluate(() => {
    const s = window.studio;
    s.viewFrom(s.bounds.getSize(new s.camera.position.constructor()).length() * 0.8);
    s.renderer.render(s.scene3d, s.camera);
    const gl = s.renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let n = 0;
    for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - 0x22) + Math.abs(px[i + 1] - 0x33) + Math.abs(px[i + 2] - 0x44) > 12) ++n;
    return n / (w * h);
  });
  console.log(`non-background pixels: ${(covered * 100).toFixed(1)} %`);
  if (!(covered > 0.05)) fail(`the canvas draws too little: ${covered}`);

  // Triangles drawn as the slider moves out (geometric steps from the
  // near view to the slider's end): never more, and fewer at the end.
  const max = await page.$eval('#distance-slider', (e) => Number(e.max));
  const near = await page.evaluate(() => window.studio.bounds.getSize(new window.studio.camera.position.constructor()).length() * 0.8);
  const distances = [0, 1, 2, 3, 4, 5, 6].map((i) => near * Math.pow(max / near, i / 6));
  const counts = [];
  for (const d of distances) {
    await page.evaluate((x) => window.studio.viewFrom(x), d);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    counts.push(await page.evaluate(() => window.studio.trianglesDrawn));
    // What the written file draws from this eye: every LOD's child by its
    // own distance (VRML 1.0's rule), from the server's level geometry.
    const expected = await page.evaluate(async () => {
      const s = window.studio, eye = s.camera.position;
      const g = await (await fetch(`/api/geometry?which=output&path=${encodeURIComponent(s.current)}`)).json();
      let n = 0;
      for (const m of g.shapes) n += m.indices.length / 3;
      for (const l of g.lods) {
        const d = Math.hypot(eye.x - l.center[0], eye.y - l.center[1], eye.z - l.center[2]);
        const child = Math.min(l.ranges.filter((r) => r <= d).length, l.levels.length - 1);
        for (const m of l.levels[child]) n += m.indices.length / 3;
      }
      return n;
    });
    if (counts.at(-1) !== expected) fail(`at ${d.toPrecision(4)} the page draws ${counts.at(-1)} triangles, the file ${expected}`);
  }
  console.log(`triangles drawn at ${distances.map((d) => d.toPrecision(4)).join(', ')}: ${counts.join(', ')}`);
  for (let i = 1; i < counts.length; ++i) if (counts[i] > counts[i - 1]) fail(`more triangles farther out: ${counts}`);
  if (!(counts.at(-1) < counts[0])) fail(`the drawn triangles do not fall: ${counts}`);
  // Selecting a shape in the tree marks its meshes (every level) and its
  // statistics rows; clicking a drawn mesh selects its node in the tree.
  const shapeLine = await page.evaluate(() => window.studio.result.shapes[0].line);
  await page.click(`#tree .node[data-line="${shapeLine}"]`);
  const marked = await page.evaluate(() => window.studio.meshes.filter((m) => m.userData.selected && m.material.emissive.getHex() !== 0).length);
  const markedRows = await page.$$eval('#stats tbody tr.selected', (r) => r.length);
  const levelCount = await page.evaluate(() => window.studio.result.shapes[0].levels.length);
  console.log(`selecting line ${shapeLine}: ${marked} meshes marked, ${markedRows} statistics rows`);
  if (marked < 2) fail(`selecting a shape in the tree marks ${marked} meshes, not those of its levels`);
  if (markedRows !== levelCount) fail(`selected shape: ${markedRows} statistics rows marked, it has ${levelCount} levels`);
  if (!(await page.$eval('#selection', (e) => e.textContent)).includes(`line ${shapeLine}`)) fail('the selection is not described');
  await page.evaluate((d) => window.studio.viewFrom(d), near * 1.5);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const target = await page.evaluate(() => {
    // The screen point of a drawn mesh's first vertex that the ray from
    // the eye meets first on that mesh.
    const s = window.studio, c = s.renderer.domElement.getBoundingClientRect();
    for (const m of s.meshes) {
      let o = m, shown = true;
      for (; o; o = o.parent) shown &&= o.visible;
      if (!shown) continue;
      const box = new s.camera.position.constructor();
      m.geometry.computeBoundingBox(); m.geometry.boundingBox.getCenter(box);
      const p = box.applyMatrix4(m.matrixWorld).project(s.camera);
      if (Math.abs(p.x) > 0.95 || Math.abs(p.y) > 0.95) continue;
      const hit = s.pick(p.x, p.y);
      if (hit && hit.userData.line > 0) return { x: c.left + (p.x + 1) / 2 * c.width, y: c.top + (1 - p.y) / 2 * c.height, line: hit.userData.line };
    }
    return null;
  });
  if (!target) fail('no drawn mesh to click');
  else {
    await page.mouse.click(target.x, target.y);
    const picked = await page.$eval('#tree .node.selected', (e) => Number(e.dataset.line)).catch(() => null);
    console.log(`clicked the view at ${target.x.toFixed(0)},${target.y.toFixed(0)}: tree node of line ${picked} selected`);
    if (picked !== target.line) fail(`clicking a mesh of line ${target.line} selects tree line ${picked}`);
  }
  await page.evaluate(() => window.studio.selectLines([]));

  // Side by side from far out: the left half (level 0) draws the full
  // scene, the right half what the LODs choose, so the halves differ.
  await page.evaluate((d) => window.studio.viewFrom(d), max * 0.5);
  await page.click('#side-by-side');
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const halves = await page.evaluate(() => {
    const s = window.studio, c = s.renderer.domElement;
    s.renderSideBySide(c.clientWidth, c.clientHeight);
    const gl = s.renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight, half = Math.floor(w / 2);
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let differ = 0;
    for (let y = 0; y < h; ++y) for (let x = 0; x < half; ++x) {
      const a = (y * w + x) * 4, b = (y * w + x + half) * 4;
      if (Math.abs(px[a] - px[b]) + Math.abs(px[a + 1] - px[b + 1]) + Math.abs(px[a + 2] - px[b + 2]) > 12) ++differ;
    }
    return { differ: differ / (half * h), triangles: s.renderer.info.render.triangles };
  });
  console.log(`side by side far out: ${(halves.differ * 100).toFixed(2)} % of the pixels differ between the halves`);
  if (!(halves.differ > 0)) fail('side by side: level 0 and the LOD draw the same pixels far out');
  await page.click('#side-by-side');

  // Deviation colours: from the middle distance (levels past 0 drawn) the
  // toggle changes the drawn colours, and some pixels are greener or redder
  // than blue (a vertex away from level 0).
  await page.evaluate((d) => window.studio.viewFrom(d), distances[2]);
  const frame = () => page.evaluate(() => {
    const s = window.studio;
    s.renderer.render(s.scene3d, s.camera);
    const gl = s.renderer.getContext();
    const px = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
    gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, px);
    return Array.from(px);
  });
  const before = await frame();
  await page.click('#colour-deviation');
  const after = await frame();
  let changed = 0, offBlue = 0;
  for (let i = 0; i < after.length; i += 4) {
    if (Math.abs(after[i] - before[i]) + Math.abs(after[i + 1] - before[i + 1]) + Math.abs(after[i + 2] - before[i + 2]) > 12) ++changed;
    if (Math.max(after[i], after[i + 1]) > after[i + 2] + 40) ++offBlue;
  }
  const devMax = await page.evaluate(() => window.studio.deviationMax);
  console.log(`deviation colours (max ${devMax.toPrecision(3)}): ${(changed / (after.length / 4) * 100).toFixed(1)} % of the pixels change, ${(offBlue / (after.length / 4) * 100).toFixed(2)} % green or red`);
  if (!(changed / (after.length / 4) > 0.02)) fail('the deviation toggle does not change the drawn colours');
  if (!(devMax > 0) || offBlue === 0) fail('no vertex away from level 0 is drawn green or red');
  await page.click('#colour-deviation');

  // The editor holds the scene's text (highlighted by the VRML mode); a
  // broken edit re-parsed reports its line and marks it, and the loaded
  // scene stays.
  const shown = await page.evaluate(() => window.studio.editor.getValue());
  if (!shown.startsWith('#VRML V1.0 ascii')) fail(`the editor does not show the scene: ${shown.slice(0, 40)}`);
  const highlighted = await page.$$eval('.CodeMirror .cm-type', (e) => e.length);
  if (highlighted === 0) fail('the editor highlights no node type');
  const brokenLine = await page.evaluate(() => {
    const ed = window.studio.editor, lines = ed.getValue().split('\n');
    const at = lines.findIndex((l, i) => i > 0 && l.includes('{'));
    lines[at] = lines[at].replace('{', '{ 1.5 )');
    ed.setValue(lines.join('\n'));
    return at + 1;
  });
  await page.click('#reparse');
  await page.waitForFunction(() => document.querySelector('#parse-error').textContent !== '', { timeout: 20000 });
  const reported = await page.$eval('#parse-error', (e) => e.textContent);
  const markedLines = await page.evaluate(() => [...document.querySelectorAll('.CodeMirror .parse-error-line')].length);
  console.log(`broken edit on line ${brokenLine}: "${reported}", ${markedLines} line marked`);
  if (!reported.startsWith(`line ${brokenLine}:`)) fail(`the broken edit on line ${brokenLine} reports "${reported}"`);
  if (markedLines !== 1) fail(`${markedLines} lines marked for the parse error`);

  // The example's Texture2 (an inline SFImage) is drawn as a texture map.
  const textured = await page.evaluate(() => window.studio.meshes.filter((m) => m.userData.own.map).length);
  if (textured === 0) fail('no mesh draws the scene\'s texture');
  // The per-type tabs: one type's panel at a time; its quality goes into
  // the command line.
  await page.click('#type-tabs button[data-type="cone"]');
  const visible = await page.$$eval('#per-type > div', (d) => d.filter((x) => !x.hidden).map((x) => x.dataset.type));
  if (visible.join() !== 'cone') fail(`the Cone tab shows the panels ${visible}`);
  await page.type('#per-type input[name="quality-cone"]', '2');
  const command = await page.$eval('#command-line', (e) => e.value);
  if (!command.includes('--quality cone=2')) fail(`the Cone tab's quality is not in the command line: ${command}`);
  console.log(`${textured} textured meshes; Cone tab: ${command}`);
  // The reading, writing and message options go into the command line too.
  await page.click('#options input[name="minimize"]');
  await page.click('#options input[name="inline"]');
  await page.click('#options input[name="verbose-join"]');
  await page.click('#options input[name="verbose-face"]');
  await page.select('#options select[name="format"]', 'x3dv');
  await page.type('#options input[name="floats-per-line"]', '3');
  await page.type('#options input[name="max-triangles"]', '500000');
  const written = await page.$eval('#command-line', (e) => e.value);
  for (const part of ['--floats-per-line 3 --format x3dv --inline', '--max-triangles 500000 --minimize',
    '--verbose face --verbose join'])
    if (!written.includes(part)) fail(`'${part}' is not in the command line: ${written}`);
  console.log(`writing options: ${written}`);
  // Back to the defaults for the runs below.
  for (const name of ['minimize', 'inline', 'verbose-join', 'verbose-face']) await page.click(`#options input[name="${name}"]`);
  await page.select('#options select[name="format"]', '');
  await page.$eval('#options', (f) => {
    for (const n of ['floats-per-line', 'max-triangles']) f.elements[n].value = '';
    f.dispatchEvent(new Event('input', { bubbles: true }));
  });

  if (process.env.STUDIO_SCREENSHOT) {  // the README's picture
    await page.evaluate((d) => window.studio.viewFrom(d), near * 1.5);
    await page.evaluate((d) => window.studio.viewFrom(d), distances[1]);
    await page.click('#colour-deviation');
    await page.evaluate(() => { document.getElementById('side').scrollTop = 0; });  // the panel from its top
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.screenshot({ path: process.env.STUDIO_SCREENSHOT });
  }

  if (bunny) {
    // Make LOD on the bunny with the defaults, then with error range 10 %:
    // the statistics change, and equal what `lodforge lod` writes with it.
    const makeLod = async () => {
      await page.evaluate(() => { window.studio.result = null; });  // the run's own result, not the last one
      await page.click('#make-lod');
      await page.waitForFunction(() => window.studio.result && !window.studio.running, { timeout: 300000 });
      return page.evaluate(() => window.studio.result.shapes.map((s) => s.levels.map((l) => [l.triangles, l.from_distance])));
    };
    await page.click('#files tbody tr[data-path$="bunny.wrl"]');
    await page.waitForFunction(() => window.studio.current && window.studio.current.endsWith('bunny.wrl') && !window.studio.result, { timeout: 60000 });
    const defaults = await makeLod();
    await page.$eval('#options input[name="error-range"]', (e) => { e.value = '10'; e.dispatchEvent(new Event('input', { bubbles: true })); });
    const tenPercent = await makeLod();
    if (JSON.stringify(defaults) === JSON.stringify(tenPercent)) fail('error range 10 % does not change the statistics');
    const stats = join(work, 'stats.json');
    execFileSync(exe, ['lod', bunny, '-o', join(work, 'bunny_lod.wrl'), '--error-range', '10', '--stats', stats, '-q'],
      { stdio: ['ignore', 'ignore', 'pipe'] });
    const written = JSON.parse(readFileSync(stats, 'utf8')).shapes.map((s) =>
      s.levels.map((l, i) => [l.triangles, i === 0 ? 0 : s.ranges[i - 1]]));
    const close = (a, b) => Math.abs(a - b) <= 1e-5 * Math.max(1, Math.abs(b));
    const same = written.length === tenPercent.length && written.every((levels, k) => levels.length === tenPercent[k].length &&
      levels.every(([t, d], i) => t === tenPercent[k][i][0] && (i === 0 || close(tenPercent[k][i][1], d))));
    if (!same) fail(`the page shows ${JSON.stringify(tenPercent)}, lod writes ${JSON.stringify(written)}`);
    console.log(`bunny: ${tenPercent[0].length} levels at error range 10 %, as lod --error-range 10 writes (${JSON.stringify(tenPercent[0])})`);
  }
  // Gzip-compressed uploads (.wrl.gz, .wrz) load as the plain file does: the
  // same shape and triangle counts in the file list.
  const rowOf = (name) => page.$$eval('#files tbody tr', (r, n) =>
    (r.map((x) => [...x.cells].map((c) => c.textContent)).find((c) => c[0] === n) || []).slice(2, 4), name);
  const plain = await rowOf(scenePath.split('/').pop());
  for (const name of ['example.wrl.gz', 'example.wrz']) {
    const packed = join(work, name);
    writeFileSync(packed, gzipSync(readFileSync(scenePath)));
    await (await page.$('#upload-file')).uploadFile(packed);
    await page.waitForFunction((n) => window.studio.current && window.studio.current.endsWith(n), { timeout: 60000 }, name);
    const row = await rowOf(name);
    if (JSON.stringify(row) !== JSON.stringify(plain)) fail(`the upload ${name} lists ${row}, the plain file ${plain}`);
    console.log(`upload ${name}: ${row.join(', ')}`);
  }
  if (errors.length) fail(`console errors: ${errors.join(' | ')}`);
} catch (e) {
  fail(e.stack || e.message);
} finally {
  await browser.close();
  server.kill();
  rmSync(work, { recursive: true, force: true });
}
if (!process.exitCode) console.log('1 passed, 0 failed');
