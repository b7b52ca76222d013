// The package and the viewer page in headless Chromium (the system's
// browser, driven by puppeteer-core; nothing is downloaded): the page
// loads; every test file decodes bit for bit as the `swm` CLI decodes it,
// on the page's thread and in the Web Worker; opened in the viewer, each
// shows its counts and draws the model (non-background pixels); the
// Sharpen&Bend toggle shows the `--sharpen --bend 1` mesh; a damaged file
// shows the decoder's message and the page still opens the next file. The
// glTF plugin (src/gltf.js) with a pool of workers loads the coded scene
// of tests/web.rs as `swm decode` expands it, its PNG texture decoded,
// and rejects damage; the viewer opens the .glb and draws the same
// pixels as for the expanded scene, and opens its sample scene.
//
//   SWM_WEB_CASES=DIR node test/browser.mjs --chromium /usr/bin/chromium
//     [--bench FILE.swm [--runs N]] [--screenshot OUT.png FILE.swm|FILE.glb [--viewport WxH]]
//
// --bench times decode() of FILE on the page's thread (after warm-up) and
// prints the figures as JSON; --screenshot writes the viewer showing
// FILE. Both skip the tests.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';
import { serve } from '../scripts/serve.mjs';
import { bitDiff, loadCases } from './cases.mjs';

const web = dirname(dirname(fileURLToPath(import.meta.url)));
const args = process.argv.slice(2);
const option = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
const executablePath = option('--chromium') ?? process.env.SWM_CHROMIUM ?? '/usr/bin/chromium';
const TIMEOUT = 60_000;

// The flags the issue gives for this machine: no GPU, no sandbox (root
// in a container), and no background networking, whose refused
// connections otherwise stall Chromium here. SwiftShader draws WebGL.
const FLAGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
];

async function main() {
  const benchFile = option('--bench');
  const shotOut = option('--screenshot');
  const mounts = {};
  if (benchFile) mounts['/bench'] = dirname(resolve(benchFile));
  if (shotOut) mounts['/shot'] = dirname(resolve(args[args.indexOf('--screenshot') + 2]));
  const tests = !benchFile && !shotOut;
  const data = tests ? loadCases(process.env.SWM_WEB_CASES ?? fail('set SWM_WEB_CASES')) : null;
  if (tests) mounts['/cases'] = process.env.SWM_WEB_CASES;

  const server = await serve({ root: web, mounts });
  const origin = `http://127.0.0.1:${server.address().port}`;
  const profile = mkdtempSync(join(tmpdir(), 'swm-chromium-'));
  const browser = await puppeteer.launch({
    executablePath,
    headless: true,
    args: [...FLAGS, `--user-data-dir=${profile}`],
    defaultViewport: viewport(option('--viewport') ?? '800x600'),
    timeout: TIMEOUT,
  });
  try {
    const page = await browser.newPage();
    page.setDefaultTimeout(TIMEOUT);
    const problems = [];
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    page.on('console', (m) => m.type() === 'error' && problems.push(`console: ${m.text()}`));
    page.on('response', (r) => r.status() >= 400 && problems.push(`HTTP ${r.status()}: ${r.url()}`));
    if (benchFile) {
      await page.goto(`${origin}/demo/`);
      await waitState(page, 'ready');
      const runs = Number(option('--runs') ?? 50);
      const figures = await page.evaluate(bench, `/bench/${basename(benchFile)}`, runs);
      console.log(JSON.stringify({ file: benchFile, runs, userAgent: await browser.version(), ...figures }));
    } else if (shotOut) {
      const file = args[args.indexOf('--screenshot') + 2];
      await page.goto(`${origin}/demo/?file=/shot/${basename(file)}`);
      await waitState(page, 'shown');
      await page.screenshot({ path: shotOut });
      console.log(`wrote ${shotOut}`);
    } else {
      await page.goto(`${origin}/demo/`);
      await waitState(page, 'ready');
      await checkDecodes(page, data);
      await checkViewer(page, data);
      await checkGltf(page, data, problems);
      await checkSample(page, origin);
      await checkStreaming(page, origin, data);
      assert.deepEqual(problems, [], 'the page logged errors');
      console.log(`browser: ${data.cases.length} files, ${await browser.version()}: ok`);
    }
  } finally {
    await browser.close();
    server.close();
    rmSync(profile, { recursive: true, force: true });
  }
}

/** Puppeteer's viewport of a "WxH" option. */
function viewport(size) {
  const [width, height] = size.split('x').map(Number);
  if (!(width > 0 && height > 0)) fail(`--viewport wants WxH, not ${size}`);
  return { width, height };
}

function fail(message) {
  throw new Error(message);
}

function waitState(page, state) {
  return page.waitForFunction((s) => document.body.dataset.state === s, {}, state);
}

/** In the page: decode() every case on this thread and in the worker. */
async function decodeInPage(names, options) {
  const swm = await import('/src/swm.js');
  const { SWMWorker } = await import('/src/worker.js');
  await swm.init();
  const worker = new SWMWorker();
  // Base64 of the arrays' bytes: strings cross the DevTools protocol
  // intact, bit for bit.
  const b64 = (a) => {
    const bytes = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
    let s = '';
    for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
    return btoa(s);
  };
  const pack = (r) => ({ positions: b64(r.positions), indices: b64(r.indices), info: r.info });
  const out = [];
  for (const name of names) {
    const bytes = new Uint8Array(await (await fetch(`/cases/${name}`)).arrayBuffer());
    const main = pack(swm.decode(bytes, options));
    const inWorker = pack(await worker.decode(bytes, options));
    out.push({ main, worker: inWorker });
  }
  worker.terminate();
  return out;
}

function unpack(r) {
  const bytes = Buffer.from(r.positions, 'base64');
  const ibytes = Buffer.from(r.indices, 'base64');
  return {
    positions: new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length)),
    indices: new Uint32Array(ibytes.buffer.slice(ibytes.byteOffset, ibytes.byteOffset + ibytes.length)),
    info: r.info,
  };
}

async function checkDecodes(page, data) {
  const names = data.cases.map((c) => c.swm);
  for (const [options, which] of [[{}, 'plain'], [{ sharpen: true, bendSteps: 1 }, 'sharpened']]) {
    const results = await page.evaluate(decodeInPage, names, options);
    data.cases.forEach((c, i) => {
      for (const where of ['main', 'worker']) {
        const r = unpack(results[i][where]);
        const what = `${c.name} (${which}, ${where} thread)`;
        assert.equal(bitDiff(r.positions, c[which].positions, `${what} positions`), '');
        assert.equal(bitDiff(r.indices, c[which].indices, `${what} indices`), '');
        assert.equal(r.info.mode, c.mode, what);
      }
    });
  }
  // SWMLoader as the README shows it, over HTTP, on the page's thread and
  // with a worker; and its onError for a damaged file.
  const loaded = await page.evaluate(async (name, bad) => {
    const { SWMLoader } = await import('/src/three.js');
    const { SWMWorker } = await import('/src/worker.js');
    const loader = new SWMLoader().setDecodeOptions({ sharpen: true, bendSteps: 1 });
    const g = await loader.loadAsync(`/cases/${name}`);
    const worker = new SWMWorker();
    const w = await loader.setWorker(worker).loadAsync(`/cases/${name}`);
    const error = await new Promise((resolve) => loader.load(`/cases/${bad}`, () => resolve(null), undefined, resolve));
    worker.terminate();
    return {
      positions: Array.from(g.getAttribute('position').array.slice(0, 6)),
      triangles: g.getIndex().count / 3,
      workerTriangles: w.getIndex().count / 3,
      hasNormals: g.getAttribute('normal') !== undefined,
      error: error && error.message,
    };
  }, data.cases[0].swm, data.corrupt.swm);
  const first = data.cases[0];
  assert.deepEqual(loaded.positions, Array.from(first.sharpened.positions.slice(0, 6)));
  assert.equal(loaded.triangles, first.sharpened.indices.length / 3);
  assert.equal(loaded.workerTriangles, first.sharpened.indices.length / 3);
  assert.equal(loaded.hasNormals, true);
  assert.equal(loaded.error, data.corrupt.message);

  // Errors cross the worker as SWMErrors with the decoder's message.
  const error = await page.evaluate(async (name) => {
    const { SWMWorker } = await import('/src/worker.js');
    const worker = new SWMWorker();
    const bytes = new Uint8Array(await (await fetch(`/cases/${name}`)).arrayBuffer());
    try {
      await worker.decode(bytes);
      return null;
    } catch (e) {
      return { name: e.name, code: e.code, message: e.message };
    } finally {
      worker.terminate();
    }
  }, data.corrupt.swm);
  assert.deepEqual(error, { name: 'SWMError', code: 'format', message: data.corrupt.message });
}

/** Non-background pixels of the viewer's canvas, counted in the page. */
function drawnPixels(page) {
  return page.evaluate(() => {
    const canvas = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(canvas, 0, 0);
    const px = ctx.getImageData(0, 0, copy.width, copy.height).data;
    // The scene's background, #1d2126.
    let n = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 0x1d) + Math.abs(px[i + 1] - 0x21) + Math.abs(px[i + 2] - 0x26) > 24) n++;
    }
    return { drawn: n, total: px.length / 4 };
  });
}

async function openInViewer(page, file) {
  // Clear a previous file's 'error' first: the page marks the new file
  // only once its bytes are read, and until then a stale 'error' would
  // end the wait below (a race that made the check after the damaged
  // file fail now and then).
  const shown = await page.evaluate(() => {
    document.body.dataset.state = 'uploading';
    return Number(document.body.dataset.shown ?? 0);
  });
  const input = await page.$('#file');
  await input.uploadFile(file);
  await page.waitForFunction(
    (n) => Number(document.body.dataset.shown ?? 0) > n || document.body.dataset.state === 'error',
    {},
    shown,
  );
  return page.evaluate(() => ({
    state: document.body.dataset.state,
    vertices: document.getElementById('vertices').textContent,
    triangles: document.getElementById('triangles').textContent,
    error: document.getElementById('error').textContent,
  }));
}

const fmt = (n) => n.toLocaleString('en-US');

async function checkViewer(page, data) {
  const dir = process.env.SWM_WEB_CASES;
  const empty = await drawnPixels(page);
  assert.equal(empty.drawn, 0, 'the canvas is not blank before a file is opened');
  for (const c of data.cases) {
    const shown = await openInViewer(page, join(dir, c.swm));
    assert.equal(shown.state, 'shown', `${c.name}: ${shown.error}`);
    assert.equal(shown.vertices, fmt(c.plain.positions.length / 3), c.name);
    assert.equal(shown.triangles, fmt(c.plain.indices.length / 3), c.name);
    if (c.plain.indices.length > 0) {
      const { drawn, total } = await drawnPixels(page);
      assert.ok(drawn > total / 100, `${c.name}: the model covers ${drawn} of ${total} pixels`);
    }
  }
  // The toggle decodes the file shown again with Sharpen&Bend.
  const last = data.cases[data.cases.length - 1];
  const before = await page.evaluate(() => Number(document.body.dataset.shown));
  await page.click('#sharpen');
  await page.waitForFunction((n) => Number(document.body.dataset.shown) > n, {}, before);
  const triangles = await page.$eval('#triangles', (e) => e.textContent);
  assert.equal(triangles, fmt(last.sharpened.indices.length / 3), 'triangles after Sharpen&Bend');
  await page.click('#sharpen');
  await page.waitForFunction((n) => Number(document.body.dataset.shown) > n + 1, {}, before);

  // A damaged file: the decoder's message on the page, and the page goes on.
  const bad = await openInViewer(page, join(dir, data.corrupt.swm));
  assert.equal(bad.state, 'error');
  assert.equal(bad.error, `${data.corrupt.swm}: ${data.corrupt.message}`);
  const good = await openInViewer(page, join(dir, data.cases[0].swm));
  assert.equal(good.state, 'shown', `after the damaged file: ${good.error}`);
  assert.equal(good.error, '', 'the error message stays after a good file');
  const { drawn } = await drawnPixels(page);
  assert.ok(drawn > 0, 'nothing drawn after the damaged file');
}

/**
 * In the page: each mesh of the glTF at `url` (or of `bytes`, base64)
 * loaded by GLTFLoader, with the swm plugin and a pool of two workers
 * when `plugin`: its name, attributes (an FNV-1a hash of each one's
 * bytes), counts, material and texture image size.
 */
async function loadGltfInPage(url, plugin, bytes) {
  const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
  const { SWMMeshCompressionExtension } = await import('/src/gltf.js');
  const { SWMWorkerPool } = await import('/src/worker.js');
  const pool = new SWMWorkerPool({ size: 2 });
  const loader = new GLTFLoader();
  if (plugin) loader.register((parser) => new SWMMeshCompressionExtension(parser, pool));
  const hash = (a) => {
    const b = new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
    let h = 0x811c9dc5;
    for (const x of b) h = Math.imul(h ^ x, 0x01000193) >>> 0;
    return `${a.constructor.name}:${a.length}:${h}`;
  };
  try {
    const gltf = bytes
      ? await loader.parseAsync(Uint8Array.from(atob(bytes), (c) => c.charCodeAt(0)).buffer, '')
      : await loader.loadAsync(url);
    const meshes = [];
    gltf.scene.traverse((o) => {
      if (!o.isMesh) return;
      const attributes = Object.fromEntries(Object.entries(o.geometry.attributes).map(([k, v]) => [k, hash(v.array)]));
      meshes.push({
        name: o.name,
        parent: o.parent.name,
        attributes,
        index: hash(o.geometry.index.array),
        material: o.material.name,
        map: o.material.map ? [o.material.map.image.width, o.material.map.image.height] : null,
      });
    });
    return { meshes, coded: gltf.userData.swm?.primitives.length ?? 0, workers: pool.workers.length };
  } catch (e) {
    return { error: { name: e.name, code: e.code, message: e.message } };
  } finally {
    pool.terminate();
  }
}

/** A hash of the viewer's canvas, and its non-background pixels. */
function canvasPixels(page) {
  return page.evaluate(() => {
    const canvas = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const ctx = copy.getContext('2d');
    ctx.drawImage(canvas, 0, 0);
    return Array.from(ctx.getImageData(0, 0, copy.width, copy.height).data);
  });
}

/** A pixel of the coded scene's drawing differs from the uncompressed
 * scene's when some channel moved by more than this (of 255). */
const ORIGINAL_STEP = 32;
/** At most this fraction of the pixels the scene covers may differ so. */
const ORIGINAL_DIFFER = 0.15;

/** The glTF plugin in the browser, and the viewer opening a coded scene. */
async function checkGltf(page, data, problems) {
  const { scene } = data;
  const got = await page.evaluate(loadGltfInPage, `/cases/${scene.coded}`, true);
  const want = await page.evaluate(loadGltfInPage, `/cases/${scene.decoded}`, false);
  assert.equal(got.error, undefined, JSON.stringify(got.error));
  assert.deepEqual(got.meshes, want.meshes, 'the plugin loads what `swm decode` expands');
  assert.equal(got.coded, 3);
  assert.equal(got.workers, 2, 'the three files went to both workers of the pool');
  const names = got.meshes.map((m) => m.name);
  assert.deepEqual(names, ['crate', 'ball', 'ring', 'small_crate']);
  const [crate, ball] = got.meshes;
  assert.deepEqual(crate.map, [16, 16], 'the checker texture is decoded and kept');
  assert.deepEqual(ball.map, [16, 16]);
  assert.deepEqual(Object.keys(ball.attributes).sort(), ['color', 'normal', 'position', 'uv', 'uv1']);
  assert.equal(ball.parent, 'arm');

  // A flipped bit in the ball's .swm file: the worker's error, naming it.
  const damaged = Buffer.from(scene.bytes.coded);
  const jsonLength = damaged.readUInt32LE(12);
  const json = JSON.parse(damaged.subarray(20, 20 + jsonLength).toString('utf8'));
  const view = json.bufferViews[json.meshes[1].primitives[0].extensions.SWM_mesh_compression.bufferView];
  damaged[28 + jsonLength + view.byteOffset + (view.byteLength >> 1)] ^= 0x10;
  const bad = await page.evaluate(loadGltfInPage, '', true, damaged.toString('base64'));
  assert.equal(bad.error?.name, 'SWMError', JSON.stringify(bad));
  assert.equal(bad.error.code, 'format');
  assert.match(bad.error.message, /^SWM_mesh_compression: mesh 1 primitive 0: /);

  // A worker that cannot start fails the load instead of leaving it waiting.
  const before = problems.length;
  const stuck = await page.evaluate(async (url) => {
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const { SWMMeshCompressionExtension } = await import('/src/gltf.js');
    const { SWMWorkerPool } = await import('/src/worker.js');
    const { SWMWorker } = await import('/src/worker.js');
    const pool = new SWMWorkerPool({ workerUrl: '/no-such-worker.js' });
    const loader = new GLTFLoader().register((parser) => new SWMMeshCompressionExtension(parser, pool));
    const messages = [];
    // Twice: the second load must not wait on the dead workers of the first.
    for (let i = 0; i < 2; i++) {
      try {
        await loader.loadAsync(url);
        messages.push(null);
      } catch (e) {
        messages.push(e.message);
      }
    }
    pool.terminate();
    // A terminated worker refuses work instead of leaving it waiting.
    const worker = new SWMWorker();
    worker.terminate();
    const late = await worker.decode(new Uint8Array(4)).then(() => null, (e) => e.code);
    return { messages, late };
  }, `/cases/${scene.coded}`);
  for (const message of stuck.messages) {
    assert.match(message ?? '', /^SWM_mesh_compression: mesh \d primitive 0: swm worker failed/);
  }
  assert.equal(stuck.late, 'terminated');
  // Its 404 is expected, not a problem of the page.
  problems.splice(before, problems.length - before, ...problems.slice(before).filter((p) => !p.includes('no-such-worker')));

  // The viewer: the coded scene and the expanded one draw the same pixels.
  const dir = process.env.SWM_WEB_CASES;
  const shown = await openInViewer(page, join(dir, scene.coded));
  assert.equal(shown.state, 'shown', shown.error);
  const coded = await canvasPixels(page);
  const { drawn, total } = await drawnPixels(page);
  assert.ok(drawn > total / 50, `the scene covers ${drawn} of ${total} pixels`);
  const expanded = await openInViewer(page, join(dir, scene.decoded));
  assert.equal(expanded.state, 'shown', expanded.error);
  assert.equal(expanded.triangles, shown.triangles);
  const plain = await canvasPixels(page);
  let differ = 0;
  for (let i = 0; i < plain.length; i += 4) {
    if (plain[i] !== coded[i] || plain[i + 1] !== coded[i + 1] || plain[i + 2] !== coded[i + 2]) differ++;
  }
  assert.ok(differ <= total / 1000, `${differ} of ${total} pixels differ between the coded and the expanded scene`);
  const mode = await page.$eval('#mode', (e) => e.textContent);
  assert.equal(mode, 'glTF, 0 of 3 primitives swm');

  // Against the uncompressed scene: the textured primitives are coded at
  // 12 bits a coordinate with their texture coordinates and normals, the
  // red ring at the default 2 b/v, so the two drawings differ where the
  // ring's silhouette and shading moved. Stated threshold: at most
  // ORIGINAL_DIFFER of the pixels the scene covers differ by more than
  // ORIGINAL_STEP in some channel (BENCHMARKS.md, "Web").
  const original = await openInViewer(page, join(dir, scene.plain));
  assert.equal(original.state, 'shown', original.error);
  const source = await canvasPixels(page);
  let far = 0;
  for (let i = 0; i < source.length; i += 4) {
    const d = Math.max(
      Math.abs(source[i] - coded[i]),
      Math.abs(source[i + 1] - coded[i + 1]),
      Math.abs(source[i + 2] - coded[i + 2]),
    );
    if (d > ORIGINAL_STEP) far++;
  }
  console.log(`coded against uncompressed scene: ${far} of the ${drawn} pixels drawn differ by more than ${ORIGINAL_STEP}`);
  assert.ok(
    far <= ORIGINAL_DIFFER * drawn,
    `${far} of the ${drawn} pixels drawn differ by more than ${ORIGINAL_STEP} between the coded and the uncompressed scene`,
  );
}

/** The sample scene the viewer offers (demo/sample-scene.glb) opens and is drawn. */
async function checkSample(page, origin) {
  await page.goto(`${origin}/demo/`);
  await waitState(page, 'ready');
  await Promise.all([page.waitForNavigation(), page.click('a[href="?file=sample-scene.glb"]')]);
  await page.waitForFunction(() => ['shown', 'error'].includes(document.body.dataset.state));
  const got = await page.evaluate(() => ({
    state: document.body.dataset.state,
    mode: document.getElementById('mode').textContent,
    error: document.getElementById('error').textContent,
  }));
  assert.deepEqual(got, { state: 'shown', mode: 'glTF, 3 of 3 primitives swm', error: '' });
  const { drawn, total } = await drawnPixels(page);
  assert.ok(drawn > total / 50, `the sample scene covers ${drawn} of ${total} pixels`);
}

/**
 * The viewer over a slow connection (`&rate=`, bytes a second): the
 * displaced file's base mesh is shown before its last bytes are in, then
 * each finer level, and at the end the whole file's mesh.
 */
async function checkStreaming(page, origin, data) {
  const c = data.cases.find((x) => x.mode === 'displaced');
  // About two seconds for the whole file, in pieces of a twentieth.
  const rate = Math.max(100, Math.ceil(c.bytes.length / 2));
  await page.goto(`${origin}/demo/?file=/cases/${basename(c.swm)}&rate=${rate}`);
  await waitState(page, 'shown');
  const got = await page.evaluate(() => ({
    levels: document.body.dataset.levels,
    at: document.body.dataset.levelBytes,
    triangles: document.getElementById('triangles').textContent,
    error: document.getElementById('error').textContent,
  }));
  assert.equal(got.error, '', c.name);
  assert.equal(got.levels, '0,1,2', `${c.name}: levels shown while streaming`);
  const at = got.at.split(',').map(Number);
  assert.ok(at[0] < c.bytes.length, `${c.name}: the base mesh waited for all ${c.bytes.length} bytes (${at})`);
  assert.ok(at[0] < at[1] && at[1] <= at[2], `${c.name}: levels at ${at}`);
  assert.equal(got.triangles, fmt(c.plain.indices.length / 3), `${c.name}: the whole mesh at the end`);
  const { drawn, total } = await drawnPixels(page);
  assert.ok(drawn > total / 100, `${c.name}: the streamed model covers ${drawn} of ${total} pixels`);
}

/** In the page: decode() `url` `runs` times on the page's thread. */
async function bench(url, runs) {
  const swm = await import('/src/swm.js');
  await swm.init();
  const bytes = new Uint8Array(await (await fetch(url)).arrayBuffer());
  for (let i = 0; i < 10; i++) swm.decode(bytes); // warm-up: tier-up of the module
  const times = [];
  let info = null;
  for (let i = 0; i < runs; i++) {
    const start = performance.now();
    info = swm.decode(bytes).info;
    times.push(performance.now() - start);
  }
  times.sort((a, b) => a - b);
  return {
    vertices: info.vertices,
    triangles: info.triangles,
    bytes: info.bytes,
    min_ms: times[0],
    median_ms: times[Math.floor(runs / 2)],
  };
}

main().catch((e) => {
  console.error(e.stack ?? String(e));
  process.exit(1);
});
