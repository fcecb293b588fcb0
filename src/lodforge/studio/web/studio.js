// The studio's page: files, scene tree, LOD options and run, statistics,
// messages, and a three.js view in which every LOD node switches by its own
// distance at the ranges of the file (THREE.LOD.addLevel).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const TYPES = ['polygon', 'line', 'sphere', 'cone', 'cylinder', 'cube'];
const LEVEL_COLOURS = [0x2e9e44, 0xe0c020, 0xe07020, 0xd02030, 0x9040c0, 0x3060d0, 0x20a0a0];

// What the page holds; window.studio lets tests and the console look at it.
const state = { files: [], current: null, result: null, lods: [], meshes: [], bounds: null };
window.studio = state;

async function api(method, url, body) {
  const res = await fetch(url, {
    method, headers: { 'Content-Type': 'application/json' },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const json = await res.json();
  if (!res.ok) throw new Error(json.error || res.statusText);
  return json;
}

function element(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v; else if (k.startsWith('on')) e.addEventListener(k.slice(2), v); else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

// ---- files ----
async function loadFiles() {
  const { files } = await api('GET', '/api/files');
  state.files = files;
  const body = $('files').tBodies[0];
  body.replaceChildren();
  for (const f of files) {
    const shapes = Object.entries(f.shapes).map(([t, n]) => `${t} ${n}`).join(', ');
    const row = element('tr', { 'data-path': f.path, onclick: () => select(f.path) },
      element('td', {}, f.path.split('/').pop()), element('td', {}, String(f.size)),
      element('td', {}, f.error ? '' : shapes), element('td', {}, f.error ? '' : String(f.triangles)));
    body.append(row);
    if (f.error) body.append(element('tr', {}, element('td', { colspan: 4, class: 'error parse-error' }, f.error)));
  }
  if (!state.current && files.length) await select(files.find((f) => !f.error)?.path || files[0].path);
}

async function select(path) {
  state.current = path;
  for (const tr of $('files').tBodies[0].rows) tr.classList.toggle('selected', tr.dataset.path === path);
  const f = state.files.find((x) => x.path === path);
  $('save-path').value = path.replace(/(\.[^./]+)?$/, '_lod$1');
  updateCommand();
  $('tree').replaceChildren();
  await loadText(path);
  if (f && f.error) return;
  const tree = await api('GET', `/api/tree?path=${encodeURIComponent(path)}`);
  $('tree').append(...tree.map(treeNode));
  const status = await api('GET', `/api/lod?path=${encodeURIComponent(path)}`);
  showRun(status);
  $('which').value = status.state === 'done' ? 'output' : 'input';
  await loadGeometry();
}

// The lines of a node and of everything under it: selecting a group selects
// the shapes in it (meshes carry the line of the shape they come from).
function linesUnder(n, out = []) {
  out.push(n.line);
  for (const c of n.children || []) linesUnder(c, out);
  return out;
}

function treeNode(n) {
  const label = `${n.name ? `DEF ${n.name} ` : ''}${n.use ? 'USE ' : ''}${n.type}  (line ${n.line})`;
  const fields = Object.entries(n.fields || {}).map(([k, v]) => element('div', { class: 'fields' }, `${k} ${v}`));
  const pick = (e) => { e.preventDefault(); e.stopPropagation(); selectLines(linesUnder(n), n.line); };
  const head = element('span', { class: 'node', 'data-line': n.line, onclick: pick }, label);
  if (!n.children || (n.children.length === 0 && fields.length === 0)) return element('div', { class: 'leaf' }, head);
  const d = element('details', {}, element('summary', {}, head), ...fields, ...n.children.map(treeNode));
  d.open = n.children.length > 0 && n.children.length < 20;
  return d;
}

// ---- selection: tree node, meshes and statistics rows of the same lines ----
const SELECTED_GLOW = new THREE.Color(0x906000), NO_GLOW = new THREE.Color(0);
function selectLines(lines, line) {
  const set = new Set(lines);
  state.selected = line === undefined ? null : { line, lines: [...set] };
  for (const m of state.meshes) {
    const on = set.has(m.userData.line);
    m.userData.selected = on;
    for (const mat of [m.userData.own, m.userData.byLevel, m.userData.byDeviation]) mat?.emissive.copy(on ? SELECTED_GLOW : NO_GLOW);
  }
  for (const e of document.querySelectorAll('#tree .node.selected')) e.classList.remove('selected');
  const node = document.querySelector(`#tree .node[data-line="${line}"]`);
  if (node) {
    node.classList.add('selected');
    for (let p = node.parentElement; p && p.id !== 'tree'; p = p.parentElement) if (p.tagName === 'DETAILS') p.open = true;
    node.scrollIntoView({ block: 'nearest' });
  }
  for (const tr of $('stats').tBodies[0].rows) tr.classList.toggle('selected', set.has(Number(tr.dataset.line)));
  $('selection').textContent = selectionText(set);
}
state.selectLines = selectLines;

function selectionText(set) {
  if (!state.selected) return '';
  const n = state.meshes.filter((m) => m.userData.selected).length;
  const shapes = (state.result ? state.result.shapes : []).filter((s) => set.has(s.line));
  const levels = shapes.map((s) => `${s.type} (line ${s.line}): ` + s.levels.map((l, i) =>
    `L${i} ${l.triangles} tri, ${l.vertices} vert, error ${l.error.toPrecision(3)}${i ? `, from ${l.from_distance.toPrecision(4)}` : ''}`).join('; '));
  return `selected line ${state.selected.line}: ${n} meshes${levels.length ? ' · ' + levels.join(' · ') : ' (no LOD statistics: Make LOD)'}`;
}

$('open-form').addEventListener('submit', async (e) => {
  e.preventDefault();
  $('open-error').textContent = '';
  try {
    const f = await api('POST', '/api/open', { path: $('open-path').value });
    await loadFiles();
    await select(f.path);
  } catch (err) { $('open-error').textContent = err.message; }
});

// A scene file's text. Gzip-compressed data (.wrl.gz, .wrz, .iv.gz: known by
// the gzip magic bytes, as the CLI's reader knows it) is inflated here, so the
// upload carries the scene's text whatever the file's compression.
async function sceneText(file) {
  const head = new Uint8Array(await file.slice(0, 2).arrayBuffer());
  if (head[0] !== 0x1f || head[1] !== 0x8b) return file.text();
  try {
    return await new Response(file.stream().pipeThrough(new DecompressionStream('gzip'))).text();
  } catch (err) {
    throw new Error(`${file.name}: corrupt gzip data (${err.message})`);
  }
}

$('upload-file').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  $('open-error').textContent = '';
  try {
    const f = await api('POST', '/api/upload', { name: file.name, text: await sceneText(file) });
    await loadFiles();
    await select(f.path);
  } catch (err) { $('open-error').textContent = err.message; }
});

// ---- editor: CodeMirror 5 (a classic script, window.CodeMirror) ----
CodeMirror.defineSimpleMode('vrml', {
  start: [
    { regex: /#.*/, token: 'comment' },
    { regex: /"(?:[^\\"]|\\.)*"?/, token: 'string' },
    { regex: /(?:DEF|USE)\b/, token: 'keyword', next: 'name' },
    { regex: /(?:fields|isA|TRUE|FALSE|NULL)\b/, token: 'keyword' },
    { regex: /[-+]?(?:0[xX][0-9a-fA-F]+|(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)/, token: 'number' },
    { regex: /[A-Z][A-Za-z0-9_]*(?=\s*\{)/, token: 'type' },
    { regex: /[A-Z][A-Z0-9_]*\b/, token: 'atom' },
    { regex: /[A-Za-z_][A-Za-z0-9_]*/, token: 'attribute' },
    { regex: /[{}\[\]]/, token: 'bracket' },
  ],
  name: [{ regex: /\s+/, token: null }, { regex: /[^\s{}\[\]]+/, token: 'variable-2', next: 'start' }],
  meta: { lineComment: '#' },
});
const editor = CodeMirror.fromTextArea($('editor'), { mode: 'vrml', lineNumbers: true });
state.editor = editor;
let markedLine = null;

function markParseError(line) {
  if (markedLine !== null) editor.removeLineClass(markedLine, 'background', 'parse-error-line');
  markedLine = line;
  if (line !== null) editor.addLineClass(line, 'background', 'parse-error-line');
}

async function loadText(path) {
  const t = await api('GET', `/api/text?path=${encodeURIComponent(path)}`);
  editor.setValue(t.text);
  editor.clearHistory();
  markParseError(null);
  $('parse-error').textContent = '';
  $('parse-state').textContent = t.edited ? 'edited (not saved)' : '';
  // A file that does not parse shows its error in the editor too.
  const f = state.files.find((x) => x.path === path);
  const at = f && f.error && /:(\d+):(\d+): /.exec(f.error);
  if (at) showParseError({ error: f.error, line: Number(at[1]), column: Number(at[2]) });
}

function showParseError(r) {
  $('parse-error').textContent = r.line ? `line ${r.line}:${r.column}: ${r.error}` : r.error;
  if (r.line) {
    markParseError(r.line - 1);
    editor.setCursor({ line: r.line - 1, ch: Math.max(0, r.column - 1) });
    editor.scrollIntoView(null, 100);
  }
}

$('reparse').addEventListener('click', async () => {
  $('parse-error').textContent = '';
  markParseError(null);
  try {
    const r = await api('POST', '/api/parse', { path: state.current, text: editor.getValue() });
    if (!r.parsed) { showParseError(r); $('parse-state').textContent = 'parse error'; return; }
    const cursor = editor.getCursor();
    await loadFiles();
    await select(state.current);
    editor.setCursor(cursor);
    $('parse-state').textContent = 'parsed (not saved)';
  } catch (err) { $('parse-error').textContent = err.message; }
});

// ---- options and the command line ----
// One tab per shape type, as the seed's LoD dialog (Sphere | Cylinder | Cone
// | Polygon | Line | Cube): its quality (0 an empty node, 1 no levels, else
// how many levels) and its manual ranges. A tab with a setting is marked.
const TAB_ORDER = ['sphere', 'cylinder', 'cone', 'polygon', 'line', 'cube'];
function showTab(t) {
  for (const b of $('type-tabs').children) b.classList.toggle('active', b.dataset.type === t);
  for (const p of $('per-type').children) p.hidden = p.dataset.type !== t;
}
for (const t of TAB_ORDER.filter((x) => TYPES.includes(x))) {
  $('type-tabs').append(element('button', { type: 'button', 'data-type': t, onclick: () => showTab(t) }, t[0].toUpperCase() + t.slice(1)));
  $('per-type').append(element('div', { 'data-type': t },
    element('label', {}, 'quality ', element('input', { name: `quality-${t}`, type: 'number', min: 0, step: 1, placeholder: 'auto' }),
      element('small', {}, ' 0 empty node, 1 no levels, n levels')),
    element('label', {}, 'ranges ', element('input', { name: `ranges-${t}`, placeholder: 'a,b,...', size: 16 }))));
}
showTab(TAB_ORDER[0]);
function markTabs() {
  for (const b of $('type-tabs').children) {
    const t = b.dataset.type;
    b.classList.toggle('set', [`quality-${t}`, `ranges-${t}`].some((n) => $('options').elements[n].value !== ''));
  }
}

function options() {
  const form = $('options');
  const o = {};
  const defaults = { method: 'qem', export: 'spec' };
  for (const e of form.elements) {
    if (!e.name) continue;
    // verbose-CATEGORY: one box per category of --verbose, in the page's order.
    if (e.name.startsWith('verbose-')) { if (e.checked) (o.verbose ||= []).push(e.name.slice(8)); continue; }
    if (e.type === 'checkbox') { if (e.checked) o[e.name] = true; continue; }
    if (e.value === '' || defaults[e.name] === e.value) continue;
    if (e.name.startsWith('quality-')) (o.quality ||= []).push(`${e.name.slice(8)}=${e.value}`);
    else if (e.name === 'ranges-all') (o.ranges ||= []).push(e.value);
    else if (e.name.startsWith('ranges-')) (o.ranges ||= []).push(`${e.name.slice(7)}=${e.value}`);
    else o[e.name] = e.type === 'number' ? Number(e.value) : e.value;
  }
  return o;
}
state.options = options;

function shellWord(w) { return /^[A-Za-z0-9\/._\-=,+:]+$/.test(w) ? w : `'${w.replace(/'/g, `'\\''`)}'`; }

// The same text the server builds (lod_request.h): keys in alphabetical order.
function updateCommand() {
  if (!state.current) return;
  const args = ['lodforge', 'lod', state.current, '-o', $('save-path').value];
  const o = options();
  for (const k of Object.keys(o).sort()) {
    const v = o[k];
    if (Array.isArray(v)) for (const x of v) args.push(`--${k}`, x);
    else if (v === true) args.push(`--${k}`);
    else args.push(`--${k}`, String(v));
  }
  $('command-line').value = args.map(shellWord).join(' ');
}
$('options').addEventListener('input', () => { markTabs(); updateCommand(); });
$('save-path').addEventListener('input', updateCommand);
$('copy-command').addEventListener('click', () => {
  $('command-line').select();
  navigator.clipboard?.writeText($('command-line').value).catch(() => document.execCommand('copy'));
});

// ---- the run ----
$('make-lod').addEventListener('click', async () => {
  $('lod-error').textContent = '';
  try {
    const started = await api('POST', '/api/lod', { path: state.current, options: options() });
    $('lod-state').textContent = 'running';
    state.running = true;
    await poll();
    $('which').value = 'output';
    await loadGeometry();
  } catch (err) { $('lod-error').textContent = err.message; }
  state.running = false;
});

async function poll() {
  for (;;) {
    const s = await api('GET', `/api/lod?path=${encodeURIComponent(state.current)}`);
    const p = s.progress;
    $('progress').value = p.total ? p.done / p.total : 0;
    if (s.state !== 'running') { showRun(s); if (s.state === 'failed') throw new Error(s.error); return s; }
    await new Promise((r) => setTimeout(r, 200));
  }
}

function showRun(s) {
  state.result = s.result || null;
  $('lod-state').textContent = s.state === 'idle' ? '' : s.state;
  if (s.state === 'done') { $('progress').value = 1; $('command-line').value = s.command_line.replace(/ -o \S+/, ` -o ${shellWord($('save-path').value)}`); }
  showStatistics();
  showMessages();
}

$('save').addEventListener('click', async () => {
  $('save-state').textContent = '';
  try {
    const r = await api('POST', '/api/save', { path: state.current, output: $('save-path').value });
    $('save-state').textContent = `written ${r.written} as ${r.format} (${r.bytes} bytes)`;
  } catch (err) { $('save-state').textContent = err.message; $('save-state').className = 'error'; }
});

// ---- statistics and messages ----
function showStatistics() {
  const body = $('stats').tBodies[0];
  body.replaceChildren();
  const r = state.result;
  drawPlot(r ? r.triangles_by_distance : []);
  if (!r) return;
  for (const s of r.shapes) {
    s.levels.forEach((l, i) => body.append(element('tr', { 'data-line': s.line, onclick: () => selectLines([s.line], s.line) },
      element('td', {}, i ? '' : `${s.type}${s.name ? ' ' + s.name : ''} (line ${s.line})`), element('td', {}, String(i)),
      element('td', {}, String(l.triangles)), element('td', {}, String(l.vertices)),
      element('td', {}, l.error.toPrecision(3)), element('td', {}, l.from_distance < 0 ? '' : l.from_distance.toPrecision(4)))));
  }
}

function drawPlot(points) {
  const c = $('plot'), g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  g.strokeStyle = '#888'; g.strokeRect(40, 10, c.width - 50, c.height - 40);
  if (!points.length) return;
  // Distance on a log scale: the switches of small and large objects are
  // decades apart.
  const ds = points.map((p) => p.distance).filter((d) => d > 0);
  const minD = Math.min(...ds) || 1, maxD = Math.max(...ds) || 1, maxT = Math.max(...points.map((p) => p.triangles)) || 1;
  const span = Math.log(maxD / minD) || 1;
  const x = (d) => 40 + (c.width - 50) * (d > 0 ? Math.log(d / minD) / span : 0), y = (t) => c.height - 30 - (c.height - 40) * t / maxT;
  g.strokeStyle = '#2060c0'; g.beginPath();
  points.forEach((p, i) => (i ? g.lineTo(x(p.distance), y(p.triangles)) : g.moveTo(x(p.distance), y(p.triangles))));
  g.stroke();
  g.fillStyle = '#000';
  g.fillText(`${maxT} triangles`, 42, 20); g.fillText(`distance ${maxD.toPrecision(4)} (log scale)`, c.width - 170, c.height - 12); g.fillText(minD.toPrecision(3), 40, c.height - 12); g.fillText('0', 30, c.height - 30);
}

function showMessages() {
  const msgs = state.result ? state.result.messages : [];
  for (const [sel, key] of [['msg-category', 'category'], ['msg-level', 'level']]) {
    const keep = $(sel).value;
    const values = [...new Set(msgs.map((m) => m[key]))];
    $(sel).replaceChildren(element('option', { value: '' }, 'all'), ...values.map((v) => element('option', { value: v }, v)));
    $(sel).value = values.includes(keep) ? keep : '';
  }
  filterMessages();
}
function filterMessages() {
  const cat = $('msg-category').value, lvl = $('msg-level').value;
  const msgs = (state.result ? state.result.messages : []).filter((m) => (!cat || m.category === cat) && (!lvl || m.level === lvl));
  $('messages').tBodies[0].replaceChildren(...msgs.map((m) => element('tr', {},
    element('td', {}, m.category), element('td', {}, m.level), element('td', {}, m.text))));
}
$('msg-category').addEventListener('change', filterMessages);
$('msg-level').addEventListener('change', filterMessages);

// ---- 3D view ----
const renderer = new THREE.WebGLRenderer({ canvas: $('canvas'), antialias: true });
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x223344);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
scene.add(camera);
camera.add(new THREE.DirectionalLight(0xffffff, 2.2));
scene.add(new THREE.AmbientLight(0xffffff, 0.6));
const controls = new OrbitControls(camera, renderer.domElement);
const root = new THREE.Group();
scene.add(root);
state.renderer = renderer; state.camera = camera; state.controls = controls; state.scene3d = scene;

// Textures by file (served by /api/texture from the allowed folders) or by
// inline SFImage (w, h, components, then one integer per pixel, bottom row
// first as OpenGL reads it), one THREE.Texture each.
const textures = new Map();
function textureOf(t) {
  const key = t.file !== undefined ? `file:${t.file}` : `image:${t.image.join(',')}`;
  if (textures.has(key)) return textures.get(key);
  let tex;
  if (t.file !== undefined) {
    tex = new THREE.TextureLoader().load(`/api/texture?path=${encodeURIComponent(state.current)}&file=${encodeURIComponent(t.file)}`);
  } else {
    const [w, h, c] = t.image, px = new Uint8Array(w * h * 4);
    for (let i = 0; i < w * h; ++i) {
      const v = t.image[3 + i] >>> 0;
      const bytes = c === 1 ? [v & 255, v & 255, v & 255, 255] : c === 2 ? [(v >> 8) & 255, (v >> 8) & 255, (v >> 8) & 255, v & 255]
        : c === 3 ? [(v >> 16) & 255, (v >> 8) & 255, v & 255, 255] : [(v >>> 24) & 255, (v >> 16) & 255, (v >> 8) & 255, v & 255];
      px.set(bytes, i * 4);
    }
    tex = new THREE.DataTexture(px, w, h);
    tex.flipY = false;
    tex.needsUpdate = true;
  }
  tex.wrapS = tex.wrapT = THREE.RepeatWrapping;
  tex.colorSpace = THREE.SRGBColorSpace;
  textures.set(key, tex);
  return tex;
}

function meshOf(m, offset, level) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(m.positions, 3));
  if (m.colors) g.setAttribute('color', new THREE.Float32BufferAttribute(m.colors, 3));
  const group = new THREE.Group();
  const matrix = new THREE.Matrix4().fromArray(m.matrix).premultiply(offset);
  group.matrixAutoUpdate = false; group.matrix.copy(matrix);
  if (m.indices.length) {
    g.setIndex(m.indices); g.computeVertexNormals();
    const map = m.texture && m.texcoords && textureOf(m.texture);
    if (map) g.setAttribute('uv', new THREE.Float32BufferAttribute(m.texcoords, 2));
    // A texture replaces the diffuse colour, as VRML 1.0 draws an RGB one.
    const own = new THREE.MeshLambertMaterial(map ? { map, side: THREE.DoubleSide } : { vertexColors: !!m.colors, side: THREE.DoubleSide });
    const byLevel = new THREE.MeshLambertMaterial({ color: LEVEL_COLOURS[level % LEVEL_COLOURS.length], side: THREE.DoubleSide });
    // The server's colours of `compare --colored` (colorize_deviation).
    const byDeviation = m.deviation_colors && new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
    const mesh = new THREE.Mesh(g, own);
    // "Triangles drawn" counts what the LODs choose, in view or not.
    mesh.frustumCulled = false;
    mesh.userData = {
      own, byLevel, byDeviation, line: m.line, deviation: m.deviation,
      ownColors: g.getAttribute('color'),
      deviationColors: m.deviation_colors && new THREE.Float32BufferAttribute(m.deviation_colors, 3),
    };
    colourMesh(mesh);
    state.meshes.push(mesh);
    group.add(mesh);
  }
  if (m.lines.length) {
    const lg = new THREE.BufferGeometry();
    lg.setAttribute('position', g.getAttribute('position'));
    lg.setIndex(m.lines);
    group.add(new THREE.LineSegments(lg, new THREE.LineBasicMaterial({ color: 0xdddddd })));
  }
  return group;
}

async function loadGeometry() {
  const which = $('which').value;
  const geo = await api('GET', `/api/geometry?path=${encodeURIComponent(state.current)}&which=${which}`);
  for (const c of [...root.children]) root.remove(c);
  state.meshes = []; state.lods = [];
  textures.clear();
  state.deviationMax = geo.deviation_max || 0;
  $('deviation-scale').textContent = `0 … ${state.deviationMax.toPrecision(3)}`;
  const none = new THREE.Matrix4();
  for (const s of geo.shapes) root.add(meshOf(s, none, 0));
  for (const l of geo.lods) {
    const lod = new THREE.LOD();
    lod.position.fromArray(l.center);
    const offset = new THREE.Matrix4().makeTranslation(-l.center[0], -l.center[1], -l.center[2]);
    // Child i from range[i-1] on, as a VRML 1.0 browser switches: beyond the
    // last range the child after it (or the last child); children past that
    // one are never drawn.
    l.levels.slice(0, l.ranges.length + 1).forEach((meshes, i) => {
      const level = new THREE.Group();
      // A generated level's shapes carry no line of their own: they are
      // the level-0 shapes at the same places, and select with them.
      meshes.forEach((m, j) => level.add(meshOf(m.line ? m : { ...m, line: l.levels[0][j]?.line || 0 }, offset, i)));
      lod.addLevel(level, i === 0 ? 0 : l.ranges[i - 1]);
    });
    root.add(lod);
    state.lods.push({ lod, ranges: l.ranges, line: l.line, name: l.name });
  }
  root.updateMatrixWorld(true);
  state.bounds = new THREE.Box3().setFromObject(root, true);
  if (state.bounds.isEmpty()) state.bounds.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  const size = state.bounds.getSize(new THREE.Vector3()).length();
  const farthest = Math.max(size * 3, ...state.lods.map((l) => (l.ranges.at(-1) || 0) * 1.3));
  controls.target.copy(state.bounds.getCenter(new THREE.Vector3()));
  camera.near = size / 1000; camera.far = farthest * 4 + size * 4; camera.updateProjectionMatrix();
  $('distance-slider').max = String(farthest);
  if (!state.viewSet) { viewFrom(size * 1.2); state.viewSet = true; }
  if (state.selected) selectLines(state.selected.lines, state.selected.line);
}
$('which').addEventListener('change', () => loadGeometry().catch((e) => { $('lod-error').textContent = e.message; }));

// Puts the camera `d` from the scene's centre along the current view direction.
function viewFrom(d) {
  const dir = camera.position.clone().sub(controls.target);
  if (dir.lengthSq() === 0) dir.set(0, 0, 1);
  camera.position.copy(controls.target).add(dir.setLength(Math.max(d, 1e-6)));
  controls.update();
  $('distance-slider').value = String(d);
}
state.viewFrom = viewFrom;
$('distance-slider').addEventListener('input', (e) => viewFrom(Number(e.target.value)));
// One colouring for every mesh: deviation colours over level colours over
// the scene's own.
function colourMesh(mesh) {
  const u = mesh.userData;
  const deviation = $('colour-deviation').checked && u.deviationColors;
  const colors = deviation ? u.deviationColors : u.ownColors;
  if (colors) mesh.geometry.setAttribute('color', colors);
  mesh.material = deviation ? u.byDeviation : $('colour-levels').checked ? u.byLevel : u.own;
}
function colourAll() {
  for (const m of state.meshes) colourMesh(m);
  $('colour-levels').disabled = $('colour-deviation').checked;
}
$('colour-levels').addEventListener('change', colourAll);
$('colour-deviation').addEventListener('change', colourAll);

// A click (not a drag) on the view selects the nearest drawn mesh.
const raycaster = new THREE.Raycaster();
let pressedAt = null;
renderer.domElement.addEventListener('pointerdown', (e) => { pressedAt = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!pressedAt || Math.hypot(e.clientX - pressedAt[0], e.clientY - pressedAt[1]) > 4) return;
  const r = renderer.domElement.getBoundingClientRect();
  const hit = pick((e.clientX - r.left) / r.width * 2 - 1, -(e.clientY - r.top) / r.height * 2 + 1);
  if (hit) selectLines([hit.userData.line], hit.userData.line); else selectLines([]);
});
function drawn(o) {
  for (; o; o = o.parent) if (!o.visible) return false;
  return true;
}
function pick(x, y) {
  raycaster.setFromCamera(new THREE.Vector2(x, y), camera);
  const hit = raycaster.intersectObjects(state.meshes.filter(drawn), false)[0];
  return hit ? hit.object : null;
}
state.pick = pick;

// Level 0 on the left (every LOD held at its first child), what the LODs
// draw from this eye on the right, same camera: popping shows as a
// difference between the halves. The right half renders last, so the
// triangles drawn are the LODs'.
function renderSideBySide(w, h) {
  const half = Math.floor(w / 2);
  camera.aspect = half / Math.max(1, h); camera.updateProjectionMatrix();
  renderer.setScissorTest(true);
  for (const l of state.lods) {
    l.lod.autoUpdate = false;
    l.lod.levels.forEach((level, i) => { level.object.visible = i === 0; });
  }
  renderer.setViewport(0, 0, half, h); renderer.setScissor(0, 0, half, h);
  renderer.render(scene, camera);
  for (const l of state.lods) l.lod.autoUpdate = true;
  renderer.setViewport(half, 0, w - half, h); renderer.setScissor(half, 0, w - half, h);
  renderer.render(scene, camera);
  renderer.setScissorTest(false); renderer.setViewport(0, 0, w, h);
  camera.aspect = w / Math.max(1, h); camera.updateProjectionMatrix();
}
state.renderSideBySide = renderSideBySide;

function frame() {
  const c = renderer.domElement;
  if (c.width !== c.clientWidth || c.height !== c.clientHeight) {
    renderer.setSize(c.clientWidth, c.clientHeight, false);
    camera.aspect = c.clientWidth / Math.max(1, c.clientHeight); camera.updateProjectionMatrix();
  }
  if ($('side-by-side').checked) renderSideBySide(c.clientWidth, c.clientHeight);
  else renderer.render(scene, camera);
  state.trianglesDrawn = renderer.info.render.triangles;
  const d = camera.position.distanceTo(controls.target);
  state.distance = d;
  $('distance').textContent = d.toPrecision(4);
  $('slider-value').textContent = Number($('distance-slider').value).toPrecision(4);
  $('triangles-drawn').textContent = String(state.trianglesDrawn);
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

loadFiles().catch((e) => { $('open-error').textContent = e.message; });
