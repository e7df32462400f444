// Tokenize .lay files with vscode-textmate + vscode-oniguruma, the TextMate engine VS Code
// uses, and print one snapshot per file: each line, then each token that is not blank with
// its scopes (without `source.lay`, on every token, and the meta.* region scopes).
//
// usage: node tokenize.js GRAMMAR.json FILE.lay... (writes the snapshots, in order, to stdout
// as a JSON object: file -> snapshot text)
"use strict";

const fs = require("fs");
const path = require("path");
const vsctm = require("vscode-textmate");
const oniguruma = require("vscode-oniguruma");

async function main() {
  const [grammarPath, ...files] = process.argv.slice(2);
  const wasm = fs.readFileSync(path.join(__dirname, "node_modules", "vscode-oniguruma", "release", "onig.wasm"));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new vsctm.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
      createOnigString: (text) => new oniguruma.OnigString(text),
    }),
    loadGrammar: async () => vsctm.parseRawGrammar(fs.readFileSync(grammarPath, "utf8"), grammarPath),
  });
  const grammar = await registry.loadGrammar("source.lay");
  if (!grammar) throw new Error(`no grammar for source.lay in ${grammarPath}`);
  const snapshots = {};
  for (const file of files) {
    const out = [];
    let state = vsctm.INITIAL;
    const lines = fs.readFileSync(file, "utf8").replace(/\r\n/g, "\n").split("\n");
    if (lines.length && lines[lines.length - 1] === "") lines.pop();
    lines.forEach((line, index) => {
      const result = grammar.tokenizeLine(line, state);
      state = result.ruleStack;
      out.push(`${index + 1}| ${line}`);
      for (const token of result.tokens) {
        const text = line.substring(token.startIndex, token.endIndex);
        if (!text.trim()) continue;
        // meta.* scopes name the regions (section, line kind); the snapshot keeps what
        // themes colour
        const scopes = token.scopes.filter((scope) => scope !== "source.lay" && !scope.startsWith("meta."));
        out.push(`    ${JSON.stringify(text)} ${scopes.join(" ")}`);
      }
    });
    snapshots[file] = out.join("\n") + "\n";
  }
  process.stdout.write(JSON.stringify(snapshots));
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
