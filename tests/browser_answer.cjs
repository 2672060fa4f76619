// The answer first (SPEC section 14), in a real browser: node browser_answer.cjs CHROMIUM
// NAME=REPORT_DIR,STABILITY_JSON[,LIFETIME_JSON]... For each report: the first thing under
// the title is the answer section, its words open with the verdict, and its numbers are those
// of `heavytop stability --format json` (and, damped, `heavytop lifetime --format json`).
const puppeteer = require("puppeteer-core");
const fs = require("fs");
const path = require("path");

const [chromium, ...reports] = process.argv.slice(2);
let failures = 0;
function check(name, what, ok, detail = "") {
  console.log(`${ok ? "ok  " : "FAIL"} ${name}: ${what}${detail ? ": " + detail : ""}`);
  if (!ok) failures++;
}
const same = (a, b) => (a === null && b === null) || (a !== null && b !== null && Math.abs(a - b) <= 1e-12 * Math.abs(b));

(async () => {
  const browser = await puppeteer.launch({
    executablePath: chromium, headless: true,
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox",
           "--no-first-run", "--disable-extensions", "--disable-background-networking"],
  });
  for (const spec of reports) {
    const [name, files] = spec.split("=");
    const [dir, stabilityFile, lifetimeFile] = files.split(",");
    const want = JSON.parse(fs.readFileSync(stabilityFile, "utf8")).answer;
    const page = await browser.newPage();
    await page.goto("file://" + path.resolve(dir, "report.html"), { waitUntil: "load" });
    const got = await page.evaluate(() => {
      const h1 = document.querySelector("h1");
      const first = h1 && h1.nextElementSibling;
      const a = document.getElementById("answer");
      const num = (k) => (a.dataset[k] === "null" ? null : Number(a.dataset[k]));
      return {
        title: h1 ? h1.textContent : "", firstId: first ? first.id : "", text: a ? a.querySelector("p.answer").textContent : "",
        verdict: a && a.dataset.verdict, proven: a && a.dataset.proven === "true",
        falls_at: a && num("fallsAt"), lifetime: a && num("lifetime"), max_tilt: a && num("maxTilt"), min_spin: a && num("minSpin"),
      };
    });
    check(name, "the answer is the first section under the title", got.firstId === "answer", `${got.title} / ${got.firstId}`);
    const headline = { "stays up": /^(Stays up\.|Hangs steadily\.)/, "falls": /^Falls/, "stays up for the horizon": /^Stays up for the/ }[want.verdict];
    check(name, "its words open with the verdict", headline.test(got.text), got.text.slice(0, 120));
    check(name, "verdict and proof as stability --format json", got.verdict === want.verdict && got.proven === want.proven,
          `${got.verdict}/${got.proven} vs ${want.verdict}/${want.proven}`);
    for (const k of ["falls_at", "lifetime", "max_tilt", "min_spin"])
      check(name, `${k} as stability --format json`, same(got[k], want[k]), `${got[k]} vs ${want[k]}`);
    if (lifetimeFile) {
      const life = JSON.parse(fs.readFileSync(lifetimeFile, "utf8"));
      check(name, "falls at lifetime's fall time", same(got.falls_at, life.fall.time) && same(got.lifetime, life.fall.time),
            `${got.falls_at} vs ${life.fall.time}`);
      check(name, "the lifetime figure follows the answer", await page.evaluate(() =>
        !!document.querySelector("#answer img[src='lifetime.svg']")));
    }
    await page.close();
  }
  await browser.close();
  process.exit(failures ? 1 : 0);
})().catch((err) => { console.log("FAIL", err.stack || err); process.exit(1); });
