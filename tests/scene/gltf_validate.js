// Runs the Khronos glTF Validator (npm package gltf-validator) on the files given and fails when
// any reports an error or a warning. A missing package is a failure: scripts/install-deps.sh
// installs it wherever Node is (the calling script skips only when Node itself is absent).
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.log('FAIL: the npm package gltf-validator is not installed (scripts/install-deps.sh installs it)');
  process.exit(1);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const resolved = path.resolve(path.dirname(file), decodeURIComponent(uri));
        fs.readFile(resolved, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
  });
  const issues = report.issues;
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos`);
  for (const m of issues.messages) console.log(`  [${m.severity}] ${m.code} ${m.pointer || ''}: ${m.message}`);
  return issues.numErrors + issues.numWarnings;
}

(async () => {
  let problems = 0;
  for (const file of process.argv.slice(2)) problems += await validate(file);
  process.exit(problems === 0 ? 0 : 1);
})().catch((e) => {
  console.log(`validator failed: ${e}`);
  process.exit(1);
});
