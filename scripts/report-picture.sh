#!/usr/bin/env bash
# Makes docs/report.png, the README's picture: the built-in example's report as `heavytop`
# writes it, its top screenful in headless Chromium (puppeteer-core from the build's npm
# packages). Run after ./scripts/build.sh --tests (it needs build/heavytop, chromium, node).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && "$root/build/heavytop" > /dev/null)
NODE_PATH="$root/build/report/web/node_modules" node - "$work/heavytop-report/report.html" "$root/docs/report.png" <<'JS'
const puppeteer = require("puppeteer-core");
const [page_file, out] = process.argv.slice(2);
(async () => {
  const browser = await puppeteer.launch({
    executablePath: "/usr/bin/chromium", headless: true,
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox",
           "--no-first-run", "--disable-extensions", "--disable-background-networking"],
    defaultViewport: { width: 1200, height: 1100 },
  });
  const page = await browser.newPage();
  await page.goto("file://" + page_file, { waitUntil: "load" });
  await page.waitForSelector("#scene-canvas", { timeout: 20000 }).catch(() => {});
  await new Promise((r) => setTimeout(r, 2500));  // the top has turned a little
  await page.screenshot({ path: out });
  await browser.close();
})().catch((e) => { console.error(e); process.exit(1); });
JS
echo "wrote docs/report.png"
