// The explorer page in a real browser (Debian's chromium, headless, driven by puppeteer-core):
//   node browser_explore.cjs CHROMIUM HEAVYTOP PAGE.html WORK_DIR
// Loads PAGE.html (as `heavytop explore` wrote it) from file:// and checks SPEC section 15:
// window.heavytop.stability equals `heavytop stability --format json` (1e-12 relative; the
// integrated quantities, wander and answer, 1e-6) for seeded random bodies (symmetric and not,
// hanging, damped, spins in rpm), simulate equals the CSV (1e-9), bad input throws the command
// line's one-line message, no request leaves the page's folder, no console error, and typing a
// spin changes the verdict shown; dropping the mesh example gives the body `heavytop body` gives
// (1e-12), parts added and removed in the list give the command line's body of those parts; the
// 3D view (WebGL, the report's) draws the mesh's own triangles and moves; a click on the map
// shows that point's motion in it. Then the page's benchmarks (medians, the browser's clock).
// Issues 42 and 46: every option of `heavytop stability` (from its --help) given to `heavytop
// explore` gives the page stability's answer with that option; the table examples' answers
// (headline, words, events) are stability's and the 3D view draws the table; simulate refuses
// too many samples and the flags the page sets itself; malformed #config= links (some random)
// start the page with a one-line message. HEAVYTOP_SHOW_TIMES=1 prints each check's time.
// With REPORT_DIR (a folder `heavytop report` wrote): the report carries the explorer, which
// opens inside it at the report's body and spin, and a map point's link opens there.
// Exit 0 when all pass.
const puppeteer = require("puppeteer-core");
const fs = require("fs");
const os = require("os");
const path = require("path");
const { spawnSync } = require("child_process");

const [chromium, heavytop, pageFile, work, examples, reportDir] = process.argv.slice(2);
let failures = 0;
const testStart = Date.now();
function check(what, ok, detail = "") {
  const at = process.env.HEAVYTOP_SHOW_TIMES ? `[${((Date.now() - testStart) / 1000).toFixed(1)} s] ` : "";
  console.log(`${ok ? "ok  " : "FAIL"} ${at}${what}${detail ? ": " + detail : ""}`);
  if (!ok) failures++;
  return ok;
}

// The command line on the same TOML text, in WORK_DIR under the name the page's core uses.
function cli(toml, args) {
  fs.writeFileSync(path.join(work, "config.toml"), toml);
  const r = spawnSync(heavytop, [args[0], "--config", "config.toml", ...args.slice(1)], { cwd: work, encoding: "utf8",
                                                                                       maxBuffer: 1 << 28 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr.trim() };
}

// Deterministic random numbers (mulberry32).
function rng(seed) {
  return () => {
    seed |= 0; seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
function bodies(count) {
  const r = rng(20261202), list = [];
  const between = (a, b) => a + (b - a) * r();
  for (let i = 0; i < count; i++) {
    const A = between(1e-5, 1e-3);
    const symmetric = i % 3 !== 2;
    const B = symmetric ? A : A * between(0.8, 1.25);
    const C = Math.min(A + B, Math.max(Math.abs(A - B), A)) * between(0.2, 0.95) + Math.abs(A - B);
    const c = { body: { A, B, C, mass: between(0.02, 2), length: between(0.005, 0.1) * (i % 5 === 1 ? -1 : 1) },
                motion: { theta0: between(0.001, 0.2) } };
    if (i % 4 === 0) c.body.gravity = between(1, 20);
    const wc = Math.sqrt(4 * A * c.body.mass * (c.body.gravity || 9.81) * Math.abs(c.body.length)) / C;
    const spin = wc * between(0.3, 3);
    if (i % 6 === 5) c.motion.spin_rpm = (spin * 60) / (2 * Math.PI); else c.motion.spin = spin;
    if (i % 4 === 3) c.damping = { transverse: C * between(0, 0.05), axial: C * between(0.01, 0.1), friction: i % 8 === 7 ? C * between(0.1, 1) : 0 };
    if (i % 7 === 6) c.motion.phi_rate0 = between(-1, 1);
    list.push(c);
  }
  return list;
}

// Numbers equal to `tol` relative (of the larger, or of `scale` for entries of one array such
// as eigenvalues, whose small parts are rounding noise of the large ones); the rest equal.
// Integrated quantities (wander, answer) to 1e-6, but a falling body's largest tilt (chaotic)
// only has to pass the fall's tilt (1 rad) in both, and a message holding an integrated time
// (the step limit reached at t = ...) is compared with its numbers to 1e-4.
function compare(a, b, where, tol, scale, out) {
  const integrated = /^\.(wander|answer|lifetime)/.test(where);
  const t = integrated ? Math.max(tol, 1e-6) : tol;
  if (integrated && /max_tilt$/.test(where) && a > 1 && b > 1) return out;
  if (integrated && typeof a === "string" && typeof b === "string") {
    const numbers = (s) => (s.match(/-?\d+(\.\d+)?(e[-+]?\d+)?/g) || []).map(Number);
    const [na, nb] = [numbers(a), numbers(b)];
    const same = a.replace(/-?\d+(\.\d+)?(e[-+]?\d+)?/g, "#") === b.replace(/-?\d+(\.\d+)?(e[-+]?\d+)?/g, "#") &&
                 na.every((x, i) => Math.abs(x - nb[i]) <= 1e-4 * Math.max(Math.abs(x), Math.abs(nb[i])));
    if (!same) out.push(`${where}: ${JSON.stringify(a)} != ${JSON.stringify(b)}`);
    return out;
  }
  if (typeof a === "number" && typeof b === "number") {
    // A tilt near 0 (a top asleep) is known to the attitude's rounding, about 1e-15 rad: its
    // relative tolerance is taken of at least 1e-9 rad.
    const s = Math.max(Math.abs(a), Math.abs(b), scale || 0, /tilt$/.test(where) ? 1e-9 : 0);
    if (!(Math.abs(a - b) <= t * s)) out.push(`${where}: ${a} != ${b}`);
  } else if (Array.isArray(a) && Array.isArray(b)) {
    if (a.length !== b.length) return out.push(`${where}: ${a.length} entries != ${b.length}`);
    const flat = a.flat(2).filter((x) => typeof x === "number");
    // Eigenvalues are known to the rounding of the largest: the whole list's scale, kept for its
    // [re, im] pairs (not each pair's own: a zero eigenvalue is rounding-sized either way).
    const sc = /eigenvalues$/.test(where) ? Math.max(0, ...flat.map(Math.abs)) : scale;
    a.forEach((x, i) => compare(x, b[i], `${where}[${i}]`, tol, sc, out));
  } else if (a && b && typeof a === "object" && typeof b === "object") {
    const keys = new Set([...Object.keys(a), ...Object.keys(b)]);
    // A model's growth rate (the eigenvalues' largest real part) is 0 up to their rounding.
    const eig = Array.isArray(a.eigenvalues) ? Math.max(0, ...a.eigenvalues.flat(2).map(Math.abs)) : 0;
    for (const k of keys) {
      if (!(k in a) || !(k in b)) { out.push(`${where}.${k}: only in ${k in a ? "the page" : "the command line"}`); continue; }
      compare(a[k], b[k], `${where}.${k}`, tol, k === "growth_rate" ? eig : scale, out);
    }
  } else if (a !== b) out.push(`${where}: ${JSON.stringify(a)} != ${JSON.stringify(b)}`);
  return out;
}

function parseCsv(text) {
  const lines = text.trim().split("\n");
  return { columns: lines[0].split(","), rows: lines.slice(1).map((l) => l.split(",").map(Number)) };
}
function compareTrajectory(page, native, tol) {
  const out = [];
  if (page.columns.join() !== native.columns.join()) return [`columns ${page.columns} != ${native.columns}`];
  if (page.rows.length !== native.rows.length) return [`${page.rows.length} rows != ${native.rows.length}`];
  // tilt and azimuth are functions of theta and phi (SPEC 2) through sines and cosines: an
  // unstable linear model's angles grow without bound (1e17 rad), and their 1e-9 relative
  // error is then that many radians of tilt. Their tolerance grows with the largest angle so far
  // (azimuth is unwrapped: an error stays in it).
  const [ith, iph] = [native.columns.indexOf("theta"), native.columns.indexOf("phi")];
  let largest = 1;
  const angleScale = native.rows.map((r) => (largest = Math.max(largest, Math.abs(r[ith]), Math.abs(r[iph]))));
  page.columns.forEach((name, j) => {
    // A conserved quantity's drift is relative already and rounding-sized: to 1e-9 absolute.
    const scale = /_drift$/.test(name) ? 1 : Math.max(...native.rows.map((r) => Math.abs(r[j])));
    const angular = name === "tilt" || name === "azimuth";
    let worst = 0;
    page.rows.forEach((r, i) => {
      worst = Math.max(worst, Math.abs(r[j] - native.rows[i][j]) / ((scale || 1) * (angular ? angleScale[i] : 1)));
    });
    if (!(worst <= tol)) out.push(`${name}: off by ${worst.toExponential(2)} of its scale`);
  });
  return out;
}

// A page that lets requests inside `folder` (and data: URLs) through and aborts and records every
// other one, and records console errors and uncaught exceptions.
async function guardedPage(browser, folder) {
  const page = await browser.newPage();
  const foreign = [], errors = [];
  await page.setRequestInterception(true);
  page.on("request", (req) => {
    const url = req.url();
    const local = url.startsWith("file://") && decodeURIComponent(new URL(url).pathname).startsWith(folder + path.sep);
    if (local || url.startsWith("data:")) req.continue();
    else { foreign.push(url); req.abort(); }
  });
  page.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
  page.on("pageerror", (err) => errors.push(String(err)));
  return { page, foreign, errors };
}

// The frame whose URL ends with `suffix` once its page says it is ready. The frame is looked up
// afresh at each poll: Chromium may commit a file:// page in another process, a new Frame, and a
// wait on an earlier one never ends (the "ready" timeouts under load). On time-out, what each
// frame showed is in the error.
async function readyFrame(page, suffix, timeout) {
  const deadline = Date.now() + timeout;
  let seen = [];
  while (Date.now() < deadline) {
    seen = [];
    for (const f of page.frames()) {
      let state = "?";
      try { state = await f.evaluate(() => `ready=${document.body && document.body.dataset.ready}, ${document.readyState}`); }
      catch (err) { state = `not evaluable (${String(err.message || err).split("\n")[0]})`; }
      seen.push(`${f.url()} [${f.isDetached() ? "detached" : "attached"}]: ${state}`);
      if (f.url().endsWith(suffix) && !f.isDetached() && state.startsWith("ready=1")) return f;
    }
    await new Promise((r) => setTimeout(r, 250));
  }
  throw new Error(`no ready frame ending in ${suffix} after ${timeout} ms; frames: ${seen.join(" | ")}`);
}

// The explorer inside a report: the report's folder only, no console error.
async function checkReport(browser) {
  const folder = path.resolve(reportDir);
  const { page, foreign, errors } = await guardedPage(browser, folder);
  await page.goto("file://" + path.join(folder, "report.html"), { waitUntil: "load" });
  await page.waitForSelector("#scene-canvas", { timeout: 20000 });
  const t0 = Date.now();
  await page.click("#explorer-open");
  await page.waitForSelector("#explorer-frame:not([hidden])");
  // The frame that holds explore.html, not the iframe's first about:blank: a file:// page is its
  // own origin, so Chromium may commit explore.html in another process, a new Frame, and a wait on
  // the old one never ends (the "ready" timeouts under load).
  const frame = await readyFrame(page, "/explore.html", 60000);
  const inside = await frame.evaluate(() => ({ spin: Number(document.getElementById("spin").value), answer: document.getElementById("answer").textContent,
                                               canvas: !!document.getElementById("scene-canvas"), version: window.heavytop.version,
                                               A: Number(document.getElementById("A").value) }));
  const data = await page.evaluate(() => ({ spin: window.HEAVYTOP_REPORT.spin, A: window.HEAVYTOP_REPORT.body.A }));
  check("the report opens the explorer inside it at its own body and spin", inside.spin === data.spin && inside.A === data.A && inside.canvas,
        `${Date.now() - t0} ms; spin ${inside.spin} (report ${data.spin}); ${inside.answer.slice(0, 80)}`);
  // Its answer is the command line's for the report's body and spin.
  const cfg = await frame.evaluate(() => heavytopExplorer.config());
  const toml = await frame.evaluate((c) => heavytopExplorer.toml(c), cfg);
  const got = await frame.evaluate((c) => heavytop.stability(c), cfg);
  const native = cli(toml, ["stability", "--format", "json"]);
  const diff = native.status === 0 ? compare(got, JSON.parse(native.stdout), "", 1e-12, 0, []) : [native.stderr];
  check("the explorer in the report answers as the command line", diff.length === 0, diff.slice(0, 3).join("; "));
  await (await page.$("#explorer-embed")).screenshot({ path: path.join(work, "report-explorer.png") });
  // A map point of the report's own (precomputed) explorer links to the explorer at that point.
  const link = await page.evaluate(() => {
    const cv = document.getElementById("explorer"), M = window.HEAVYTOP_REPORT.map, r = cv.getBoundingClientRect();
    cv.scrollIntoView();
    const pad = { l: 70, r: 20, t: 20, b: 50 }, pw = cv.width - pad.l - pad.r, ph = cv.height - pad.t - pad.b;
    const x = pad.l + 0.3 * pw, y = pad.t + 0.35 * ph;
    const q = cv.getBoundingClientRect();
    cv.dispatchEvent(new MouseEvent("click", { clientX: q.left + (x * q.width) / cv.width, clientY: q.top + (y * q.height) / cv.height, bubbles: true }));
    const a = document.getElementById("explorer-point");
    return a ? { href: a.getAttribute("href"), text: document.getElementById("explorer-info").textContent } : null;
  });
  if (check("a map point of the report links to the explorer at that point", !!link && /^explore\.html#config=/.test(link.href), link && link.text.slice(0, 120))) {
    const config = JSON.parse(decodeURIComponent(link.href.replace(/^explore\.html#config=/, "")));
    const there = await browser.newPage();
    there.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
    there.on("pageerror", (err) => errors.push(String(err)));
    await there.goto("file://" + path.join(folder, link.href), { waitUntil: "load" });
    await there.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 30000 });
    const shown = await there.evaluate(() => ({ spin: Number(document.getElementById("spin").value), B: Number(document.getElementById("B").value) }));
    check("the link opens the explorer at the point's spin and body", shown.spin === config.motion.spin && shown.B === config.body.B,
          `spin ${shown.spin}, B ${shown.B}`);
    await there.close();
  }
  check("the report with its explorer: no request leaves its folder", foreign.length === 0, foreign.join(" "));
  check("the report with its explorer: no console error", errors.length === 0, errors.join(" | "));
  await page.close();
}

// ---- every option of `heavytop stability` reaches the page (issue 46) ----------------------
// The options are read from `heavytop stability --help` (the command line's own list, so a key
// added there is tested here, or fails for want of a test value below). Each is given, with a
// non-default value, to `heavytop explore`; the page it writes answers as `heavytop stability`
// with the same option: its JSON to 1e-12 (integrated quantities 1e-6) and the answer's words.
// The value must change stability's JSON (from BASE alone), or the equality would show nothing.
const horizonOfTable = ["--horizon", "5"];  // a table's answer follows the motion: a short one
const testValues = {
  "--A": [[], "5e-5"], "--B": [[], "5e-5"], "--C": [[], "1.5e-5"], "--mass": [[], "0.07"], "--gravity": [[], "9.7"],
  "--length": [[], "0.02"],
  "--tip-radius": [["--contact", "frictionless", ...horizonOfTable], "0.004"],
  "--rim-radius": [["--contact", "rolling", "--theta0", "0.3", ...horizonOfTable], "0.01"],
  "--spin": [[], "150"], "--theta0": [[], "0.1"], "--phi0": [[], "0.05"], "--theta_rate0": [[], "0.5"],
  "--phi_rate0": [[], "0.5"], "--spin-rpm": [[], "1500"],
  "--transverse-damping": [[], "1e-7"], "--axial-damping": [[], "2e-6"], "--friction": [[], "1e-5"],
  "--driven": [["--axial-damping", "2e-6"], "true"],
  "--contact": [["--tip-radius", "0.002", ...horizonOfTable], "rolling"],
  "--table-friction": [["--contact", "sliding", "--tip-radius", "0.002", ...horizonOfTable], "0.2"],
  "--friction-law": [["--contact", "sliding", "--table-friction", "0.3", "--tip-radius", "0.002", ...horizonOfTable], "coulomb"],
  "--slip-speed": [["--contact", "sliding", "--table-friction", "0.3", "--tip-radius", "0.002", ...horizonOfTable], "0.5"],
  "--tip-material": [["--contact", "sliding", "--table-friction", "0.3", "--tip-radius", "0.002", "--friction-law", "contensou",
                      "--table-material", "oak", ...horizonOfTable], "brass"],
  "--table-material": [["--contact", "sliding", "--table-friction", "0.3", "--tip-radius", "0.002", "--friction-law", "contensou",
                        "--tip-material", "steel", ...horizonOfTable], "glass"],
  "--rolling-resistance": [["--contact", "sliding", "--table-friction", "0.3", "--tip-radius", "0.002", ...horizonOfTable], "1e-4"],
  "--air": [["--contact", "frictionless", "--tip-radius", "0.002", ...horizonOfTable], "true"],
  "--horizon": [["--spin", "100"], "20"], "--max-tilt": [["--spin", "60"], "0.5"],
  "--lifetime-horizon": [["--axial-damping", "2e-6"], "50"],
  // Below its critical spin the toy top nutates to 1.45 rad: its 100 s need more steps than these.
  "--max-steps": [["--spin", "100", "--max-tilt", "2"], "2000"],
  "--theta0-deg": [[], "5"], "--phi0-deg": [["--theta0", "0.1"], "3"], "--max-tilt-deg": [["--spin", "60"], "30"],
};
function stabilityOptions() {
  const help = spawnSync(heavytop, ["stability", "--help"], { encoding: "utf8" }).stdout;
  const names = [];
  for (const line of help.split("\n")) {
    const m = /^ {2}(?:-\w,)?(--[A-Za-z0-9_-]+)/.exec(line);
    // --brief trims the text the command prints: no option of the answer. --uncertain: not on
    // the page yet (issue 44; browser_explore.sh says so too).
    if (m && !["--help", "--config", "--format", "--output", "--brief", "--uncertain"].includes(m[1])) names.push(m[1]);
  }
  return names;
}
// The first paragraph of `heavytop stability` (text): the answer in words.
const cliWords = (args) => {
  const r = spawnSync(heavytop, ["stability", ...args], { encoding: "utf8" });
  return r.status === 0 ? r.stdout.split("\n\n")[0] : `(exit ${r.status}) ${r.stderr.trim()}`;
};
const cliJson = (args) => {
  const r = spawnSync(heavytop, ["stability", ...args, "--format", "json"], { encoding: "utf8" });
  return r.status === 0 ? JSON.parse(r.stdout) : { error: r.stderr.trim() };
};
// What the page shows and holds now.
const pageState = (page) => page.evaluate(() => {
    const c = heavytopExplorer.current();
    return { stability: c && c.stability, words: c && c.words, config: heavytopExplorer.config(), options: heavytopExplorer.options(),
             headline: (document.querySelector("#answer .headline") || {}).textContent, error: document.getElementById("error").textContent,
             notice: document.getElementById("notice").textContent };
  });
// `heavytop explore ARGS` into work/NAME.html, opened in a new tab; what the page shows and holds.
async function explorePage(browser, name, args) {
  const file = path.join(work, `${name}.html`);
  const made = spawnSync(heavytop, ["explore", ...args, "--output", file], { encoding: "utf8" });
  if (made.status !== 0) return { error: `heavytop explore ${args.join(" ")}: exit ${made.status}: ${made.stderr.trim()}` };
  const page = await browser.newPage();
  const errors = [];
  page.on("pageerror", (err) => errors.push(String(err)));
  page.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
  await page.goto("file://" + file, { waitUntil: "load" });
  await page.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 60000 });
  const shown = await pageState(page);
  shown.errors = errors;
  shown.page = page;
  return shown;
}
// `heavytop explore ARGS`'s start (the page's HEAVYTOP_CONFIG, as it wrote it) opened in `page`
// as a load opens it (heavytopExplorer.open: the inputs and the answer; the motion and the 3D view
// are the links' and the examples' tests): one page for many starts, a load each being seconds
// on the loaded 2-core machine.
async function exploreStart(page, args) {
  const made = spawnSync(heavytop, ["explore", ...args, "--output", "-"], { encoding: "utf8", maxBuffer: 1 << 26 });
  if (made.status !== 0) return { error: `heavytop explore ${args.join(" ")}: exit ${made.status}: ${made.stderr.trim()}` };
  // The whole configuration, or (when it holds no more than the body and motion) HEAVYTOP_INITIAL.
  const m = /window\.HEAVYTOP_CONFIG = (\{.*?\});<\/script>/.exec(made.stdout);
  const initial = /window\.HEAVYTOP_INITIAL = (\{.*?\});<\/script>/.exec(made.stdout);
  if (!m && !initial) return { error: `heavytop explore ${args.join(" ")}: no start in the page` };
  const start = m ? JSON.parse(m[1]) : { config: JSON.parse(initial[1]) };
  const thrown = await page.evaluate((st) => { try { heavytopExplorer.open(st, false); return null; } catch (e) { return String(e); } }, start);
  const shown = await pageState(page);
  if (thrown) shown.error = thrown;
  shown.errors = [];
  return shown;
}
// Words equal, their numbers to 1e-4 (a time or tilt integrated, printed to 4 digits).
function sameWords(a, b) {
  return compare(a, b, ".answer.words", 0, 0, []).length === 0;
}
async function checkEveryOption(browser, mainPage) {
  const options = stabilityOptions();
  check("stability --help lists the options (body, motion, damping, table, answer)", options.length >= 25 &&
        ["--A", "--driven", "--contact", "--horizon", "--tip-radius"].every((o) => options.includes(o)), options.join(" "));
  for (const option of options) {
    const test = testValues[option];
    if (!check(`${option}: has a test value (a new option of stability needs one in browser_explore.cjs)`, !!test)) continue;
    const [base, value] = test;
    const args = [...base, option, value];
    const want = cliJson(args), without = cliJson(base);
    if (!check(`${option} ${value}: stability accepts it`, !want.error, want.error)) continue;
    check(`${option} ${value}: changes stability's answer (else this test shows nothing)`,
          compare(want, without, "", 1e-12, 0, []).length > 0);
    const shown = await exploreStart(mainPage, args);
    if (!check(`heavytop explore ${args.join(" ")}: the page starts`, !shown.error && !!shown.stability, shown.error)) continue;
    const diff = compare(shown.stability, want, "", 1e-12, 0, []);
    check(`heavytop explore ${args.join(" ")}: the page answers as heavytop stability`, diff.length === 0 && !shown.error,
          diff.slice(0, 3).join("; ") || shown.error);
    const words = cliWords(args);
    check(`heavytop explore ${args.join(" ")}: the page's words are stability's`, sameWords(shown.words, words),
          `${(shown.words || "").slice(0, 100)} | ${words.slice(0, 100)}`);
  }
  // A link carries every key the page's form holds: the configuration of a page given them all
  // (a pivot with damping and a motor; a table), as #config=, opens at the same configuration.
  for (const [name, args] of [["every-key-pivot", ["--A", "5e-5", "--B", "4.8e-5", "--C", "1.3e-5", "--mass", "0.07", "--gravity", "9.7",
                                                 "--length", "0.02", "--tip-radius", "0.001", "--rim-radius", "0.002", "--spin", "150",
                                                 "--theta0", "0.1", "--phi0", "0.05", "--theta-rate0", "0.2", "--phi-rate0", "0.3",
                                                 "--transverse-damping", "1e-7", "--axial-damping", "2e-6", "--friction", "1e-6",
                                                 "--driven", "true", "--horizon", "20", "--max-tilt", "0.8", "--lifetime-horizon", "40"]],
                              ["every-key-table", ["--config", path.join(examples, "rising-top.toml"), "--slip-speed", "0.8", "--horizon", "3",
                                                 "--phi0", "0.02", "--theta-rate0", "0.1", "--phi-rate0", "0.1"]]]) {
    const shown = await exploreStart(mainPage, args);
    if (!check(`${name}: the page starts`, !shown.error && !!shown.stability, shown.error)) continue;
    const want = cliJson(args);
    const diff = compare(shown.stability, want, "", 1e-12, 0, []);
    check(`${name}: the page answers as heavytop stability ${args.join(" ")}`, diff.length === 0, diff.slice(0, 3).join("; "));
    // The link opened in the main page as a load opens it (the page's own link parsing).
    const hash = "#config=" + encodeURIComponent(JSON.stringify(shown.config));
    const again = await mainPage.evaluate((h) => { heavytopExplorer.open(h); return heavytopExplorer.config(); }, hash);
    check(`${name}: a link with its configuration opens at the same configuration`, compare(again, shown.config, "", 0, 0, []).length === 0,
          `${JSON.stringify(again).slice(0, 200)} vs ${JSON.stringify(shown.config).slice(0, 200)}`);
  }
}

// ---- the table (issue 42, SPEC section 16) ------------------------------------------------------
// The examples on a table opened by `heavytop explore --config`: the page's answer (the headline,
// the words, the JSON with its events) is `heavytop stability`'s; the 3D view draws the table.
async function checkTable(browser) {
  {  // The body's own losses (issue 43): a wooden top of parts on oak, its air on the parts' surfaces.
    const args = ["--config", path.join(examples, "wooden-top-on-table.toml"), "--horizon", "5"];
    const shown = await explorePage(browser, "table-wooden-top", args);
    if (check("wooden top on a table: the page starts", !shown.error && !!shown.stability, shown.error || shown.errors.join(" | "))) {
      const want = cliJson(args);
      const diff = compare(shown.stability, want, "", 1e-12, 0, []);
      check(`wooden top on a table: the page's answer equals heavytop stability's (spins ${want.answer.table.spin_down.time_to_critical} s ` +
            "asleep, by its parts' air)", diff.length === 0 && shown.config.body.part !== undefined, diff.slice(0, 3).join("; "));
      check("wooden top on a table: the page's words are stability's", sameWords(shown.words, cliWords(args)),
            `${shown.words} | ${cliWords(args)}`);
      check("wooden top on a table: no page error", shown.errors.length === 0, shown.errors.join(" | "));
    }
  }
  for (const example of ["tippe-top", "rising-top", "rolling-coin"]) {
    const file = path.join(examples, `${example}.toml`);
    const shown = await explorePage(browser, `table-${example}`, ["--config", file]);
    if (!check(`${example}: the page starts`, !shown.error && !!shown.stability, shown.error || shown.errors.join(" | "))) continue;
    const want = cliJson(["--config", file]);
    const diff = compare(shown.stability, want, "", 1e-12, 0, []);
    const t = want.answer.table;
    check(`${example}: the page's answer equals heavytop stability's (${want.answer.verdict}; turns over ${t.turns_over_at}, ` +
          `upright ${t.upright_at}, track ${t.track})`, diff.length === 0, diff.slice(0, 3).join("; "));
    const words = cliWords(["--config", file]);
    const headline = words.slice(0, words.indexOf(" " + want.answer.reason));
    check(`${example}: the page's headline is stability's ("${headline}")`, shown.headline === headline, shown.headline);
    check(`${example}: the page's words are stability's`, sameWords(shown.words, words), `${shown.words} | ${words}`);
    const c = shown.config;
    check(`${example}: the page's inputs hold the table`, !!c.table && want.table.contact === c.table.contact &&
          (want.table.friction === undefined || want.table.friction === c.table.friction) &&
          c.body.tip_radius === want.table.tip_radius && c.body.rim_radius === want.table.rim_radius, JSON.stringify(c));
    // The 3D view: the report's, with the table and P's track (D.table).
    await shown.page.waitForFunction(() => /on the table/.test(document.getElementById("view-note").textContent), { timeout: 60000 })
      .catch(() => {});
    const view = await shown.page.evaluate(() => ({ note: document.getElementById("view-note").textContent, motion: document.getElementById("motion-info").textContent,
                                                    shapes: window.heavytopView && window.heavytopView.shapes.map((s) => s.shape),
                                                    follow: !document.getElementById("follow-label").hidden }));
    check(`${example}: the 3D view draws it on the table with P's track`, /on the table/.test(view.note) && view.follow, `${view.note} ${JSON.stringify(view.shapes)}`);
    check(`${example}: the tilt is plotted over the motion on the table`, /on the table/.test(view.motion), view.motion);
    check(`${example}: no page error`, shown.errors.length === 0, shown.errors.join(" | "));
    if (example === "tippe-top") {  // paused past the turn-over, P's track drawn so far
      await shown.page.evaluate(() => {
        if (window.heavytopView && window.heavytopView.time !== undefined) {
          const play = document.getElementById("play");
          if (play.textContent === "Pause") play.click();
          const scrub = document.getElementById("scrub");
          scrub.value = "7000";
          scrub.dispatchEvent(new Event("input", { bubbles: true }));
        }
      });
      await new Promise((r) => setTimeout(r, 500));
      await shown.page.screenshot({ path: path.join(work, "explore-table.png"), fullPage: true });
    }
    await shown.page.close();
  }
}

// ---- runs that do not end (issue 46): the page's step budget ------------------------------------
// The page gives the commands that take it its own --max-steps (its limit, web/heavytop_wasm.cpp):
// a run that needs more ends as the command line's with that --max-steps, not after the command
// line's 10^8 steps (minutes in WebAssembly, the page frozen). A larger max_steps is refused.
const fromMessage = (re, text) => Number((re.exec(text || "") || [])[1]);
async function checkLongRuns(browser, page) {
  const toy = { body: { A: 4.35e-5, B: 4.35e-5, C: 1.2e-5, mass: 0.06, length: 0.025 }, motion: { spin: 200, theta0: 0.05 } };
  const thrown = (f, ...a) => page.evaluate((f, a) => {
    try { return { value: heavytop[f](...a) }; } catch (e) { return { message: e.message, isError: e instanceof Error }; }
  }, f, a);
  // The limits: simulate's (Taylor, DOP853: the slowest steps) and stability's on a pivot (DOPRI5),
  // larger; a table's answer (DOP853) has simulate's.
  const limits = {};
  const onTable = { ...toy, body: { ...toy.body, tip_radius: 0.002 }, table: { contact: "frictionless" } };
  for (const [f, cfg, what] of [["simulate", toy, "simulate"], ["stability", toy, "stability"], ["stability", onTable, "stability on a table"]]) {
    const over = await thrown(f, cfg, { max_steps: 1e12 });
    const limit = fromMessage(/^heavytop: error: --max-steps: must be at most (\d+) in the page/, over.message);
    const just = limit > 0 ? await thrown(f, cfg, { max_steps: limit + 1 }) : {};
    limits[what] = check(`${what}: max_steps 1e12 and the limit + 1 are refused naming --max-steps and the page's limit`,
                         limit > 0 && just.isError && just.message === over.message, over.message) ? limit : 0;
  }
  const within = await thrown("simulate", toy, { t_end: 1, max_steps: limits.simulate });
  check("simulate(toy, {max_steps: the limit}) is taken", !within.message, within.message);
  const limit = limits.simulate;
  if (!limit) return;
  check("stability's limit on a pivot (DOPRI5) is larger than simulate's; on a table it is simulate's",
        limits.stability > limit && limits["stability on a table"] === limit, JSON.stringify(limits));
  const toml = await page.evaluate((c) => heavytopExplorer.toml(c), toy);
  // simulate over 1e7 s: the command line's failure at --max-steps LIMIT, naming the time reached;
  // a max_steps below the limit is the command line's too.
  for (const [options, steps] of [[{ t_end: 1e7 }, limit], [{ t_end: 1e7, max_steps: 1000 }, 1000]]) {
    const r = await thrown("simulate", toy, options);
    const native = cli(toml, ["simulate", "--t-end", "1e7", "--max-steps", String(steps), "--format", "csv"]);
    const reached = fromMessage(/before t = ([-+.\de]+) s/, r.message);
    check(`simulate(toy, ${JSON.stringify(options)}) throws the command line's failure with --max-steps ${steps}, naming the time reached`,
          r.isError && native.status === 1 && sameWords(r.message, native.stderr) && r.message.includes(`max_steps = ${steps} `) &&
          reached > 0 && reached < 1e7, `${r.message || "no error"} | ${native.stderr}`);
  }
  // The budget is the nonlinear model's (simulate refuses --max-steps with another): a linear model
  // over 1e7 s, asked for or the configuration's [simulate] model, is the command line's run.
  for (const [cfg, options, args] of [[toy, { model: "linearized", t_end: 1e7, samples: 11 }, ["--model", "linearized"]],
                                      [{ ...toy, simulate: { model: "body-fixed" } }, { t_end: 1e7, samples: 11 }, []]]) {
    const r = await thrown("simulate", cfg, options);
    const native = cli(await page.evaluate((c) => heavytopExplorer.toml(c), cfg), ["simulate", ...args, "--t-end", "1e7", "--samples", "11", "--format", "csv"]);
    const d = r.message || native.status !== 0 ? [r.message || native.stderr] : compareTrajectory(r.value, parseCsv(native.stdout), 1e-9);
    check(`simulate(${cfg.simulate ? "[simulate] model = body-fixed" : "toy"}, ${JSON.stringify(options)}): no budget, the command line's run`,
          d.length === 0, d.slice(0, 3).join("; "));
  }
  // In the page: a spin of 1e7 rad/s typed in, whose 10 s of motion need more steps than the
  // budget: the motion's panel says so in the command line's words (the answer is a proof: no run).
  await page.evaluate((c) => heavytopExplorer.open({ config: c }, false), toy);
  await page.select("#spin-unit", "rad/s");
  await page.click("#spin", { clickCount: 3 });
  await page.type("#spin", "1e7");
  await page.waitForFunction(() => /^motion: /.test(document.getElementById("motion-info").textContent), { timeout: 60000 }).catch(() => {});
  const motion = await page.$eval("#motion-info", (e) => e.textContent);
  const fast = cli(await page.evaluate(() => heavytopExplorer.toml(heavytopExplorer.config())),
                   ["simulate", "--model", "nonlinear", "--t-end", "10", "--samples", "1001", "--max-steps", String(limit), "--format", "csv"]);
  check("a spin of 1e7 rad/s typed in: the motion's panel shows the run's failure at the page's budget, as the command line words it",
        /^motion: /.test(motion) && fast.status === 1 && sameWords(motion.replace(/^motion: /, ""), fast.stderr), `${motion} | ${fast.stderr}`);

  // The answer's run over a horizon of 1e7 s (a body not proven stable, which does not fall): it
  // stops at the page's budget and says so, the horizon it covered, as `stability --max-steps`.
  const takes = /^ {2}--max-steps\b/m.test(spawnSync(heavytop, ["stability", "--help"], { encoding: "utf8" }).stdout);
  if (!check("heavytop stability takes --max-steps (the page's budget for the answer's run)", takes,
             takes ? "" : "cli/stability_command.cpp has no --max-steps: the page cannot bound stability's run")) return;
  const slow = { ...toy, motion: { spin: 100, theta0: 0.05 } };  // below its critical spin, it nutates to 1.45 rad
  const slowToml = await page.evaluate((c) => heavytopExplorer.toml(c), slow);
  const stabilityLimit = limits.stability;
  const args = ["--horizon", "1e7", "--max-tilt", "2", "--max-steps", String(stabilityLimit)];
  // A max_steps of the person's: the command line's answer with it (its numbers to 1e-12, 1e-6 integrated).
  const few = await thrown("stability", slow, { horizon: 1e7, max_tilt: 2, max_steps: 10000 });
  const fewNative = cli(slowToml, ["stability", "--horizon", "1e7", "--max-tilt", "2", "--max-steps", "10000", "--format", "json"]);
  const fewDiff = few.message || fewNative.status !== 0 ? [few.message || fewNative.stderr] : compare(few.value, JSON.parse(fewNative.stdout), "", 1e-12, 0, []);
  check(`stability(body, {horizon: 1e7, max_tilt: 2, max_steps: 10000}) answers as stability --max-steps 10000: the run stopped (horizon ${few.value && few.value.answer.horizon} s)`,
        fewDiff.length === 0 && few.value.answer.horizon < 1e7 && /could be computed only to t = .*max_steps = 10000 /.test(few.value.answer.reason),
        fewDiff.slice(0, 3).join("; ") || (few.value && few.value.answer.reason));
  // The page's limit: the same, but the time reached after millions of steps is a sum of as many
  // step sizes, and the page's (WebAssembly) and the command line's step controllers part at a
  // rounding along the way (the same to the last digit after 10^4 steps, 6.5e-5 apart after 10^5,
  // 4.4e-5 after 10^6): it is compared as the stopped run's message shows it, to 1e-4.
  const got = await thrown("stability", slow, { horizon: 1e7, max_tilt: 2 });
  const native = cli(slowToml, ["stability", ...args, "--format", "json"]);
  const a = got.value && got.value.answer;
  const want = native.status === 0 ? JSON.parse(native.stdout) : null;
  const diff = got.message || !want ? [got.message || native.stderr]
                                    : compare(got.value, want, "", 1e-12, 0, []).filter((d) => !d.startsWith(".answer.horizon: "));
  const reached = want && Math.abs(a.horizon - want.answer.horizon) <= 1e-4 * want.answer.horizon;
  check(`stability(body, {horizon: 1e7, max_tilt: 2}) stops at the page's limit and says so (horizon ${a && a.horizon} s), as stability ${args.join(" ")}`,
        diff.length === 0 && reached && a.horizon < 1e7 && new RegExp(`could be computed only to t = .*max_steps = ${stabilityLimit} `).test(a.reason),
        diff.slice(0, 3).join("; ") || `${a && a.reason} | ${want && want.answer.horizon}`);
  // In the page: the horizon typed in, the answer shown is that one, in stability's words.
  await page.evaluate((c) => heavytopExplorer.open({ config: c }, false), slow);
  await page.click("#max_tilt", { clickCount: 3 });
  await page.type("#max_tilt", "2");
  await page.click("#horizon", { clickCount: 3 });
  await page.type("#horizon", "1e7");
  await page.waitForFunction(() => { const c = heavytopExplorer.current(); return c && c.options.horizon === 1e7; }, { timeout: 60000 }).catch(() => {});
  const shown = await pageState(page);
  const text = cli(slowToml, ["stability", ...args, "--format", "text"]);
  const words = text.status === 0 ? text.stdout.split("\n\n")[0] : text.stderr;
  const box = await page.$eval("#answer", (e) => e.textContent);
  check("the horizon 1e7 typed in: the page shows the answer of the run that stopped, in stability's words",
        sameWords(shown.words, words) && /could be computed only to t = /.test(box), `${box} | ${words}`);
  await page.evaluate(() => { for (const id of ["horizon", "max_tilt"]) document.getElementById(id).value = ""; });
}

// ---- the tilt in degrees (issue 45) ---------------------------------------------------------------
// The tilt's unit selector, as the spin's rpm: 30 typed in degrees is the answer of
// 0.5235987755982988 rad typed in rad; the configuration stays in rad (motion.theta0), a change of
// unit keeps the tilt's double, and a link made in degrees opens at the same configuration.
async function checkDegrees(browser) {
  const page = await browser.newPage();
  const errors = [];
  page.on("pageerror", (err) => errors.push(String(err)));
  page.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
  await page.goto("file://" + path.resolve(pageFile), { waitUntil: "load" });
  await page.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 60000 });
  const shownAfter = async (unit, text) => {
    if (unit) await page.select("#theta0-unit", unit);
    if (text !== undefined) {
      await page.click("#theta0", { clickCount: 3 });
      await page.keyboard.press("Backspace");
      await page.type("#theta0", text);
    }
    await new Promise((r) => setTimeout(r, 600));
    return page.evaluate(() => ({ field: document.getElementById("theta0").value, config: heavytopExplorer.config(),
                                  current: heavytopExplorer.current(), answer: document.getElementById("answer").textContent }));
  };
  if (!check("the tilt has a unit selector (rad, degrees)", await page.$("#theta0-unit option[value=deg]") !== null)) { await page.close(); return; }
  const start = await shownAfter();
  const inDegrees = await shownAfter("deg");
  check("choosing degrees shows the tilt in degrees, the configuration's tilt unchanged (rad)",
        Number(inDegrees.field) === Number((start.config.motion.theta0 * 180 / Math.PI).toPrecision(12)) &&
        inDegrees.config.motion.theta0 === start.config.motion.theta0, `${start.field} rad -> ${inDegrees.field} degrees, theta0 ${inDegrees.config.motion.theta0}`);
  const thirty = await shownAfter(null, "30");
  const rad = await shownAfter("rad", "0.5235987755982988");
  check("30 degrees typed in is motion.theta0 = 0.5235987755982988 rad", thirty.config.motion.theta0 === 0.5235987755982988 &&
        rad.config.motion.theta0 === 0.5235987755982988, `${thirty.config.motion.theta0}, ${rad.config.motion.theta0}`);
  const diff = thirty.current && rad.current ? compare(thirty.current.stability, rad.current.stability, "", 0, 0, []) : ["no answer"];
  check("30 degrees gives the answer of 0.5235987755982988 rad (its JSON and words, exactly)",
        diff.length === 0 && thirty.current.words === rad.current.words && thirty.answer === rad.answer && compare(thirty.current.stability, start.current.stability, "", 1e-12, 0, []).length > 0,
        diff.slice(0, 3).join("; ") || thirty.answer.slice(0, 100));
  // Back in degrees: a link of the page's configuration opens at the same configuration.
  await shownAfter("deg");
  const again = await page.evaluate(() => {
    const c = heavytopExplorer.config();
    heavytopExplorer.open("#config=" + encodeURIComponent(JSON.stringify(c)));
    return { before: c, after: heavytopExplorer.config(), field: document.getElementById("theta0").value };
  });
  check("in degrees, a link of the page's configuration opens at the same configuration", compare(again.after, again.before, "", 0, 0, []).length === 0 &&
        again.field === "30", `${again.field}: ${JSON.stringify(again.after.motion)}`);
  await page.screenshot({ path: path.join(work, "explore-degrees.png"), fullPage: false });
  check("the tilt in degrees: no page error", errors.length === 0, errors.join(" | "));
  await page.close();
}

// ---- hostile input (issue 46) -------------------------------------------------------------------
async function checkHostile(browser, page) {
  const toy = { body: { A: 4.35e-5, B: 4.35e-5, C: 1.2e-5, mass: 0.06, length: 0.025 }, motion: { spin: 200, theta0: 0.05 } };
  const t0 = Date.now();
  const huge = await page.evaluate((c) => { try { heavytop.simulate(c, { samples: 1e8 }); return null; } catch (e) { return e.message; } }, toy);
  check("simulate(toy, {samples: 1e8}) is refused at once, naming --samples and its limit", Date.now() - t0 < 5000 &&
        /^heavytop: error: --samples: must be at most \d+/.test(huge || ""), `${huge} (${Date.now() - t0} ms)`);
  // The limit is the command line's where it holds the whole run in memory (--format json).
  const limit = Number(/at most (\d+)/.exec(huge || "")?.[1]);
  fs.writeFileSync(path.join(work, "config.toml"), await page.evaluate((c) => heavytopExplorer.toml(c), toy));
  const json = spawnSync(heavytop, ["simulate", "--config", "config.toml", "--samples", String(limit + 1), "--format", "json"], { cwd: work, encoding: "utf8" });
  check("the page's limit on samples is the command line's (simulate --format json)", json.status === 2 &&
        json.stderr.includes(`--samples: must be at most ${limit} `), json.stderr.trim());
  for (const [options, flag] of [[{ help: true }, "--help"], [{ config: "x.toml" }, "--config"], [{ output: "x" }, "--output"],
                                 [{ format: "json" }, "--format"], [{ colour: 3 }, "--colour"]]) {
    const r = await page.evaluate((c, o) => { try { return { value: heavytop.simulate(c, o) }; } catch (e) { return { message: e.message }; } }, toy, options);
    check(`simulate(toy, ${JSON.stringify(options)}) throws naming ${flag}`, !!r.message && r.message.startsWith("heavytop: error:") &&
          r.message.includes(flag), r.message || JSON.stringify(r.value).slice(0, 80));
  }
  const st = await page.evaluate((c) => { try { heavytop.stability(c, { help: true }); return null; } catch (e) { return e.message; } }, toy);
  check("stability(toy, {help: true}) throws naming --help", /^heavytop: error: --help/.test(st || ""), st);
  const unknown = await page.evaluate((c) => { try { heavytop.stability(c, { horizont: 5 }); return null; } catch (e) { return e.message; } }, toy);
  const cliUnknown = spawnSync(heavytop, ["stability", "--config", "config.toml", "--horizont", "5", "--format", "json"], { cwd: work, encoding: "utf8" });
  check("stability(toy, {horizont: 5}) throws the command line's message", unknown === cliUnknown.stderr.trim(), `${unknown} | ${cliUnknown.stderr.trim()}`);
  // Links: not JSON, not an object, no body, a body of the wrong type, random bytes: the page
  // starts at the toy top and says why in one line.
  const r = rng(46);
  const randomText = (n) => Array.from({ length: n }, () => String.fromCharCode(32 + Math.floor(r() * 95))).join("");
  // Keys from the configuration fuzzer's dictionary (fuzz/config.dict: heavytop's sections and keys).
  const dict = path.join(examples, "..", "fuzz", "config.dict");
  const words = fs.existsSync(dict) ? fs.readFileSync(dict, "utf8").split("\n").map((l) => /^"([A-Za-z0-9_]+)"$/.exec(l)).filter(Boolean).map((m) => m[1]) : [];
  const keys = ["body", "motion", "damping", "table", "part", ...words];
  const randomJson = () => {
    const pick = (xs) => xs[Math.floor(r() * xs.length)];
    const value = (d) => pick([() => null, () => r() * 10 - 5, () => pick([true, false]), () => randomText(4), () => [value(d + 1)],
                               () => (d > 3 ? 1 : Object.fromEntries(Array.from({ length: 1 + Math.floor(r() * 4) }, () => [pick(keys), value(d + 1)])))])();
    return JSON.stringify({ [pick(keys)]: value(1), [pick(keys)]: value(1) });
  };
  const links = ["{}", "", "null", "[]", "3", '"x"', "{", '{"motion": {"spin": 5}}', '{"body": 3}', '{"body": {"part": 3}}',
                 '{"body": {"part": [3, null]}}', '{"body": {"A": "x"}, "motion": null}', '{"body": {}, "table": {"contact": 7}}',
                 "%E0%A4%A", '{"body": {"A": 1e400}}', '{"__proto__": {"body": 1}}'];
  for (let i = 0; i < 12; i++) links.push(i % 2 ? randomJson() : randomText(1 + Math.floor(r() * 30)));
  // Each link opened in this page as a load opens it (heavytopExplorer.open: the page's own link
  // parsing, inputs, answer, motion and 3D view); the first two ("{}", not JSON) by a real load of the page.
  let started = 0;
  const failed = [];
  const errors = [];
  page.on("pageerror", (err) => errors.push(String(err)));
  for (const [i, link] of links.entries()) {
    const hash = "#config=" + (link.startsWith("%") ? link : encodeURIComponent(link));
    let state, ready = true, thrown = null;
    const before = errors.length;
    if (i < 2) {
      const p = await browser.newPage();
      p.on("pageerror", (err) => errors.push(String(err)));
      p.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
      await p.goto("file://" + path.resolve(pageFile) + hash, { waitUntil: "load" });
      ready = await p.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 60000 }).then(() => true, () => false);
      state = await pageState(p);
      state.A = await p.evaluate(() => document.getElementById("A").value);
      await p.close();
    } else {
      thrown = await page.evaluate((h) => { try { heavytopExplorer.open(h); return null; } catch (e) { return String(e); } }, hash);
      state = await pageState(page);
      state.A = await page.evaluate(() => document.getElementById("A").value);
    }
    // Started: ready, nothing uncaught, an answer or the core's one-line message; a link without a
    // body says so in one line.
    const said = state.notice || state.error;
    const ok = ready && !thrown && errors.length === before && (!!state.stability || /^heavytop: error: /.test(state.error)) &&
               !/\n/.test(said.trim()) && (state.notice !== "" || (state.config && /"body"\s*:\s*\{/.test(link)));
    if (ok) started++; else failed.push(`${JSON.stringify(link)}: ready=${ready} ${thrown || ""} ${errors.slice(before).join(" | ")} ${JSON.stringify(state).slice(0, 200)}`);
    if (link === "{}") check("explore.html#config={} starts at the toy top with a one-line message",
                             ok && Math.abs(Number(state.A) - 4.35e-5) < 1e-15 && /no body/.test(state.notice), JSON.stringify(state).slice(0, 200));
  }
  check(`malformed links (#config=, ${links.length} of them, 12 random): the page always starts and says why in one line`,
        started === links.length, failed.slice(0, 3).join(" || "));
}

(async () => {
  const folder = path.dirname(path.resolve(pageFile));
  const browser = await puppeteer.launch({
    executablePath: chromium, headless: true,
    // WebGL without a GPU: SwiftShader through ANGLE (as browser_report.cjs).
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox", "--disable-quic", "--no-first-run", "--disable-background-networking",
           "--disable-component-update", "--disable-sync", "--disable-extensions",
           `--user-data-dir=${fs.mkdtempSync(path.join(os.tmpdir(), "heavytop-chromium-"))}`],
    defaultViewport: { width: 1280, height: 1000 },
  });
  const { page, foreign, errors } = await guardedPage(browser, folder);

  const t0 = Date.now();
  await page.goto("file://" + path.resolve(pageFile), { waitUntil: "load" });
  await page.waitForFunction(() => document.body.dataset.ready === "1", { timeout: 30000 });
  check("the page loads and answers", true, `${Date.now() - t0} ms`);
  const v = spawnSync(heavytop, ["--version"], { encoding: "utf8" });
  const pageVersion = await page.evaluate(() => heavytop.version);
  if (v.status === 0) check("heavytop.version is `heavytop --version`", pageVersion === v.stdout.trim(), pageVersion);
  else check("heavytop.version is `heavytop VERSION` (this heavytop has no --version yet)", /^heavytop \d+\.\d+\.\d+$/.test(pageVersion), pageVersion);
  check("heavytop has stability, simulate and version",
        (await page.evaluate(() => Object.keys(window.heavytop).sort().join())) === "simulate,stability,version");

  // ---- stability and simulate against the command line ----
  const list = bodies(24);
  // A body from its parts (SPEC section 10): [[body.part]] from an array of objects.
  list.push({ body: { part: [{ shape: "cone", radius: 0.02, height: 0.02, density: 700 },
                             { shape: "cylinder", radius: 0.003, height: 0.05, z0: 0.0, density: 7800 }] },
              motion: { spin: 300, theta0: 0.05 } });
  let worstKinds = { hanging: 0, damped: 0, asymmetric: 0, rpm: 0, parts: 0 };
  for (const [i, cfg] of list.entries()) {
    const toml = await page.evaluate((c) => heavytopExplorer.toml(c), cfg);
    const got = await page.evaluate((c) => { try { return heavytop.stability(c); } catch (e) { return { error: e.message }; } }, cfg);
    const native = cli(toml, ["stability", "--format", "json"]);
    const kind = [cfg.body.part && "parts", cfg.body.length < 0 && "hanging", cfg.damping && "damped", cfg.body.A !== cfg.body.B && "asymmetric",
                  cfg.motion.spin_rpm !== undefined && "rpm"].filter(Boolean);
    kind.forEach((k) => worstKinds[k]++);
    if (native.status !== 0) {
      check(`body ${i} (${kind.join(", ") || "symmetric"}): the command line's error equals the page's`, got.error === native.stderr,
            `${got.error} | ${native.stderr}`);
      continue;
    }
    const diff = got.error ? [got.error] : compare(got, JSON.parse(native.stdout), "", 1e-12, 0, []);
    check(`body ${i} (${kind.join(", ") || "symmetric"}): stability equals the command line's`, diff.length === 0, diff.slice(0, 4).join("; "));
    if (i % 2 === 0 || cfg.damping) {
      for (const model of i % 4 === 0 ? ["nonlinear", "linearized"] : ["nonlinear"]) {
        const opts = { model, t_end: 3, samples: 301 };
        const run = await page.evaluate((c, o) => { try { return heavytop.simulate(c, o); } catch (e) { return { error: e.message }; } }, cfg, opts);
        const csv = cli(toml, ["simulate", "--model", model, "--t-end", "3", "--samples", "301", "--format", "csv"]);
        const d = run.error || csv.status !== 0 ? [run.error || csv.stderr] : compareTrajectory(run, parseCsv(csv.stdout), 1e-9);
        check(`body ${i}: simulate ${model} equals the CSV`, d.length === 0, d.slice(0, 3).join("; "));
      }
    }
  }
  check("the bodies include hanging, damped, asymmetric ones, spins in rpm and parts",
        Object.values(worstKinds).every((n) => n > 0), JSON.stringify(worstKinds));

  // ---- bad input: the command line's one-line message ----
  const toy = { body: { A: 4.35e-5, B: 4.35e-5, C: 1.2e-5, mass: 0.06, length: 0.025 }, motion: { spin: 200, theta0: 0.05 } };
  const bad = [
    [{ ...toy, body: { ...toy.body, mass: -1 } }, null],
    [{ ...toy, body: { ...toy.body, A: undefined } }, null],
    [{ ...toy, body: { ...toy.body, colour: 3 } }, null],
    [{ ...toy, motion: { spin: "fast" } }, null],
    [{ ...toy, motion: { spin: 1, spin_rpm: 2 } }, null],
    [{ ...toy, damping: { axial: -1 } }, null],
    [{ ...toy, shape: { x: 1 } }, null],
    [{ ...toy, body: { ...toy.body, B: 1 } }, null],
    [{ ...toy, body: { part: [{ shape: "mesh", file: "top.stl", density: 700 }] } }, null],
    [{ ...toy, body: { part: [{ shape: "cone", radius: 0.02, height: 0.02 }] } }, null],
    [toy, { model: "nonlinear", t_end: -1, samples: 11 }],
    [toy, { model: "nope", t_end: 1, samples: 11 }],
    [toy, { model: "nonlinear", t_end: 1, samples: 1 }],
    [toy, { model: "lagrange-exact", t_end: 1, samples: 1.5 }],
  ];
  for (const [cfg, sim] of bad) {
    const toml = await page.evaluate((c) => heavytopExplorer.toml(c), cfg);
    const args = sim ? ["simulate", "--model", sim.model, "--t-end", String(sim.t_end), "--samples", String(sim.samples), "--format", "csv"]
                     : ["stability", "--format", "json"];
    const native = cli(toml, args);
    const thrown = await page.evaluate((c, s) => {
      try { s ? heavytop.simulate(c, s) : heavytop.stability(c); return null; }
      catch (e) { return { message: e.message, isError: e instanceof Error }; }
    }, cfg, sim);
    check(`bad input throws the command line's message (${native.stderr})`,
          native.status === 2 && thrown && thrown.isError && thrown.message === native.stderr,
          thrown ? thrown.message : "nothing thrown");
  }

  // ---- a person typing a spin ----
  const before = await page.$eval("#answer", (e) => e.textContent);
  await page.click("#spin", { clickCount: 3 });
  await page.keyboard.press("Backspace");
  await page.type("#spin", "50");
  await new Promise((r) => setTimeout(r, 500));
  const after = await page.$eval("#answer", (e) => e.textContent);
  check("typing a spin changes the verdict shown", before !== after && /unstable|falls/.test(after + (await page.$eval("#models", (e) => e.textContent))),
        `${before} -> ${after}`);
  const mapInfo = await page.$eval("#map-info", (e) => e.textContent);
  check("the stability map is drawn", /in \d+ ms/.test(mapInfo), mapInfo);
  // A click on the map shows that point's motion (the inputs move to it).
  const spinBefore = await page.$eval("#spin", (e) => e.value);
  const mapCanvas = await page.$("#map");
  await mapCanvas.scrollIntoView();
  const box = await mapCanvas.boundingBox();
  await page.mouse.click(box.x + box.width * 0.8, box.y + box.height * 0.5);
  await new Promise((r) => setTimeout(r, 300));
  const spinAfter = await page.$eval("#spin", (e) => e.value);
  check("clicking the map shows that point's motion", spinAfter !== spinBefore &&
        /computed in/.test(await page.$eval("#motion-info", (e) => e.textContent)), `spin ${spinBefore} -> ${spinAfter}`);
  await page.screenshot({ path: path.join(work, "explore.png"), fullPage: true });

  // ---- the 3D view: WebGL draws and moves ----
  // The view's canvas (preserveDrawingBuffer) read back: pixels unlike the clear colour, and two
  // frames 400 ms apart that differ while the time advances.
  const frame = () => page.evaluate(() => {
    const c = document.getElementById("scene-canvas");
    if (!c) return null;
    const g = document.createElement("canvas");
    g.width = c.width; g.height = c.height;
    const x = g.getContext("2d");
    x.drawImage(c, 0, 0);
    const d = x.getImageData(0, 0, g.width, g.height).data;
    let drawn = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - 0xf4) + Math.abs(d[i + 1] - 0xf6) + Math.abs(d[i + 2] - 0xf8) > 24 && !(d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250)) drawn++;
      hash = (Math.imul(hash, 31) + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) | 0;
    }
    return { drawn, pixels: d.length / 4, hash, time: window.heavytopView.time, frames: window.heavytopView.frames,
             webgl: !!(c.getContext("webgl2") || c.getContext("webgl")) };
  });
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  const f1 = await frame();
  await sleep(400);
  const f2 = await frame();
  check("the 3D view draws (WebGL)", f1 && f1.webgl && f1.drawn > 0.02 * f1.pixels, f1 && `${f1.drawn} of ${f1.pixels} pixels drawn`);
  check("the 3D view moves (two frames differ, time advances)", f1 && f2 && f1.hash !== f2.hash && f2.time > f1.time && f2.frames > f1.frames,
        f1 && f2 && `t ${f1.time.toFixed(4)} -> ${f2.time.toFixed(4)}, frames ${f1.frames} -> ${f2.frames}`);
  // A click on the map: the view shows the new point's run (rebuilt, with the point's spin).
  const viewBefore = await page.evaluate(() => { window.heavytopView.marked = true; return Number(document.getElementById("spin").value); });
  await page.mouse.click(box.x + box.width * 0.3, box.y + box.height * 0.5);
  await sleep(400);
  const viewAfter = await page.evaluate(() => ({ marked: !!window.heavytopView.marked, spin: Number(document.getElementById("spin").value) }));
  check("clicking the map shows that point's motion in the 3D view", !viewAfter.marked && viewAfter.spin !== viewBefore,
        `spin ${viewBefore} -> ${viewAfter.spin}`);

  // ---- dropping the mesh example: the body `heavytop body` gives ----
  const stl = path.join(examples, "meshes", "spinning-top.stl");
  const bytes = fs.readFileSync(stl);
  await page.evaluate((b64) => {
    const data = Uint8Array.from(atob(b64), (ch) => ch.charCodeAt(0));
    const dt = new DataTransfer();
    dt.items.add(new File([data], "spinning-top.stl"));
    const drop = document.getElementById("drop");
    drop.dispatchEvent(new DragEvent("dragover", { dataTransfer: dt, bubbles: true, cancelable: true }));
    drop.dispatchEvent(new DragEvent("drop", { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, bytes.toString("base64"));
  await page.waitForFunction(() => document.querySelectorAll("#part-list .part").length === 1, { timeout: 5000 })
    .catch(async (e) => { console.log("state", await page.evaluate(() => ({ config: JSON.stringify(heavytopExplorer.config()), mode: document.getElementById("body-mode").value, parts: document.querySelectorAll("#part-list .part").length, error: document.getElementById("error").textContent }))); console.log("errors", errors); throw e; });
  // The example's part: millimetres (the drop's default) and maple, 700 kg/m^3, typed in.
  await page.click("#part-list .part-amount", { clickCount: 3 });
  await page.keyboard.press("Backspace");
  await page.type("#part-list .part-amount", "700");
  await sleep(600);
  const dropped = await page.evaluate(() => {
    const c = heavytopExplorer.config();
    return { config: c, body: heavytopExplorer.body(c), shapes: window.heavytopView.shapes.map((s) => ({ shape: s.shape, triangles: s.triangles })),
             made: document.getElementById("body-made").textContent };
  });
  const exampleBody = spawnSync(heavytop, ["body", "--config", path.join(examples, "mesh-top.toml"), "--format", "json"], { encoding: "utf8" });
  const bodyDiff = exampleBody.status === 0 ? compare(dropped.body, JSON.parse(exampleBody.stdout), "", 1e-12, 0, []) : [exampleBody.stderr];
  check("dropping the mesh example gives the body `heavytop body` gives (1e-12)", bodyDiff.length === 0,
        bodyDiff.slice(0, 4).join("; ") || `${dropped.made}`);
  const stlTriangles = bytes.readUInt32LE(80);
  check("the 3D view draws the dropped mesh's own triangles", dropped.shapes.length === 1 && dropped.shapes[0].shape === "mesh" &&
        dropped.shapes[0].triangles === stlTriangles, `${JSON.stringify(dropped.shapes)}, ${stlTriangles} in the file`);
  // ---- the parts list: add a part (a steel disc), the command line's body of the same parts ----
  await page.click("#add-part");
  await sleep(600);
  const added = await page.evaluate(() => {
    const c = heavytopExplorer.config();
    return { config: c, toml: heavytopExplorer.toml(c), body: heavytopExplorer.body(c), answer: document.getElementById("answer").textContent,
             shapes: window.heavytopView.shapes.map((s) => s.shape) };
  });
  fs.mkdirSync(path.join(work, "meshes"), { recursive: true });
  fs.copyFileSync(stl, path.join(work, added.config.body.part[0].file));
  const addedNative = cli(added.toml, ["body", "--format", "json"]);
  const addedDiff = addedNative.status === 0 ? compare(added.body, JSON.parse(addedNative.stdout), "", 1e-12, 0, []) : [addedNative.stderr];
  check("a part added in the list: the command line's body of the same parts", added.config.body.part.length === 2 && addedDiff.length === 0 &&
        added.shapes.join() === "mesh,cylinder" && Math.abs(added.body.mass - dropped.body.mass) > 1e-6,
        addedDiff.slice(0, 3).join("; ") || `${added.shapes.join()}, mass ${dropped.body.mass} -> ${added.body.mass} kg`);
  await (await page.$("#scene")).screenshot({ path: path.join(work, "explore-view.png") });
  await page.screenshot({ path: path.join(work, "explore-parts.png"), fullPage: true });
  const removeButtons = await page.$$("#part-list .part-remove");
  await removeButtons[1].click();
  await sleep(600);
  const removed = await page.evaluate(() => heavytopExplorer.body(heavytopExplorer.config()));
  check("removing it gives the mesh's body again", compare(removed, dropped.body, "", 1e-15, 0, []).length === 0, `mass ${removed.mass} kg`);

  // ---- benchmarks ----
  const bench = await page.evaluate(() => heavytopExplorer.benchmark());
  bench.page_bytes = fs.statSync(pageFile).size;
  console.log("benchmark " + JSON.stringify(bench));
  fs.writeFileSync(path.join(work, "benchmark.json"), JSON.stringify(bench, null, 1));

  check("no request leaves the page's folder", foreign.length === 0, foreign.join(" "));
  check("no console error", errors.length === 0, errors.join(" | "));
  await checkHostile(browser, page);
  await checkLongRuns(browser, page);
  await checkDegrees(browser);
  await checkEveryOption(browser, page);
  await checkTable(browser);
  if (reportDir) await checkReport(browser);
  await browser.close();
  process.exit(failures ? 1 : 0);
})().catch((err) => { console.log("FAIL", err.stack || err); process.exit(1); });
