// The viewer page: decodes a .swm file in a Web Worker (the page stays
// responsive), shows it lit and orbitable, with its figures. A .glb or
// .gltf (one file: its buffers and images embedded) is loaded by
// GLTFLoader with the SWM_mesh_compression plugin, its .swm files
// decoded by a pool of workers, and shown with its own materials,
// textures and node tree. With "slow
// connection" on, the file's bytes arrive at a set rate instead and are
// decoded as they come (StreamDecoder): a displaced-subdivision file shows
// its base mesh first and each finer level once its bytes are in. State
// for scripts and tests: body[data-state] is loading | ready | decoding |
// streaming | shown | error, body[data-shown] counts the meshes shown,
// body[data-levels] lists the levels a stream showed ("0,1,2") and
// body[data-level-bytes] the bytes in when each was shown.
// `?file=URL` opens a file at load, `&sharpen=1` with Sharpen&Bend,
// `&rate=N` streams it at N bytes a second.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { SWMMeshCompressionExtension } from '../src/gltf.js';
import { toBufferGeometry } from '../src/three.js';
import { SWMWorker, SWMWorkerPool } from '../src/worker.js';
import { decodeStream, init } from '../src/swm.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const body = document.body;
const decoder = new SWMWorker();
const pool = new SWMWorkerPool(); // the .swm files of a glTF scene
const gltfLoader = new GLTFLoader().register((parser) => new SWMMeshCompressionExtension(parser, pool));
let current = null; // { name, bytes } of the file shown
let shown = 0;

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2126);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.2));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
camera.position.set(0, 0, 3);
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', render);
const material = new THREE.MeshStandardMaterial({ color: 0xd8c8a8, roughness: 0.6, metalness: 0.0, flatShading: false });
let mesh = null; // the object shown: a Mesh of a .swm file, or a glTF scene

function render() {
  renderer.render(scene, camera);
}

function resize() {
  renderer.setSize(window.innerWidth, window.innerHeight, false);
  camera.aspect = window.innerWidth / window.innerHeight;
  camera.updateProjectionMatrix();
  render();
}
window.addEventListener('resize', resize);
resize();

/** Shows `geometry`; `frame`: move the camera to it (not for a finer level of the mesh shown). */
function show(geometry, frame = true) {
  display(new THREE.Mesh(geometry, material), frame);
}

/** Shows `object` instead of the one shown, which is released. */
function display(object, frame = true) {
  if (mesh) {
    scene.remove(mesh);
    mesh.traverse((o) => {
      o.geometry?.dispose();
      if (o.material && o.material !== material) {
        for (const value of Object.values(o.material)) if (value?.isTexture) value.dispose();
        o.material.dispose();
      }
    });
  }
  mesh = object;
  scene.add(mesh);
  if (!frame) {
    render();
    return;
  }
  // Frame the bounding sphere.
  const { center, radius } = new THREE.Box3().setFromObject(object).getBoundingSphere(new THREE.Sphere());
  const r = radius > 0 && Number.isFinite(radius) ? radius : 1;
  controls.target.copy(center);
  const distance = r / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2));
  camera.position.copy(center).add(new THREE.Vector3(0.2, 0.1, 1).normalize().multiplyScalar(distance * 1.05));
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.update();
  render();
}

function figures(info) {
  const fmt = (n) => n.toLocaleString('en-US');
  $('mode').textContent = info.version ? `${info.mode} (v${info.version})` : info.mode;
  $('vertices').textContent = fmt(info.vertices);
  $('triangles').textContent = fmt(info.triangles);
  // A scene's bytes: the whole file, then its .swm files'.
  $('bytes').textContent = info.swmBytes === undefined ? fmt(info.bytes) : `${fmt(info.bytes)} (swm ${fmt(info.swmBytes)})`;
  // Bits per triangle of the swm data: of a scene, its coded primitives'.
  const [bits, tris] = info.swmBytes === undefined ? [8 * info.bytes, info.triangles] : [8 * info.swmBytes, info.codedTriangles];
  $('bpt').textContent = tris ? (bits / tris).toFixed(2) : '–';
  $('ms').textContent = `${info.decodeMs.toFixed(1)} ms`;
}

/** `bytes` as a stream of pieces that arrive at `rate` bytes a second. */
async function* throttled(bytes, rate) {
  const tick = 100; // ms
  const piece = Math.max(1, Math.round((rate * tick) / 1000));
  for (let at = 0; at < bytes.length; at += piece) {
    await new Promise((r) => setTimeout(r, tick));
    yield bytes.subarray(at, at + piece);
  }
}

/** Decodes `bytes` as they arrive at `rate` bytes a second, showing each level. */
async function stream(name, bytes, rate) {
  body.dataset.state = 'streaming';
  body.dataset.levels = '';
  body.dataset.levelBytes = '';
  const sharpen = $('sharpen').checked;
  const options = { normals: true, sharpen, bendSteps: sharpen ? 1 : 0 };
  await init();
  const levels = [];
  const at = [];
  const result = await decodeStream(throttled(bytes, rate), options, (level) => {
    if (current.bytes !== bytes) return;
    show(toBufferGeometry(level), levels.length === 0);
    figures(level.info);
    levels.push(level.info.level);
    at.push(level.info.bytes);
    $('level').textContent = `${level.info.level} (${level.info.bytes.toLocaleString('en-US')} of ${bytes.length.toLocaleString('en-US')} bytes in)`;
    body.dataset.levels = levels.join(',');
    body.dataset.levelBytes = at.join(',');
  });
  return result;
}

/** Whether `bytes` are a glTF document: a GLB, or JSON (a .gltf) by its name. */
function isGltf(name, bytes) {
  const magic = String.fromCharCode(...bytes.subarray(0, 4));
  return magic === 'glTF' || /\.gltf$/i.test(name);
}

/**
 * Loads a glTF scene through GLTFLoader and the plugin; its figures are
 * those of its coded primitives (their .swm bytes and decoded counts)
 * and the time of the whole load.
 */
async function openScene(bytes) {
  const started = performance.now();
  const gltf = await gltfLoader.parseAsync(bytes.slice().buffer, '');
  const coded = gltf.userData.swm?.primitives ?? [];
  let vertices = 0;
  let triangles = 0;
  const counted = new Set();
  gltf.scene.traverse((o) => {
    if (!o.isMesh || counted.has(o.geometry)) return;
    counted.add(o.geometry);
    vertices += o.geometry.attributes.position.count;
    triangles += (o.geometry.index?.count ?? o.geometry.attributes.position.count) / 3;
  });
  return {
    object: gltf.scene,
    info: {
      mode: `glTF, ${coded.length} of ${counted.size} primitives swm`,
      version: '',
      vertices,
      triangles,
      bytes: bytes.length,
      swmBytes: coded.reduce((n, p) => n + p.bytes, 0),
      codedTriangles: coded.reduce((n, p) => n + p.triangles, 0),
      decodeMs: performance.now() - started,
    },
  };
}

async function open(name, bytes) {
  current = { name, bytes };
  $('name').textContent = name;
  $('error').textContent = '';
  $('level').textContent = '–';
  body.dataset.state = 'decoding';
  const sharpen = $('sharpen').checked;
  const rate = $('slow').checked ? Number($('rate').value) : 0;
  try {
    if (isGltf(name, bytes)) {
      const { object, info } = await openScene(bytes);
      if (current.bytes !== bytes) return;
      display(object);
      figures(info);
      body.dataset.shown = String(++shown);
      body.dataset.state = 'shown';
      return;
    }
    const result = rate > 0
      ? await stream(name, bytes, rate)
      : await decoder.decode(bytes, { normals: true, sharpen, bendSteps: sharpen ? 1 : 0 });
    if (current.bytes !== bytes) return; // a newer file took over
    show(toBufferGeometry(result), !body.dataset.levels || rate === 0);
    figures(result.info);
    body.dataset.shown = String(++shown);
    body.dataset.state = 'shown';
  } catch (e) {
    if (current.bytes !== bytes) return;
    $('error').textContent = `${name}: ${e.message}`;
    body.dataset.state = 'error';
  }
}

async function openFile(file) {
  open(file.name, new Uint8Array(await file.arrayBuffer()));
}

$('file').addEventListener('change', (e) => {
  if (e.target.files.length) openFile(e.target.files[0]);
});
$('sharpen').addEventListener('change', () => {
  if (current) open(current.name, current.bytes);
});
window.addEventListener('dragover', (e) => {
  e.preventDefault();
  body.classList.add('dragging');
});
window.addEventListener('dragleave', () => body.classList.remove('dragging'));
window.addEventListener('drop', (e) => {
  e.preventDefault();
  body.classList.remove('dragging');
  if (e.dataTransfer.files.length) openFile(e.dataTransfer.files[0]);
});

const params = new URLSearchParams(location.search);
$('sharpen').checked = params.get('sharpen') === '1';
if (params.has('rate')) {
  $('slow').checked = true;
  $('rate').value = params.get('rate');
}
body.dataset.state = 'ready';
if (params.has('file')) {
  const url = params.get('file');
  fetch(url)
    .then((r) => (r.ok ? r.arrayBuffer() : Promise.reject(new Error(`HTTP ${r.status}`))))
    .then((b) => open(url.split('/').pop(), new Uint8Array(b)))
    .catch((e) => {
      $('error').textContent = `${url}: ${e.message}`;
      body.dataset.state = 'error';
    });
}
