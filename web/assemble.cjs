// Puts the explorer page together: web/explore.html with the Emscripten module (its
// WebAssembly inlined as base64), the report's page script (its 3D view; absent when the build
// had no npm; between marks, so that a report's copy can load the report's own instead:
// report::explorer_page()) and web/explore.js in it: one self-contained file.
//   node web/assemble.cjs OUT.html explore.html heavytop-core.js explore.js [heavytop-report.js]
const fs = require("fs");
const [out, html, core, page, view] = process.argv.slice(2);
const inline = (file) => fs.readFileSync(file, "utf8").replace(/<\/script/gi, "<\\/script");
let text = fs.readFileSync(html, "utf8");
const parts = [["/*HEAVYTOP_CORE*/", inline(core)], ["/*HEAVYTOP_PAGE*/", inline(page)],
               ["/*HEAVYTOP_VIEW*/", "/*HEAVYTOP_VIEW_BEGIN*/" +
                (view ? inline(view) : "window.heavytopView3DMissing = 'the build had no npm packages (three.js)';") +
                "\n/*HEAVYTOP_VIEW_END*/"]];
for (const [mark, content] of parts) {
  const at = text.indexOf(mark);
  if (at < 0) throw new Error(`${html}: no ${mark}`);
  text = text.slice(0, at) + content + text.slice(at + mark.length);
}
fs.writeFileSync(out + ".tmp", text);
fs.renameSync(out + ".tmp", out);
