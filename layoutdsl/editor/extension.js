// The VS Code side of layoutdsl's editor support: the grammar and language configuration are
// declared in package.json; this starts `layoutdsl lsp` (or the command the setting
// `layoutdsl.command` names) for .lay files, over standard input and output.
"use strict";

const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

exports.activate = async function activate() {
  const [command, ...args] = vscode.workspace.getConfiguration("layoutdsl").get("command", ["layoutdsl", "lsp"]);
  client = new LanguageClient(
    "layoutdsl",
    "layoutdsl",
    { command, args },
    { documentSelector: [{ scheme: "file", language: "lay" }, { scheme: "untitled", language: "lay" }] },
  );
  await client.start();
};

exports.deactivate = function deactivate() {
  return client ? client.stop() : undefined;
};
