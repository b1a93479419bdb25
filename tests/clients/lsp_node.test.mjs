// fscript-lsp driven by Microsoft's LSP client libraries (npm vscode-jsonrpc 10 and
// vscode-languageserver-protocol 3.18), under node's test runner. The packages come from the
// npm folder named by LSP_NPM_DIR (dev.sh installs them in build/npm); the server is LSP_SERVER.
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { createRequire } from "node:module";
import { pathToFileURL } from "node:url";
import path from "node:path";

const require = createRequire(path.join(process.env.LSP_NPM_DIR, "package.json"));
const rpc = await import(pathToFileURL(require.resolve("vscode-jsonrpc/node")).href);
const proto = await import(pathToFileURL(require.resolve("vscode-languageserver-protocol")).href);

function start() {
  const child = spawn(process.env.LSP_SERVER, [], { stdio: ["pipe", "pipe", "ignore"] });
  const conn = rpc.createMessageConnection(new rpc.StreamMessageReader(child.stdout), new rpc.StreamMessageWriter(child.stdin));
  const diagnostics = [];
  const waiters = [];
  conn.onNotification(proto.PublishDiagnosticsNotification.type, (p) => {
    diagnostics.push(p);
    while (waiters.length) waiters.shift()(p);
  });
  conn.listen();
  const next = () => new Promise((resolve) => waiters.push(resolve));
  return { child, conn, diagnostics, next };
}

const uri = "file:///virtual/ball.fs";
const text = "function ball(p, r) {\n  return r - p * p;\n}\nfunction FRep(x, y, z, t) {\n  return ball(x, 0.5) + ball(y, 0.25);\n}\n";

test("fscript-lsp with vscode-jsonrpc: life cycle, sync and the features", async () => {
  const { child, conn, next } = start();
  const init = await conn.sendRequest(proto.InitializeRequest.type, { processId: process.pid, rootUri: null, capabilities: {} });
  assert.equal(init.capabilities.hoverProvider, true);
  assert.equal(init.capabilities.textDocumentSync.change, proto.TextDocumentSyncKind.Incremental);
  await conn.sendNotification(proto.InitializedNotification.type, {});
  let d = next();
  await conn.sendNotification(proto.DidOpenTextDocumentNotification.type, { textDocument: { uri, languageId: "fscript", version: 10, text } });
  // The slab of two 1D balls goes on along z: a shape diagnostic, as a hint.
  assert.deepEqual((await d).diagnostics.map((x) => [x.code, x.severity]), [["shape-cut", proto.DiagnosticSeverity.Hint]]);
  d = next();
  await conn.sendNotification(proto.DidChangeTextDocumentNotification.type, {
    textDocument: { uri, version: 15 },
    contentChanges: [{ range: { start: { line: 1, character: 13 }, end: { line: 1, character: 14 } }, text: "q" }],
  });
  const bad = await d;
  assert.equal(bad.version, 15);
  assert.match(bad.diagnostics[0].message, /unknown name 'q'/);
  d = next();
  await conn.sendNotification(proto.DidChangeTextDocumentNotification.type, { textDocument: { uri, version: 20 }, contentChanges: [{ text }] });
  assert.equal((await d).diagnostics.filter((x) => x.severity !== proto.DiagnosticSeverity.Hint).length, 0);
  const hover = await conn.sendRequest(proto.HoverRequest.type, { textDocument: { uri }, position: { line: 4, character: 10 } });
  assert.match(hover.contents.value, /function ball\(p, r\)/);
  const items = await conn.sendRequest(proto.CompletionRequest.type, { textDocument: { uri }, position: { line: 4, character: 11 } });
  assert.ok(items.items.some((i) => i.label === "ball"));
  const def = await conn.sendRequest(proto.DefinitionRequest.type, { textDocument: { uri }, position: { line: 4, character: 27 } });
  assert.deepEqual(def.range.start, { line: 0, character: 9 });
  const refs = await conn.sendRequest(proto.ReferencesRequest.type, { textDocument: { uri }, position: { line: 0, character: 10 }, context: { includeDeclaration: true } });
  assert.equal(refs.length, 3);
  const edit = await conn.sendRequest(proto.RenameRequest.type, { textDocument: { uri }, position: { line: 0, character: 10 }, newName: "sphere" });
  assert.equal(edit.changes[uri].length, 3);
  const sig = await conn.sendRequest(proto.SignatureHelpRequest.type, { textDocument: { uri }, position: { line: 4, character: 17 } });
  assert.equal(sig.signatures[0].label, "ball(p, r)");
  assert.equal(sig.activeParameter, 1);
  await assert.rejects(conn.sendRequest("textDocument/noSuchThing", {}), (e) => e.code === -32601);
  await conn.sendRequest(proto.ShutdownRequest.type);
  const exited = new Promise((resolve) => child.on("exit", resolve));
  await conn.sendNotification(proto.ExitNotification.type);
  assert.equal(await exited, 0);
  conn.dispose();
});

test("fscript-lsp with vscode-jsonrpc: a shape diagnostic and its quick fix", async () => {
  const { child, conn, next } = start();
  await conn.sendRequest(proto.InitializeRequest.type, { processId: process.pid, rootUri: null, capabilities: {} });
  await conn.sendNotification(proto.InitializedNotification.type, {});
  const wrl = "file:///virtual/cut.wrl";
  const scene = '#VRML V2.0 utf8\nFShape { geometry FGeometry {\n  definition "1.2 - x^2 - y^2 - z^2"\n  bboxSize 2 2 2 } }\n';
  let d = next();
  await conn.sendNotification(proto.DidOpenTextDocumentNotification.type, { textDocument: { uri: wrl, languageId: "vrml", version: 1, text: scene } });
  const got = (await d).diagnostics;
  assert.equal(got.length, 1);
  assert.equal(got[0].code, "shape-cut");
  assert.equal(got[0].severity, proto.DiagnosticSeverity.Warning);
  assert.match(got[0].message, /bboxSize 2.6 2.6 2.6 holds it whole/);
  const actions = await conn.sendRequest(proto.CodeActionRequest.type, { textDocument: { uri: wrl }, range: got[0].range, context: { diagnostics: got } });
  assert.equal(actions[0].title, "Set the box to 2.6 2.6 2.6");
  const edit = actions[0].edit.changes[wrl][0];
  assert.deepEqual(edit.range, { start: { line: 3, character: 11 }, end: { line: 3, character: 16 } });
  d = next();
  await conn.sendNotification(proto.DidChangeTextDocumentNotification.type, { textDocument: { uri: wrl, version: 2 }, contentChanges: [{ range: edit.range, text: edit.newText }] });
  assert.deepEqual((await d).diagnostics, []);
  await conn.sendRequest(proto.ShutdownRequest.type);
  const exited = new Promise((resolve) => child.on("exit", resolve));
  await conn.sendNotification(proto.ExitNotification.type);
  assert.equal(await exited, 0);
  conn.dispose();
});

test("fscript-lsp with vscode-jsonrpc: fscript.profile and its code lenses", async () => {
  const { child, conn, next } = start();
  let refreshed = 0;
  conn.onRequest("workspace/codeLens/refresh", () => {
    refreshed += 1;
    return null;
  });
  const caps = { workspace: { codeLens: { refreshSupport: true } } };
  const init = await conn.sendRequest(proto.InitializeRequest.type, { processId: process.pid, rootUri: null, capabilities: caps });
  assert.ok(init.capabilities.executeCommandProvider.commands.includes("fscript.profile"));
  assert.ok(init.capabilities.codeLensProvider);
  await conn.sendNotification(proto.InitializedNotification.type, {});
  const wrl = "file:///virtual/union.wrl";
  // The heavy branch (line 7, 0-based) is needed only near its small ball in a corner.
  const scene = [
    "#VRML V2.0 utf8",
    "FShape { geometry FGeometry {",
    "  resolution [96 96 96]",
    "  bboxSize 2.4 2.4 2.4",
    '  definition "function FRep(x, y, z, t) {',
    "    light = 0.6 - sqrt(x*x + y*y + z*z);",
    "    w = sin(3*x) * cos(5*y) + sin(7*z) * cos(2*x) + sin(4*y) * cos(6*z) + sin(9*x) * sin(8*y);",
    "    heavy = 0.15 - sqrt((x-0.8)*(x-0.8) + (y-0.8)*(y-0.8) + (z-0.8)*(z-0.8)) + 0.01 * w;",
    "    return max(light, heavy);",
    '  }" } }',
    "",
  ].join("\n");
  const d = next();
  await conn.sendNotification(proto.DidOpenTextDocumentNotification.type, { textDocument: { uri: wrl, languageId: "vrml", version: 1, text: scene } });
  await d;
  let lenses = await conn.sendRequest(proto.CodeLensRequest.type, { textDocument: { uri: wrl } });
  assert.equal(lenses.length, 1);
  assert.equal(lenses[0].command.command, "fscript.profile");
  const result = await conn.sendRequest(proto.ExecuteCommandRequest.type, lenses[0].command);
  assert.equal(result.shapes.length, 1);
  assert.ok(result.shapes[0].regions > 0);
  assert.equal(refreshed, 1);
  lenses = await conn.sendRequest(proto.CodeLensRequest.type, { textDocument: { uri: wrl } });
  const at = (line) => lenses.find((l) => l.range.start.line === line && l.command.command === "");
  assert.match(at(5).command.title, /runs at (9\d\.\d|100\.0)% of points$/);
  const heavy = at(6).command.title.match(/runs at ([\d.]+)% of points$/);
  assert.ok(Number(heavy[1]) < 30, at(6).command.title);
  await conn.sendRequest(proto.ShutdownRequest.type);
  const exited = new Promise((resolve) => child.on("exit", resolve));
  await conn.sendNotification(proto.ExitNotification.type);
  assert.equal(await exited, 0);
  conn.dispose();
});
