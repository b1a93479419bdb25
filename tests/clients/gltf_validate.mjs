// Validates a .glb with the Khronos glTF-Validator (npm gltf-validator), installed in the folder
// named by GLTF_VALIDATOR_DIR (dev.sh test installs it under build/npm). Exit 0: no errors.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';

const require = createRequire(process.env.GLTF_VALIDATOR_DIR.replace(/\/?$/, '/'));
const validator = require('gltf-validator');
const bytes = new Uint8Array(await readFile(process.argv[2]));
const report = await validator.validateBytes(bytes, { maxIssues: 100 });
const { numErrors, numWarnings, messages } = report.issues;
console.log(JSON.stringify({ numErrors, numWarnings, triangles: report.info && report.info.totalTriangleCount,
  messages: messages.filter((m) => m.severity <= 1).slice(0, 10) }));
process.exit(numErrors === 0 ? 0 : 1);
