// Puts the explorer page together: web/explore.html with the Emscripten module (its
// WebAssembly inlined as base64) and web/explore.js in it: one self-contained file.
//   node web/assemble.cjs explore.html heavytop-core.js explore.js OUT.html
const fs = require("fs");
const [html, core, page, out] = process.argv.slice(2);
const inline = (file) => fs.readFileSync(file, "utf8").replace(/<\/script/gi, "<\\/script");
let text = fs.readFileSync(html, "utf8");
for (const [mark, file] of [["/*HEAVYTOP_CORE*/", core], ["/*HEAVYTOP_PAGE*/", page]]) {
  const at = text.indexOf(mark);
  if (at < 0) throw new Error(`${html}: no ${mark}`);
  text = text.slice(0, at) + inline(file) + text.slice(at + mark.length);
}
fs.writeFileSync(out + ".tmp", text);
fs.renameSync(out + ".tmp", out);
