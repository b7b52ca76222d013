// The viewer page: decodes a .swm file in a Web Worker (the page stays
// responsive), shows it lit and orbitable, with its figures. State for
// scripts and tests: body[data-state] is loading | ready | decoding |
// shown | error, body[data-shown] counts the meshes shown.
// `?file=URL` opens a file at load, `&sharpen=1` with Sharpen&Bend.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { toBufferGeometry } from '../src/three.js';
import { SWMWorker } from '../src/worker.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const body = document.body;
const decoder = new SWMWorker();
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
let mesh = null;

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

function show(geometry) {
  if (mesh) {
    scene.remove(mesh);
    mesh.geometry.dispose();
  }
  mesh = new THREE.Mesh(geometry, material);
  scene.add(mesh);
  // Frame the bounding sphere.
  const { center, radius } = geometry.boundingSphere;
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
  $('mode').textContent = `${info.mode} (v${info.version})`;
  $('vertices').textContent = fmt(info.vertices);
  $('triangles').textContent = fmt(info.triangles);
  $('bytes').textContent = fmt(info.bytes);
  $('bpt').textContent = info.triangles ? ((8 * info.bytes) / info.triangles).toFixed(2) : '–';
  $('ms').textContent = `${info.decodeMs.toFixed(1)} ms`;
}

async function open(name, bytes) {
  current = { name, bytes };
  $('name').textContent = name;
  $('error').textContent = '';
  body.dataset.state = 'decoding';
  const sharpen = $('sharpen').checked;
  try {
    const result = await decoder.decode(bytes, { normals: true, sharpen, bendSteps: sharpen ? 1 : 0 });
    if (current.bytes !== bytes) return; // a newer file took over
    show(toBufferGeometry(result));
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
