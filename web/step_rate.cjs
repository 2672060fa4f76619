// The page's integration steps per second (web/README.md, "Runs that do not end"): the core's
// runs in Node, each stopped by --max-steps N, timed by the wall clock; the page's step budget
// (kPageMaxSteps, web/heavytop_wasm.cpp) is chosen from the slowest.
//   NODE_PATH=/usr/share/nodejs node web/step_rate.cjs build/web/heavytop-core.js [N] [REPEATS]
const fs = require("fs");
const path = require("path");
const [corePath, stepsArg, repeatsArg] = process.argv.slice(2);
const steps = Number(stepsArg || 200000), repeats = Number(repeatsArg || 3);
const toy = "[body]\nA = 4.35e-05\nB = 4.35e-05\nC = 1.2e-05\nmass = 0.06\nlength = 0.025\n[motion]\nspin = 200.0\ntheta0 = 0.05\n";
const examples = path.join(__dirname, "..", "examples");
// The page's runs: auto's choice for the toy top, conservative and damped, DOPRI5 (the answer's
// run) and DOP853, and a table's (examples/tippe-top.toml: DOP853 with the contact's forces). The
// integrator that ran is the one the failure names.
const cases = [
  ["toy top, auto", toy, []],
  ["toy top, dopri5", toy, ["--integrator", "dopri5"]],
  ["toy top, dop853", toy, ["--integrator", "dop853"]],
  ["damped toy top, auto", toy + "[damping]\naxial = 1e-9\ntransverse = 1e-9\n", []],
  ["damped toy top, dopri5 (lifetime's run)", toy + "[damping]\naxial = 1e-9\ntransverse = 1e-9\n", ["--integrator", "dopri5"]],
  ["tippe-top.toml on its table, auto", fs.readFileSync(path.join(examples, "tippe-top.toml"), "utf8"), []],
];
globalThis.createHeavytopCore = require(path.resolve(corePath));
createHeavytopCore().then((core) => {
  const run = (toml, extra) => {
    const args = new core.StringList();
    for (const a of ["--t-end", "1e9", "--samples", "11", "--max-steps", String(steps), ...extra]) args.push_back(a);
    const t0 = process.hrtime.bigint();
    const r = core.simulate(toml, args);
    const ms = Number(process.hrtime.bigint() - t0) / 1e6;
    args.delete();
    return { ms, status: r.status, message: r.message };
  };
  run(toy, []);  // V8 compiles each function at its first call
  const out = {};
  for (const [name, toml, extra] of cases) {
    const times = [];
    let last;
    for (let i = 0; i < repeats; i++) { last = run(toml, extra); times.push(last.ms); }
    times.sort((a, b) => a - b);
    const ms = times[Math.floor(times.length / 2)];
    // Stopped by the limit, else the figure is not a step's.
    const stopped = last.status === 1 && last.message.includes(`max_steps = ${steps} `);
    out[name] = stopped ? { integrator: last.message.split(":")[2].trim(), us_per_step: Number(((1000 * ms) / steps).toPrecision(3)),
                            steps_per_s: Math.round((1000 * steps) / ms) }
                        : { error: `not stopped by --max-steps ${steps}: exit ${last.status} ${last.message}` };
  }
  // stability's answer (DOPRI5 with the tilt watched): the toy top below its critical spin, which
  // nutates to 1.45 rad and never passes --max-tilt 2, stopped by --max-steps (when stability takes it).
  const name = "stability's answer, toy top at 100 rad/s, --max-tilt 2";
  const times = [];
  let answer;
  for (let i = 0; i < repeats; i++) {
    const args = new core.StringList();
    for (const a of ["--horizon", "1e9", "--max-tilt", "2", "--max-steps", String(steps)]) args.push_back(a);
    const t0 = process.hrtime.bigint();
    const r = core.stability(toy.replace("spin = 200.0", "spin = 100.0"), args, "json");
    times.push(Number(process.hrtime.bigint() - t0) / 1e6);
    args.delete();
    answer = r.status === 0 ? JSON.parse(new TextDecoder().decode(r.output)).answer : { reason: r.message };
  }
  times.sort((a, b) => a - b);
  out[name] = (answer.reason || "").includes(`max_steps = ${steps} `)
    ? { integrator: "dopri5", us_per_step: Number(((1000 * times[Math.floor(repeats / 2)]) / steps).toPrecision(3)) }
    : { error: `not stopped by --max-steps ${steps}: ${answer.reason}` };
  console.log(JSON.stringify({ steps, repeats, median_of: repeats, cases: out }, null, 1));
});
