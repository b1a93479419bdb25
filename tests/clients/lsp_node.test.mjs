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
  assert.deepEqual((await d).diagnostics, []);
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
  assert.deepEqual((await d).diagnostics, []);
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
