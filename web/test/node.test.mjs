// The package in Node (no browser): every test file decodes to exactly
// what the `swm` CLI decodes it to, with and without Sharpen&Bend, with
// the CLI's normals; errors are SWMErrors with the decoder's message and
// leave the decoder usable; SWMLoader builds the same BufferGeometry.
// Run by tests/web.rs: SWM_WEB_CASES=DIR node --test test/node.test.mjs;
// `npm test` (after `npm run build`) makes its own files (cases.mjs).
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { DEFAULT_LIMITS, decode, decodeStream, init, isReady, StreamDecoder, SWMError } from '../src/swm.js';
import { SWMLoader } from '../src/three.js';
import { bitDiff, casesDir, loadCases } from './cases.mjs';

const { cases, corrupt, attributed } = loadCases(casesDir());

test('decode() before init() throws', async () => {
  // A second copy of the module (another URL), never initialized.
  const fresh = await import('../src/swm.js?uninitialized');
  assert.equal(fresh.isReady(), false);
  assert.throws(() => fresh.decode(cases[0].bytes), { name: 'SWMError', code: 'init' });
});

test('init() loads the module from the package', async () => {
  await init();
  assert.equal(isReady(), true);
  await init(); // a second call is a no-op
});

test('every mode decodes bit for bit as the CLI decodes', async () => {
  await init();
  const modes = new Set();
  for (const c of cases) {
    const r = decode(c.bytes, { normals: true });
    assert.equal(bitDiff(r.positions, c.plain.positions, `${c.name} positions`), '');
    assert.equal(bitDiff(r.indices, c.plain.indices, `${c.name} indices`), '');
    assert.equal(bitDiff(r.normals, c.normals, `${c.name} normals`), '');
    assert.equal(r.info.mode, c.mode, c.name);
    assert.equal(r.info.version, c.version, c.name);
    assert.equal(r.info.bytes, c.bytes.length, c.name);
    assert.equal(r.info.vertices, c.plain.positions.length / 3, c.name);
    assert.equal(r.info.triangles, c.plain.indices.length / 3, c.name);
    assert.equal(decode(c.bytes).normals, undefined, `${c.name}: normals not asked for`);
    modes.add(c.mode);
  }
  assert.deepEqual([...modes].sort(), ['displaced', 'lossless', 'swing']);
});

test('maxLevel gives what `swm decode --max-level 1` gives', async () => {
  await init();
  for (const c of cases) {
    const r = decode(c.bytes, { maxLevel: 1 });
    assert.equal(bitDiff(r.positions, c.level1.positions, `${c.name} positions`), '');
    assert.equal(bitDiff(r.indices, c.level1.indices, `${c.name} indices`), '');
  }
  const displaced = cases.find((c) => c.mode === 'displaced');
  // The golden file's two levels: a quarter of the triangles at level 1.
  assert.equal(displaced.level1.indices.length * 4, displaced.plain.indices.length);
  assert.throws(() => decode(displaced.bytes, { maxLevel: -1 }), { name: 'SWMError', code: 'argument' });
});

test('a stream hands out each level of a displaced file as its bytes arrive', async () => {
  await init();
  for (const c of cases) {
    // In pieces of 64 bytes: every level comes out once, in order, and is
    // what decode() gives at that level; finish() is the whole decode.
    const stream = new StreamDecoder({ normals: true });
    const levels = [];
    for (let at = 0; at < c.bytes.length; at += 64) {
      const r = stream.push(c.bytes.subarray(at, at + 64));
      if (!r) continue;
      const want = decode(c.bytes, { maxLevel: r.info.level, normals: true });
      assert.equal(bitDiff(r.positions, want.positions, `${c.name} level ${r.info.level}`), '');
      assert.equal(bitDiff(r.indices, want.indices, `${c.name} level ${r.info.level}`), '');
      assert.equal(bitDiff(r.normals, want.normals, `${c.name} level ${r.info.level} normals`), '');
      assert.ok(r.info.bytes <= at + 64, c.name);
      levels.push(r.info.level);
    }
    const whole = stream.finish();
    assert.equal(bitDiff(whole.positions, c.plain.positions, `${c.name} finish`), '');
    assert.equal(whole.info.level, undefined);
    if (c.mode === 'displaced') {
      assert.deepEqual(levels, [0, 1, 2], c.name);
      assert.equal(bitDiff(decode(c.bytes, { maxLevel: 1 }).positions, c.level1.positions, c.name), '');
    } else {
      assert.deepEqual(levels, [], `${c.name}: only displaced files have levels`);
    }
    assert.throws(() => stream.push(c.bytes), { name: 'SWMError', code: 'argument' });
  }
  // decodeStream over a ReadableStream: the same levels, then the file.
  const displaced = cases.find((c) => c.mode === 'displaced');
  const body = new ReadableStream({
    start(controller) {
      for (let at = 0; at < displaced.bytes.length; at += 100) controller.enqueue(displaced.bytes.slice(at, at + 100));
      controller.close();
    },
  });
  const seen = [];
  const whole = await decodeStream(body, {}, (r) => seen.push(r.info.level));
  assert.deepEqual(seen, [0, 1, 2]);
  assert.equal(bitDiff(whole.positions, displaced.plain.positions, 'decodeStream'), '');
  // Cut short: the levels so far, then the decoder's error; the decoder stays usable.
  const cut = displaced.bytes.subarray(0, displaced.bytes.length - 3);
  await assert.rejects(decodeStream([cut]), { name: 'SWMError', code: 'format' });
  assert.equal(decode(displaced.bytes).positions.length, displaced.plain.positions.length);
});

test('Sharpen&Bend gives what `swm decode --sharpen --bend 1` gives', async () => {
  await init();
  for (const c of cases) {
    const r = decode(c.bytes, { sharpen: true, bendSteps: 1 });
    assert.equal(bitDiff(r.positions, c.sharpened.positions, `${c.name} positions`), '');
    assert.equal(bitDiff(r.indices, c.sharpened.indices, `${c.name} indices`), '');
  }
});

test('a damaged file throws the decoder message, and the decoder still works', async () => {
  await init();
  assert.throws(() => decode(corrupt.bytes), (e) => {
    assert.ok(e instanceof SWMError && e instanceof Error);
    assert.equal(e.code, 'format');
    assert.equal(e.message, corrupt.message);
    return true;
  });
  assert.throws(() => decode(new Uint8Array(0)), { name: 'SWMError', code: 'format' });
  const r = decode(cases[0].bytes);
  assert.equal(bitDiff(r.positions, cases[0].plain.positions, 'after an error'), '');
});

test('limits and options are checked', async () => {
  await init();
  const c = cases.find((x) => x.plain.positions.length > 3);
  assert.throws(() => decode(c.bytes, { limits: { maxVertices: 1 } }), { name: 'SWMError', code: 'limit' });
  assert.throws(() => decode(c.bytes, { limits: { maxAllocBytes: 64 } }), { name: 'SWMError', code: 'limit' });
  assert.throws(() => decode(c.bytes, { bendSteps: -1 }), { name: 'SWMError', code: 'argument' });
  assert.throws(() => decode(c.bytes, { limits: { maxFaces: NaN } }), { name: 'SWMError', code: 'argument' });
  assert.throws(() => decode('not bytes'), { name: 'SWMError', code: 'argument' });
  // The defaults let every test file through; an ArrayBuffer is accepted.
  const copy = c.bytes.slice().buffer;
  assert.equal(decode(copy, { limits: DEFAULT_LIMITS }).info.vertices, c.plain.positions.length / 3);
});

test('SWMLoader.parse returns the decoded BufferGeometry', async () => {
  const loader = new SWMLoader();
  await loader.init();
  for (const c of cases) {
    const g = loader.parse(c.bytes.slice().buffer);
    assert.equal(g.isBufferGeometry, true);
    assert.equal(bitDiff(g.getAttribute('position').array, c.plain.positions, `${c.name} position`), '');
    assert.equal(bitDiff(g.getIndex().array, c.plain.indices, `${c.name} index`), '');
    assert.equal(bitDiff(g.getAttribute('normal').array, c.normals, `${c.name} normal`), '');
    assert.equal(g.userData.swm.mode, c.mode);
    assert.ok(g.boundingSphere.radius > 0 || c.plain.positions.length === 0);
  }
  const g = await loader.setDecodeOptions({ sharpen: true, bendSteps: 1 }).parseAsync(cases[0].bytes);
  assert.equal(bitDiff(g.getIndex().array, cases[0].sharpened.indices, 'parseAsync, Sharpen&Bend'), '');
  await assert.rejects(loader.parseAsync(corrupt.bytes), { name: 'SWMError', message: corrupt.message });
});

test('attribute streams come per vertex, as the Rust API splits them, into three.js attributes', async () => {
  await init();
  const a = attributed;
  const r = decode(a.bytes, { normals: true });
  assert.equal(bitDiff(r.positions, a.positions, 'split positions'), '');
  assert.equal(bitDiff(r.indices, a.indices, 'split indices'), '');
  assert.equal(r.normals.length, r.positions.length);
  assert.deepEqual(r.attributes.map((s) => [s.kind, s.set, s.dims]), a.streams.map((s) => [s.kind, s.set, s.dims]));
  r.attributes.forEach((s, k) => assert.equal(bitDiff(s.values, a.streams[k].values, `stream ${s.kind}`), ''));
  // Every file without streams decodes without the key; one with them
  // (a displaced file's colours) with as many.
  for (const c of cases) {
    if (c.streams) assert.equal(decode(c.bytes).attributes.length, c.streams, c.name);
    else assert.equal(decode(c.bytes).attributes, undefined, c.name);
  }

  const g = new SWMLoader();
  await g.init();
  const geometry = g.parse(a.bytes);
  const byKind = Object.fromEntries(a.streams.map((s) => [s.kind, s]));
  // The file's normals, not the computed ones; uv; RGBA colours.
  assert.equal(bitDiff(geometry.getAttribute('normal').array, byKind.normal.values, 'normal'), '');
  assert.equal(bitDiff(geometry.getAttribute('uv').array, byKind.texcoord.values, 'uv'), '');
  assert.equal(geometry.getAttribute('color').itemSize, 4);
  assert.equal(bitDiff(geometry.getAttribute('color').array, byKind.color.values, 'color'), '');
});
