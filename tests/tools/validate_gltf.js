// Runs the Khronos glTF-Validator (npm gltf-validator, installed by
// scripts/install-gltf-validator.sh) on one .gltf/.glb file and prints a
// JSON summary on stdout: {"errors": N, "warnings": N, "infos": N,
// "messages": [...the errors and warnings...]}. External buffers and images
// are read relative to the file, as a viewer would.
//   node validate_gltf.js VALIDATOR_DIR FILE
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(path.join(process.argv[2], 'node_modules', 'gltf-validator'));
const file = process.argv[3];
const dir = path.dirname(file);

validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
  uri: path.basename(file),
  maxIssues: 1000,
  externalResourceFunction: (uri) => new Promise((resolve, reject) => {
    fs.readFile(path.resolve(dir, decodeURIComponent(uri)), (err, data) => {
      if (err) reject(err.toString()); else resolve(new Uint8Array(data));
    });
  }),
}).then((report) => {
  const issues = report.issues;
  const messages = issues.messages.filter((m) => m.severity <= 1)
                       .map((m) => `${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
  process.stdout.write(JSON.stringify({errors: issues.numErrors, warnings: issues.numWarnings,
                                       infos: issues.numInfos, messages}) + '\n');
}, (error) => {
  process.stdout.write(JSON.stringify({errors: 1, warnings: 0, infos: 0,
                                       messages: ['validator failed: ' + error]}) + '\n');
});
