// three.js (npm `three`, its GLTFLoader) loads and draws glTF files in
// headless Chromium (Debian's `chromium`, driven by puppeteer-core from
// scripts/install-web-deps.sh), one browser for all files. Per file it
// reports load errors, console errors and warnings, the share of the frame
// that is not background, and the triangles drawn (renderer.info.render):
//   full:   every LOD at level 0 (and the share of the frame it covers),
//   framed: LODs switching, camera framing the bounding sphere,
//   steps:  LODs switching, camera moving out in eight geometric steps,
//   far:    the last step, beyond the farthest switch distance.
// three.js ignores MSFT_lod, so the page builds a THREE.LOD per node that
// carries it, as an engine would: level 0 is the node, level k the node
// MSFT_lod names, level k taking over where the node's bounding sphere (as
// Babylon.js takes it: the half diagonal of the mesh's box times the node's
// largest world scale) covers MSFT_screencoverage[k - 1] of the screen height
// (coverage = r / (d·tan(fov/2)), the rule the glTF writer states); a
// coverage beyond the last level is where the node vanishes.
//   node threejs_draw_gltf.mjs [--chromium PATH] FILE...   (JSON line per file)
// Exit 0 drawn (whatever the figures), 1 the script failed, 77 Chromium
// cannot start.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { ChromiumCannotStart, launchChromium } from './launch_chromium.mjs';

export { ChromiumCannotStart };

const here = path.dirname(fileURLToPath(import.meta.url));
const three = path.join(here, '..', '..', 'node_modules', 'three');

// The page: three.js by an import map from the repository's node_modules.
const PAGE = `<!doctype html><html><head><link rel="icon" href="data:,"></head><body style="margin:0">
<script type="importmap">{"imports": {"three": "/three/build/three.module.js",
  "three/addons/": "/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const SIZE = 400, FOV = 50, BACKGROUND = [0x20, 0xe0, 0xa0];
const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.setSize(SIZE, SIZE);
renderer.setClearColor(new THREE.Color().setRGB(...BACKGROUND.map((c) => c / 255), THREE.SRGBColorSpace));
document.body.appendChild(renderer.domElement);

// Pixels of the frame just drawn that differ from the clear colour.
function coveredShare() {
  const gl = renderer.getContext();
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const px = new Uint8Array(w * h * 4);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
  let n = 0;
  for (let i = 0; i < px.length; i += 4)
    if (Math.abs(px[i] - BACKGROUND[0]) + Math.abs(px[i + 1] - BACKGROUND[1]) + Math.abs(px[i + 2] - BACKGROUND[2]) > 12) ++n;
  return n / (w * h);
}

function draw(scene, camera) {
  renderer.render(scene, camera);
  return renderer.info.render.triangles;
}

// A THREE.LOD in place of each node carrying MSFT_lod.
async function buildLods(gltf) {
  const parser = gltf.parser, json = parser.json, lods = [];
  const byNode = new Map();
  gltf.scene.traverse((o) => {
    const a = parser.associations.get(o);
    if (a && a.nodes !== undefined && !byNode.has(a.nodes)) byNode.set(a.nodes, o);
  });
  const tanHalf = Math.tan(THREE.MathUtils.degToRad(FOV) / 2);
  gltf.scene.updateMatrixWorld(true);
  for (const [index, object] of byNode) {
    const node = json.nodes[index];
    const ext = node.extensions && node.extensions.MSFT_lod;
    if (!ext) continue;
    const coverage = (node.extras && node.extras.MSFT_screencoverage) || [];
    const ids = ext.ids || [];
    const lod = new THREE.LOD();
    lod.name = (node.name || 'node' + index) + ' (LOD)';
    lod.position.copy(object.position);
    lod.quaternion.copy(object.quaternion);
    lod.scale.copy(object.scale);
    const parent = object.parent;
    parent.add(lod);
    parent.remove(object);
    // Child nodes stay in view whatever the level.
    for (const c of [...object.children]) {
      const a = parser.associations.get(c);
      if (a && a.nodes !== undefined && json.nodes[index].children?.includes(a.nodes)) lod.add(c);
    }
    // The radius Babylon.js gives the mesh: half the diagonal of its
    // primitives' box, times the node's largest world scale.
    const box = new THREE.Box3();
    object.traverse((o) => {
      if (!o.geometry) return;
      o.geometry.computeBoundingBox();
      box.union(o.geometry.boundingBox);
    });
    const radius = box.getSize(new THREE.Vector3()).length() / 2 * object.matrixWorld.getMaxScaleOnAxis();
    const distances = coverage.map((c) => (c > 0 ? radius / (c * tanHalf) : Infinity));
    object.position.set(0, 0, 0); object.quaternion.identity(); object.scale.set(1, 1, 1);
    lod.addLevel(object, 0);
    for (let k = 0; k < ids.length; ++k) {
      const level = (await parser.getDependency('node', ids[k])).clone();
      level.position.set(0, 0, 0); level.quaternion.identity(); level.scale.set(1, 1, 1);
      lod.addLevel(level, distances[k] ?? Infinity);
    }
    if (distances.length > ids.length) lod.addLevel(new THREE.Object3D(), distances[ids.length]);
    // THREE.LOD sorts its levels by distance: the file's order is checked here.
    let order = '';
    if (coverage.length !== ids.length && coverage.length !== ids.length + 1)
      order = coverage.length + ' coverages for ' + (ids.length + 1) + ' levels';
    else if (coverage.some((c, k) => k > 0 && !(c < coverage[k - 1])))
      order = 'coverages not decreasing: ' + coverage;
    lods.push({ lod, name: node.name || 'node ' + index, levels: ids.length + 1, distances, order });
  }
  return lods;
}

window.drawGltf = async (url) => {
  const result = { loaded: false };
  let gltf;
  try {
    gltf = await new GLTFLoader().loadAsync(url);
  } catch (e) {
    result.error = String(e && e.message || e);
    return result;
  }
  result.loaded = true;
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.AmbientLight(0xffffff, 1.0));
  const sun = new THREE.DirectionalLight(0xffffff, 2.0);
  sun.position.set(1, 2, 3);
  scene.add(sun);
  const lods = await buildLods(gltf);
  result.lodNodes = lods.map((l) => l.name);
  result.lodLevels = lods.map((l) => l.levels);
  result.lodOrderErrors = lods.filter((l) => l.order).map((l) => l.name + ': ' + l.order);
  scene.updateMatrixWorld(true);
  const sphere = new THREE.Box3().setFromObject(gltf.scene).getBoundingSphere(new THREE.Sphere());
  const radius = sphere.radius > 0 && isFinite(sphere.radius) ? sphere.radius : 1;
  result.radius = radius;
  const framing = radius / Math.sin(THREE.MathUtils.degToRad(FOV) / 2) * 1.05;
  let farthest = framing;
  for (const l of lods) for (const d of l.distances) if (isFinite(d)) farthest = Math.max(farthest, d + 2 * radius);
  const camera = new THREE.PerspectiveCamera(FOV, 1, radius / 1000, farthest * 4);
  const direction = new THREE.Vector3(0.6, 0.5, 0.8).normalize();
  const view = (d) => {
    camera.position.copy(sphere.center).addScaledVector(direction, d);
    camera.lookAt(sphere.center);
    camera.updateMatrixWorld();
  };
  view(framing);
  for (const l of lods) { l.lod.autoUpdate = false; l.lod.levels.forEach((v, i) => { v.object.visible = i === 0; }); }
  result.full = draw(scene, camera);
  result.coveredFull = coveredShare();
  for (const l of lods) l.lod.autoUpdate = true;
  result.framed = draw(scene, camera);
  result.covered = coveredShare();
  // Eight steps out, geometric, the last beyond every switch distance.
  result.steps = [];
  for (let i = 1; i <= 8; ++i) {
    view(framing * Math.pow(farthest * 1.5 / framing, i / 8));
    result.steps.push(draw(scene, camera));
  }
  result.far = result.steps.at(-1);
  return result;
};
window.ready = true;
</script></body></html>`;

const MIME = { '.js': 'text/javascript', '.html': 'text/html', '.png': 'image/png', '.jpg': 'image/jpeg',
               '.jpeg': 'image/jpeg', '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json' };

// /page.html, /three/... from node_modules, /fs/ABSOLUTE_PATH for the files
// (so relative buffer and image URIs resolve beside them).
function serve() {
  const server = createServer(async (req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    let file;
    if (url === '/page.html') { res.writeHead(200, { 'content-type': 'text/html' }); res.end(PAGE); return; }
    if (url.startsWith('/three/')) file = path.join(three, path.normalize(url.slice('/three/'.length)));
    else if (url.startsWith('/fs/')) file = path.normalize(url.slice('/fs'.length));
    try {
      if (!file) throw new Error('not found');
      const data = await readFile(file);
      res.writeHead(200, { 'content-type': MIME[path.extname(file).toLowerCase()] || 'application/octet-stream' });
      res.end(data);
    } catch {
      res.writeHead(404); res.end();
    }
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// One browser with the page loaded: `draw(file)` gives {file, loaded, error,
// consoleErrors, warnings, covered, coveredFull, full, framed, steps, far,
// lodNodes, lodLevels, lodOrderErrors}; `close()` ends it.
export async function openDrawer({ chromium } = {}) {
  const browser = await launchChromium(chromium);
  const server = await serve();
  const close = async () => { await browser.close(); server.close(); };
  try {
    const page = await browser.newPage();
    let errors = [], warnings = [];
    page.on('console', (m) => {
      if (m.type() === 'error') errors.push(m.text());
      else if (m.type() === 'warn' || m.type() === 'warning') warnings.push(m.text());
    });
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`http://127.0.0.1:${server.address().port}/page.html`, { waitUntil: 'load' });
    await page.waitForFunction(() => window.ready, { timeout: 30000 });
    if (errors.length) throw new Error(`the page does not start: ${errors.join(' | ')}`);
    const draw = async (file) => {
      errors = []; warnings = [];
      const url = '/fs' + path.resolve(file).split('/').map(encodeURIComponent).join('/');
      const r = await page.evaluate((u) => window.drawGltf(u), url);
      return { file, ...r, consoleErrors: errors, warnings };
    };
    return { draw, close };
  } catch (e) {
    await close();
    throw e;
  }
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  let chromium;
  if (args[0] === '--chromium') { chromium = args[1]; args.splice(0, 2); }
  try {
    const drawer = await openDrawer({ chromium });
    try {
      for (const file of args) console.log(JSON.stringify(await drawer.draw(file)));
    } finally {
      await drawer.close();
    }
  } catch (e) {
    console.error(e.message);
    process.exit(e instanceof ChromiumCannotStart ? 77 : 1);
  }
}
