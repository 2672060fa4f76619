// The explorer page's benchmark over several page loads (web/README.md, "Performance"): for each
// load heavytopExplorer.benchmark() (medians, the browser's clock), the first verdict from the
// load event and the 3D view rebuilt; printed as the median, least and largest over the loads.
//   NODE_PATH=build/report/web/node_modules node web/bench_page.cjs PAGE.html [LOADS] [CHROMIUM]
const puppeteer = require("puppeteer-core");
const loads = Number(process.argv[3] || 5);
(async () => {
  const browser = await puppeteer.launch({ executablePath: process.argv[4] || "/usr/bin/chromium", headless: true,
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox"], defaultViewport: { width: 1280, height: 1000 } });
  const runs = [];
  for (let k = 0; k < loads; k++) {
    const page = await browser.newPage();
    await page.goto("file://" + require("path").resolve(process.argv[2]), { waitUntil: "load" });
    const loadAt = await page.evaluate(() => performance.getEntriesByType("navigation")[0].loadEventEnd);
    await page.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 60000 });
    const b = await page.evaluate(() => heavytopExplorer.benchmark());
    const v = await page.evaluate(() => { const c = heavytopExplorer.config(); const ts = [];
      for (let i = 0; i < 5; i++) { const t = performance.now(); window.heavytopView.dispose(); window.heavytopView3D.show(heavytopExplorer.view(c, 10, 1001)); ts.push(performance.now() - t); }
      ts.sort((a, b) => a - b); return ts[2]; });
    b.first_verdict_from_load_ms = b.first_verdict_ms - loadAt;
    b.view_rebuilt_ms = v;
    runs.push(b);
    await page.close();
  }
  const med = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };
  const out = {};
  for (const key of Object.keys(runs[0])) out[key] = { median: med(runs.map((r) => r[key])), min: Math.min(...runs.map((r) => r[key])), max: Math.max(...runs.map((r) => r[key])) };
  console.log(JSON.stringify(out, null, 1));
  await browser.close();
})();
