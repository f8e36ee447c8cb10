// The dashboard page (docs/dashboard.md): long-polls /api/updates for everything it shows, fetches
// the latest frame when a newer one exists, and posts the operator's actions to /api/action. Every
// request carries the user's token; the dashboard passes it on, and the server's roles decide.
"use strict";

const $ = (id) => document.getElementById(id);
const MIN_POLL_MS = 500;     // at most 2 answers a second per page, however often data changes
const CHART_EVERY_MS = 2000; // charts redrawn at most every 2 s: a page should cost the cores it
                             // may share with the solver (a browser beside the server) next to nothing
const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"];
const DASHES = [[], [6, 3], [2, 2], [8, 3, 2, 3]];

const ui = {
  token: sessionStorage.getItem("cascade-token") || "",
  role: null, selected: null, version: -1, frameSeq: -1, frameKey: "",
  chartKey: "", chartMembers: "", chartsDrawn: 0, controller: null,
};
// For tests and measurements (tests/browser/test_dashboard.py): the charts, and each frame shown
// with the wall time it reached the page.
window.dashboard = { charts: {}, frames: [], updates: 0, ui };

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
const headers = () => (ui.token ? { Authorization: "Bearer " + ui.token } : {});
const short = (name) => name.replace(/^simulations\//, "");
const fmt = (x, digits = 4) => (x === null || x === undefined ? "–" : Number(x).toPrecision(digits));

// ---- the long poll ------------------------------------------------------------------------------

async function pollForever() {
  for (;;) {
    const started = Date.now();
    ui.controller = new AbortController();
    try {
      const query = new URLSearchParams({ version: ui.version });
      if (ui.selected) {
        query.set("selected", ui.selected);
        query.set("field", $("field").value);
        query.set("camera", $("camera").value);
      }
      const response = await fetch("/api/updates?" + query, { headers: headers(), signal: ui.controller.signal });
      const body = await response.json();
      if (!response.ok) {
        showRefusal(response.status, body);
        ui.version = -1;
        await sleep(1000);
        continue;
      }
      ui.version = body.version;
      window.dashboard.updates += 1;
      render(body);
    } catch (error) {
      if (error.name !== "AbortError") {
        showConnection(false, "dashboard unreachable — reconnecting");
        ui.version = -1;
        await sleep(1000);
      }
    }
    await sleep(Math.max(0, MIN_POLL_MS - (Date.now() - started)));
  }
}

// Ends the current long poll so that the next one asks at once (a new selection, token or view).
function wake() {
  ui.version = -1;
  if (ui.controller) ui.controller.abort();
}

function showConnection(up, text) {
  const el = $("connection");
  setText(el, text);
  el.classList.toggle("down", !up);
}

function showRefusal(status, body) {
  if (status === 503) {
    showConnection(false, "server unreachable — reconnecting");
  } else {
    showConnection(true, "server connected");
    $("role").textContent = `${body.code}: ${body.error}`;
    setControls(false, null);
  }
}

// ---- what the page shows ------------------------------------------------------------------------

function render(body) {
  if (body.reachable === false) {
    const since = new Date(body.since * 1000).toLocaleTimeString();
    showConnection(false, `server unreachable — reconnecting (since ${since}): ${body.error}`);
  } else {
    showConnection(true, body.reachable ? "server connected" : "connecting…");
  }
  ui.role = body.role;
  setText($("role"), body.role === "operator" ? "operator" : "viewer: read only");

  const sims = body.simulations;
  const names = sims.map((s) => s.name);
  if (!names.includes(ui.selected)) {
    ui.selected = names.length ? names[0] : null;
    ui.frameSeq = -1;
    if (ui.selected) wake();
  }
  renderList(sims);
  if ($("no-simulations").hidden !== sims.length > 0) $("no-simulations").hidden = sims.length > 0;
  if ($("selected").hidden !== !ui.selected) $("selected").hidden = !ui.selected;
  const sim = sims.find((s) => s.name === ui.selected);
  if (!sim) return;
  renderStatus(sim, sims);
  setControls(body.role === "operator" && body.reachable === true, sim);
  renderFrame(body.frame);
  const chartKey = JSON.stringify(Object.entries(body.family).map(([name, h]) =>
    [name, h.times.length && h.times[h.times.length - 1], h.events.length, h.rain.length && h.rain[h.rain.length - 1]]));
  const members = Object.keys(body.family).join(" ");
  if (chartKey !== ui.chartKey && (members !== ui.chartMembers || Date.now() - ui.chartsDrawn >= CHART_EVERY_MS)) {
    ui.chartMembers = members;  // a new selection or branch is drawn at once
    ui.chartKey = chartKey;
    ui.chartsDrawn = Date.now();
    renderCharts(body.family, sims);
  }
}

// Sets an element's text only when it differs: every change costs the browser a layout, and
// the pages share the machine's cores with the solver when they run beside the server.
function setText(el, text) {
  text = String(text);
  if (el.textContent !== text) el.textContent = text;
}

// Roots first, each followed by its forks (indented), so that branches of one run stand together.
// Rows are rebuilt only when the simulations or their family change; otherwise their cells are
// updated in place.
function renderList(sims) {
  const children = {};
  const known = new Set(sims.map((s) => s.name));
  for (const s of sims) {
    const parent = known.has(s.parent) ? s.parent : "";
    (children[parent] = children[parent] || []).push(s);
  }
  const rows = [];
  const add = (s, depth) => {
    rows.push([s, depth]);
    for (const c of children[s.name] || []) add(c, depth + 1);
  };
  for (const s of children[""] || []) add(s, 0);

  const tbody = $("sim-list");
  const shape = JSON.stringify(rows.map(([s, depth]) => [s.name, s.case, s.parent, s.fork_step, depth]));
  if (tbody.dataset.shape !== shape) {
    tbody.dataset.shape = shape;
    tbody.replaceChildren(...rows.map(([s, depth]) => {
      const tr = document.createElement("tr");
      tr.dataset.name = s.name;
      tr.dataset.parent = s.parent || "";
      const mark = depth ? `<span class="fork-mark">${"&nbsp;&nbsp;".repeat(depth)}↳ </span>` : "";
      const fork = s.parent ? ` <span class="fork-mark">(fork of ${short(s.parent)} at step ${s.fork_step})</span>` : "";
      tr.innerHTML = `<td>${mark}<b></b> <span class="quiet"></span>${fork}</td>` +
        '<td class="state"></td><td class="num"></td><td class="num"></td><td class="num"></td>';
      tr.querySelector("b").textContent = short(s.name);       // names and case names as text, not HTML
      tr.querySelector(".quiet").textContent = s.case;
      tr.addEventListener("click", () => select(s.name));
      return tr;
    }));
  }
  rows.forEach(([s], k) => {
    const tr = tbody.rows[k];
    tr.classList.toggle("selected", s.name === ui.selected);
    const cells = tr.cells;
    setText(cells[1], s.state);
    if (cells[1].className !== "state-" + s.state) cells[1].className = "state-" + s.state;
    setText(cells[2], fmt(s.time, 6));
    setText(cells[3], fmt(s.steps_per_second, 4));
    setText(cells[4], fmt(s.rain_mm_h, 4));
  });
}

function select(name) {
  ui.selected = name;
  ui.frameSeq = -1;
  ui.chartsDrawn = 0;
  ui.chartKey = "";
  wake();
}

function renderStatus(sim, sims) {
  setText($("selected-name"), short(sim.name) + " — " + sim.case);
  const state = $("state");
  setText(state, sim.state);
  if (state.className !== "state-" + sim.state) state.className = "state-" + sim.state;
  setText($("time"), fmt(sim.time, 6));
  setText($("end-time"), fmt(sim.end_time, 6));
  setText($("step"), sim.step);
  setText($("speed"), fmt(sim.steps_per_second, 4));
  setText($("stage"), sim.stage);
  setText($("particles"), sim.particles);
  const forks = sims.filter((s) => s.parent === sim.name).map((s) => short(s.name));
  setText($("family-note"), (sim.parent ? `fork of ${short(sim.parent)} at step ${sim.fork_step}. ` : "") +
    (forks.length ? `forks: ${forks.join(", ")}` : ""));
  const failed = sim.state === "FAILED";
  if ($("failure").hidden === failed) $("failure").hidden = !failed;
  setText($("failure"), failed ? "FAILED: " + sim.failure_reason : "");
  if (document.activeElement !== $("rain-input") && $("rain-input").dataset.shown !== String(sim.rain_mm_h)) {
    $("rain-input").dataset.shown = sim.rain_mm_h;
    $("rain-input").value = Number(sim.rain_mm_h.toPrecision(6));  // 7.2, not 7.199999999999999
  }
  if (document.activeElement !== $("ponding-input") && $("ponding-input").dataset.shown !== String(sim.ponding_p_max)) {
    $("ponding-input").value = $("ponding-input").dataset.shown = sim.ponding_p_max;
  }
}

// A viewer's page has every control disabled (the server would refuse them anyway); an operator's
// has those that the state allows.
function setControls(operator, sim) {
  $("controls").disabled = !operator;
  if (!operator || !sim) return;
  $("start").disabled = sim.state !== "CREATED";
  $("pause").disabled = sim.state !== "RUNNING";
  $("resume").disabled = sim.state !== "PAUSED";
}

async function renderFrame(frame) {
  if (!frame) return;
  const info = $("frame-info");
  if (frame.error) setText(info, frame.error);
  if (!frame.seq || frame.seq === ui.frameSeq) return;
  const key = `${ui.selected}|${frame.field}|${frame.camera}|${frame.seq}`;
  if (key === ui.frameKey) return;
  ui.frameKey = key;
  const query = new URLSearchParams({ sim: ui.selected, field: frame.field, camera: frame.camera });
  const response = await fetch("/api/frame?" + query, { headers: headers() });
  if (!response.ok) return;
  const url = URL.createObjectURL(await response.blob());
  const img = $("frame");
  const old = img.src;
  img.onload = () => {
    if (old.startsWith("blob:")) URL.revokeObjectURL(old);
    window.dashboard.frames.push({ step: frame.step, time: frame.time, received: frame.received, shown: Date.now() / 1000 });
    if (window.dashboard.frames.length > 500) window.dashboard.frames.shift();
  };
  img.src = url;
  ui.frameSeq = frame.seq;
  const range = frame.units ? ` ${fmt(frame.range[0], 3)} to ${fmt(frame.range[1], 3)} ${frame.units}` : "";
  info.textContent = `t = ${fmt(frame.time, 6)} s, step ${frame.step}, ${frame.field}${range}` +
    (frame.error ? ` (${frame.error})` : "");
}

// ---- charts (Chart.js 3, from Debian's libjs-chart.js) ---------------------------------------------

function makeChart(id, type, yTitle, extra = {}) {
  return new Chart($(id), {
    type,
    data: { datasets: [] },
    options: Object.assign({
      animation: false, parsing: false, normalized: true, maintainAspectRatio: false,
      scales: { x: { type: "linear", title: { display: true, text: "t (s)" } },
                y: { title: { display: true, text: yTitle } } },
      elements: { point: { radius: 0 }, line: { borderWidth: 1.5 } },
      plugins: { legend: { labels: { boxWidth: 12 } } },
    }, extra),
  });
}

function chartsReady() {
  const c = window.dashboard.charts;
  if (c.probes) return c;
  c.probes = makeChart("probes-chart", "line", "probe value");
  c.rain = makeChart("rain-chart", "line", "rain (mm/h)");
  c.events = makeChart("events-chart", "scatter", "", {
    plugins: {
      legend: { display: false },
      tooltip: { callbacks: { label: (item) => `${item.raw.sim} t = ${fmt(item.raw.x, 6)} s: ${item.raw.kind}: ${item.raw.message}` } },
    },
  });
  return c;
}

function renderCharts(family, sims) {
  const charts = chartsReady();
  const branches = Object.keys(family);
  const colour = (k) => COLOURS[k % COLOURS.length];

  charts.probes.data.datasets = branches.flatMap((name, k) => family[name].probe_names.map((probe, j) => ({
    label: `${short(name)}: ${probe}`, borderColor: colour(k), backgroundColor: colour(k), borderDash: DASHES[j % DASHES.length],
    data: family[name].times.map((t, i) => ({ x: t, y: family[name].values[i][j] })),
  })));
  charts.rain.data.datasets = branches.map((name, k) => ({
    label: short(name), borderColor: colour(k), backgroundColor: colour(k), stepped: true,
    data: family[name].rain.map(([t, mm]) => ({ x: t, y: mm })),
  }));

  // Events on a timeline: one row per kind, one colour per branch; the table lists them in order.
  const kinds = [...new Set(branches.flatMap((name) => family[name].events.map((e) => e.kind)))].sort();
  charts.events.options.scales.y = {
    type: "linear", min: -0.5, max: Math.max(kinds.length - 0.5, 0.5), reverse: true,
    afterBuildTicks: (axis) => { axis.ticks = kinds.map((_, i) => ({ value: i })); },
    ticks: { autoSkip: false, callback: (v) => kinds[v] || "" },
  };
  charts.events.data.datasets = branches.map((name, k) => ({
    label: short(name), borderColor: colour(k), backgroundColor: colour(k), pointRadius: 4,
    data: family[name].events.map((e) => ({ x: e.time, y: kinds.indexOf(e.kind), sim: short(name), kind: e.kind, message: e.message })),
  }));
  for (const chart of Object.values(charts)) chart.update("none");

  const rows = branches.flatMap((name) => family[name].events.map((e) => [name, e]))
    .sort((a, b) => b[1].time - a[1].time || b[1].wall_time - a[1].wall_time).slice(0, 40);
  $("event-list").replaceChildren(...rows.map(([name, e]) => {
    const tr = document.createElement("tr");
    for (const [text, cls] of [[fmt(e.time, 6), "num"], [short(name), ""], [e.kind, ""], [e.message, ""], [e.caller, ""]]) {
      const td = document.createElement("td");
      td.textContent = text;
      td.className = cls;
      tr.appendChild(td);
    }
    return tr;
  }));
}

// ---- the operator's actions ---------------------------------------------------------------------

async function act(payload) {
  const result = $("action-result");
  result.textContent = "…";
  result.classList.remove("error");
  try {
    const response = await fetch("/api/action", {
      method: "POST",
      headers: Object.assign({ "Content-Type": "application/json" }, headers()),
      body: JSON.stringify(Object.assign({ simulation: ui.selected }, payload)),
    });
    const body = await response.json();
    result.textContent = response.ok ? body.result : `${body.code}: ${body.error}`;
    result.classList.toggle("error", !response.ok);
  } catch (error) {
    result.textContent = "the dashboard did not answer: " + error;
    result.classList.add("error");
  }
  wake();
}

function setUp() {
  for (const id of ["start", "pause", "resume", "checkpoint"]) $(id).addEventListener("click", () => act({ action: $(id).dataset.action }));
  $("rain-set").addEventListener("click", () => act({ action: "rain", intensity_mm_h: $("rain-input").value }));
  $("factor-set").addEventListener("click", () => act({ action: "rain_factor", factor: $("factor-input").value }));
  $("ponding-set").addEventListener("click", () => act({ action: "ponding", p_max: $("ponding-input").value }));
  $("fork").addEventListener("click", () => act({ action: "fork", id: $("fork-id").value, factor: $("fork-factor").value }));
  $("field").addEventListener("change", wake);
  $("camera").addEventListener("change", wake);
  $("token").value = ui.token;
  $("signin-form").addEventListener("submit", (event) => {
    event.preventDefault();
    ui.token = $("token").value.trim();
    sessionStorage.setItem("cascade-token", ui.token);
    wake();
  });
  pollForever();
}

setUp();
