// The photonfarm dashboard's script: routes by address (/, /jobs/ID, /workers), logs in, and
// follows the coordinator's event streams (server-sent events) to keep each view current.
"use strict";

const state = { csrf: "", streams: [], points: new Map(), epochs: -1, jobId: "" };
const $ = (id) => document.getElementById(id);

function showError(message) {
  $("error").textContent = message || "";
  $("error").hidden = !message;
}

// A JSON request to the coordinator; actions carry the session's CSRF token.
async function api(method, path, body) {
  const headers = { "X-CSRF-Token": state.csrf };
  if (body !== undefined) headers["Content-Type"] = "application/json";
  const response = await fetch(path, {
    method, headers, credentials: "same-origin",
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  const data = await response.json().catch(() => ({}));
  if (!response.ok) {
    const error = new Error(data.error || `${method} ${path}: HTTP ${response.status}`);
    error.status = response.status;
    throw error;
  }
  return data;
}

function closeStreams() {
  for (const stream of state.streams) stream.close();
  state.streams = [];
}

function follow(path, handlers) {
  const stream = new EventSource(path);
  for (const [name, handler] of Object.entries(handlers))
    stream.addEventListener(name, (event) => handler(JSON.parse(event.data)));
  stream.onerror = () => { if (stream.readyState === EventSource.CLOSED) showError("lost the coordinator's event stream; reload"); };
  state.streams.push(stream);
}

const stateName = (s) => (s || "JOB_STATE_UNSPECIFIED").replace("JOB_STATE_", "");
const integratorName = (s) => (s || "").replace("INTEGRATOR_", "").toLowerCase();
const count = (n) => Number(n || 0).toLocaleString("en");
const percent = (x) => (x === undefined || x === null ? "–" : (100 * x).toFixed(2) + "%");
// 1234567 -> "1.23M": photon counts and rates at a glance.
function si(x) {
  let value = Number(x || 0), unit = 0;
  while (value >= 1000 && unit < 4) { value /= 1000; ++unit; }
  return unit === 0 ? String(Math.round(value)) : value.toFixed(value < 10 ? 2 : value < 100 ? 1 : 0) + " kMGT"[unit];
}
const rate = (x) => (x ? si(x) + "/s" : "–");
// A decade's label: 10^d as a number (seconds) or a percentage (relative error).
const decade = (d, scale) => { const v = scale * 10 ** d; return v >= 1 ? String(Math.round(v)) : v.toPrecision(1); };
const measured = (e) => (e && e.rel_mse !== undefined ? Math.sqrt(e.rel_mse) : undefined);

function cell(row, text, className) {
  const td = row.insertCell();
  td.textContent = text;
  if (className) td.className = className;
  return td;
}

function show(view) {
  for (const id of ["login-view", "jobs-view", "job-view", "workers-view"]) $(id).hidden = id !== view;
  $("nav-jobs").classList.toggle("current", view === "jobs-view" || view === "job-view");
  $("nav-workers").classList.toggle("current", view === "workers-view");
}

function renderJobs(list) {
  const body = $("jobs").tBodies[0];
  body.replaceChildren();
  const jobs = list.jobs || [];
  $("no-jobs").hidden = jobs.length > 0;
  for (const job of jobs) {
    const row = body.insertRow();
    row.dataset.jobId = job.job_id;
    const link = document.createElement("a");
    link.href = "/jobs/" + encodeURIComponent(job.job_id);
    link.dataset.nav = "";
    link.textContent = job.job_id;
    row.insertCell().append(link);
    cell(row, job.name);
    cell(row, stateName(job.state), "state " + stateName(job.state));
    cell(row, integratorName(job.integrator));
    cell(row, count(job.photons), "number");
    cell(row, count(job.epochs), "number");
    cell(row, rate(job.photons_per_second), "number");
    cell(row, percent(job.estimated_error), "number");
    cell(row, percent(measured(job.reference_error)), "number");
    cell(row, job.workers_active, "number");
    cell(row, job.priority, "number");
    cell(row, job.owner);
  }
}

function renderWorkers(list) {
  const body = $("workers").tBodies[0];
  body.replaceChildren();
  const workers = list.workers || [];
  $("no-workers").hidden = workers.length > 0;
  for (const worker of workers) {
    const row = body.insertRow();
    const [backend, ...device] = (worker.backend || "").split(": ");
    cell(row, worker.worker_id);
    cell(row, backend);
    cell(row, device.join(": ") || (backend === "cpu" ? "CPU (Embree)" : ""));
    cell(row, worker.threads, "number");
    cell(row, worker.batches_leased, "number");
    cell(row, count(worker.batches_done), "number");
    cell(row, rate(worker.photons_per_second), "number");
    cell(row, Number(worker.seconds_since_heartbeat).toFixed(1) + " s ago", "number");
    cell(row, worker.peer || "this process");
  }
}

// The error-against-time plot, log-log: one circle per epoch and series, each carrying its
// values (data-seconds, data-error) for scripts and tests.
function renderPlot() {
  const svg = $("plot");
  const width = svg.width.baseVal.value, height = svg.height.baseVal.value;
  const left = 48, right = 10, top = 10, bottom = 30;
  const series = [];
  for (const point of state.points.values()) {
    const seconds = Number(point.seconds);
    if (!(seconds > 0)) continue;
    if (point.estimated_rel_mse > 0)
      series.push({ kind: "estimated", seconds, error: Math.sqrt(point.estimated_rel_mse), epoch: point.epochs });
    const m = measured(point.reference_error);
    if (m > 0) series.push({ kind: "measured", seconds, error: m, epoch: point.epochs });
  }
  svg.replaceChildren();
  const ns = "http://www.w3.org/2000/svg";
  const add = (name, attributes, text) => {
    const element = document.createElementNS(ns, name);
    for (const [key, value] of Object.entries(attributes)) element.setAttribute(key, value);
    if (text !== undefined) element.textContent = text;
    svg.append(element);
    return element;
  };
  if (series.length === 0) {
    add("text", { x: left, y: height / 2 }, "no error estimate yet (from the second epoch)");
    return;
  }
  const log = Math.log10;
  const xs = series.map((p) => log(p.seconds)), ys = series.map((p) => log(p.error));
  const x0 = Math.floor(Math.min(...xs)), x1 = Math.max(Math.ceil(Math.max(...xs)), x0 + 1);
  const y0 = Math.floor(Math.min(...ys)), y1 = Math.max(Math.ceil(Math.max(...ys)), y0 + 1);
  const px = (v) => left + ((v - x0) / (x1 - x0)) * (width - left - right);
  const py = (v) => height - bottom - ((v - y0) / (y1 - y0)) * (height - top - bottom);
  for (let d = x0; d <= x1; ++d) {
    add("line", { class: "grid", x1: px(d), x2: px(d), y1: top, y2: height - bottom });
    add("text", { x: px(d) - 8, y: height - bottom + 14 }, decade(d, 1));
  }
  for (let d = y0; d <= y1; ++d) {
    add("line", { class: "grid", x1: left, x2: width - right, y1: py(d), y2: py(d) });
    add("text", { x: 2, y: py(d) + 3 }, decade(d, 100) + "%");
  }
  add("line", { class: "axis", x1: left, x2: width - right, y1: height - bottom, y2: height - bottom });
  add("line", { class: "axis", x1: left, x2: left, y1: top, y2: height - bottom });
  add("text", { x: width / 2 - 20, y: height - 4 }, "seconds");
  for (const p of series)
    add("circle", {
      class: "point " + p.kind, r: 2.5, cx: px(log(p.seconds)), cy: py(log(p.error)),
      "data-seconds": p.seconds, "data-error": p.error, "data-epoch": p.epoch,
    });
}

function renderJob(view) {
  const job = view.status;
  for (const point of view.points || []) state.points.set(point.epochs, point);  // by epoch: a resent point replaces itself
  $("job-name").textContent = job.name;
  $("job-id").textContent = job.job_id;
  const name = stateName(job.state);
  $("job-state").textContent = name;
  $("job-state").className = "state " + name;
  $("cancel").disabled = name !== "RUNNING";
  const facts = [
    ["Integrator", integratorName(job.integrator)], ["Epochs", count(job.epochs)],
    ["Photons", count(job.photons)], ["Rate", rate(job.photons_per_second)],
    ["Elapsed", Number(job.elapsed_seconds).toFixed(1) + " s"],
    ["Estimated error", percent(job.estimated_error)],
    ["Measured error", percent(measured(job.reference_error))],
    ["Workers", job.workers_active], ["Priority", job.priority], ["Client", job.owner],
    ["Budget spent", percent(job.budget_fraction)], ["NaN/Inf dropped", count(job.nonfinite_discarded)],
  ];
  if (job.message) facts.push(["Message", job.message]);
  $("job-facts").replaceChildren(...facts.flatMap(([term, value]) => {
    const dt = document.createElement("dt"), dd = document.createElement("dd");
    dt.textContent = term;
    dd.textContent = value;
    return [dt, dd];
  }));
  const list = (id, items, none) => $(id).replaceChildren(...(items.length ? items : [none]).map((text) => {
    const li = document.createElement("li");
    li.textContent = text;
    return li;
  }));
  list("features", (job.scene_features || "").split(", ").filter(Boolean), "–");
  list("warnings", job.warnings || [], "none");
  if (Number(job.epochs) !== state.epochs) {
    state.epochs = Number(job.epochs);
    refreshImage();
  }
  renderPlot();
}

function refreshImage() {
  const image = $("job-image");
  if (state.epochs <= 0) return;
  image.dataset.epoch = state.epochs;
  image.src = `/api/jobs/${encodeURIComponent(state.jobId)}/image.png?exposure=${$("exposure").value}&epoch=${state.epochs}`;
}

async function openJob(jobId) {
  Object.assign(state, { jobId, points: new Map(), epochs: -1 });
  $("job-image").removeAttribute("src");
  $("download-exr").href = `/api/jobs/${encodeURIComponent(jobId)}/image.exr`;
  show("job-view");
  renderJob(await api("GET", `/api/jobs/${encodeURIComponent(jobId)}`));
  follow(`/api/jobs/${encodeURIComponent(jobId)}/events`, {
    job: (view) => {
      renderJob(view);
      if (stateName(view.status.state) !== "RUNNING") closeStreams();  // its last message
    },
  });
}

async function route() {
  closeStreams();
  showError("");
  const path = location.pathname;
  try {
    if (path.startsWith("/jobs/")) return await openJob(decodeURIComponent(path.slice(6)));
    show(path === "/workers" ? "workers-view" : "jobs-view");
    follow("/api/events", { jobs: renderJobs, workers: renderWorkers });
  } catch (error) {
    if (error.status === 401) return showLogin();
    showError(error.message);
  }
}

function showLogin() {
  closeStreams();
  show("login-view");
  $("logout").hidden = true;
  $("who").textContent = "";
}

function signedIn(session) {
  state.csrf = session.csrf_token;
  $("who").textContent = session.name;
  $("logout").hidden = !session.tokens_required;
}

async function start() {
  document.addEventListener("click", (event) => {
    const link = event.target.closest("a[data-nav]");
    if (!link || event.ctrlKey || event.metaKey) return;
    event.preventDefault();
    history.pushState(null, "", link.getAttribute("href"));
    route();
  });
  window.addEventListener("popstate", route);
  $("login-form").addEventListener("submit", async (event) => {
    event.preventDefault();
    try {
      signedIn(await api("POST", "/api/login", { token: $("token").value }));
      $("token").value = "";
      showError("");
      await route();
    } catch (error) {
      showError(error.message);
    }
  });
  $("logout").addEventListener("click", async () => {
    await api("POST", "/api/logout").catch(() => {});
    showLogin();
  });
  $("cancel").addEventListener("click", async () => {
    try {
      const response = await api("POST", `/api/jobs/${encodeURIComponent(state.jobId)}/cancel`);
      renderJob({ status: response.status, points: [] });
    } catch (error) {
      showError(error.message);
    }
  });
  // Small films shown at least 384 pixels wide, pixels kept sharp (dashboard.css).
  $("job-image").addEventListener("load", (event) => {
    event.target.style.width = Math.min(768, Math.max(384, event.target.naturalWidth)) + "px";
  });
  $("exposure").addEventListener("input", () => {
    $("exposure-value").textContent = $("exposure").value;
    refreshImage();
  });
  try {
    signedIn(await api("GET", "/api/session"));
    await route();
  } catch (error) {
    if (error.status === 401) showLogin();
    else showError(error.message);
  }
}

start();
