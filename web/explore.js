// The explorer page's script (SPEC section 15). Thin: window.heavytop turns a configuration
// object into the configuration file's TOML text and runs the command line's own commands in
// the WebAssembly core (web/heavytop_wasm.cpp); the JSON and CSV it returns are io/'s.
"use strict";
(function () {
  const loadStart = performance.now();
  const $ = (id) => document.getElementById(id);

  // ---- Configuration object -> the configuration file (SPEC section 4) -----------------------
  const bareKey = /^[A-Za-z0-9_-]+$/;
  const tomlKey = (k) => (bareKey.test(k) ? k : JSON.stringify(k));
  function tomlValue(v) {
    if (typeof v === "number") {
      if (Number.isNaN(v)) return "nan";
      if (!Number.isFinite(v)) return v > 0 ? "inf" : "-inf";
      const s = String(v);  // the shortest text that reads back to the same double
      return /[.eE]/.test(s) ? s : s + ".0";
    }
    if (typeof v === "boolean") return v ? "true" : "false";
    if (typeof v === "string") return JSON.stringify(v);
    if (Array.isArray(v)) return "[" + v.map(tomlValue).join(", ") + "]";
    return String(v);  // null, an object...: not TOML, refused by the core's parser as the file would be
  }
  function toml(config) {
    if (config === null || typeof config !== "object" || Array.isArray(config))
      throw new Error("heavytop: error: the configuration must be an object of sections, e.g. {body: {A: 1, ...}, motion: {spin: 3}}");
    let out = "";
    for (const [section, table] of Object.entries(config)) {
      if (table === undefined) continue;
      if (table === null || typeof table !== "object" || Array.isArray(table)) {
        out = `${tomlKey(section)} = ${tomlValue(table)}\n` + out;  // a top-level key: the parser names it
        continue;
      }
      out += `[${tomlKey(section)}]\n`;
      const arrays = [];
      for (const [key, value] of Object.entries(table)) {
        if (value === undefined) continue;
        if (Array.isArray(value) && value.length && value.every((x) => x && typeof x === "object" && !Array.isArray(x)))
          arrays.push([key, value]);  // [[body.part]]
        else out += `${tomlKey(key)} = ${tomlValue(value)}\n`;
      }
      for (const [key, list] of arrays)
        for (const item of list) {
          out += `[[${tomlKey(section)}.${tomlKey(key)}]]\n`;
          for (const [k, v] of Object.entries(item)) if (v !== undefined) out += `${tomlKey(k)} = ${tomlValue(v)}\n`;
        }
    }
    return out;
  }

  // ---- window.heavytop ------------------------------------------------------------------------
  let core = null;
  const utf8 = new TextDecoder();
  function check(r) {
    if (r.status !== 0) throw new Error(r.message);
    if (r.message) console.warn(r.message);  // the command line's warnings on stderr
    return utf8.decode(r.output);  // a view of the core's memory, valid until its next call
  }
  function stability(config) { return JSON.parse(check(core.stability(toml(config)))); }
  function lifetime(config) { return JSON.parse(check(core.lifetime(toml(config)))); }
  // `heavytop body --format json`: the body the configuration describes (of its parts, meshes read).
  function body(config) { return JSON.parse(check(core.body(toml(config)))); }
  // The 3D view's data for the nonlinear run over t_end s (report::view_data(): what the report draws).
  function view(config, t_end = 10, samples = 1001) { return JSON.parse(check(core.view(toml(config), t_end, samples))); }
  // A file the configuration can name (a dropped mesh), in the core's in-memory file system.
  function putFile(path, bytes) {
    const folders = path.split("/").slice(0, -1);
    for (let i = 1; i <= folders.length; i++) {
      const dir = folders.slice(0, i).join("/");
      if (dir && !core.FS.analyzePath(dir).exists) core.FS.mkdir(dir);
    }
    core.FS.writeFile(path, bytes);
  }
  function parseCsv(text) {
    const lines = text.split("\n");
    const columns = lines[0].split(",");
    const rows = [];
    for (let i = 1; i < lines.length; i++) {
      if (!lines[i]) continue;
      const f = lines[i].split(",");
      const row = new Array(f.length);
      for (let j = 0; j < f.length; j++) row[j] = Number(f[j]);
      rows.push(row);
    }
    return { columns, rows };
  }
  // options: {model, t_end, samples}; any other key is the flag of its name (rtol -> --rtol).
  function simulate(config, options = {}) {
    const text = toml(config);
    const args = new core.StringList();
    try {
      for (const [key, value] of Object.entries(options || {}))
        if (value !== undefined) { args.push_back("--" + key.replace(/_/g, "-")); args.push_back(String(value)); }
      return parseCsv(check(core.simulate(text, args)));
    } finally { args.delete(); }
  }
  // The stability map: one byte per point (bits: first-order, body-fixed, linearized, Lyapunov).
  function map(config, x, y) {
    const r = core.stabilityMap(toml(config), x.key, x.start, x.stop, x.count, y.key, y.start, y.stop, y.count);
    check(r);
    return new Uint8Array(r.verdicts);
  }

  // ---- The page -------------------------------------------------------------------------------
  // A link may carry the start: explore.html#config={...} (the report's map points link so).
  const fromLink = (() => {
    const m = /^#config=(.*)$/.exec(location.hash);
    if (!m) return null;
    try { return JSON.parse(decodeURIComponent(m[1])); } catch (e) { return null; }
  })();
  const initial = fromLink || window.HEAVYTOP_INITIAL || {
    body: { A: 6.0e-6 + 3.75e-5, B: 6.0e-6 + 3.75e-5, C: 1.2e-5, mass: 0.060, length: 0.025, gravity: 9.81 },
    motion: { spin: 200.0, theta0: 0.05, phi0: 0 },
    damping: { transverse: 0, axial: 0, friction: 0 },
  };
  const bodyKeys = ["A", "B", "C", "mass", "length", "gravity"];
  const momentKeys = ["A", "B", "C", "mass", "length"];
  // ---- The parts list ([[body.part]], SPEC section 10) --------------------------------------
  // Each part's keys by shape, with their units; "density" or "mass" besides.
  const partKeys = {
    cylinder: [["radius", "m"], ["height", "m"], ["z0", "m"]],
    tube: [["radius", "m"], ["inner_radius", "m"], ["height", "m"], ["z0", "m"]],
    cone: [["radius", "m"], ["height", "m"], ["z0", "m"], ["apex", ""]],
    sphere: [["radius", "m"], ["z0", "m"]],
    mesh: [["file", ""], ["units", ""]],
  };
  const choices = { apex: ["down", "up"], units: ["m", "mm"] };
  let parts = [];  // the parts as the configuration lists them (numbers, or text for file, units, apex)
  function drawParts() {
    const list = $("part-list");
    list.innerHTML = "";
    parts.forEach((part, i) => {
      const box = document.createElement("div");
      box.className = "part";
      box.dataset.index = i;
      list.append(box);
      const head = document.createElement("div");
      head.className = "part-head";
      const shape = document.createElement("select");
      shape.className = "part-shape";
      for (const k of Object.keys(partKeys)) { const o = document.createElement("option"); o.value = o.textContent = k; shape.append(o); }
      shape.value = part.shape;
      shape.addEventListener("change", () => {
        const next = { shape: shape.value, [part.mass !== undefined ? "mass" : "density"]: part.mass ?? part.density };
        for (const [k] of partKeys[shape.value]) if (part[k] !== undefined) next[k] = part[k];
        parts[i] = next;
        drawParts();
        changed(true);
      });
      const remove = document.createElement("button");
      remove.type = "button";
      remove.className = "part-remove";
      remove.textContent = "remove";
      remove.addEventListener("click", () => { parts.splice(i, 1); drawParts(); changed(true); });
      head.append(`body.part[${i}] `, shape, remove);
      box.append(head);
      const field = (key, unit, element) => {
        const label = document.createElement("label");
        label.append(key, element);
        const u = document.createElement("span"); u.className = "unit"; u.textContent = unit; label.append(u);
        box.append(label);
      };
      for (const [key, unit] of partKeys[part.shape]) {
        let input;
        if (choices[key]) {
          input = document.createElement("select");
          for (const c of choices[key]) { const o = document.createElement("option"); o.value = o.textContent = c; input.append(o); }
          input.value = part[key] ?? choices[key][0];
          input.addEventListener("change", () => { part[key] = input.value; changed(true); });
        } else if (key === "file") {
          input = document.createElement("input");
          input.type = "text"; input.readOnly = true; input.value = part.file ?? "";
        } else {
          input = document.createElement("input");
          input.type = "number"; input.step = "any"; input.value = part[key] ?? "";
          input.addEventListener("input", () => { part[key] = input.value.trim() === "" ? undefined : Number(input.value); changed(true); });
        }
        input.className = `part-${key}`;
        field(key, unit, input);
      }
      // density or mass: exactly one (SPEC).
      const which = document.createElement("select");
      which.className = "part-amount-key";
      for (const c of ["density", "mass"]) { const o = document.createElement("option"); o.value = o.textContent = c; which.append(o); }
      which.value = part.mass !== undefined ? "mass" : "density";
      const amount = document.createElement("input");
      amount.type = "number"; amount.step = "any"; amount.className = "part-amount";
      amount.value = part[which.value] ?? "";
      const unit = () => (which.value === "mass" ? "kg" : "kg/m³");
      const read = () => {
        delete part.density; delete part.mass;
        if (amount.value.trim() !== "") part[which.value] = Number(amount.value);
        amount.nextSibling.textContent = unit();
      };
      which.addEventListener("change", () => { read(); changed(true); });
      amount.addEventListener("input", () => { read(); changed(true); });
      const label = document.createElement("label");
      const u = document.createElement("span"); u.className = "unit"; u.textContent = unit();
      label.append(which, amount, u);
      box.append(label);
    });
  }
  const defaultPart = () => ({ shape: "cylinder", radius: 0.02, height: 0.005, z0: 0.02, density: 7800 });
  // A dropped mesh: its bytes into the core's file system as meshes/NAME (meshes/2-NAME for a
  // second file of that name), a mesh part naming it.
  const meshNames = new Set();
  function addMesh(name, bytes) {
    const clean = (name.split(/[\\/]/).pop() || "mesh.stl").replace(/[^A-Za-z0-9._-]/g, "_");
    let path = `meshes/${clean}`;  // as a configuration beside its meshes/ folder names it
    for (let k = 2; meshNames.has(path); k++) path = `meshes/${k}-${clean}`;  // another file of that name
    meshNames.add(path);
    putFile(path, bytes);
    if ($("body-mode").value !== "parts") { $("body-mode").value = "parts"; parts = []; showMode(); }
    parts.push({ shape: "mesh", file: path, units: "mm", density: 1000 });
    drawParts();
    changed(true);
    return path;
  }
  function showMode() {
    const byParts = $("body-mode").value === "parts";
    $("moments").classList.toggle("hidden", byParts);
    $("parts").classList.toggle("hidden", !byParts);
  }
  const dampingKeys = ["transverse", "axial", "friction"];
  const rpm = 60 / (2 * Math.PI);
  function fillInputs(c) {
    if (c.body.part) {
      $("body-mode").value = "parts";
      parts = c.body.part.map((p) => ({ ...p }));
      drawParts();
    } else $("body-mode").value = "moments";
    showMode();
    for (const k of bodyKeys) if (!c.body.part || k === "gravity") $(k).value = c.body[k] ?? (k === "gravity" ? 9.81 : "");
    $("spin").value = $("spin-unit").value === "rpm" ? (c.motion.spin || 0) * rpm : c.motion.spin || 0;
    $("theta0").value = c.motion.theta0 || 0;
    $("phi0").value = c.motion.phi0 || 0;
    for (const k of dampingKeys) $(k).value = (c.damping && c.damping[k]) || 0;
  }
  // The configuration the inputs describe (an empty field is left out: the core says what is missing).
  function readInputs() {
    const num = (id) => ($(id).value.trim() === "" ? undefined : Number($(id).value));
    const c = { body: {}, motion: {}, damping: {} };
    if ($("body-mode").value === "parts") {
      c.body.gravity = num("gravity");
      c.body.part = parts.map((p) => ({ ...p }));
    } else for (const k of bodyKeys) c.body[k] = num(k);
    const spin = num("spin");
    if ($("spin-unit").value === "rpm") c.motion.spin_rpm = spin; else c.motion.spin = spin;
    c.motion.theta0 = num("theta0");
    c.motion.phi0 = num("phi0");
    for (const k of ["theta_rate0", "phi_rate0"]) if (initial.motion[k]) c.motion[k] = initial.motion[k];  // from `heavytop explore`
    for (const k of dampingKeys) if (num(k)) c.damping[k] = num(k);
    if (!Object.keys(c.damping).length) delete c.damping;
    return c;
  }
  const damped = (c) => !!c.damping;

  const fmt = (x, d = 4) => (x === null || x === undefined ? "–" : typeof x === "number" ? Number(x.toPrecision(d)).toString() : String(x));
  const deg = (r) => fmt((r * 180) / Math.PI, 3) + "°";
  const spinWords = (w) => (w === null || w === undefined ? "–" : `${fmt(w)} rad/s (${fmt(w * rpm)} rpm)`);
  const intervals = (list) => (list || []).map(([a, b]) => `[${fmt(a)}, ${b === null ? "∞" : fmt(b)}]`).join(" ∪ ") || "none";

  let firstVerdictAt = null, current = null;
  // The body of parts as the core makes it (heavytop body's JSON), for the map's axes and shown.
  let madeBody = null;
  function showVerdict() {
    const config = readInputs();
    let s;
    try {
      if (config.body.part) {
        madeBody = body(config);
        const b = madeBody;
        $("body-made").textContent = `They make A = ${fmt(b.A, 6)}, B = ${fmt(b.B, 6)}, C = ${fmt(b.C, 6)} kg m², ` +
          `mass ${fmt(b.mass, 6)} kg, centre of mass at ${fmt(b.length, 6)} m on the axis (heavytop body).`;
      }
      s = stability(config);
      $("error").textContent = "";
    } catch (e) {
      $("error").textContent = e.message;
      $("answer").textContent = "—";
      $("answer").className = "";
      return false;
    }
    current = { config, stability: s };
    const box = $("answer");
    if (s.answer) {
      const a = s.answer;
      box.className = a.verdict === "stays up" ? "up" : a.verdict === "falls" ? "falls" : "horizon";
      let text = `It ${a.verdict}${a.proven ? " (proven)" : ""}.`;
      if (a.falls_at !== null && a.falls_at !== undefined) text += ` It falls at t = ${fmt(a.falls_at)} s.`;
      if (a.max_tilt !== null && a.max_tilt !== undefined) text += ` Largest tilt ${fmt(a.max_tilt)} rad (${deg(a.max_tilt)}).`;
      if (a.min_spin !== null && a.min_spin !== undefined) text += ` Proven stable from ${spinWords(a.min_spin)}.`;
      if (a.lifetime !== null && a.lifetime !== undefined) text += ` Lifetime ${fmt(a.lifetime)} s.`;
      box.innerHTML = "";
      box.append(text);
      if (a.reason) { const r = document.createElement("div"); r.className = "small"; r.textContent = a.reason; box.append(r); }
    } else {
      const v = s.lyapunov ? s.lyapunov.verdict : "?";
      box.className = v === "stable" ? "up" : v === "unstable" ? "falls" : "horizon";
      box.textContent = `Lyapunov verdict at ${spinWords(s.spin)}: ${v}` +
        (s.wander && s.wander.max_tilt !== null ? `; largest tilt ${fmt(s.wander.max_tilt)} rad (${deg(s.wander.max_tilt)})` : "");
    }
    box.dataset.verdict = box.textContent;
    const tbody = $("models").querySelector("tbody");
    tbody.innerHTML = "";
    for (const [name, m] of Object.entries(s.models)) {
      const tr = document.createElement("tr");
      tr.innerHTML = `<td>${name}</td><td class="${m.stable ? "yes" : "no"}">${m.stable ? "stable" : "unstable"}</td>` +
        `<td>${spinWords(m.critical_spin)}</td><td>${intervals(m.stable_spin_intervals)}</td>`;
      tbody.append(tr);
    }
    const d = $("details");
    d.innerHTML = "";
    const p = (t) => { const e = document.createElement("p"); e.textContent = t; d.append(e); };
    if (s.lyapunov)
      p(`Lyapunov (the real body): ${s.lyapunov.verdict}` + (s.lyapunov.certificate ? `, certificate: ${s.lyapunov.certificate}` : "") +
        `; proven stable spins: ${intervals(s.lyapunov.stable_spin_intervals)}`);
    if (s.wander) p(`Largest tilt: ${s.wander.max_tilt === null ? "–" : fmt(s.wander.max_tilt) + " rad (" + deg(s.wander.max_tilt) + ")"}, ${s.wander.method}` +
      (s.wander.horizon ? ` over ${fmt(s.wander.horizon)} s` : "") + (s.wander.note ? ` (${s.wander.note})` : ""));
    if (damped(config)) {
      try {
        const l = lifetime(config);
        p(`Lifetime: the spin decays to the critical spin at t = ${fmt(l.spin_decay.time_to_critical)} s; ` +
          (l.fall && l.fall.time !== null ? `it falls at t = ${fmt(l.fall.time)} s spinning at ${spinWords(l.fall.spin)}` : `no fall within ${fmt(l.horizon)} s`) + ".");
      } catch (e) { p("Lifetime: " + e.message); }
    }
    if (firstVerdictAt === null) firstVerdictAt = performance.now();
    return true;
  }

  // ---- The stability map ----------------------------------------------------------------------
  const mapKeys = ["spin", "B/A", "C/A", "A", "B", "C", "mass", "length", "gravity"];
  let mapState = null;
  // The body's moments: as given, or as its parts make them.
  const momentsOf = (c) => (c.body.part ? { ...(madeBody || {}), gravity: c.body.gravity } : c.body);
  function baseValue(c, key) {
    if (key === "spin") return c.motion.spin ?? (c.motion.spin_rpm ?? 0) / rpm;
    const b = momentsOf(c);
    if (key === "B/A") return b.B / b.A;
    if (key === "C/A") return b.C / b.A;
    return b[key];
  }
  function defaultRange(key) {
    const c0 = readInputs(), c = { ...c0, body: momentsOf(c0) }, v = baseValue(c, key);
    if (key === "spin") return [0, Math.max(1, 2 * Math.abs(v))];
    // The ratios a real body can take with the other moments held (the triangle inequalities).
    if (key === "B/A") return [Math.abs(c.body.C - c.body.A) / c.body.A * (1 + 1e-6) + 1e-6, (c.body.C + c.body.A) / c.body.A * (1 - 1e-6)];
    if (key === "C/A") return [Math.max(0.01, Math.abs(c.body.B - c.body.A) / c.body.A * (1 + 1e-6) + 1e-6), (c.body.B + c.body.A) / c.body.A * (1 - 1e-6)];
    if (key === "length") return [-2 * Math.abs(v), 2 * Math.abs(v)];
    return [v / 4, v * 2];
  }
  function axesOf(n) {
    return [
      { key: $("map-x").value, start: Number($("map-x0").value), stop: Number($("map-x1").value), count: n },
      { key: $("map-y").value, start: Number($("map-y1").value), stop: Number($("map-y0").value), count: n },  // top row first
    ];
  }
  function drawMap() {
    const n = Math.max(2, Math.min(400, Math.round(Number($("map-n").value) || 100)));
    // sweep's grid is row-major with its first axis slowest: rows are y (top to bottom), columns x.
    const [x, y] = axesOf(n);
    let verdicts;
    const t0 = performance.now();
    try {
      verdicts = map(readInputs(), y, x);
    } catch (e) {
      $("map-info").textContent = e.message;
      return;
    }
    const ms = performance.now() - t0;
    const bit = 1 << Number($("map-model").value);
    const canvas = $("map"), g = canvas.getContext("2d");
    const image = g.createImageData(n, n);
    for (let i = 0; i < n * n; i++) {
      const v = verdicts[i], stable = v & bit, linear = v & 4;
      const [r, gr, b] = stable ? [60, 170, 80] : linear ? [230, 200, 90] : [215, 80, 70];
      image.data.set([r, gr, b, 255], 4 * i);
    }
    const off = document.createElement("canvas");
    off.width = off.height = n;
    off.getContext("2d").putImageData(image, 0, 0);
    g.imageSmoothingEnabled = false;
    g.clearRect(0, 0, canvas.width, canvas.height);
    g.drawImage(off, 0, 0, canvas.width, canvas.height);
    // The current body's point.
    const c = readInputs();
    const px = ((baseValue(c, x.key) - x.start) / (x.stop - x.start)) * canvas.width;
    const py = ((baseValue(c, y.key) - y.start) / (y.stop - y.start)) * canvas.height;
    g.strokeStyle = "#000"; g.lineWidth = 2;
    g.beginPath(); g.moveTo(px - 7, py); g.lineTo(px + 7, py); g.moveTo(px, py - 7); g.lineTo(px, py + 7); g.stroke();
    mapState = { x, y, n };
    $("map-info").textContent = `${x.key} → (${fmt(x.start)} … ${fmt(x.stop)}), ${y.key} ↑ (${fmt(y.stop)} … ${fmt(y.start)}), ${n}×${n} in ${ms.toFixed(0)} ms; ` +
      `green: stable (${$("map-model").selectedOptions[0].text}), yellow: linearized stable only, red: unstable`;
  }
  function setKey(c, key, value) {
    // A body of parts moved along a body key is given by its moments from there on.
    if (key !== "spin" && c.body.part) {
      const b = momentsOf(c);
      c.body = { gravity: b.gravity };
      for (const k of momentKeys) c.body[k] = b[k];
    }
    if (key === "spin") { delete c.motion.spin_rpm; c.motion.spin = value; }
    else if (key === "B/A") c.body.B = value * c.body.A;
    else if (key === "C/A") c.body.C = value * c.body.A;
    else c.body[key] = value;
  }
  function mapClick(ev) {
    if (!mapState) return;
    const rect = $("map").getBoundingClientRect();
    const fx = (ev.clientX - rect.left) / rect.width, fy = (ev.clientY - rect.top) / rect.height;
    const { x, y } = mapState;
    const c = readInputs();
    setKey(c, x.key, x.start + fx * (x.stop - x.start));
    setKey(c, y.key, y.start + fy * (y.stop - y.start));
    fillInputs(c.motion.spin_rpm !== undefined ? c : { ...c, motion: { ...c.motion } });
    update({ map: true });
  }

  // ---- The motion ----------------------------------------------------------------------------
  function drawMotion() {
    const c = readInputs();
    const canvas = $("motion"), g = canvas.getContext("2d");
    g.clearRect(0, 0, canvas.width, canvas.height);
    let run;
    const t0 = performance.now();
    try { run = simulate(c, { model: "nonlinear", t_end: 10, samples: 1001 }); }
    catch (e) { $("motion-info").textContent = "motion: " + e.message; return; }
    const ms = performance.now() - t0;
    const col = (name) => run.columns.indexOf(name);
    const it = col("t"), itilt = col("tilt"), ith = col("theta"), iph = col("phi");
    const tilt = run.rows.map((r) => (itilt >= 0 ? r[itilt] : Math.acos(Math.cos(r[ith]) * Math.cos(r[iph]))));
    const tmax = run.rows[run.rows.length - 1][it];
    const ymax = Math.max(1e-9, ...tilt.filter(Number.isFinite)) * 1.1;
    const L = 50, R = 10, T = 10, B = 30, W = canvas.width - L - R, H = canvas.height - T - B;
    g.strokeStyle = "#999"; g.lineWidth = 1; g.strokeRect(L, T, W, H);
    g.fillStyle = "#333"; g.font = "12px sans-serif";
    g.fillText("0", L - 12, T + H + 4); g.fillText(deg(ymax), 2, T + 10);
    g.fillText("t = 0", L, T + H + 18); g.fillText(`${fmt(tmax)} s`, L + W - 30, T + H + 18);
    g.strokeStyle = "#c33"; g.lineWidth = 1.5; g.beginPath();
    run.rows.forEach((r, i) => {
      const X = L + (r[it] / tmax) * W, Y = T + H - (tilt[i] / ymax) * H;
      i ? g.lineTo(X, Y) : g.moveTo(X, Y);
    });
    g.stroke();
    $("motion-info").textContent = `The nonlinear body's tilt from the vertical over 10 s (largest ${deg(Math.max(...tilt))}), computed in ${ms.toFixed(0)} ms. Click the map to see another point's motion.`;
  }

  // ---- The 3D view: the report's own (report/web/src/main.js), on this page's run ------------------
  let shown3d = null;
  function drawView() {
    const note = $("view-note");
    if (!window.heavytopView3D) { note.textContent = `No 3D view in this page: ${window.heavytopView3DMissing}.`; return; }
    let data;
    const t0 = performance.now();
    try { data = view(readInputs(), 10, 1001); }
    catch (e) { note.textContent = "3D view: " + e.message; return; }
    if (shown3d) shown3d.dispose();
    shown3d = window.heavytopView3D.show(data);
    const what = data.parts.length ? `its ${data.parts.length} part${data.parts.length > 1 ? "s" : ""} (${data.parts.map((p) => p.shape).join(", ")})`
                                   : "the uniform ellipsoid with its mass and moments" + (data.shape.note ? ` (not to scale: ${data.shape.note})` : "");
    note.textContent = `The body drawn as ${what}; the run computed and drawn in ${(performance.now() - t0).toFixed(0)} ms.`;
  }

  function update(what = {}) {
    const ok = showVerdict();
    if (!ok) return;
    drawMotion();
    drawView();
    if (what.map) drawMap();
  }
  let pending = false;
  // An input changed: the verdict at once, on every keystroke; the motion, the view (and the map) after a pause.
  function changed(map) {
    showVerdict();
    if (pending) return;
    pending = true;
    setTimeout(() => { pending = false; update({ map }); }, 150);
  }

  function setupMap(key, which) {
    const [a, b] = defaultRange(key);
    // Four digits, rounded inwards (a ratio's range ends at what a real body allows).
    const round = (v, up) => {
      if (v === 0) return 0;
      const q = Math.pow(10, Math.floor(Math.log10(Math.abs(v))) - 3);
      return Number(((up ? Math.ceil(v / q) : Math.floor(v / q)) * q).toPrecision(4));
    };
    $(`map-${which}0`).value = round(a, a < b);
    $(`map-${which}1`).value = round(b, !(a < b));
  }

  function start() {
    $("version").textContent = core.version();
    for (const which of ["x", "y"])
      for (const k of mapKeys) { const o = document.createElement("option"); o.value = o.textContent = k; $(`map-${which}`).append(o); }
    $("map-x").value = "spin";
    $("map-y").value = "B/A";
    fillInputs(initial);
    setupMap("spin", "x"); setupMap("B/A", "y");
    const schedule = changed;
    $("body-mode").addEventListener("change", () => {
      const c = readInputs();
      if ($("body-mode").value === "parts" && !parts.length) parts = [defaultPart()];
      if ($("body-mode").value === "moments" && madeBody)  // the parts' moments, to go on from
        for (const k of momentKeys) $(k).value = madeBody[k];
      showMode();
      drawParts();
      schedule(true);
      return c;
    });
    $("add-part").addEventListener("click", () => { parts.push(defaultPart()); drawParts(); schedule(true); });
    const drop = $("drop");
    const take = (file) => file.arrayBuffer().then((b) => addMesh(file.name, new Uint8Array(b)));
    drop.addEventListener("dragover", (e) => { e.preventDefault(); drop.classList.add("over"); });
    drop.addEventListener("dragleave", () => drop.classList.remove("over"));
    drop.addEventListener("drop", (e) => {
      e.preventDefault();
      drop.classList.remove("over");
      for (const f of e.dataTransfer.files) take(f);
    });
    $("mesh-file").addEventListener("change", (e) => { for (const f of e.target.files) take(f); });
    for (const id of [...bodyKeys, "spin", "theta0", "phi0", ...dampingKeys]) $(id).addEventListener("input", () => schedule(true));
    $("spin-unit").addEventListener("change", () => {
      const v = Number($("spin").value);
      $("spin").value = Number(($("spin-unit").value === "rpm" ? v * rpm : v / rpm).toPrecision(12));
      schedule(false);
    });
    for (const w of ["x", "y"]) $(`map-${w}`).addEventListener("change", () => { setupMap($(`map-${w}`).value, w); drawMap(); });
    for (const id of ["map-x0", "map-x1", "map-y0", "map-y1", "map-n", "map-model"]) $(id).addEventListener("change", drawMap);
    $("map").addEventListener("click", mapClick);
    showVerdict();
    // Ready even if a drawing fails (its error is then the page's, for a person and for the tests).
    setTimeout(() => { try { drawMotion(); drawView(); drawMap(); } finally { document.body.dataset.ready = "1"; } }, 0);
  }

  // ---- Benchmarks (browser clock; medians) ------------------------------------------------------
  const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };
  function time(f, n) { const ts = []; for (let i = 0; i < n; i++) { const t = performance.now(); f(i); ts.push(performance.now() - t); } return median(ts); }
  function benchmark() {
    const c = JSON.parse(JSON.stringify(initial));
    $("spin-unit").value = "rad/s";
    fillInputs(initial);
    return {
      first_verdict_ms: firstVerdictAt,  // since the navigation started (performance.now's origin)
      core_ready_ms: coreReadyAt,
      verdict_ms: time((i) => { c.motion.spin = 100 + i; stability(c); }, 51),
      verdict_shown_ms: time((i) => { $("spin").value = 150 + i; showVerdict(); }, 51),
      toy_top_10s_1001_ms: time(() => simulate(initial, { model: "nonlinear", t_end: 10, samples: 1001 }), 11),
      map_200x200_ms: time(() => map(initial, { key: "spin", start: 0, stop: 400, count: 200 }, { key: "B/A", start: 0.75, stop: 1.25, count: 200 }), 5),
    };
  }

  let coreReadyAt = null;
  createHeavytopCore().then((m) => {
    core = m;
    coreReadyAt = performance.now();
    window.heavytop = Object.freeze({ stability, simulate, version: m.version() });
    window.heavytopExplorer = { toml, map, lifetime, body, view, putFile, addMesh, config: readInputs, benchmark, loadStart };
    start();
  });
})();
