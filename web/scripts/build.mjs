// Builds dist/swm.wasm: the swm-wasm crate (web/wasm) for
// wasm32-unknown-unknown with the workspace's `wasm` profile, then
// binaryen's wasm-opt (npm package `binaryen`). Needs the Rust toolchain
// with `rustup target add wasm32-unknown-unknown` and `npm ci` here.
//
// wasm-opt is skipped when dist/swm.wasm is newer than cargo's output
// (cargo itself is incremental), so a second build takes about a second.
//
// Usage: node scripts/build.mjs [--force]
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, renameSync, statSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const web = dirname(dirname(fileURLToPath(import.meta.url)));
const out = join(web, 'dist', 'swm.wasm');
const force = process.argv.includes('--force');

// The features rustc enables by default for wasm32-unknown-unknown; the
// optimizer must accept them and adds no others.
const FEATURES = [
  '--enable-bulk-memory',
  '--enable-nontrapping-float-to-int',
  '--enable-sign-ext',
  '--enable-mutable-globals',
  '--enable-multivalue',
  '--enable-reference-types',
];

function fail(message) {
  console.error(`build: ${message}`);
  process.exit(1);
}

/** Runs cargo and returns the path of the .wasm artifact it reports. */
function cargoBuild() {
  const args = [
    'build', '-p', 'swm-wasm', '--lib',
    '--target', 'wasm32-unknown-unknown',
    '--profile', 'wasm',
    '--message-format', 'json-render-diagnostics',
  ];
  // opt-level "z" (the `wasm` profile) with LLVM's inliner threshold
  // raised from its -Oz value of 5 to 30: the module grows by 4 KB gzip
  // and decodes the bunny 1.3x faster (BENCHMARKS.md, "Web"). An outer
  // RUSTFLAGS would replace these flags, so it is not passed on.
  const env = { ...process.env, CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS: '-Cllvm-args=-inline-threshold=30' };
  delete env.RUSTFLAGS;
  delete env.CARGO_ENCODED_RUSTFLAGS;
  const run = spawnSync('cargo', args, {
    cwd: web,
    env,
    encoding: 'utf8',
    stdio: ['ignore', 'pipe', 'inherit'],
    maxBuffer: 64 << 20,
  });
  if (run.error) fail(`cannot run cargo: ${run.error.message} (install Rust: https://rustup.rs)`);
  if (run.status !== 0) fail(`cargo build failed (is the target installed? rustup target add wasm32-unknown-unknown)`);
  let wasm = null;
  for (const line of run.stdout.split('\n')) {
    if (!line.startsWith('{')) continue;
    const msg = JSON.parse(line);
    if (msg.reason === 'compiler-artifact' && msg.target?.name === 'swm_wasm') {
      wasm = msg.filenames.find((f) => f.endsWith('.wasm')) ?? wasm;
    }
  }
  if (!wasm) fail('cargo reported no .wasm artifact for swm-wasm');
  return wasm;
}

function optimize(input) {
  const bin = join(web, 'node_modules', 'binaryen', 'bin', 'wasm-opt');
  if (!existsSync(bin)) fail(`${bin} not found (run \`npm ci\` in ${web})`);
  const tmp = `${out}.tmp`;
  const run = spawnSync(
    process.execPath,
    [bin, input, '-o', tmp, '-Oz', '--converge', ...FEATURES, '--strip-debug', '--strip-producers'],
    { stdio: 'inherit' },
  );
  if (run.status !== 0) fail('wasm-opt failed');
  // Renamed into place so that an interrupted build leaves no half file.
  renameSync(tmp, out);
}

const input = cargoBuild();
mkdirSync(dirname(out), { recursive: true });
const fresh = existsSync(out) && statSync(out).mtimeMs >= statSync(input).mtimeMs;
if (force || !fresh) {
  optimize(input);
  console.error(`build: ${out}: ${statSync(out).size} bytes (cargo: ${statSync(input).size})`);
} else {
  console.error(`build: ${out} is up to date`);
}
