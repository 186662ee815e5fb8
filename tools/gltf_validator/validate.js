// Runs the Khronos glTF validator (npm gltf-validator, installed here by ci/setup.sh) over the
// files named on the command line. Prints one line per file:
//   <file>: <errors> errors, <warnings> warnings[: <code> <pointer> <message>; ...]
// (the issues listed are the errors, at most five) and exits 1 when any file has an error,
// 2 when a file cannot be read or validated at all. A first argument --ignore=CODE,CODE mutes
// those issue codes (for files written with known, reported defects).
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file, ignored) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    ignoredIssues: ignored,
    externalResourceFunction: (uri) =>
      fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
  });
  const errors = report.issues.messages.filter((m) => m.severity === 0);
  const listed = errors.slice(0, 5).map((m) => `${m.code} ${m.pointer || ''} ${m.message}`).join('; ');
  console.log(`${file}: ${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings${listed ? ': ' + listed : ''}`);
  return report.issues.numErrors;
}

(async () => {
  let status = 0;
  let files = process.argv.slice(2);
  let ignored = [];
  if (files.length && files[0].startsWith('--ignore=')) {
    ignored = files[0].slice('--ignore='.length).split(',');
    files = files.slice(1);
  }
  for (const file of files) {
    try {
      if (await validate(file, ignored)) status = Math.max(status, 1);
    } catch (e) {
      console.log(`${file}: not validated: ${String(e).split('\n')[0]}`);
      status = 2;
    }
  }
  process.exit(status);
})();
