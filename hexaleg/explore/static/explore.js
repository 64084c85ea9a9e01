// hexaleg explore: sliders -> GET /api/evaluate -> numbers, requirements, chart, stance.
// Plain JavaScript, no library. Each redraw is timed with performance marks: "redraw"
// measures run from the slider's input event to the page drawn with its answer.
"use strict";

const explorer = {loaded: null, answer: null, reach: null, cloud: null, redraws: 0, exact: {},
                  pending: false, inFlight: false, view: {yaw: -0.6, pitch: 0.45}};
window.explorer = explorer;

function value(answer, key) {
  return key.split(".").reduce((o, k) => (o === null || o === undefined ? o : o[k]), answer);
}

function slider(parent, key, label, low, high, start, step) {
  const row = document.createElement("label");
  const input = document.createElement("input");
  Object.assign(input, {type: "range", min: low, max: high, step: step, value: start, id: key});
  const out = document.createElement("output");
  row.append(label, input, out);
  parent.append(row);
  const show = () => { out.textContent = Number(input.value).toPrecision(3); };
  input.addEventListener("input", () => { delete explorer.exact[key]; show(); changed(); });
  show();
  explorer.exact[key] = start;  // not moved: the loaded value, not the range input's rounding
  return input;
}

const LOADED_MOTOR = "__loaded__";  // the design file's own motor, not a catalog entry

function motorChoice(parent, joint, loaded) {
  const row = document.createElement("label");
  const select = document.createElement("select");
  select.id = "motor_" + joint;
  const options = [["", "ratings only (no motor model)"]];
  const mine = loaded.values.actuators[joint];
  if (mine === null && loaded.has_actuators) options.push([LOADED_MOTOR, "the design file's motor"]);
  for (const m of loaded.catalog) {
    options.push([m.name, `${m.name} (${m.peak_torque} / ${m.continuous_torque} N·m, ${m.mass} kg)`]);
  }
  for (const [v, text] of options) {
    const o = document.createElement("option");
    o.value = v; o.textContent = text;
    select.append(o);
  }
  select.value = motorStart(loaded, joint);
  select.addEventListener("change", () => {  // a motor model needs a motor at every joint type
    if (select.value !== "") {
      for (const other of ["root", "hip", "knee"]) {
        const choice = document.getElementById("motor_" + other);
        if (choice.value === "") choice.value = select.value;
      }
    }
    changed();
  });
  row.append(joint, select);
  parent.append(row);
}

function motorStart(loaded, joint) {
  const mine = loaded.values.actuators[joint];
  return mine !== null ? mine : loaded.has_actuators ? LOADED_MOTOR : "";
}

function heading(parent, text) {
  const h = document.createElement("h2");
  h.textContent = text;
  parent.append(h);
  return h;
}

function buildControls(loaded) {
  const c = document.getElementById("controls");
  const v = loaded.values;
  const s = loaded.sliders;
  heading(c, "legs [m]");
  for (const key of ["l1", "l2", "l3"]) slider(c, key, s[key][2], s[key][0], s[key][1], v[key], "any");
  heading(c, "nominal posture [rad]");  // within the stance limits
  const p = loaded.posture;
  slider(c, "theta2", "hip θ2", p.theta2[0], p.theta2[1], v.nominal_angles[1], "any");
  slider(c, "theta3", "knee θ3", p.theta3[0], p.theta3[1], v.nominal_angles[2], "any");
  postureJob(c, loaded);
  const body = ["body_length", "body_width"].filter((key) => key in s);  // not a file's body
  if (body.length) heading(c, "body [m]");
  for (const key of body) slider(c, key, s[key][2], s[key][0], s[key][1], v[key], "any");
  heading(c, "payload");
  const leg = v.l1 + v.l2 + v.l3;  // the ranges scale with the robot: 1 m legs, 50 kg
  slider(c, "payload", "mass [kg]", 0, Math.max(50 * leg, 2 * v.payload), v.payload, "any");
  slider(c, "payload_x", "at x [m]", -v.body_length / 2, v.body_length / 2, v.payload_at[0], "any");
  slider(c, "payload_y", "at y [m]", -v.body_width / 2, v.body_width / 2, v.payload_at[1], "any");
  heading(c, "gait (tripod)");
  slider(c, "speed", "speed [m/s]", 0.02 * leg, Math.max(leg, 2 * v.speed), v.speed, "any");
  slider(c, "stride", "stride [m]", 0.01 * leg, Math.max(0.6 * leg, 2 * v.stride), v.stride,
         "any");
  slider(c, "step_height", "step height [m]", 0.01 * leg, Math.max(0.3 * leg, 2 * v.step_height),
         v.step_height, "any");
  const slope = loaded.slope_deg;  // the ground rising along the heading: + uphill, − downhill
  slider(c, "slope_deg", "walking slope [°]", slope[0], slope[1], v.slope_deg, "any");
  if (loaded.robot) {  // an imported robot: its motors are its file's ratings
    const name = loaded.robot.split("/").pop();
    heading(c, "robot " + name + ": body, masses and ratings the file's").title = loaded.robot;
    return;
  }
  heading(c, "motors (peak / continuous torque, mass)");
  for (const joint of ["root", "hip", "knee"]) motorChoice(c, joint, loaded);
}

function postureJob(parent, loaded) {  // "best posture": a job whose answer moves the sliders
  const row = document.createElement("label");
  const select = document.createElement("select");
  select.id = "posture_objective";
  for (const [sense, names] of Object.entries(loaded.objectives)) {
    for (const name of names) {
      const o = document.createElement("option");
      o.value = sense + "=" + name;
      o.textContent = sense + " " + name.replaceAll("_", " ");
      select.append(o);
    }
  }
  select.value = loaded.posture_objective;
  row.append("for", select);
  const box = document.createElement("div");
  box.className = "job";
  box.dataset.kind = "posture";
  const button = document.createElement("button");
  button.type = "button";
  button.textContent = "best posture";
  if (!loaded.posture_search) {  // a robot file stands within its own limits: slid, not searched
    button.disabled = true;
    button.title = "a robot file's posture is its own: slide it (hexaleg posture refuses it)";
  }
  const bar = document.createElement("progress");
  Object.assign(bar, {max: 1, value: 0});
  const state = document.createElement("span");
  state.className = "job-state";
  box.append(button, bar, state);
  parent.append(row, box);
}

function query() {
  const get = (id) => id in explorer.exact ? String(explorer.exact[id])
    : document.getElementById(id).value;  // loaded or set by a job: exact, not the slider's rounding
  const v = explorer.loaded.values;
  const params = new URLSearchParams();
  for (const key of ["l1", "l2", "l3", "body_length", "body_width", "payload", "stride",
                     "speed", "step_height"]) {
    if (document.getElementById(key)) params.set(key, get(key));
  }
  const slope = get("slope_deg");  // sent once moved: else the loaded conditions' grounds
  if (Number(slope) !== v.slope_deg) params.set("slope_deg", slope);
  params.set("theta2", get("theta2"));
  params.set("theta3", get("theta3"));
  params.set("payload_at", [get("payload_x"), get("payload_y"), v.payload_at[2]].join(","));
  for (const joint of ["root", "hip", "knee"]) {
    if (!document.getElementById("motor_" + joint)) continue;
    const motor = get("motor_" + joint);
    if (motor !== LOADED_MOTOR) params.set("actuators." + joint, motor);
  }
  return params.toString();
}
explorer.query = query;

function changed() {
  performance.mark("input-" + (explorer.redraws + 1));
  if (explorer.inFlight) { explorer.pending = true; return; }
  evaluate();
}

async function evaluate() {
  explorer.inFlight = true;
  explorer.pending = false;
  const number = ++explorer.redraws;
  const start = performance.getEntriesByName("input-" + number).length ? "input-" + number : null;
  const status = document.getElementById("status");
  try {
    const answer = await fetch("api/evaluate?" + query()).then((r) => r.json().then(
      (body) => ({ok: r.ok, body: body})));
    const results = document.getElementById("results");
    if (!answer.ok) {  // what is shown is the last design measured, not the sliders'
      status.textContent = answer.body.error + " (the numbers shown are of the last design measured)";
      status.className = "error";
      results.classList.add("stale");
      document.getElementById("pictures").classList.add("stale");
    } else {
      results.classList.remove("stale");
      document.getElementById("pictures").classList.remove("stale");
      explorer.answer = answer.body;
      await loadReach();
      draw(answer.body);
      status.textContent = (answer.body.error ||
        "measured in " + answer.body.evaluate_ms.toFixed(0) + " ms, " +
        walkedOn(answer.body.grounds)) + gaitHint(answer.body);
      status.title = answer.body.grounds.map((g) => g.text).join("; ");
      status.className = answer.body.error ? "error" : "";
    }
  } catch (err) {
    status.textContent = "the explorer does not answer: " + err;
    status.className = "error";
  }
  performance.mark("drawn-" + number);
  if (start) performance.measure("redraw", start, "drawn-" + number);
  explorer.inFlight = false;
  if (explorer.pending) evaluate();
}

async function loadReach() {  // only while it is shown: a redraw without it does not pay it
  explorer.reach = document.getElementById("reach").checked
    ? (await fetch("api/reach?" + query()).then((r) => r.json())).reach : null;
}

function draw(answer) {
  drawNumbers(answer);
  drawStructure(answer.structure);
  drawRequirements(answer.requirements, answer.requirements_conditions);
  drawExtremes(answer.extremes);
  drawScene(answer);
  drawChart();
}

function drawNumbers(answer) {
  const body = document.querySelector("#numbers tbody");
  body.replaceChildren();
  for (const {key, label, text, unit} of answer.rows) {  // the rows as the server declares them
    const x = value(answer, key);
    const tr = document.createElement("tr");
    tr.dataset.key = key;
    tr.dataset.value = x === null || x === undefined ? "" : String(x);
    const why = answer.limited_by[key] ? answer.limited_by[key].description
      : (answer.unmeasured[key] || "");
    const shown = x === null || x === undefined ? "—" : Number(x).toPrecision(4);
    for (const [text, cls] of [[label, ""], [shown + " " + unit, "value"], [why, "why"]]) {
      const td = document.createElement("td");
      td.textContent = text;
      if (cls) td.className = cls;
      tr.append(td);
    }
    tr.firstChild.title = text;  // what it is, with its source
    body.append(tr);
  }
}

function drawStructure(structure) {  // the legs' tubes, from the same evaluation
  const box = document.getElementById("structure");
  box.hidden = !structure;
  if (!structure) return;
  const body = box.querySelector("tbody");
  body.replaceChildren();
  const mm = (x) => (1000 * x).toFixed(1) + " mm";
  const rows = Object.entries(structure.tubes).map(([segment, t]) => [segment,
    "⌀ " + mm(t.outer_diameter) + ", wall " + mm(t.wall) + ", " + t.mass.toFixed(3) + " kg",
    segment]);
  const w = structure.worst;
  rows.push(["worst stress ratio", structure.worst_ratio.toFixed(3) + " (" + w.leg + " " +
    w.segment + ", " + w.case + ")", "worst_ratio"]);
  rows.push(["foot deflection", mm(structure.deflection) + " (limit " +
    mm(structure.deflection_limit) + ")", "deflection"]);
  for (const [label, text, key] of rows) {
    const tr = document.createElement("tr");
    tr.dataset.key = key;
    for (const cell of [label, text]) {
      const td = document.createElement("td");
      td.textContent = cell;
      tr.append(td);
    }
    body.append(tr);
  }
  const sizing = structure.sizing;
  box.querySelector("p").textContent = structure.material + (sizing ? ", sized in " +
    sizing.iterations + " rounds" + (sizing.found ? "" : ": no tubes of the grid hold, the " +
    "strongest shown") : "") + (structure.feasible ? "" : " — OVER its strength or deflection limit");
  box.classList.toggle("failed", !structure.feasible);
}

function conditionText(c) {  // a number, a triple, or records (the grounds) field by field
  const shown = (x) => x === null ? "none" : typeof x === "number" ? Number(x.toPrecision(4))
    : Array.isArray(x) ? x.map((y) => typeof y === "number" ? Number(y).toPrecision(3)
      : shown(y)).join(x.every((y) => typeof y === "number") ? ", " : "; ")
    : typeof x === "object" ? Object.entries(x).map(([k, v]) => k + " " + shown(v)).join(", ")
    : x;
  return c.name + " " + shown(c.shown) + " (required " + shown(c.required) + ")";
}

function drawRequirements(checks, unlike) {
  const box = document.getElementById("requirements");
  box.hidden = !checks;
  if (!checks) return;
  const note = box.querySelector("p");  // the checks read the numbers shown: say under what
  note.textContent = unlike.length ? "checked under the sliders' conditions, not the " +
    "requirements': " + unlike.map(conditionText).join("; ") : "";
  note.hidden = !unlike.length;
  const list = box.querySelector("ul");
  list.replaceChildren();
  for (const c of checks) {
    const li = document.createElement("li");
    li.className = c.met ? "met" : "failed";
    li.dataset.name = c.name;
    const got = c.value === null || c.value === undefined ? "" : " — " + Number(c.value).toPrecision(4);
    const why = !c.met && c.limited_by ? " (" + (c.limited_by.description || c.limited_by) + ")" : "";
    li.textContent = (c.met ? "✓ " : "✗ ") + c.text + got + why;
    list.append(li);
  }
}

function project(p, view, scale, centre) {
  const cy = Math.cos(view.yaw), sy = Math.sin(view.yaw);
  const cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
  const x = cy * p[0] - sy * p[1];
  const y = sy * p[0] + cy * p[1];
  return [centre[0] + scale * x, centre[1] - scale * (cp * p[2] - sp * y)];
}

function walkedOn(grounds) {  // one ground in words; several (up, down, across) in short
  if (grounds.length === 1) return "walking on " + grounds[0].text;
  const ways = grounds.map((g) => (/walked ([^,]+)/.exec(g.text) || [null, g.text])[1]);
  return "walking " + ways.join(", ") + " a " + Math.abs(grounds[0].slope_deg).toPrecision(3) +
    "° slope (each number the worst)";
}

function gaitHint(answer) {  // a gait too big for the robot: say what to change
  const walking = answer.limited_by.max_speed || answer.limited_by.walking_payload_capacity;
  const why = walking ? walking.description || "" : "";
  return /out of reach|no stride/.test(why)
    ? " — the gait is too big for this robot: shorten the stride or the step height (sliders, or the design file's [gait])"
    : "";
}

function legColour(u) {
  if (u === null || u === undefined) return "#999";
  return u > 1 ? "#d03030" : u > 0.8 ? "#e0a000" : "#2e8b57";
}

function drawScene(answer) {
  const canvas = document.getElementById("scene");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const shown = shownExtreme(answer);
  const chains = shown ? shown.chains : answer.stance.chains;
  document.getElementById("pose-note").textContent = shown ? shown.name + " " +
    shown.value.toFixed(4) + unitOf(shown.name) + ", stopped by " + shown.limited_by : "";
  const span = Math.max(...chains.flat().map((p) => Math.hypot(p[0], p[1], p[2])));
  const scale = 0.42 * Math.min(canvas.width, canvas.height) / span;
  const centre = [canvas.width / 2, canvas.height * 0.62];
  const at = (p) => project(p, explorer.view, scale, centre);
  ctx.strokeStyle = "#dde";
  for (let i = -4; i <= 4; i++) {  // ground grid, z = 0
    const d = span * i / 4;
    for (const [a, b] of [[[d, -span, 0], [d, span, 0]], [[-span, d, 0], [span, d, 0]]]) {
      ctx.beginPath(); ctx.moveTo(...at(a)); ctx.lineTo(...at(b)); ctx.stroke();
    }
  }
  const roots = chains.map((c) => c[0]);
  const mid = roots.reduce((m, p) => [m[0] + p[0] / 6, m[1] + p[1] / 6, m[2] + p[2] / 6], [0, 0, 0]);
  roots.sort((a, b) => Math.atan2(a[1] - mid[1], a[0] - mid[0]) - Math.atan2(b[1] - mid[1], b[0] - mid[0]));
  ctx.fillStyle = "rgba(90,110,140,0.35)"; ctx.strokeStyle = "#567";
  ctx.beginPath();
  roots.forEach((p, i) => (i ? ctx.lineTo(...at(p)) : ctx.moveTo(...at(p))));
  ctx.closePath(); ctx.fill(); ctx.stroke();
  if (document.getElementById("reach").checked && explorer.reach) {
    ctx.fillStyle = "rgba(40,90,200,0.35)";
    explorer.reach.forEach((points, leg) => {
      const z = answer.stance.chains[leg][answer.stance.chains[leg].length - 1][2];
      for (const [x, y] of points) {
        const [u, v] = at([x, y, z]);
        ctx.fillRect(u - 1, v - 1, 2, 2);
      }
    });
  }
  const used = answer.stance.utilisation;
  ctx.lineWidth = 4;
  chains.forEach((chain, leg) => {
    ctx.strokeStyle = legColour(used[leg]);
    ctx.beginPath();
    chain.forEach((p, i) => (i ? ctx.lineTo(...at(p)) : ctx.moveTo(...at(p))));
    ctx.stroke();
    const foot = at(chain[chain.length - 1]);
    ctx.fillStyle = "#333"; ctx.beginPath(); ctx.arc(foot[0], foot[1], 3, 0, 2 * Math.PI); ctx.fill();
    ctx.fillText(answer.stance.legs[leg] + (used[leg] === null ? "" :
      " " + (100 * used[leg]).toFixed(0) + " %"), foot[0] + 5, foot[1] + 12);
  });
  ctx.lineWidth = 1;
}

function unitOf(name) {
  return "xyz".includes(name[0]) && name.length === 2 ? " m" : " rad";
}

function shownExtreme(answer) {
  const name = document.getElementById("pose").value;
  return name ? answer.extremes.find((x) => x.name === name) || null : null;
}

function drawExtremes(extremes) {
  const pose = document.getElementById("pose");
  if (pose.options.length === 1) {
    for (const x of extremes) {
      const o = document.createElement("option");
      o.value = x.name; o.textContent = "the extreme " + x.name;
      pose.append(o);
    }
  }
  const body = document.querySelector("#extremes tbody");
  body.replaceChildren();
  for (const x of extremes) {
    const tr = document.createElement("tr");
    tr.addEventListener("click", () => { pose.value = x.name; drawScene(explorer.answer); });
    for (const text of [x.name, x.value.toFixed(4) + unitOf(x.name), x.limited_by]) {
      const td = document.createElement("td");
      td.textContent = text;
      tr.append(td);
    }
    body.append(tr);
  }
}

function drawChart() {
  const canvas = document.getElementById("chart");
  const ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const answer = explorer.answer;
  const points = explorer.cloud ? explorer.cloud.points : [];
  const v = answer ? {l3_ratio: Number(document.getElementById("l3").value) /
    ["l1", "l2", "l3"].reduce((s, k) => s + Number(document.getElementById(k).value), 0),
    fb: answer.fb, walking_payload_capacity: answer.walking_payload_capacity} : null;
  const panels = [["fb", "FB"], ["walking_payload_capacity", "walking payload [kg]"]];
  panels.forEach(([key, label], i) => {
    const x0 = 40 + i * canvas.width / 2, w = canvas.width / 2 - 55, y0 = 15, h = canvas.height - 45;
    const values = points.map((p) => p[key]).concat(v ? [v[key]] : []).filter((x) => x !== null);
    const highest = Math.max(0, ...values);
    const top = highest > 0 ? highest * 1.1 : 1;  // none above zero: a unit axis, not 1e-9
    const xs = (r) => x0 + w * (r - 0.1) / 0.65, ys = (y) => y0 + h - h * y / top;
    ctx.strokeStyle = "#889"; ctx.strokeRect(x0, y0, w, h);
    ctx.fillStyle = "#333";
    ctx.fillText(label, x0 + 4, y0 + 12);
    ctx.fillText("l3/L 0.1", x0, y0 + h + 14); ctx.fillText("0.75", x0 + w - 20, y0 + h + 14);
    ctx.fillText(String(Number(top.toPrecision(2))), x0 - 36, y0 + 10); ctx.fillText("0", x0 - 12, y0 + h);
    for (const p of points) {
      if (p[key] === null) continue;
      ctx.fillStyle = `hsl(${210 + 120 * p.l1_ratio}, 30%, ${40 + 150 * p.l1_ratio}%)`;
      ctx.fillRect(xs(p.l3_ratio) - 2, ys(p[key]) - 2, 4, 4);
    }
    if (v && v[key] !== null) {
      ctx.fillStyle = "#d00";
      ctx.beginPath(); ctx.arc(xs(v.l3_ratio), ys(v[key]), 5, 0, 2 * Math.PI); ctx.fill();
    }
  });
}

async function pollCloud() {
  const cloud = await fetch("api/cloud").then((r) => r.json());
  explorer.cloud = cloud;
  drawChart();
  const caption = document.getElementById("chart-caption");
  if (!cloud.ready) { setTimeout(pollCloud, 1000); return; }
  caption.textContent = "the study's designs (" + cloud.points.length + ", at coxa ratios " +
    [...new Set(cloud.points.map((p) => Number(p.l1_ratio.toPrecision(3))))].join(", ") +
    "; lighter: longer coxa) and this one (red): tibia ratio l3/L against FB and against " +
    "the walking payload capacity" + (cloud.error ? " — " + cloud.error : "");
}

const JOB_ANSWERS = {
  posture: (a) => "θ2 " + a.best.nominal_angles[1].toFixed(3) + ", θ3 " +
    a.best.nominal_angles[2].toFixed(3) + " rad: " +
    a.best.objective.name.replaceAll("_", " ") + " " + a.best.objective.value.toPrecision(4) +
    " (as posed " + a.yours.objective.value.toPrecision(4) + ")" +
    (a.feasible ? "" : " — no posture meets every requirement"),
  free: (a) => "FB " + a.fb.toPrecision(4) + " with the other five coordinates free" +
    (a.converged ? "" : " (not shown to be the maximum)"),
  decide: (a) => a.best ? "best: l1 " + a.best.design.l1.toPrecision(3) + ", l2 " +
    a.best.design.l2.toPrecision(3) + ", l3 " + a.best.design.l3.toPrecision(3) + " m, " +
    a.best.objective.name + " " + a.best.objective.value.toPrecision(4) +
    (a.feasible ? "" : " (no design met every requirement)") : "no answer",
};

function showJob(box, job) {
  const bar = box.querySelector("progress");
  const state = box.querySelector(".job-state");
  const button = box.querySelector("button");
  box.dataset.state = job.state;
  if (job.state === "none") return;
  if (job.total) { bar.max = job.total; bar.value = job.done; } else bar.removeAttribute("value");
  button.textContent = job.state === "running" ? "stop" : box.dataset.label;
  const seconds = job.elapsed.toFixed(0) + " s";
  state.textContent = job.state === "running" ? (job.total ? job.done + "/" + job.total + ", " : "") +
    seconds : job.state === "done" ? JOB_ANSWERS[job.kind](job.answer) + " (" + seconds +
    (box.dataset.lengths ? ", for l = " + box.dataset.lengths + " m" : "") + ")"
    : job.state + (job.error ? ": " + job.error : "");
  if (job.state === "done") { bar.max = 1; bar.value = 1; }
  if (job.state === "done" && JOB_DONE[job.kind] && box.dataset.applied !== String(job.pid)) {
    box.dataset.applied = String(job.pid);  // once per job: the sliders moved to its answer
    JOB_DONE[job.kind](job.answer);
  }
}

const JOB_DONE = {
  posture: (a) => {  // the sliders moved to the best posture, and the design measured there
    for (const [id, angle] of [["theta2", a.best.nominal_angles[1]],
                               ["theta3", a.best.nominal_angles[2]]]) {
      const input = document.getElementById(id);
      input.value = angle;
      input.nextElementSibling.textContent = Number(input.value).toPrecision(3);
      explorer.exact[id] = angle;  // the range input keeps 15 digits: the query sends them all
    }
    changed();
  },
};

function jobParams(kind) {  // what a job asks beside the design shown: the posture's objective
  return kind === "posture" ? "&" + document.getElementById("posture_objective").value : "";
}

async function pollJob(box) {
  const job = await fetch("api/job?kind=" + box.dataset.kind).then((r) => r.json());
  showJob(box, job);
  if (job.state === "running") setTimeout(() => pollJob(box), 500);
}

async function startOrStopJob(box) {
  const kind = box.dataset.kind;
  const running = box.dataset.state === "running";
  const url = running ? "api/job/stop?kind=" + kind
    : "api/job?kind=" + kind + "&" + query() + jobParams(kind);
  if (!running) {  // the answer is of the design shown now: say which
    box.dataset.lengths = ["l1", "l2", "l3"].map(
      (k) => Number(document.getElementById(k).value).toPrecision(3)).join(", ");
  }
  const r = await fetch(url, {method: "POST"});
  const job = await r.json();
  if (!r.ok) { box.querySelector(".job-state").textContent = job.error; return; }
  showJob(box, job);
  if (job.state === "running") setTimeout(() => pollJob(box), 500);
}

function reset() {
  explorer.exact = {};
  const v = explorer.loaded.values;
  const start = {l1: v.l1, l2: v.l2, l3: v.l3, body_length: v.body_length,
    body_width: v.body_width, theta2: v.nominal_angles[1], theta3: v.nominal_angles[2],
    payload: v.payload, payload_x: v.payload_at[0], payload_y: v.payload_at[1],
    speed: v.speed, stride: v.stride, step_height: v.step_height, slope_deg: v.slope_deg};
  for (const [id, x] of Object.entries(start)) {
    const input = document.getElementById(id);
    if (!input) continue;
    input.value = x;
    input.nextElementSibling.textContent = Number(x).toPrecision(3);
    explorer.exact[id] = x;
  }
  for (const joint of ["root", "hip", "knee"]) {
    const choice = document.getElementById("motor_" + joint);
    if (choice) choice.value = motorStart(explorer.loaded, joint);
  }
  changed();
}

async function save() {
  const out = document.getElementById("saved");
  const r = await fetch("api/save?" + query(), {method: "POST"});
  const body = await r.json();
  out.textContent = r.ok ? "wrote " + body.wrote : body.error;
}

function turnable(canvas) {
  let last = null;
  canvas.addEventListener("pointerdown", (e) => { last = [e.clientX, e.clientY]; });
  window.addEventListener("pointerup", () => { last = null; });
  canvas.addEventListener("pointermove", (e) => {
    if (!last || !explorer.answer) return;
    explorer.view.yaw += (e.clientX - last[0]) * 0.01;
    explorer.view.pitch = Math.min(1.5, Math.max(0, explorer.view.pitch + (e.clientY - last[1]) * 0.01));
    last = [e.clientX, e.clientY];
    drawScene(explorer.answer);
  });
}

async function start() {
  explorer.loaded = await fetch("api/loaded").then((r) => r.json());
  buildControls(explorer.loaded);
  document.getElementById("reset").addEventListener("click", reset);
  document.getElementById("save").addEventListener("click", save);
  turnable(document.getElementById("scene"));
  document.getElementById("pose").addEventListener("change", () => drawScene(explorer.answer));
  document.getElementById("reach").addEventListener("change", async () => {
    await loadReach();
    drawScene(explorer.answer);
  });
  for (const box of document.querySelectorAll(".job")) {
    const button = box.querySelector("button");
    box.dataset.label = button.textContent;
    button.addEventListener("click", () => startOrStopJob(box));
  }
  pollCloud();
  await evaluate();
}
explorer.started = start();
