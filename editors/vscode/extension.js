// The client side: starts fscript-lsp over stdio for .fs files and .wrl scenes.
const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const command = vscode.workspace.getConfiguration("fscript").get("server.path") || "fscript-lsp";
  const server = { command, transport: TransportKind.stdio };
  client = new LanguageClient("fscript", "FScript", { run: server, debug: server }, {
    documentSelector: [
      { scheme: "file", language: "fscript" },
      { scheme: "file", language: "vrml" },
    ],
  });
  context.subscriptions.push({ dispose: () => client && client.stop() });
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
