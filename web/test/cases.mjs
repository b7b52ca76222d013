// The test files that tests/web.rs prepares (SWM_WEB_CASES, a folder):
// manifest.json lists `.swm` files of every mode with what the `swm` CLI
// decodes them to (binary PLY, and GLB for the normals), a damaged
// file with the CLI's error message, and a file with attribute streams
// beside the Rust API's split mesh and streams (raw little-endian arrays), and a
// textured glTF scene coded with SWM_mesh_compression beside what `swm decode`
// expands it to. Parsers for those outputs, and bit-for-bit comparison.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

/**
 * The folder of test files: SWM_WEB_CASES or the first argument (what
 * tests/web.rs passes), else web/test/cases/, made afresh on each run by
 * the test `web_cases_are_made` of tests/web.rs (cargo, from the
 * repository's root), so that `npm test` works on its own after
 * `npm run build` and never compares with an older CLI's output.
 */
export function casesDir() {
  const given = process.env.SWM_WEB_CASES ?? process.argv[2];
  if (given) return given;
  const here = dirname(fileURLToPath(import.meta.url));
  const dir = join(here, 'cases');
  const root = join(here, '..', '..');
  const args = ['test', '-p', 'swm-cli', '--test', 'web', '--', '--exact', 'web_cases_are_made'];
  console.error(`making the test files in ${dir}: cargo ${args.join(' ')} (the first build takes minutes)`);
  execFileSync('cargo', args, {
    cwd: root,
    stdio: ['ignore', 'ignore', 'inherit'],
    env: { ...process.env, SWM_WEB_CASES_OUT: dir },
  });
  return dir;
}

export function manifest(dir) {
  return JSON.parse(readFileSync(join(dir, 'manifest.json'), 'utf8'));
}

/** Positions and indices of a binary little-endian PLY as `swm decode` writes it (with or without per-vertex attributes). */
export function readPly(bytes) {
  const end = bytes.indexOf('end_header\n');
  if (end < 0) throw new Error('PLY without end_header');
  const header = bytes.subarray(0, end).toString('latin1');
  if (!header.includes('format binary_little_endian 1.0')) throw new Error('not a binary little-endian PLY');
  const vertices = Number(/element vertex (\d+)/.exec(header)[1]);
  const faces = Number(/element face (\d+)/.exec(header)[1]);
  // A vertex is x, y, z (float) first, then whatever else the file
  // holds (normals, colours): its stride is the sum of its properties.
  const size = { char: 1, uchar: 1, int8: 1, uint8: 1, short: 2, ushort: 2, int16: 2, uint16: 2,
    int: 4, uint: 4, int32: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8 };
  const vertexPart = header.split('element vertex')[1].split('element face')[0];
  const stride = [...vertexPart.matchAll(/property (\w+) \w+/g)].reduce((n, m) => n + size[m[1]], 0);
  const view = new DataView(bytes.buffer, bytes.byteOffset + end + 'end_header\n'.length);
  const positions = new Float32Array(3 * vertices);
  for (let v = 0; v < vertices; v++) {
    for (let k = 0; k < 3; k++) positions[3 * v + k] = view.getFloat32(stride * v + 4 * k, true);
  }
  const indices = new Uint32Array(3 * faces);
  let at = stride * vertices;
  for (let f = 0; f < faces; f++) {
    if (view.getUint8(at) !== 3) throw new Error(`PLY face ${f} is not a triangle`);
    for (let k = 0; k < 3; k++) indices[3 * f + k] = view.getUint32(at + 1 + 4 * k, true);
    at += 13;
  }
  return { positions, indices };
}

/** The NORMAL attribute of the one mesh in a GLB that `swm decode` writes. */
export function readGlbNormals(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const jsonLength = view.getUint32(12, true);
  const gltf = JSON.parse(bytes.subarray(20, 20 + jsonLength).toString('utf8'));
  const bin = 20 + jsonLength + 8;
  const accessor = gltf.accessors[gltf.meshes[0].primitives[0].attributes.NORMAL];
  const bufferView = gltf.bufferViews[accessor.bufferView];
  const offset = bin + (bufferView.byteOffset ?? 0) + (accessor.byteOffset ?? 0);
  const normals = new Float32Array(3 * accessor.count);
  for (let i = 0; i < normals.length; i++) normals[i] = view.getFloat32(offset + 4 * i, true);
  return normals;
}

/** Every case with its bytes and the CLI's decodings loaded. */
export function loadCases(dir) {
  const m = manifest(dir);
  const read = (f) => readFileSync(join(dir, f));
  return {
    ...m,
    cases: m.cases.map((c) => ({
      ...c,
      bytes: new Uint8Array(read(c.swm)),
      plain: readPly(read(c.ply)),
      sharpened: readPly(read(c.sharpened_ply)),
      level1: readPly(read(c.level1_ply)),
      normals: readGlbNormals(read(c.glb)),
    })),
    corrupt: { ...m.corrupt, bytes: new Uint8Array(read(m.corrupt.swm)) },
    attributed: attributed(m.attributed, read),
    scene: { ...m.scene, bytes: { coded: read(m.scene.coded) } },
  };
}

/** The attributed case: its file and the split mesh and streams the Rust API decodes it to. */
function attributed(a, read) {
  const f32 = (f) => { const b = read(f); return new Float32Array(b.buffer, b.byteOffset, b.length / 4).slice(); };
  const u32 = (f) => { const b = read(f); return new Uint32Array(b.buffer, b.byteOffset, b.length / 4).slice(); };
  return {
    bytes: new Uint8Array(read(a.swm)),
    positions: f32(a.positions),
    indices: u32(a.indices),
    streams: a.streams.map((s) => ({ kind: s.kind, set: s.set, dims: s.dims, values: f32(s.values) })),
  };
}

/**
 * Where two typed arrays first differ bit for bit ("" when they are the
 * same), for assertion messages.
 */
export function bitDiff(actual, expected, what) {
  if (actual.length !== expected.length) {
    return `${what}: ${actual.length} values, the CLI gives ${expected.length}`;
  }
  const a = new Uint32Array(actual.buffer, actual.byteOffset, actual.length);
  const b = new Uint32Array(expected.buffer, expected.byteOffset, expected.length);
  for (let i = 0; i < a.length; i++) {
    if (a[i] !== b[i]) return `${what}[${i}]: ${actual[i]}, the CLI gives ${expected[i]}`;
  }
  return '';
}
