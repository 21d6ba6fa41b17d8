// onefold explore: the page draws what the server computes; it computes no geometry.
// Each control change asks /api/state for the design's new state (the Python
// solver is the one source of truth) and draws the form, the flat pattern, the
// numbers and the messages it returns. The Simulate button is simulate.js's, the
// Steel view (every settled design simulated) steel_view.js's, the Compensate
// button compensate.js's; the reduced frames of a drag on a slow GPU are quality.js's.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/OrbitControls.js';
import { createSimulation } from './simulate.js';
import { createQuality } from './quality.js';
import { createSteelView } from './steel_view.js';
import { createCompensation } from './compensate.js';

const $ = (id) => document.getElementById(id);

// Controls with a range slider and a number box (id and id-num); the number box
// holds the value sent (it may hold a bad value: the server says what is wrong).
const SLIDERS = ['alpha', 'beta', 'hc_fraction', 'width', 'height', 'apex_fraction',
  'x_plus', 'x_minus', 'y_plus', 'y_minus', 'thickness', 'bend_radius'];
const PLAIN = ['model', 'divisions', 'radius', 'polygon', 'cone_forming'];
const SHEET_FIELDS = {
  rectangle: ['width', 'height', 'apex_fraction'],
  quadrilateral: ['x_plus', 'x_minus', 'y_plus', 'y_minus'],
  polygon: ['polygon'],
};
const COMMON = ['model', 'alpha', 'beta', 'hc_fraction', 'radius', 'divisions', 'thickness', 'bend_radius',
  'cone_forming'];

let templateKey = null;
let sheetKind = 'rectangle';
let units = '';
let updates = 0;

// -- controls -------------------------------------------------------------
function valueOf(name) {
  return SLIDERS.includes(name) ? $(`${name}-num`).value : $(name).value;
}

function setValue(name, text) {
  if (SLIDERS.includes(name)) {
    $(`${name}-num`).value = text;
    $(name).value = text;
  } else {
    $(name).value = text;
  }
}

function query(onlyTemplate = false) {
  const q = new URLSearchParams();
  if (templateKey !== null) q.set('template', templateKey);
  if (onlyTemplate) return q.toString();
  for (const name of [...COMMON, ...SHEET_FIELDS[sheetKind]]) q.set(name, valueOf(name));
  return q.toString();
}

function setRange(name, lo, hi) {
  const r = $(name);
  if (!(Number.isFinite(lo) && Number.isFinite(hi) && hi > lo)) return;
  r.min = String(lo);
  r.max = String(hi);
  r.step = String((hi - lo) / 1000);
  r.value = $(`${name}-num`).value;
}

// Slider bounds are display ranges only; the number box accepts any value.
function fitRanges(page) {
  const v = page.values;
  const num = (k) => Number(v[k]);
  for (const k of ['width', 'height', 'x_plus', 'x_minus', 'y_plus', 'y_minus']) {
    if (k in v) setRange(k, num(k) / 5, num(k) * 3);
  }
  const size = page.sheet_size;
  setRange('thickness', 0, Math.max(4 * num('thickness'), size / 200));
  setRange('bend_radius', 0, Math.max(4 * num('bend_radius'), 4 * num('thickness'), size / 200));
}

function fillControls(page) {
  sheetKind = page.sheet_kind;
  units = page.units;
  for (const [k, text] of Object.entries(page.values)) setValue(k, text);
  for (const fs of document.querySelectorAll('fieldset[data-kind]')) fs.hidden = fs.dataset.kind !== sheetKind;
  for (const u of document.querySelectorAll('.unit')) u.textContent = units;
  fitRanges(page);
}

// -- 3D view --------------------------------------------------------------
THREE.Object3D.DEFAULT_UP.set(0, 0, 1); // z up, as the form stands on the ground
const canvas = $('view');
// no preserveDrawingBuffer: nothing reads the canvas back (the downloads are the
// server's files), and keeping the buffer costs a copy of it on every frame
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xeef1f5);
const camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1000);
scene.add(camera);
const headlight = new THREE.DirectionalLight(0xffffff, 2.2);
headlight.position.set(0.6, 0.8, 1.0);
camera.add(headlight);
scene.add(new THREE.HemisphereLight(0xffffff, 0x777777, 1.3));
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', render);
controls.addEventListener('start', () => quality.orbit(true));
controls.addEventListener('end', () => quality.orbit(false));

// The sheet: one mesh drawn on both sides (one pass over its triangles instead
// of a mesh per side: software GL's cost of a frame is much per triangle); the
// standard material takes the top face's colour, metalness and roughness on
// front faces and the underside's on back faces.
const TOP = { color: 0xb9c6d3, metalness: 0.25, roughness: 0.5 };
const UNDER = { color: 0xa8825e, metalness: 0.1, roughness: 0.7 };
const sheetMaterial = new THREE.MeshStandardMaterial({
  ...TOP, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
});
sheetMaterial.onBeforeCompile = (shader) => {
  Object.assign(shader.uniforms, {
    underDiffuse: { value: new THREE.Color(UNDER.color) },
    underMetalness: { value: UNDER.metalness },
    underRoughness: { value: UNDER.roughness },
  });
  // the fragment shader's lines that read the colour, metalness and roughness
  // (the last two in their chunks, not yet included)
  const chunk = (name) => THREE.ShaderChunk[name];
  const swap = [
    ['vec4 diffuseColor = vec4( diffuse, opacity );',
      'vec4 diffuseColor = vec4( gl_FrontFacing ? diffuse : underDiffuse, opacity );'],
    ['#include <metalnessmap_fragment>', chunk('metalnessmap_fragment').replace(
      'float metalnessFactor = metalness;',
      'float metalnessFactor = gl_FrontFacing ? metalness : underMetalness;')],
    ['#include <roughnessmap_fragment>', chunk('roughnessmap_fragment').replace(
      'float roughnessFactor = roughness;',
      'float roughnessFactor = gl_FrontFacing ? roughness : underRoughness;')],
  ];
  let text = shader.fragmentShader;
  for (const [from, to] of swap) {
    if (!text.includes(from) || !to.includes('gl_FrontFacing')) {
      throw new Error(`three.js shader changed: no "${from}"`);
    }
    text = text.replace(from, to);
  }
  shader.fragmentShader = `uniform vec3 underDiffuse;\nuniform float underMetalness;\nuniform float underRoughness;\n${text}`;
};
const edgeMaterial = new THREE.LineBasicMaterial({ color: 0x374151 });
const BEND_COLOURS = { UP: 0xd62828, DOWN: 0x1d4ed8 };
const form = new THREE.Group();
const decorations = new THREE.Group();
// the ground: a flat matte plane (Lambert: the colour a rough standard material
// gives it, to one level in 255, at a third of the cost of drawing it in software GL)
const groundMaterial = new THREE.MeshLambertMaterial({ color: 0xd5dbe2 });
const ground = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), groundMaterial);
// the ground's grid: 12 x 12 cells of a unit square, scaled to the form's ground
const grid = new THREE.GridHelper(1, 12, 0x9aa5b1, 0xbac3cc);
grid.rotation.x = Math.PI / 2; // GridHelper lies in x-z; the ground is x-y
scene.add(ground, grid, form, decorations);
let framed = false;

// The form's meshes and lines are made once and updated in place on every state:
// the positions are copied into the same buffer while the mesh keeps its size, the
// triangles (and the lines, derived from them) are replaced only when they change.
let geometry = null; // the form's surface (both sides' meshes share it)
let lines = null; // the sheet's edge and the crease: LineSegments on the same positions
let meshKey = null; // the server's mesh_key of `geometry`'s triangles
const surfaces = [new THREE.Mesh(undefined, sheetMaterial)];
const edges = new THREE.LineSegments(undefined, edgeMaterial);
form.add(...surfaces, edges);
// crease halves (rods: a unit cylinder along y, scaled) and the apex (a unit sphere)
const rodGeometry = new THREE.CylinderGeometry(1, 1, 1, 10);
const rods = [];
const apexBall = new THREE.Mesh(new THREE.SphereGeometry(1, 20, 12),
  new THREE.MeshBasicMaterial({ color: 0xf59e0b }));
decorations.add(apexBall);

function decode(b64, Type) {
  const text = atob(b64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i += 1) bytes[i] = text.charCodeAt(i);
  return new Type(bytes.buffer);
}

// The edges of the mesh that only one triangle has (index pairs): the sheet's
// outline, and the crease, where the two sides' meshes meet (they share no
// vertex there but the apex).
function boundaryEdges(index, vertexCount) {
  const seen = new Map();
  for (let t = 0; t < index.length; t += 3) {
    for (let k = 0; k < 3; k += 1) {
      const a = index[t + k];
      const b = index[t + (k + 1) % 3];
      const key = a < b ? a * vertexCount + b : b * vertexCount + a;
      seen.set(key, (seen.get(key) || 0) + 1);
    }
  }
  const out = [];
  for (const [key, n] of seen) {
    if (n === 1) out.push(Math.floor(key / vertexCount), key % vertexCount);
  }
  return vertexCount < 65536 ? new Uint16Array(out) : new Uint32Array(out);
}

function setSurface(f) {
  const positions = decode(f.positions, Float32Array);
  // the server leaves the triangles out when they are those the page has
  const same = geometry && f.mesh_key === meshKey;
  if (same) {
    const attr = geometry.getAttribute('position');
    attr.array.set(positions);
    attr.needsUpdate = true;
  } else {
    geometry?.dispose();
    lines?.dispose();
    geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const IndexType = f.index_type === 'uint16' ? Uint16Array : Uint32Array;
    const index = decode(f.indices, IndexType);
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    lines = new THREE.BufferGeometry();
    lines.setAttribute('position', geometry.getAttribute('position'));
    lines.setIndex(new THREE.BufferAttribute(boundaryEdges(index, f.vertex_count), 1));
    for (const m of surfaces) m.geometry = geometry;
    edges.geometry = lines;
    meshKey = f.mesh_key;
  }
  geometry.computeVertexNormals(); // shading only
  geometry.computeBoundingSphere();
  lines.boundingSphere = geometry.boundingSphere;
}

function placeRod(mesh, a, b, radius) {
  const pa = new THREE.Vector3(...a);
  const dir = new THREE.Vector3(...b).sub(pa);
  mesh.scale.set(radius, dir.length(), radius);
  mesh.position.copy(pa).addScaledVector(dir, 0.5);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), dir.normalize());
}

function drawForm(f, fit) {
  setSurface(f);
  const lo = new THREE.Vector3(...f.bbox.min);
  const hi = new THREE.Vector3(...f.bbox.max);
  const size = Math.max(hi.x - lo.x, hi.y - lo.y, hi.z - lo.z) || 1;
  while (rods.length < f.crease.length) {
    const rod = new THREE.Mesh(rodGeometry, new THREE.MeshBasicMaterial());
    rods.push(rod);
    decorations.add(rod);
  }
  rods.forEach((rod, i) => {
    const c = f.crease[i];
    rod.visible = c !== undefined;
    if (!c) return;
    rod.material.color.setHex(BEND_COLOURS[c.bend]);
    placeRod(rod, c.points[0], c.points[1], size * 0.004);
  });
  apexBall.scale.setScalar(size * 0.012);
  apexBall.position.set(...f.apex);

  const cx = (lo.x + hi.x) / 2;
  const cy = (lo.y + hi.y) / 2;
  const extent = 1.8 * Math.max(hi.x - lo.x, hi.y - lo.y);
  ground.scale.set(extent, extent, 1);
  ground.position.set(cx, cy, -1e-3 * size);
  grid.scale.set(extent, 1, extent);
  grid.position.set(cx, cy, -5e-4 * size);

  if (fit || !framed) {
    const centre = lo.clone().add(hi).multiplyScalar(0.5);
    const dist = (0.95 * size) / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2));
    camera.near = size / 500;
    camera.far = size * 200;
    camera.position.copy(centre).add(new THREE.Vector3(0.9, -1.5, 0.6).normalize().multiplyScalar(dist));
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
    framed = true;
  }
}

function resize() {
  const box = canvas.parentElement.getBoundingClientRect();
  const w = Math.max(1, Math.floor(box.width));
  const h = Math.max(1, Math.floor(canvas.getBoundingClientRect().height));
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}

// Each frame at the quality of the moment (quality.js): reduced while a drag
// goes on and full frames are slow here, full otherwise.
const quality = createQuality({
  renderer,
  draw: () => renderer.render(scene, camera),
  busy: () => inflight || pending !== null,
  onSettled: () => window.dispatchEvent(new CustomEvent('explore:settled', {
    detail: { done: performance.now(), quality: quality.quality() },
  })),
});

function render() {
  return quality.render();
}

const resizer = new ResizeObserver(resize);
resizer.observe(canvas.parentElement);
resizer.observe(canvas); // the simulation panel below it grows and shrinks

const simulation = createSimulation({ scene, form, render, query: () => query() });
const steel = createSteelView({ simulation, render });
// a compensation's values go into the controls as typed ones would
createCompensation({
  query: () => query(),
  lawName: simulation.lawName,
  load: (values) => {
    for (const [k, text] of Object.entries(values)) setValue(k, text);
    request();
  },
});

// -- numbers and messages ---------------------------------------------------
function fmt(x, digits = 5) {
  return x === null || x === undefined ? '–' : String(Number(Number(x).toPrecision(digits)));
}
function len(x) {
  return x === null || x === undefined ? '–' : `${fmt(x, 6)} ${units}`;
}
// an area in the design's unit² as one orders sheet metal: m² for mm designs,
// ft² for inch and foot designs (a 22 m² blank, not 22274271 mm²)
const AREA_UNITS = { mm: ['m²', 1e6], m: ['m²', 1], in: ['ft²', 144], ft: ['ft²', 1] };
function area(x) {
  const [name, per] = AREA_UNITS[units] || [`${units}²`, 1];
  return x === null || x === undefined ? '–' : `${fmt(x / per)} ${name}`;
}

function showNumbers(n) {
  const halves = { plus_x: '+x half', minus_x: '−x half' };
  $('fold-angles').textContent = Object.entries(n.fold_angles)
    .map(([k, v]) => `${halves[k] || k}: ${Number(v.deg).toFixed(2)}° ${v.bend}`).join(' · ');
  $('apex-height').textContent = len(n.apex_height);
  $('form-height').textContent = len(n.height);
  $('form-span').textContent = len(n.span);
  // the footprint as `onefold solve` prints it: width x depth (x, y), 6 significant digits
  $('form-footprint').textContent = n.width === null ? '–'
    : `${fmt(n.width, 6)} × ${fmt(n.depth, 6)} ${units}, hull area ${area(n.footprint_area)}`
      + (n.stable === false ? ' (no stable resting face)' : '');
  $('flat-size').textContent = n.flat_size ? `${fmt(n.flat_size[0])} × ${fmt(n.flat_size[1])} ${units}` : '–';
  $('relief-hole').textContent = n.relief_hole ? `Ø ${len(n.relief_hole)}` : (n.relief_hole === 0 ? 'none' : '–');
  $('angle-error').textContent = `${fmt(n.angle_condition_error_deg, 3)}°`;
}

function showMessages(messages) {
  const ul = $('messages');
  ul.replaceChildren();
  for (const el of document.querySelectorAll('#controls .invalid')) el.classList.remove('invalid');
  if (!messages.length) {
    const li = document.createElement('li');
    li.className = 'none';
    li.textContent = 'none';
    ul.append(li);
  }
  for (const m of messages) {
    const li = document.createElement('li');
    li.className = m.level;
    li.textContent = `${m.level}: ${m.text}`;
    ul.append(li);
    for (const c of m.controls || []) {
      $(c)?.classList.add('invalid');
      $(`${c}-num`)?.classList.add('invalid');
    }
  }
}

function setDownloads(q, enabled) {
  for (const a of document.querySelectorAll('#downloads a')) {
    a.href = `/download/${a.dataset.kind}?${q}`;
    a.setAttribute('aria-disabled', enabled ? 'false' : 'true');
  }
}

// -- the update loop: one request at a time, the latest values win -------------
// Each update leaves performance marks (benchmarks/bench_explore.py reads them):
// explore:request (asked), explore:answer (the server's answer arrives),
// explore:parsed (JSON read), explore:form (numbers, messages and the 3D form
// set), explore:drawn (the flat pattern set, the 3D view rendered).
const MARKS = ['explore:request', 'explore:answer', 'explore:parsed', 'explore:form', 'explore:drawn'];
let inflight = false;
let pending = null; // {templateOnly, fit}
let frameQuality = null; // the quality of the frame the last update drew
let frameWidth = null; // that frame's drawing-buffer width (px)
let sliding = false; // a slider is held (its input events, until its change)
let settledOn = { q: '', ok: false }; // the design of the last state drawn

function request(templateOnly = false, fit = false) {
  steel.changing(); // a simulation shows the design it was asked for only
  pending = { templateOnly: templateOnly || pending?.templateOnly || false, fit: fit || pending?.fit || false };
  if (!inflight) run();
}

async function run() {
  const job = pending;
  pending = null;
  inflight = true;
  const started = performance.now();
  const q = query(job.templateOnly);
  frameQuality = null;
  frameWidth = null;
  $('status').textContent = 'solving…';
  try {
    for (const m of MARKS) performance.clearMarks(m);
    performance.mark('explore:request');
    const res = await fetch(`/api/state?${q}${meshKey ? `&mesh=${meshKey}` : ''}`);
    performance.mark('explore:answer');
    const state = await res.json();
    performance.mark('explore:parsed');
    apply(state, job, res.ok ? q : null);
    const ms = performance.now() - started;
    $('status').textContent = state.ok
      ? `updated in ${Math.round(ms)} ms (server ${Math.round(state.server_ms)} ms)`
      : 'the design has an error: see the messages';
    finish(started, state.ok, state.server_ms, frameQuality, frameWidth);
  } catch (err) {
    showMessages([{ level: 'error', text: `no answer from the server (${err})`, controls: [] }]);
    $('status').textContent = 'server not reachable';
    finish(started, false);
  } finally {
    inflight = false;
    if (pending) run();
    else {
      quality.settle(); // a drag that ended while this update was on its way
      if (!sliding) steel.settled(settledOn.q, settledOn.ok);
    }
  }
}

function apply(state, job, q) {
  if (state.page) {
    if (job.templateOnly) fillControls(state.page);
  }
  showMessages(state.messages || []);
  document.body.classList.toggle('has-error', !state.ok);
  simulation.setEnabled(state.ok && !pending);
  settledOn = { q: query(), ok: state.ok };
  if (!state.ok) {
    setDownloads(q || '', false);
    return;
  }
  showNumbers(state.numbers);
  drawForm(state.form, job.fit);
  performance.mark('explore:form');
  $('flat').innerHTML = state.flat_svg
    || '<p class="no-flat">No flat pattern for these values: see the messages.</p>';
  setDownloads(query(), true);
  frameQuality = render();
  frameWidth = $('view').width;
  performance.mark('explore:drawn');
}

function finish(started, ok, serverMs = null, frame = null, width = null) {
  requestAnimationFrame(() => {
    updates += 1;
    document.body.dataset.updates = String(updates);
    window.dispatchEvent(new CustomEvent('explore:updated', {
      detail: {
        started, done: performance.now(), ok, server_ms: serverMs, quality: frame, width,
      },
    }));
  });
}

// -- wiring ---------------------------------------------------------------
for (const name of SLIDERS) {
  $(name).addEventListener('input', () => {
    $(`${name}-num`).value = $(name).value;
    quality.slide(); // a drag of the slider goes on until its change event
    sliding = true;
    request();
  });
  $(name).addEventListener('change', () => {
    quality.endSlide();
    sliding = false; // the release: the Steel view asks for its design's steel at once,
    steel.released(query()); // beside the state on its way (an error: the state's line)
  });
  $(`${name}-num`).addEventListener('input', () => {
    $(name).value = $(`${name}-num`).value;
    request();
  });
}
let typing = null;
for (const name of PLAIN) {
  $(name).addEventListener('input', () => {
    clearTimeout(typing);
    typing = setTimeout(request, name === 'polygon' ? 300 : 0);
  });
}
$('template').addEventListener('change', () => {
  templateKey = $('template').value;
  request(true, true);
});
$('controls').addEventListener('submit', (ev) => ev.preventDefault());

for (const a of document.querySelectorAll('#downloads a')) {
  a.addEventListener('click', async (ev) => {
    ev.preventDefault();
    const note = $('download-message');
    if (a.getAttribute('aria-disabled') === 'true') {
      note.textContent = 'Fix the values first: the design has an error.';
      return;
    }
    note.textContent = `making the ${a.dataset.kind.toUpperCase()} file…`;
    try {
      const res = await fetch(a.href);
      if (!res.ok) {
        note.textContent = `${a.dataset.kind.toUpperCase()}: ${await res.text()}`;
        return;
      }
      const name = /filename="([^"]+)"/.exec(res.headers.get('Content-Disposition') || '')?.[1] || 'onefold';
      const url = URL.createObjectURL(await res.blob());
      const link = document.createElement('a');
      link.href = url;
      link.download = name;
      document.body.append(link);
      link.click();
      link.remove();
      setTimeout(() => URL.revokeObjectURL(url), 60000);
      note.textContent = `saved ${name}`;
    } catch (err) {
      note.textContent = `download failed (${err})`;
    }
  });
}

async function start() {
  const res = await fetch('/api/templates');
  const info = await res.json();
  const select = $('template');
  for (const t of info.templates) {
    const opt = document.createElement('option');
    opt.value = t.key;
    opt.textContent = t.key;
    opt.title = t.description;
    select.append(opt);
  }
  templateKey = info.initial;
  select.value = templateKey;
  resize();
  request(true, true);
}

start();
