// The client side: starts fscript-lsp over stdio for .fs files and .wrl scenes, and the
// "FVRML: Preview" command (the live preview in the browser).
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
  // FVRML: Preview: the server starts `fvrml-run SCENE --serve` (fscript.preview) and gives its URL,
  // opened in the browser; the page follows every save.
  context.subscriptions.push(vscode.commands.registerCommand("fvrml.preview", async () => {
    const editor = vscode.window.activeTextEditor;
    if (!editor) return;
    try {
      const result = await client.sendRequest("workspace/executeCommand", {
        command: "fscript.preview",
        arguments: [editor.document.uri.toString()],
      });
      await vscode.env.openExternal(vscode.Uri.parse(result.url));
    } catch (e) {
      vscode.window.showErrorMessage("FVRML preview: " + e.message);
    }
  }));
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
