// Runs a wasm32-wasip1 program under Node.js, with one host folder visible
// to it: `node wasi_run.mjs PROGRAM.wasm HOST_DIR GUEST_DIR [ARGS...]`.
// The `cross_platform` program runs `scene_hashes` with it.
import { readFile } from 'node:fs/promises';
import { argv, exit } from 'node:process';
import { WASI } from 'node:wasi';

const [program, hostDir, guestDir, ...args] = argv.slice(2);
if (!program || !hostDir || !guestDir) {
  console.error('usage: node wasi_run.mjs PROGRAM.wasm HOST_DIR GUEST_DIR [ARGS...]');
  exit(2);
}
const wasi = new WASI({
  version: 'preview1',
  args: [program, ...args],
  preopens: { [guestDir]: hostDir },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(program));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
exit(wasi.start(instance));
