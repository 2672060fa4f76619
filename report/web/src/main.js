// The report page's interactive parts: the top in 3D (three.js), the interactive plots
// (uPlot) and the clickable stability explorer. Bundled by esbuild into one classic script
// (heavytop-report.js) because pages opened from file:// may not import ES modules; its data
// come from report-data.js (window.HEAVYTOP_REPORT), written by heavytop beside it.
// Every number shown here was computed by heavytop (report/src/report.cpp); this file only
// draws them: the attitude is composed from the report's theta, phi, psi as SPEC section 2
// defines it, R = R_eta(theta) R_xi(phi) Rz(psi).
import {
  AmbientLight, BufferAttribute, BufferGeometry, Color, CylinderGeometry, DirectionalLight, Float32BufferAttribute,
  GridHelper, Group, Line, LineBasicMaterial, LineDashedMaterial, Matrix4, Mesh, MeshBasicMaterial, MeshStandardMaterial,
  OrthographicCamera, PerspectiveCamera, Scene, SphereGeometry, TorusGeometry, ConeGeometry, Vector3, WebGLRenderer,
} from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import uPlot from "uplot";
import uPlotCss from "uplot/dist/uPlot.min.css";

const D = window.HEAVYTOP_REPORT;
const $ = (id) => document.getElementById(id);

// One colour per model, as the static figures draw them (report/src/figures.cpp).
const COLORS = { nonlinear: "#000000", "first-order": "#1f77b4", "body-fixed": "#ff7f0e", linearized: "#2ca02c",
                 "lagrange-exact": "#9467bd" };

// x to `digits` significant digits, without trailing zeros after the point (400, 0.05, 1.5e-9).
function fmt(x, digits = 4) {
  if (x === null || x === undefined || !isFinite(x)) return "–";
  const [mantissa, exponent] = Number(x).toPrecision(digits).split("e");
  const m = mantissa.includes(".") ? mantissa.replace(/0+$/, "").replace(/\.$/, "") : mantissa;
  return exponent === undefined ? m : `${m}e${exponent.replace("+", "")}`;
}

// ---- the attitude: SPEC section 2 ------------------------------------------------------------
// Q(phi, theta) = R_eta(theta) R_xi(phi); three.js's rotations are the same active right-handed
// ones, in the fixed frame (x = xi, y = eta, z = zeta up).
const mY = new Matrix4(), mX = new Matrix4(), mZ = new Matrix4();
function attitude(theta, phi, psi, out) {
  return out.copy(mY.makeRotationY(theta)).multiply(mX.makeRotationX(phi)).multiply(mZ.makeRotationZ(psi));
}
const ez = new Vector3(0, 0, 1), tmpM = new Matrix4();
function axisOf(theta, phi, out) { return out.copy(ez).applyMatrix4(attitude(theta, phi, 0, tmpM)); }

// Linear interpolation in a sampled series at fractional index u.
function lerp(series, u) {
  const i = Math.min(Math.floor(u), series.length - 2), f = u - i;
  return series[i] + f * (series[i + 1] - series[i]);
}

// ---- the 3D view ---------------------------------------------------------------------------------
function buildView() {
  const host = $("scene");
  const t = D.t, n = t.length, T = t[n - 1];
  const shape = D.shape;  // the equivalent ellipsoid: semi-axes (m) and its centre on z
  const a = shape.semi_axes[0], b = shape.semi_axes[1], c = shape.semi_axes[2], zc = shape.centre;
  const size = Math.max(a, b, c, Math.abs(zc));
  // The spindle: from the tip at O (a top) through the body to a point above it, whose path is
  // traced; a hanging body's from below it up through O to a short stub above.
  const zTop = zc >= 0 ? zc + Math.max(1.5 * c, 0.45 * size) : 0.45 * size;
  const zBottom = zc >= 0 ? 0 : zc - Math.max(1.5 * c, 0.2 * size);

  const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0xf4f6f8);
  renderer.autoClear = false;
  host.appendChild(renderer.domElement);
  renderer.domElement.id = "scene-canvas";

  const scene = new Scene();
  scene.add(new AmbientLight(0xffffff, 0.55));
  const sun = new DirectionalLight(0xffffff, 1.6);
  sun.position.set(2 * size, -3 * size, 5 * size);
  scene.add(sun);

  // The fixed frame: the floor through O (a top on its tip) or a ceiling mount (hanging), the vertical.
  const grid = new GridHelper(6 * size, 12, 0xb0b8c0, 0xd5dade);
  grid.rotation.x = Math.PI / 2;
  scene.add(grid);
  const vertical = new Line(new BufferGeometry().setFromPoints([new Vector3(0, 0, -1.3 * size), new Vector3(0, 0, zTop * 1.6)]),
                            new LineDashedMaterial({ color: 0x555555, dashSize: size / 15, gapSize: size / 20 }));
  vertical.computeLineDistances();
  vertical.layers.enable(1);
  scene.add(vertical);
  const pivot = new Mesh(new SphereGeometry(size / 25, 24, 12), new MeshStandardMaterial({ color: 0x222222 }));
  scene.add(pivot);
  // A hanging body hangs from a mount above O; a top stands on the floor (the grid) at O.
  const cone = (h) => { const g = new ConeGeometry(h / 2.2, h, 32); g.rotateX(-Math.PI / 2); g.translate(0, 0, h / 2); return g; };
  if (zc < 0) scene.add(new Mesh(cone(size / 4), new MeshStandardMaterial({ color: 0x8a939b })));

  // The body (body axes: z the spin axis): the ellipsoid with the body's mass and central
  // moments, its equator painted in sectors with one red marker so the spin shows, a spindle.
  const bodyGroup = new Group();
  bodyGroup.matrixAutoUpdate = false;
  scene.add(bodyGroup);
  const ell = new SphereGeometry(1, 96, 48);
  ell.rotateX(Math.PI / 2);  // poles on z
  const pos = ell.attributes.position, colors = [];
  for (let i = 0; i < pos.count; i++) {
    const az = Math.atan2(pos.getY(i), pos.getX(i));
    const sector = Math.floor(((az + Math.PI) / (2 * Math.PI)) * 12) % 12;
    const band = Math.abs(pos.getZ(i)) < 0.35;
    const col = sector === 0 && band ? [0.85, 0.1, 0.1] : sector % 2 ? [0.80, 0.62, 0.38] : [0.62, 0.44, 0.24];
    colors.push(...col);
  }
  ell.setAttribute("color", new Float32BufferAttribute(colors, 3));
  const ellMesh = new Mesh(ell, new MeshStandardMaterial({ vertexColors: true, roughness: 0.7 }));
  ellMesh.scale.set(a, b, c);
  ellMesh.position.z = zc;
  bodyGroup.add(ellMesh);
  const rim = new Mesh(new TorusGeometry(1, 0.035, 12, 128), new MeshStandardMaterial({ color: 0x333333 }));
  rim.scale.set(a, b, a);  // a round tube of 0.035 a
  rim.position.z = zc;
  bodyGroup.add(rim);
  const marker = new Mesh(new SphereGeometry(size / 18, 16, 8), new MeshStandardMaterial({ color: 0xd62728 }));
  marker.position.set(a * 1.02, 0, zc);
  bodyGroup.add(marker);
  const spindle = new Mesh(new CylinderGeometry(size / 40, size / 40, zTop - zBottom, 16),
                           new MeshStandardMaterial({ color: 0x9aa3ab, metalness: 0.5, roughness: 0.35 }));
  spindle.rotation.x = Math.PI / 2;
  spindle.position.z = 0.5 * (zTop + zBottom);
  bodyGroup.add(spindle);
  if (zc > 0) {  // the top's own point, on O
    const h = Math.min(0.35 * zc, size / 3);
    bodyGroup.add(new Mesh(cone(h), new MeshStandardMaterial({ color: 0x6b737a, metalness: 0.5, roughness: 0.4 })));
  }

  // The traced point: the axis at zTop. Its past path, for the truth and each model.
  const tip = (theta, phi, out) => axisOf(theta, phi, out).multiplyScalar(zTop);
  function traceOf(theta, phi, color, until) {
    const pts = new Float32Array(3 * n), v = new Vector3();
    let m = 0;
    // Up to a divergence, or a gap (null: a model that stopped on a numerical failure).
    for (let i = 0; i < n && !(until !== null && t[i] > until) && theta[i] !== null && phi[i] !== null; i++, m++) {
      tip(theta[i], phi[i], v);
      pts.set([v.x, v.y, v.z], 3 * i);
    }
    const g = new BufferGeometry();
    g.setAttribute("position", new BufferAttribute(pts, 3));
    g.setDrawRange(0, 0);
    const line = new Line(g, new LineBasicMaterial({ color }));
    line.layers.enable(1);
    line.userData.count = m;
    scene.add(line);
    return line;
  }
  const truthTrace = traceOf(D.nonlinear.theta, D.nonlinear.phi, 0x000000, null);
  const tipMark = new Mesh(new SphereGeometry(size / 30, 16, 8), new MeshStandardMaterial({ color: 0x000000 }));
  scene.add(tipMark);
  const overlays = D.models.map((m) => {
    const color = new Color(COLORS[m.name] || "#777777");
    const rod = new Line(new BufferGeometry().setFromPoints([new Vector3(), new Vector3(0, 0, zTop)]),
                         new LineBasicMaterial({ color }));
    rod.matrixAutoUpdate = false;
    const end = new Mesh(new SphereGeometry(size / 34, 16, 8), new MeshStandardMaterial({ color }));
    const trace = traceOf(m.theta, m.phi, color, m.diverged_at);
    const g = new Group();
    g.add(rod, end, trace);
    g.visible = false;
    scene.add(g);
    return { model: m, group: g, rod, end, trace, dot: null };
  });

  // Cameras: an oblique view that a mouse can turn, and an inset from straight above on the tip
  // (xi to the right, eta up: the static figure's "seen from above").
  const camera = new PerspectiveCamera(35, 1, size / 100, size * 100);
  camera.up.set(0, 0, 1);
  camera.position.set(2.3 * size, -3.0 * size, 1.6 * size + 0.6 * zTop);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(0, 0, 0.5 * (zTop + zBottom));
  controls.update();
  const top = new OrthographicCamera(-1, 1, 1, -1, size / 100, size * 100);
  top.up.set(0, 1, 0);
  top.layers.set(1);
  let extent = 0;  // the tip's largest distance from the vertical, for the inset's scale
  {
    const v = new Vector3();
    for (let i = 0; i < n; i++) { tip(D.nonlinear.theta[i], D.nonlinear.phi[i], v); extent = Math.max(extent, Math.hypot(v.x, v.y)); }
    extent = Math.max(1.25 * extent, 1e-6 * zTop);
  }
  top.position.set(0, 0, zTop * 3);
  top.lookAt(0, 0, 0);
  // In the inset (layer 1 only): the tip as a dot at the inset's scale, each model's too, and a
  // cross where the vertical is.
  const dot = (color, r) => { const m = new Mesh(new SphereGeometry(r, 16, 8), new MeshBasicMaterial({ color })); m.layers.set(1); return m; };
  const tipDot = dot(0x000000, extent / 28);
  scene.add(tipDot);
  for (const o of overlays) { o.dot = dot(new Color(COLORS[o.model.name] || "#777777"), extent / 34); o.group.add(o.dot); }
  const cross = new Line(new BufferGeometry().setFromPoints([new Vector3(-extent / 12, 0, zTop), new Vector3(extent / 12, 0, zTop),
    new Vector3(0, 0, zTop), new Vector3(0, extent / 12, zTop), new Vector3(0, -extent / 12, zTop)]), new LineBasicMaterial({ color: 0x888888 }));
  cross.layers.set(1);
  scene.add(cross);

  // ---- playback ----
  const state = { time: 0, playing: true, speed: D.playback.speed, frames: 0 };
  const scrub = $("scrub"), speedInput = $("speed"), playButton = $("play"), readout = $("time");
  const speeds = D.playback.speeds;
  speedInput.max = speeds.length - 1;
  speedInput.value = speeds.indexOf(state.speed);
  const spinNote = $("spin-note");
  function describeSpeed() {
    $("speed-value").textContent = `${fmt(state.speed, 3)}× real time`;
    // The spin between two frames at 60 frames a second: beyond 30 degrees the eye cannot follow
    // it and the marker's apparent turning is aliased (a stroboscope), though its angle is true.
    const perFrame = (D.playback.spin_rate * state.speed) / 60;
    const faithful = (Math.PI / 6) * 60 / D.playback.spin_rate;
    if (perFrame > Math.PI / 6) {
      spinNote.hidden = false;
      spinNote.textContent = `At this speed the body turns ${fmt((perFrame * 180) / Math.PI, 3)}° between frames (spin ` +
        `${fmt(D.playback.spin_rate, 4)} rad/s): the red marker is drawn at its true angle in every frame, but ` +
        `its apparent turning is stroboscopic (aliased), not the real spin. Below ${fmt(faithful, 2)}× it turns faithfully.`;
    } else spinNote.hidden = true;
  }
  describeSpeed();
  speedInput.addEventListener("input", () => { state.speed = speeds[+speedInput.value]; describeSpeed(); });
  playButton.addEventListener("click", () => {
    state.playing = !state.playing;
    if (state.playing && state.time >= T) state.time = 0;
    playButton.textContent = state.playing ? "Pause" : "Play";
  });
  scrub.addEventListener("input", () => { state.time = (T * scrub.value) / scrub.max; draw(); });
  for (const o of overlays) {
    const box = $(`overlay-${o.model.name}`);
    if (box) box.addEventListener("change", () => { o.group.visible = box.checked; draw(); });
  }
  window.heavytopView = state;  // for a reader's console (and the browser test's logs)
  // The plots jump the view to a time clicked on them.
  state.seek = (time) => { state.time = Math.max(0, Math.min(T, time)); draw(); };

  const R = new Matrix4(), v = new Vector3();
  function place(time) {
    const u = Math.min((time / T) * (n - 1), n - 1 - 1e-9);
    const i = Math.floor(u);
    const th = lerp(D.nonlinear.theta, u), ph = lerp(D.nonlinear.phi, u), ps = lerp(D.nonlinear.psi, u);
    bodyGroup.matrix.copy(attitude(th, ph, ps, R));
    bodyGroup.matrixWorldNeedsUpdate = true;
    tip(th, ph, v);
    tipMark.position.copy(v);
    tipDot.position.copy(v);
    truthTrace.geometry.setDrawRange(0, i + 1);
    for (const o of overlays) {
      const m = o.model, mt = lerp(m.theta, u), mp = lerp(m.phi, u);
      const gone = (m.diverged_at !== null && time > m.diverged_at) || !isFinite(mt) || !isFinite(mp);
      o.rod.visible = o.end.visible = o.dot.visible = !gone;
      o.trace.geometry.setDrawRange(0, Math.min(i + 1, o.trace.userData.count));
      if (gone) continue;
      o.rod.matrix.copy(attitude(mt, mp, 0, R));
      o.rod.matrixWorldNeedsUpdate = true;
      tip(mt, mp, o.end.position);
      o.dot.position.copy(o.end.position);
    }
    readout.textContent = `t = ${time.toFixed(3)} s of ${fmt(T, 4)} s`;
    scrub.value = Math.round((time / T) * scrub.max);
  }

  function resize() {
    const w = host.clientWidth, h = Math.round(w * 0.56);
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", () => { resize(); draw(); });
  resize();

  function draw() {
    place(state.time);
    const w = renderer.domElement.clientWidth, h = renderer.domElement.clientHeight;
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, w, h);
    renderer.clear();
    renderer.render(scene, camera);
    // The inset, bottom right: straight down on the tip, its loops and cusps at true scale.
    const s = Math.round(h * 0.42), x0 = w - s - 8, y0 = 8;
    renderer.setScissorTest(true);
    renderer.setScissor(x0, y0, s, s);
    renderer.setViewport(x0, y0, s, s);
    renderer.setClearColor(0xffffff);
    renderer.clear();
    top.left = -extent; top.right = extent; top.top = extent; top.bottom = -extent;
    top.updateProjectionMatrix();
    renderer.render(scene, top);
    renderer.setClearColor(0xf4f6f8);
    renderer.setScissorTest(false);
  }
  $("inset-scale").textContent = `${fmt((extent / zTop) * 1e3, 3)} mrad`;

  let last = null;
  function frame(now) {
    if (last !== null && state.playing) {
      state.time += (state.speed * Math.min(now - last, 100)) / 1000;
      if (state.time >= T) { state.time = T; state.playing = false; playButton.textContent = "Play"; }
    }
    last = now;
    draw();
    state.frames++;
    requestAnimationFrame(frame);
  }
  controls.addEventListener("change", draw);
  requestAnimationFrame(frame);
}

// ---- interactive plots -----------------------------------------------------------------------------
function buildPlots() {
  const style = document.createElement("style");
  style.textContent = uPlotCss;
  document.head.appendChild(style);
  const t = D.t, scale = D.angle_scale, unit = D.angle_unit;
  const width = () => Math.min($("plots").clientWidth, 1100);
  const sync = uPlot.sync("heavytop");
  const charts = [];
  const series = (key) => {
    const s = [{ label: "t (s)" }], data = [t];
    // The truth last, so it is drawn on top of the others.
    for (const m of D.models) {
      s.push({ label: m.name, stroke: COLORS[m.name], width: 3.5, dash: m.name === "body-fixed" ? [6, 4] : undefined });
      data.push(m[key].map((x, i) => (x === null || (m.diverged_at !== null && t[i] > m.diverged_at) ? null : x * scale)));
    }
    s.push({ label: "nonlinear (truth)", stroke: COLORS.nonlinear, width: 1.2 });  // thin, on top: models show beneath
    // theta = atan2(k_xi, k_zeta) jumps by 2 pi when the axis passes below the horizontal: a gap there, not a wall.
    const truth = D.nonlinear[key];
    data.push(truth.map((x, i) => (i > 0 && Math.abs(x - truth[i - 1]) > Math.PI ? null : x * scale)));
    return { s, data };
  };
  const cursor = { sync: { key: sync.key }, drag: { x: true, y: true } };
  for (const [key, label] of [["theta", "theta"], ["phi", "phi"]]) {
    const { s, data } = series(key);
    const el = document.createElement("div");
    el.className = "plot";
    el.id = `plot-${key}`;
    $("plots").appendChild(el);
    charts.push(new uPlot({ title: `${label}(t): every model from the same start (${unit})`, width: width(), height: 300,
                            cursor, series: s, scales: { x: { time: false } },
                            axes: [{ label: "t (s)" }, { label: `${label} (${unit})`, size: 70 }] }, data, el));
  }
  // The error of each model against the truth, log scale (null where it is 0 or the model diverged).
  const s = [{ label: "t (s)" }], data = [t];
  for (const m of D.models) {
    s.push({ label: m.name, stroke: COLORS[m.name], width: 1.5 });
    data.push(m.error.map((x, i) => (x > 0 && !(m.diverged_at !== null && t[i] > m.diverged_at) ? x : null)));
  }
  const el = document.createElement("div");
  el.className = "plot";
  el.id = "plot-errors";
  $("plots").appendChild(el);
  charts.push(new uPlot({ title: "Angle error of each model against the nonlinear body (rad, log scale)", width: width(),
                          height: 300, cursor, series: s, scales: { x: { time: false }, y: { distr: 3, log: 10 } },
                          axes: [{ label: "t (s)" },
                                 // Decades only, as 1e-9: uPlot's own labels round tiny values to 0.
                                 { label: "max(|d theta|, |d phi|) (rad)", size: 70,
                                   splits: (u, ax, min, max) => {
                                     const out = [];
                                     for (let e = Math.ceil(Math.log10(min) - 1e-9); e <= Math.floor(Math.log10(max) + 1e-9); e++) out.push(10 ** e);
                                     return out;
                                   },
                                   values: (u, splits) => splits.map((v) => {
                                     const e = Math.round(Math.log10(v));
                                     return Math.abs(v / 10 ** e - 1) < 1e-6 ? `1e${e}` : "";
                                   }) }] }, data, el));
  window.addEventListener("resize", () => charts.forEach((c) => c.setSize({ width: width(), height: 300 })));
  // A click (not a drag, which zooms) shows that moment in the 3D view.
  for (const c of charts)
    c.over.addEventListener("click", () => {
      if (c.select.width > 2 || c.cursor.left === undefined || c.cursor.left < 0 || !window.heavytopView) return;
      window.heavytopView.seek(c.posToVal(c.cursor.left, "x"));
    });
}

// ---- the stability explorer: the map's grid and the diagram's nonlinear runs, clickable ------------
function buildExplorer() {
  const canvas = $("explorer"), info = $("explorer-info"), M = D.map;
  const nx = M.x.count, ny = M.y.count;
  const pad = { l: 70, r: 20, t: 20, b: 50 };
  const W = canvas.width, H = canvas.height, pw = W - pad.l - pad.r, ph = H - pad.t - pad.b;
  const X = (v) => pad.l + ((v - M.x.start) / (M.x.stop - M.x.start)) * pw;
  const Y = (v) => pad.t + ph - ((v - M.y.start) / (M.y.stop - M.y.start)) * ph;
  const ctx = canvas.getContext("2d");
  const palette = ["#d9d9d9", "#d62728", "#1f77b4", "#2ca02c"];  // as the static map
  const code = (i) => parseInt(M.verdicts[i], 16);
  const cw = pw / (nx - 1), chh = ph / (ny - 1);
  for (let i = 0; i < nx; i++)
    for (let j = 0; j < ny; j++) {
      const c = code(i * ny + j);
      ctx.fillStyle = palette[(c & 1) + ((c >> 2) & 1) * 2];
      ctx.fillRect(X(M.x.start + (i * (M.x.stop - M.x.start)) / (nx - 1)) - cw / 2, Y(M.y.start + (j * (M.y.stop - M.y.start)) / (ny - 1)) - chh / 2, cw + 1, chh + 1);
    }
  ctx.save();
  ctx.beginPath();
  ctx.rect(pad.l, pad.t, pw, ph);
  ctx.clip();
  for (const p of D.diagram.points) {
    const x = X(p[0]), y = Y(p[1]);
    ctx.lineWidth = 2;
    ctx.strokeStyle = p[2] ? "#ffffff" : "#000000";
    ctx.beginPath();
    if (p[2]) ctx.arc(x, y, 5, 0, 2 * Math.PI);
    else { ctx.moveTo(x - 5, y - 5); ctx.lineTo(x + 5, y + 5); ctx.moveTo(x + 5, y - 5); ctx.lineTo(x - 5, y + 5); }
    ctx.stroke();
  }
  const bx = X(D.body_point[0]), by = Y(D.body_point[1]);
  ctx.strokeStyle = "#000";
  ctx.lineWidth = 3;
  ctx.beginPath();
  ctx.moveTo(bx - 10, by); ctx.lineTo(bx + 10, by); ctx.moveTo(bx, by - 10); ctx.lineTo(bx, by + 10);
  ctx.stroke();
  ctx.restore();
  ctx.fillStyle = "#222";
  ctx.font = "14px DejaVu Sans, Arial, sans-serif";
  ctx.textAlign = "center";
  for (let k = 0; k <= 5; k++) {
    const v = M.x.start + (k * (M.x.stop - M.x.start)) / 5;
    ctx.fillText(fmt(v, 3), X(v), H - pad.b + 18);
  }
  ctx.fillText(M.x.label, pad.l + pw / 2, H - 10);
  ctx.textAlign = "right";
  for (let k = 0; k <= 5; k++) {
    const v = M.y.start + (k * (M.y.stop - M.y.start)) / 5;
    ctx.fillText(fmt(v, 3), pad.l - 6, Y(v) + 5);
  }
  ctx.save();
  ctx.translate(16, pad.t + ph / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = "center";
  ctx.fillText(M.y.label, 0, 0);
  ctx.restore();

  const word = (s) => `<b class="${s ? "ok" : "bad"}">${s ? "stable" : "unstable"}</b>`;
  canvas.addEventListener("click", (e) => {
    const r = canvas.getBoundingClientRect();
    const px = ((e.clientX - r.left) * W) / r.width, py = ((e.clientY - r.top) * H) / r.height;
    const fx = (px - pad.l) / pw, fy = (pad.t + ph - py) / ph;
    if (fx < -0.01 || fx > 1.01 || fy < -0.01 || fy > 1.01) return;
    const i = Math.max(0, Math.min(nx - 1, Math.round(fx * (nx - 1)))), j = Math.max(0, Math.min(ny - 1, Math.round(fy * (ny - 1))));
    const xv = M.x.start + (i * (M.x.stop - M.x.start)) / (nx - 1), yv = M.y.start + (j * (M.y.stop - M.y.start)) / (ny - 1);
    const c = code(i * ny + j), cert = D.certificates[parseInt(M.certificates[i * ny + j], 10)];
    let html = `<p><b>${M.x.key} = ${fmt(xv, 4)}, spin = ${fmt(yv, 4)} rad/s</b> (the grid point nearest the click)` +
      `<br>first-order (4): ${word(c & 1)}; body-fixed (5): ${word(c & 2)}; linearized (exact): ${word(c & 4)}` +
      `<br>Lyapunov (the real body): ${c & 8 ? '<b class="ok">proven stable</b>' : "<b>not proven stable</b>"} ` +
      `(certificate <code>${cert}</code>)</p>`;
    // The nearest of the nonlinear runs, if the click is on one.
    let best = null, bd = 1e9;
    for (const p of D.diagram.points) {
      const d = Math.hypot(X(p[0]) - px, Y(p[1]) - py);
      if (d < bd) { bd = d; best = p; }
    }
    if (best && bd < 12)
      html += `<p>Nonlinear run at ${M.x.key} = ${fmt(best[0], 4)}, spin = ${fmt(best[1], 4)} rad/s, started ` +
        `${D.diagram.start_tilt} rad off vertical: <b class="${best[2] ? "ok" : "bad"}">${best[2] ? D.diagram.up_word : D.diagram.down_word}</b> ` +
        `(tilt ${best[2] ? "stayed within" : "passed"} ${D.diagram.max_tilt} rad within ${fmt(D.diagram.horizon, 3)} s).</p>`;
    if (Math.abs(X(D.body_point[0]) - px) < 12 && Math.abs(Y(D.body_point[1]) - py) < 12)
      html += `<p>This is the body of this report: its motion is the one in the 3D view and the plots above.</p>`;
    else
      html += `<p>The report computed no motion for this point; to see it: <code>heavytop simulate --model nonlinear ` +
        `${D.cli_body} ${M.x.key === "B/A" ? `--B ${fmt(xv * D.body.A, 6)}` : ""} --spin ${fmt(yv, 6)} ${D.cli_start}</code></p>`;
    info.innerHTML = html;
  });
}

function start() {
  for (const [name, build] of [["3D view", buildView], ["plots", buildPlots], ["stability explorer", buildExplorer]]) {
    try {
      build();
    } catch (err) {
      // Say so on the page; the static figures below stay.
      const p = document.createElement("p");
      p.className = "note";
      p.textContent = `The ${name} could not be drawn in this browser (${err.message}); the static figures below show the same.`;
      $(name === "3D view" ? "interactive" : "interactive-plots").prepend(p);
      console.error(err);
    }
  }
}
if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
else start();
