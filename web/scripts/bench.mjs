// Decode time of one .swm file in headless Chromium against native, in
// the same run (BENCHMARKS.md, "Web"): alternates `decode_timing` (the
// same library, release build, web/wasm/examples/decode_timing.rs) and
// test/browser.mjs --bench, `rounds` times each, and prints every
// measurement as JSON and the ratio of the best minimums.
//
//   node scripts/bench.mjs FILE.swm [--runs 300] [--rounds 3] [--chromium PATH]
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const web = dirname(dirname(fileURLToPath(import.meta.url)));
const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : fallback;
};
const file = args[0];
if (!file || file.startsWith('--')) {
  console.error('usage: node scripts/bench.mjs FILE.swm [--runs N] [--rounds N] [--chromium PATH]');
  process.exit(2);
}
const runs = option('--runs', '300');
const rounds = Number(option('--rounds', '3'));
const chromium = option('--chromium', '/usr/bin/chromium');

function run(program, argv, cwd) {
  const r = spawnSync(program, argv, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'] });
  if (r.status !== 0) {
    console.error(`bench: ${program} ${argv.join(' ')} failed`);
    process.exit(1);
  }
  return r.stdout;
}

run('cargo', ['build', '--release', '-q', '-p', 'swm-wasm', '--example', 'decode_timing'], web);
const meta = JSON.parse(run('cargo', ['metadata', '--format-version', '1', '--no-deps'], web));
const native = join(meta.target_directory, 'release', 'examples', 'decode_timing');
const best = { native: Infinity, browser: Infinity };
for (let i = 0; i < rounds; i++) {
  const n = JSON.parse(run(native, [file, runs]));
  console.log(JSON.stringify({ side: 'native', ...n }));
  const b = JSON.parse(run(process.execPath, ['test/browser.mjs', '--chromium', chromium, '--bench', file, '--runs', runs], web));
  console.log(JSON.stringify({ side: 'chromium', ...b }));
  best.native = Math.min(best.native, n.min_ms);
  best.browser = Math.min(best.browser, b.min_ms);
}
console.log(`best minimums: native ${best.native.toFixed(3)} ms, chromium ${best.browser.toFixed(3)} ms, ratio ${(best.browser / best.native).toFixed(2)}`);
