// Validates .glb files with the Khronos glTF-Validator (npm gltf-validator), installed in the folder
// named by GLTF_VALIDATOR_DIR (dev.sh test installs it under build/npm). One JSON line per file;
// exit 0 when no file has an error or a warning.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';

const require = createRequire(resolve(process.env.GLTF_VALIDATOR_DIR) + '/');
const validator = require('gltf-validator');
let clean = true;
for (const file of process.argv.slice(2)) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, { maxIssues: 100 });
  const { numErrors, numWarnings, messages } = report.issues;
  clean &&= numErrors === 0 && numWarnings === 0;
  console.log(JSON.stringify({ file, numErrors, numWarnings, triangles: report.info && report.info.totalTriangleCount,
    messages: messages.filter((m) => m.severity <= 1).slice(0, 10) }));
}
process.exit(clean ? 0 : 1);
