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
  // Options as the command line's flags: {horizon: 50} -> --horizon 50 (a key's "_" as "-").
  function flags(options) {
    if (options === null || options === undefined) return [];
    if (typeof options !== "object" || Array.isArray(options))
      throw new Error("heavytop: error: options: must be an object of the command's options, e.g. {horizon: 50}");
    const args = [];
    for (const [key, value] of Object.entries(options))
      if (value !== undefined) args.push("--" + key.replace(/_/g, "-"), String(value));
    return args;
  }
  function withArgs(options, f) {
    const args = new core.StringList();
    try {
      for (const a of flags(options)) args.push_back(a);
      return f(args);
    } finally { args.delete(); }
  }
  // options: the answer's {horizon, max_tilt, lifetime_horizon, max_steps} (stability's flags).
  function stability(config, options = {}) {
    const text = toml(config);
    return JSON.parse(withArgs(options, (args) => check(core.stability(text, args, "json"))));
  }
  // `heavytop stability` for people (--format text): the answer in words, then the details.
  function stabilityText(config, options = {}) {
    const text = toml(config);
    return withArgs(options, (args) => check(core.stability(text, args, "text")));
  }
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
  // options: {model, t_end, samples}; any other key is the flag of its name (rtol -> --rtol),
  // refused as the command line refuses an unknown one.
  function simulate(config, options = {}) {
    const text = toml(config);
    return parseCsv(withArgs(options, (args) => check(core.simulate(text, args))));
  }
  // The stability map: one byte per point (bits: first-order, body-fixed, linearized, Lyapunov).
  function map(config, x, y) {
    const r = core.stabilityMap(toml(config), x.key, x.start, x.stop, x.count, y.key, y.start, y.stop, y.count);
    check(r);
    return new Uint8Array(r.verdicts);
  }

  // ---- The page -------------------------------------------------------------------------------
  // The start: a link's explore.html#config={...} (the report's map points link so), else what
  // `heavytop explore` wrote (HEAVYTOP_CONFIG: the whole configuration and the answer's options;
  // a report's copy has HEAVYTOP_INITIAL: the body and motion), else the built-in toy top. A link
  // that is not JSON of a configuration with a [body] starts at the toy top, and says so.
  const toyTop = {
    body: { A: 6.0e-6 + 3.75e-5, B: 6.0e-6 + 3.75e-5, C: 1.2e-5, mass: 0.060, length: 0.025, gravity: 9.81 },
    motion: { spin: 200.0, theta0: 0.05, phi0: 0 },
    damping: { transverse: 0, axial: 0, friction: 0 },
  };
  const isObject = (x) => x !== null && typeof x === "object" && !Array.isArray(x);
  // A link's start, explore.html#config=...: {config} when it is JSON of a configuration with a
  // body, else {config: null, notice} (the one line the page shows, starting at the toy top).
  function fromLink(hash) {
    const m = /^#config=(.*)$/s.exec(hash || "");
    if (!m) return { config: null, notice: "" };
    let c;
    try { c = JSON.parse(decodeURIComponent(m[1])); } catch (e) {
      return { config: null, notice: `The link's configuration (#config=) is not JSON (${e.message}): starting from the built-in toy top.` };
    }
    if (!isObject(c))
      return { config: null, notice: "The link's configuration (#config=) must be an object of sections, {body: {...}, motion: {...}}: starting from the built-in toy top." };
    if (!isObject(c.body))
      return { config: null, notice: "The link's configuration (#config=) has no body (body: {A, B, C, mass, length} or body.part): starting from the built-in toy top." };
    return { config: c, notice: "" };
  }
  const link = fromLink(location.hash);
  const given = window.HEAVYTOP_CONFIG;
  // The configuration the inputs started from: its keys that the form does not show go on.
  let initial = link.config || (!link.notice && given && given.config) || (!link.notice && window.HEAVYTOP_INITIAL) || toyTop;
  const initialOptions = (!link.config && !link.notice && given && given.stability) || {};
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
  const motionKeys = ["theta0", "phi0", "theta_rate0", "phi_rate0"];
  const shapeKeys = ["tip_radius", "rim_radius"];  // [body]: what touches the table
  // The answer's options (stability's --horizon, --max-tilt, --lifetime-horizon, --max-steps).
  const answerKeys = ["horizon", "max_tilt", "lifetime_horizon", "max_steps"];
  const rpm = 60 / (2 * Math.PI);
  // The tilt θ₀ in rad or degrees (the configuration's motion.theta0 stays in rad). A value shown
  // in degrees keeps its radians while its text is unchanged: a unit's change or a link shown in
  // degrees reads back the same double, not one rounded through 12 digits of degrees.
  const degree = Math.PI / 180;
  let tiltShown = null;  // {text, rad}: the degrees last shown and their radians
  function showTilt(value) {
    const inDegrees = $("theta0-unit").value === "deg" && Number.isFinite(value);
    $("theta0").value = inDegrees ? Number((value / degree).toPrecision(12)) : shown(value);
    tiltShown = inDegrees ? { text: $("theta0").value, rad: value } : null;
  }
  // rad, from the field as shown in `unit` (the selector's, or the one it had before a change).
  function readTilt(unit = $("theta0-unit").value) {
    if (tiltShown && $("theta0").value === tiltShown.text) return tiltShown.rad;
    const v = num("theta0");
    return v !== undefined && unit === "deg" ? v * degree : v;
  }
  const section = (c, name) => (isObject(c[name]) ? c[name] : {});
  const givenMaterials = {};  // a start's materials given by modulus and Poisson's ratio ("tip_" and "")
  const shown = (v) => (v === undefined || v === null ? "" : v);
  // The inputs at a configuration (never throws: a value the form cannot hold is shown as text
  // and refused by the core with the command line's message).
  function fillInputs(c, options) {
    const body = section(c, "body"), motion = section(c, "motion"), damping = section(c, "damping"), table = section(c, "table");
    if (Array.isArray(body.part)) {
      $("body-mode").value = "parts";
      parts = body.part.map((p) => (isObject(p) ? { ...p } : {}));
      drawParts();
    } else $("body-mode").value = "moments";
    showMode();
    for (const k of bodyKeys) if (!Array.isArray(body.part) || k === "gravity") $(k).value = shown(body[k] ?? (k === "gravity" ? 9.81 : ""));
    for (const k of shapeKeys) $(k).value = shown(body[k]);
    const spin = motion.spin ?? (motion.spin_rpm !== undefined ? motion.spin_rpm / rpm : 0);
    $("spin").value = $("spin-unit").value === "rpm" ? spin * rpm : spin;
    for (const k of motionKeys) if (k !== "theta0") $(k).value = shown(motion[k] ?? 0);
    showTilt(motion.theta0 ?? 0);
    $("driven").checked = motion.driven === true;
    for (const k of dampingKeys) $(k).value = shown(damping[k] ?? 0);
    $("contact").value = ["frictionless", "rolling", "sliding"].includes(table.contact) ? table.contact : "pivot";
    $("table_friction").value = shown(table.friction);
    $("friction_law").value = ["coulomb", "contensou"].includes(table.friction_law) ? table.friction_law : "viscous";
    $("slip_speed").value = shown(table.slip_speed);
    // A material by name, or given by its modulus and Poisson's ratio: kept as "as given".
    for (const [id, key] of [["tip_material", "tip_"], ["table_material", ""]]) {
      const select = $(id);
      for (const o of [...select.options]) if (o.value === "given") o.remove();
      givenMaterials[key] = undefined;
      if (table[key + "modulus"] !== undefined) {
        givenMaterials[key] = { modulus: table[key + "modulus"], poisson: table[key + "poisson"] };
        select.add(new Option(`as given (E = ${table[key + "modulus"]} Pa)`, "given"));
        select.value = "given";
      } else if (typeof table[key + "material"] === "string") select.value = table[key + "material"];
    }
    $("rolling_resistance").value = shown(table.rolling_resistance);
    $("air").checked = table.air === true;
    showTable();
    if (options) for (const k of answerKeys) $(k).value = shown(options[k]);
  }
  // The inputs at a start (a configuration and the answer's options) and the one line said of it;
  // a start the form cannot show is the toy top's, said in that line.
  function show(config, options, notice = "") {
    try { fillInputs(config, options); initial = config; }
    catch (e) {
      notice = `The start's configuration could not be shown (${e.message}): starting from the built-in toy top.`;
      fillInputs(toyTop, {});
      initial = toyTop;
    }
    $("notice").textContent = notice;
  }
  // Opens a start as a page load does: a link's hash ("#config=...") or {config, stability} as
  // `heavytop explore` writes it (HEAVYTOP_CONFIG); the answer, then (unless draw is false) the
  // motion and the 3D view.
  function open(start, draw = true) {
    if (typeof start === "string") {
      const l = fromLink(start);
      show(l.config || toyTop, {}, l.notice);
    } else show(start.config, start.stability || {});
    if (draw) update({}); else showVerdict();
    return current;
  }
  function showTable() {
    const sliding = $("contact").value === "sliding";
    $("sliding-fields").classList.toggle("hidden", !sliding);
    for (const e of document.querySelectorAll(".viscous-field")) e.classList.toggle("hidden", $("friction_law").value !== "viscous");
    for (const e of document.querySelectorAll(".contensou-field")) e.classList.toggle("hidden", $("friction_law").value !== "contensou");
    for (const e of document.querySelectorAll(".rolling-field")) e.classList.toggle("hidden", $("friction_law").value === "coulomb");
    $("air-field").classList.toggle("hidden", $("contact").value === "pivot");
  }
  const num = (id) => ($(id).value.trim() === "" ? undefined : Number($(id).value));
  // The configuration the inputs describe (an empty field is left out: the core says what is
  // missing, or takes its default). The start's keys that the form does not show (the general
  // body's, a [simulate] section) go on as they were.
  function readInputs() {
    const c = {};
    for (const [k, v] of Object.entries(initial)) if (isObject(v)) c[k] = JSON.parse(JSON.stringify(v));
    c.body = c.body || {};
    c.motion = c.motion || {};
    const set = (table, key, value) => { if (value === undefined) delete table[key]; else table[key] = value; };
    if ($("body-mode").value === "parts") {
      for (const k of momentKeys) delete c.body[k];
      set(c.body, "gravity", num("gravity"));
      c.body.part = parts.map((p) => ({ ...p }));
    } else {
      delete c.body.part;
      for (const k of bodyKeys) set(c.body, k, num(k));
    }
    for (const k of shapeKeys) set(c.body, k, num(k));
    const spin = num("spin");
    delete c.motion.spin; delete c.motion.spin_rpm;
    if ($("spin-unit").value === "rpm") c.motion.spin_rpm = spin; else c.motion.spin = spin;
    for (const k of motionKeys) set(c.motion, k, k === "theta0" ? readTilt() : num(k));
    set(c.motion, "driven", $("driven").checked ? true : undefined);
    c.damping = {};
    for (const k of dampingKeys) if (num(k)) c.damping[k] = num(k);
    if (!Object.keys(c.damping).length) delete c.damping;
    const contact = $("contact").value;
    delete c.table;
    if (contact !== "pivot") {  // [table]: the keys its contact takes (the others are refused)
      c.table = { contact };
      if (contact === "sliding") {
        set(c.table, "friction", num("table_friction"));
        c.table.friction_law = $("friction_law").value;
        if (c.table.friction_law === "viscous") set(c.table, "slip_speed", num("slip_speed"));
        if (c.table.friction_law === "contensou")
          for (const [id, key] of [["tip_material", "tip_"], ["table_material", ""]]) {
            const given = $(id).value === "given" && givenMaterials[key];
            if (given) {
              c.table[key + "modulus"] = given.modulus;
              c.table[key + "poisson"] = given.poisson;
            } else c.table[key + "material"] = $(id).value;
          }
        if (c.table.friction_law !== "coulomb") set(c.table, "rolling_resistance", num("rolling_resistance"));
      }
      if ($("air").checked) {
        c.table.air = true;
        const start = section(initial, "table");  // the start's air, which the form does not show
        for (const k of ["air_density", "air_viscosity"]) if (start[k] !== undefined) c.table[k] = start[k];
      }
    }
    return c;
  }
  // The answer's options the inputs give (stability's flags).
  function readOptions() {
    const o = {};
    for (const k of answerKeys) if (num(k) !== undefined) o[k] = num(k);
    return o;
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
    let s, words;
    try {
      if (config.body.part) {
        const { table, ...pivot } = config;  // `heavytop body` is the pivot's: the parts' sums
        madeBody = body(pivot);
        const b = madeBody;
        $("body-made").textContent = `They make A = ${fmt(b.A, 6)}, B = ${fmt(b.B, 6)}, C = ${fmt(b.C, 6)} kg m², ` +
          `mass ${fmt(b.mass, 6)} kg, centre of mass at ${fmt(b.length, 6)} m on the axis (heavytop body).`;
      }
      const options = readOptions();
      s = stability(config, options);
      // The answer in the command line's words: the first paragraph of `heavytop stability`.
      words = stabilityText(config, options).split("\n\n")[0];
      $("error").textContent = "";
    } catch (e) {
      current = null;
      $("error").textContent = e.message;
      $("answer").textContent = "—";
      $("answer").className = "";
      delete $("answer").dataset.verdict;
      return false;
    }
    current = { config, options: readOptions(), stability: s, words };
    const box = $("answer");
    const a = s.answer;
    box.className = a.verdict === "stays up" ? "up" : a.verdict === "falls" || a.verdict === "leaves the table" ? "falls" : "horizon";
    // The headline: the words before the JSON's reason (stability's text is headline, reason, more).
    const at = a.reason ? words.indexOf(" " + a.reason) : -1;
    const headline = document.createElement("b");
    headline.className = "headline";
    headline.textContent = at > 0 ? words.slice(0, at) : words;
    box.innerHTML = "";
    box.append(headline, at > 0 ? words.slice(at) : "");
    const numbers = [];
    const add = (label, x, unit) => { if (x !== null && x !== undefined) numbers.push(`${label} ${fmt(x, 7)}${unit}`); };
    if (a.table) {
      add("upright from t =", a.table.upright_at, " s");
      add("turns over at t =", a.table.turns_over_at, " s");
      add("leaves the table at t =", a.table.leaves_at, " s");
      add("track", a.table.track, " m");
      add("final tilt", a.table.final_tilt, " rad");
    }
    add("falls at t =", a.falls_at, " s");
    add("largest tilt", a.max_tilt, " rad");
    add("proven stable from", a.min_spin, " rad/s");
    add("lifetime", a.lifetime, " s");
    const line = document.createElement("div");
    line.className = "numbers";
    line.textContent = `${a.verdict}${a.proven ? " (proven)" : ""}: ` + numbers.join("; ");
    box.append(line);
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
    if (s.table) {  // SPEC section 16: the spinning states on the table
      const state = (label, t) => p(t === null ? `${label}: none (a rim's axis cannot stand vertical)` :
        `${label} (${s.table.contact}): ${t.stable ? "stable" : "unstable"}${t.asymptotically ? ", asymptotically" : ""} at this spin; ` +
        `critical spin ${spinWords(t.critical_spin)}; stable spins ${intervals(t.stable_spin_intervals)}`);
      state("Spinning upright on the table", s.table.upright);
      state("Spinning inverted", s.table.inverted);
      p("The models' table above is the same body on a pivot.");
    }
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
    if (onTable(readInputs())) {  // sweep's verdicts are the pivot's (SPEC section 16: not a table's)
      const canvas = $("map");
      canvas.getContext("2d").clearRect(0, 0, canvas.width, canvas.height);
      mapState = null;
      $("map-info").textContent = "(the map's verdicts are the pivot's: set the contact to pivot to draw it)";
      return;
    }
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
  // s, the motion shown: 10 s on a pivot; on a table as the table's report shows it (report/src/
  // report.cpp table_report_horizon()): twice the answer's event (the turn-over, the rise to sleep,
  // leaving the table; a fall and a fifth more), else the answer's horizon, at most 10 s.
  function shownHorizon() {
    const a = current && current.stability.answer;
    if (!a || !a.table) return 10;
    if (a.falls_at > 0) return 1.2 * a.falls_at;
    for (const e of [a.table.turns_over_at, a.table.upright_at, a.table.leaves_at]) if (e > 0) return 2 * e;
    return Math.min(a.horizon, 10);
  }
  const onTable = (c) => !!(c && c.table && c.table.contact && c.table.contact !== "pivot");
  function drawMotion() {
    const c = readInputs(), horizon = shownHorizon();
    const canvas = $("motion"), g = canvas.getContext("2d");
    g.clearRect(0, 0, canvas.width, canvas.height);
    let run;
    const t0 = performance.now();
    try { run = simulate(c, { model: "nonlinear", t_end: horizon, samples: 1001 }); }
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
    $("motion-info").textContent = `The nonlinear body's tilt from the vertical over ${fmt(tmax)} s${onTable(c) ? " on the table" : ""} (largest ${deg(Math.max(...tilt))}), computed in ${ms.toFixed(0)} ms. Click the map to see another point's motion.`;
  }

  // ---- The 3D view: the report's own (report/web/src/main.js), on this page's run ------------------
  let shown3d = null;
  function drawView() {
    const note = $("view-note");
    if (!window.heavytopView3D) { note.textContent = `No 3D view in this page: ${window.heavytopView3DMissing}.`; return; }
    let data;
    const t0 = performance.now();
    const c = readInputs();
    // On a table P's track is drawn from every sample (its small loops would alias at 1001).
    try { data = view(c, shownHorizon(), onTable(c) ? 4001 : 1001); }
    catch (e) { note.textContent = "3D view: " + e.message; return; }
    if (shown3d) shown3d.dispose();
    $("follow").checked = true;  // the view starts following the body on a table
    $("follow-label").hidden = !data.table;
    $("inset-words").hidden = !!data.table;  // on a table no inset: P's track shows the motion
    shown3d = window.heavytopView3D.show(data);
    const what = data.parts.length ? `its ${data.parts.length} part${data.parts.length > 1 ? "s" : ""} (${data.parts.map((p) => p.shape).join(", ")})`
                                   : data.table ? "what touches the table (the tip's sphere or the rim, with the uniform ellipsoid of its mass and moments above a small tip)"
                                   : "the uniform ellipsoid with its mass and moments" + (data.shape.note ? ` (not to scale: ${data.shape.note})` : "");
    const where = data.table ? ` on the table (${data.table.contact}; the black line: the track of the contact point P)` : "";
    note.textContent = `The body drawn as ${what}${where}; the run computed and drawn in ${(performance.now() - t0).toFixed(0)} ms.`;
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
    if (!onTable(readInputs())) showVerdict();  // on a table after the pause (the answer follows the motion)
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
    show(initial, initialOptions, link.notice);
    try { setupMap("spin", "x"); setupMap("B/A", "y"); } catch (e) { $("map-info").textContent = e.message; }
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
    for (const id of [...bodyKeys, ...shapeKeys, "spin", ...motionKeys, ...dampingKeys, "table_friction", "slip_speed",
                      "rolling_resistance", ...answerKeys])
      $(id).addEventListener("input", () => schedule(true));
    for (const id of ["driven", "contact", "friction_law", "tip_material", "table_material", "air"])
      $(id).addEventListener("change", () => { showTable(); schedule(true); });
    $("spin-unit").addEventListener("change", () => {
      const v = Number($("spin").value);
      $("spin").value = Number(($("spin-unit").value === "rpm" ? v * rpm : v / rpm).toPrecision(12));
      schedule(false);
    });
    $("theta0-unit").addEventListener("change", () => {
      showTilt(readTilt($("theta0-unit").value === "deg" ? "rad" : "deg"));
      schedule(false);
    });
    for (const w of ["x", "y"]) $(`map-${w}`).addEventListener("change", () => { setupMap($(`map-${w}`).value, w); drawMap(); });
    for (const id of ["map-x0", "map-x1", "map-y0", "map-y1", "map-n", "map-model"]) $(id).addEventListener("change", drawMap);
    $("map").addEventListener("click", mapClick);
    try { showVerdict(); } catch (e) { $("error").textContent = e.message; }
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
    window.heavytopExplorer = { toml, map, lifetime, body, view, putFile, addMesh, config: readInputs, options: readOptions,
                                stabilityText, current: () => current, open, benchmark, loadStart };
    try { start(); }
    catch (e) {  // never a page that does not start: the error in one line, the page ready
      $("error").textContent = `heavytop: error: the page could not start: ${e.message}`;
      document.body.dataset.ready = "1";
    }
  });
})();
