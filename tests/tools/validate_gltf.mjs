// Validates a glTF or GLB file with the official Khronos glTF validator (the npm package
// gltf-validator, which `make test-tools` installs into the build folder).
//
//   node tests/tools/validate_gltf.mjs FILE [TOOLS_DIR]
//
// TOOLS_DIR (or the environment variable GRAFTAL_TOOLS_DIR) is the folder holding
// node_modules/gltf-validator. Prints the report's summary as one line of JSON and exits
// with 0 when the file has no errors, 1 when it has, 2 when it could not be validated.
import { createRequire } from 'node:module';
import { existsSync } from 'node:fs';
import { readFile } from 'node:fs/promises';
import path from 'node:path';

function fail(message) {
    console.log(JSON.stringify({ error: message }));
    process.exit(2);
}

const [file, toolsArgument] = process.argv.slice(2);
if (!file) fail('usage: node validate_gltf.mjs FILE [TOOLS_DIR]');
const toolsDir = toolsArgument || process.env.GRAFTAL_TOOLS_DIR;
if (!toolsDir) fail('no tools folder: pass it as the second argument or set GRAFTAL_TOOLS_DIR');
// Resolved, because require() takes a relative name for a package name, not a path.
const validatorDir = path.resolve(toolsDir, 'node_modules', 'gltf-validator');
if (!existsSync(validatorDir))
    fail(`the glTF validator is not installed in ${validatorDir}: run \`make test-tools\``);

const validator = createRequire(import.meta.url)(validatorDir);
let bytes;
try {
    bytes = new Uint8Array(await readFile(file));
} catch (e) {
    fail(`cannot read ${file}: ${e.message}`);
}

// Resources outside a .glb (a .gltf's .bin) are read from beside the file.
const externalResourceFunction = (uri) =>
    readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b));

let report;
try {
    report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0,
        externalResourceFunction,
    });
} catch (e) {
    fail(`the validator could not read ${file}: ${e}`);
}

const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
// Severity 0 is an error, 1 a warning: those are worth reading; infos and hints are counted.
const serious = messages.filter((m) => m.severity <= 1).slice(0, 20)
    .map(({ code, message, severity, pointer }) => ({ code, message, severity, pointer }));
console.log(JSON.stringify({
    file: path.basename(file),
    validatorVersion: report.validatorVersion,
    numErrors, numWarnings, numInfos, numHints,
    messages: serious,
    info: report.info && {
        version: report.info.version,
        generator: report.info.generator,
        totalVertexCount: report.info.totalVertexCount,
        totalTriangleCount: report.info.totalTriangleCount,
        materialCount: report.info.materialCount,
        drawCallCount: report.info.drawCallCount,
    },
}));
process.exit(numErrors > 0 ? 1 : 0);
