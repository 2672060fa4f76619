// The report page in a real browser (Debian's chromium, headless, driven by puppeteer-core):
// node browser_report.cjs CHROMIUM OUT_DIR NAME=REPORT_DIR...
// Loads each REPORT_DIR/report.html from file:// and checks what a student would: every request is
// a local file (any other request fails the test), no console errors, the WebGL view draws and
// animates, pause stops it, scrubbing moves it, the overlays show, every figure and plot loads,
// the explorer answers a click; the body is drawn as it is made (each part's geometry in the scene,
// at its place and size, a mesh with its file's own triangles; the ellipsoid only for a body given
// by its moments), the floor is below its lowest point, the camera sees all of it over the whole
// motion, and "exaggerate tilt x10" draws the tilt ten times as large (and back). Screenshots go to
// OUT_DIR/NAME-*.png (NAME-view, NAME-exaggerated, NAME-overlays, ...). Exit 0 when all pass.
const puppeteer = require("puppeteer-core");
const fs = require("fs");
const path = require("path");

const [chromium, outDir, ...reports] = process.argv.slice(2);
let failures = 0, current = "";
function check(what, ok, detail = "") {
  console.log(`${ok ? "ok  " : "FAIL"} ${current}: ${what}${detail ? ": " + detail : ""}`);
  if (!ok) failures++;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

(async () => {
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    // As root chromium needs --no-sandbox; WebGL without a GPU: SwiftShader through ANGLE.
    args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-gpu-sandbox",
           "--no-first-run", "--no-default-browser-check", "--disable-extensions", "--disable-background-networking"],
    defaultViewport: { width: 1280, height: 900 },
  });
  for (const report of reports) {
    const [name, reportDir] = report.split("=");
    current = name;
    await checkPage(browser, name, reportDir);
  }
  await browser.close();
  process.exit(failures ? 1 : 0);
})().catch((err) => { console.log("FAIL", err.stack || err); process.exit(1); });

async function checkPage(browser, name, reportDir) {
  const page = await browser.newPage();
  const foreign = [], errors = [], failed = [];
  await page.setRequestInterception(true);
  page.on("request", (req) => {
    if (req.url().startsWith("file://")) req.continue();
    else { foreign.push(req.url()); req.abort(); }
  });
  page.on("console", (msg) => { if (msg.type() === "error") errors.push(msg.text()); });
  page.on("pageerror", (err) => errors.push(String(err)));
  page.on("requestfailed", (req) => { if (req.url().startsWith("file://")) failed.push(req.url()); });

  const url = "file://" + path.resolve(reportDir, "report.html");
  await page.goto(url, { waitUntil: "load" });
  await page.waitForSelector("#scene-canvas", { timeout: 20000 });
  await sleep(800);
  if (!(await page.evaluate(() => !!window.heavytopView))) {
    check("the 3D view starts", false, errors.join(" | "));
    return page.close();
  }

  // Pixels of the 3D canvas (its drawing buffer is preserved) as a data URL; and a summary.
  const grab = () => page.$eval("#scene-canvas", (c) => c.toDataURL("image/png"));
  const stats = () => page.$eval("#scene-canvas", (c) => {
    const g = document.createElement("canvas");
    g.width = c.width; g.height = c.height;
    const ctx = g.getContext("2d");
    ctx.drawImage(c, 0, 0);
    const d = ctx.getImageData(0, 0, g.width, g.height).data;
    const colours = new Set();
    let dark = 0;
    for (let i = 0; i < d.length; i += 16) {
      colours.add((d[i] >> 3) << 10 | (d[i + 1] >> 3) << 5 | (d[i + 2] >> 3));
      if (d[i] + d[i + 1] + d[i + 2] < 200) dark++;
    }
    return { colours: colours.size, dark, width: c.width, height: c.height };
  });
  const view = () => page.evaluate(() => ({ ...window.heavytopView, T: window.HEAVYTOP_REPORT.t.at(-1) }));

  const webgl = await page.$eval("#scene-canvas", (c) => !!(c.getContext("webgl2") || c.getContext("webgl")));
  check("WebGL context", webgl);
  const s0 = await stats();
  check("the 3D view draws (many colours, dark strokes)", s0.colours > 30 && s0.dark > 20, JSON.stringify(s0));

  const a = await grab(), va = await view();
  await sleep(700);
  const b = await grab(), vb = await view();
  check("it animates (two frames differ, time advances)", a !== b && vb.time > va.time && vb.frames > va.frames,
        `t ${va.time.toFixed(4)} -> ${vb.time.toFixed(4)}, frames ${va.frames} -> ${vb.frames}`);
  await (await page.$("#scene")).screenshot({ path: path.join(outDir, `${name}-view.png`) });

  await page.click("#play");  // pause
  await sleep(200);
  const c = await grab(), vc = await view();
  await sleep(700);
  const d = await grab(), vd = await view();
  check("pause stops it (frames equal, time still)", c === d && vc.time === vd.time && !vd.playing,
        `t ${vc.time} -> ${vd.time}`);

  const scrubTo = async (fraction) => {
    await page.$eval("#scrub", (el, f) => { el.value = String(Math.round(f * +el.max)); el.dispatchEvent(new Event("input")); }, fraction);
    await sleep(200);
  };
  await scrubTo(0.5);
  const e = await grab(), ve = await view();
  check("scrubbing moves it (frame differs, time at half the horizon)", e !== d && Math.abs(ve.time - ve.T / 2) < 1e-3 * ve.T,
        `t = ${ve.time} of ${ve.T}`);
  const readout = await page.$eval("#time", (el) => el.textContent);
  check("the time readout follows", readout.includes((ve.T / 2).toFixed(3)), readout);

  // The body as drawn: its parts as their own shapes at their places (a mesh from its own
  // triangles), the ellipsoid only for a body given by its moments.
  const drawn = await page.evaluate(() => {
    const v = window.heavytopView, D = window.HEAVYTOP_REPORT;
    const inScene = v.shapes.map((s) => { const o = v.scene.getObjectByProperty("uuid", s.uuid); return !!o && o.visible && o.isMesh; });
    // The file's own triangle count, from the bytes the page carries: a binary STL's bytes
    // 80..83, an OBJ's faces (fans of n - 2), an ASCII PLY's "element face" (of triangles).
    const stl = D.parts.map((p) => {
      if (!p.data) return null;
      const b = Uint8Array.from(atob(p.data), (c) => c.charCodeAt(0)), text = () => new TextDecoder().decode(b);
      if (p.format === "stl")
        return new TextDecoder().decode(b.subarray(0, 5)) === "solid" ? text().split("endfacet").length - 1 : new DataView(b.buffer).getUint32(80, true);
      if (p.format === "obj")
        return text().split("\n").filter((l) => /^f\s/.test(l)).reduce((n, l) => n + l.trim().split(/\s+/).length - 3, 0);
      if (p.format === "ply") { const m = /element face (\d+)/.exec(text().slice(0, 2000)); return m ? +m[1] : null; }
      return null;
    });
    return { shapes: v.shapes.map((s) => ({ ...s, data: undefined })), parts: D.parts.map((p) => ({ ...p, data: undefined })), inScene, stl };
  });
  const near = (x, y, tol) => Math.abs(x - y) <= tol;
  if (drawn.parts.length) {
    check("a shape drawn per part, no ellipsoid", drawn.shapes.length === drawn.parts.length &&
          drawn.shapes.every((s, k) => s.shape === drawn.parts[k].shape), drawn.shapes.map((s) => s.shape).join(" "));
    check("every part's geometry is in the scene", drawn.inScene.every(Boolean) && drawn.shapes.every((s) => s.triangles > 0),
          drawn.shapes.map((s) => `${s.label}: ${s.triangles} triangles`).join(", "));
    for (const [k, p] of drawn.parts.entries()) {
      const s = drawn.shapes[k], tol = 1e-6 + 1e-3 * (p.radius || 0);
      if (p.shape === "mesh") {
        if (drawn.stl[k] !== null)
          check(`part ${k} (${p.label}): the mesh's own triangles`, s.triangles === drawn.stl[k], `${s.triangles} drawn, ${drawn.stl[k]} in the file`);
        continue;
      }
      const top = p.z0 + (p.shape === "sphere" ? 2 * p.radius : p.height);
      // A polygon of 96 sides inscribed in the circle: its widest point is the radius.
      check(`part ${k} (${p.shape}${p.apex ? ", apex " + p.apex : ""}) at its place and size`,
            near(s.min[2], p.z0, tol) && near(s.max[2], top, tol) && near(s.max[0], p.radius, tol) && near(s.min[0], -p.radius, tol),
            `z ${s.min[2].toFixed(5)}..${s.max[2].toFixed(5)} (want ${p.z0}..${top}), x to ${s.max[0].toFixed(5)} (want ${p.radius})`);
    }
  } else {
    check("a body given by its moments is drawn as its ellipsoid", drawn.shapes.length === 1 && drawn.shapes[0].shape === "ellipsoid" && drawn.inScene[0]);
  }
  // The floor below the body's lowest point over the whole motion (at O for a top above its
  // tip), and the camera keeps all of the body in view.
  const room = async (what) => {
    const m = await page.evaluate(() => window.heavytopView.measure(80));
    const D = await page.evaluate(() => ({ length: window.HEAVYTOP_REPORT.body.length }));
    const size = Math.max(...drawn.shapes.map((s) => (s.max ? Math.max(...s.max.map(Math.abs), ...s.min.map(Math.abs)) : Math.max(...s.semi_axes, Math.abs(s.centre)))));
    check(`${what}: the floor is below the body's lowest point`, m.floor <= m.lowest + 1e-6 * size,  // float32 vertices
          `floor ${m.floor.toPrecision(4)} m, lowest point ${m.lowest.toPrecision(4)} m over ${m.times + 1} times`);
    if (D.length > 0 && m.lowest >= 0) check(`${what}: a top above its tip stands on the floor at O`, m.floor === 0, `floor ${m.floor}`);
    check(`${what}: the body stays in the camera's view`, m.outside === 0, `${m.outside} corners of its box outside`);
  };
  await room("true tilt");
  // The exaggerated tilt: the picture changes, the drawn tilt is 10 times the true one (at most
  // pi); for a body never near the vertical the switch is off and says why.
  const label = await page.$eval("label.exaggerate", (el) => el.textContent.replace(/\s+/g, " ").trim());
  check("the tilt toggle is labelled as not to scale", /exaggerate tilt x10/.test(label) && /not to scale/.test(label), label);
  if (await page.$eval("#exaggerate", (el) => el.disabled)) {
    const least = await page.evaluate(() => {
      const D = window.HEAVYTOP_REPORT;
      return Math.min(...D.nonlinear.theta.map((th, i) => Math.acos(Math.cos(th) * Math.cos(D.nonlinear.phi[i]))));
    });
    check("the toggle is off only for a body never near the vertical, and says so", 10 * least >= 0.9 * Math.PI && /never nearer the vertical/.test(label),
          `least tilt ${least.toFixed(3)} rad`);
  } else {
    await scrubTo(0.37);
    const plain = await grab(), vt = await view();
    await page.click("#exaggerate");
    await sleep(300);
    const magnified = await grab(), vx = await view();
    check("exaggerating the tilt changes the picture", plain !== magnified && vx.exaggerated);
    check("the drawn tilt is 10 times the true one (at most pi)", near(vx.drawnTilt, Math.min(10 * vx.tilt, Math.PI), 1e-6) && near(vt.tilt, vx.tilt, 1e-12),
          `true ${vx.tilt.toPrecision(4)} rad, drawn ${vx.drawnTilt.toPrecision(4)} rad`);
    await (await page.$("#scene")).screenshot({ path: path.join(outDir, `${name}-exaggerated.png`) });
    await room("tilt x10");
    await page.click("#exaggerate");
    await sleep(200);
    check("the toggle off draws the true tilt again", (await grab()) === plain && !(await view()).exaggerated);
  }

  // The overlays: every approximate model's axis switched on changes the picture.
  const boxes = await page.$$eval("input[id^=overlay-]", (els) => els.map((el) => el.id));
  check("an overlay switch per model", boxes.length >= 3, boxes.join(" "));
  await scrubTo(0.9);
  const before = await grab();
  for (const id of boxes) await page.click("#" + id);
  await sleep(200);
  const after = await grab();
  check("the overlays draw", before !== after);
  await (await page.$("#scene")).screenshot({ path: path.join(outDir, `${name}-overlays.png`) });

  // Played too fast for the screen, the spin is aliased: the page says so.
  const note = await page.evaluate(() => {
    const el = document.getElementById("speed");
    const before = document.getElementById("spin-note").hidden;
    el.value = el.max;
    el.dispatchEvent(new Event("input"));
    const n = document.getElementById("spin-note");
    const after = { hidden: n.hidden, text: n.textContent };
    el.value = String(window.HEAVYTOP_REPORT.playback.speeds.indexOf(window.HEAVYTOP_REPORT.playback.speed));
    el.dispatchEvent(new Event("input"));
    return { before, ...after };
  });
  check("at the default speed the spin is shown faithfully", note.before === true);
  check("at the fastest speed the page says the spin is stroboscopic", !note.hidden && /stroboscopic/.test(note.text), note.text.slice(0, 120));

  // Every figure loads (a broken image has naturalWidth 0).
  const images = await page.$$eval("img", (els) => els.map((el) => ({ src: el.getAttribute("src"), ok: el.complete && el.naturalWidth > 0 })));
  check("every figure loads", images.length >= 6 && images.every((i) => i.ok), images.filter((i) => !i.ok).map((i) => i.src).join(" ") || `${images.length} figures`);

  // Every interactive plot is drawn (uPlot: a canvas with ink and a legend row per series).
  for (const id of ["plot-theta", "plot-phi", "plot-errors"]) {
    const p = await page.$eval(`#${id}`, (el) => {
      const cv = el.querySelector("canvas");
      if (!cv) return { ink: 0, series: 0 };
      const d = cv.getContext("2d").getImageData(0, 0, cv.width, cv.height).data;
      let ink = 0;
      for (let i = 3; i < d.length; i += 4) if (d[i] > 0) ink++;
      return { ink, series: el.querySelectorAll(".u-legend .u-series").length };
    }).catch(() => ({ ink: 0, series: 0 }));
    check(`plot ${id} drawn`, p.ink > 2000 && p.series >= 4, JSON.stringify(p));
  }

  // A click on a plot shows that moment in the 3D view.
  const over = await page.$("#plot-theta .u-over");
  await over.scrollIntoView();
  const plotBox = await over.boundingBox();
  await page.mouse.move(plotBox.x + 0.2 * plotBox.width, plotBox.y + 0.5 * plotBox.height);
  await page.mouse.click(plotBox.x + 0.25 * plotBox.width, plotBox.y + 0.5 * plotBox.height);
  await sleep(200);
  const vp = await view();
  check("a click on a plot seeks the view there", Math.abs(vp.time - 0.25 * vp.T) < 0.02 * vp.T, `t = ${vp.time} of ${vp.T}`);

  // The explorer answers a click on the body's own point with its verdicts and says it is this body.
  const info = await page.evaluate(() => {
    const cv = document.getElementById("explorer"), D = window.HEAVYTOP_REPORT, M = D.map;
    const r = cv.getBoundingClientRect();
    const pad = { l: 70, r: 20, t: 20, b: 50 }, pw = cv.width - pad.l - pad.r, ph = cv.height - pad.t - pad.b;
    const x = pad.l + ((D.body_point[0] - M.x.start) / (M.x.stop - M.x.start)) * pw;
    const y = pad.t + ph - ((D.body_point[1] - M.y.start) / (M.y.stop - M.y.start)) * ph;
    cv.dispatchEvent(new MouseEvent("click", { clientX: r.left + (x * r.width) / cv.width, clientY: r.top + (y * r.height) / cv.height, bubbles: true }));
    return document.getElementById("explorer-info").textContent;
  });
  check("the explorer answers a click", /first-order \(4\): (stable|unstable)/.test(info) && /Lyapunov/.test(info) && /body of this report/.test(info), info.slice(0, 160));

  // What a student sees, part by part (a full-page shot of a page this long tiles badly).
  for (const [id, file] of [["#plots", "plots"], ["#explorer", "explorer"], ["#explorer-info", "explorer-info"]])
    await (await page.$(id)).screenshot({ path: path.join(outDir, `${name}-${file}.png`) });
  await page.evaluate(() => window.scrollTo(0, 0));
  await page.screenshot({ path: path.join(outDir, `${name}-top.png`) });
  check("every request local (file://)", foreign.length === 0, foreign.join(" "));
  check("no missing local file", failed.length === 0, failed.join(" "));
  check("no console errors", errors.length === 0, errors.join(" | "));
  await page.close();
}
