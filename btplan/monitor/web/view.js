// btplan's browser view: a run's tree, tick by tick (btplan/monitor/browser.py serves it).
// The trace's lines hold, per tick, the statuses of the nodes it reached (by uid), and the
// whole tree on every tick that changed it; this page draws any tick from them.
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const ROW = 28;          // pixels per leaf row
const GAP = 28;          // pixels between depth columns
const CHAR = 7.3;        // width of a character of the 12px monospace font
const POLL_MS = 250;     // how often a live view asks for new ticks
const CHECKPOINT = 256;  // facts are kept whole every this many ticks

const SYMBOLS = {Fallback: "?", Sequence: "\u2192", SequenceWithMemory: "\u2192*",
  Parallel: "\u21c9", Inverter: "\u00ac", ForceSuccess: "\u22a4", ForceFailure: "\u22a5"};
const LEAVES = new Set(["Action", "Condition"]);

const view = {
  lines: [],        // parsed trace lines
  versions: [],     // trees: {rows, byUid, children, root, from} (from: index of its line)
  versionAt: [],    // line index -> index in versions
  grownAt: new Map(),  // uid -> index of the line whose tree first had it
  checkpoints: [],  // facts (a Set) before every CHECKPOINT-th line
  facts: new Set(), // facts after the last line read
  at: 0,            // the line shown
  collapsed: new Set(),
  drawn: null,      // {version, elements: Map uid -> <g>, positions}
  matches: [], matchAt: -1,
  playing: null, live: false, done: true, polling: false, frames: false,
};

const $ = (id) => document.getElementById(id);

// --- reading the trace -------------------------------------------------------------------

function addLine(line) {
  const index = view.lines.length;
  if (line.base || index === 0) {
    view.facts = new Set(line.facts_at_start || []);
  }
  if (index % CHECKPOINT === 0) view.checkpoints.push(new Set(view.facts));
  if (line.facts) {
    for (const fact of line.facts.removed) view.facts.delete(fact);
    for (const fact of line.facts.added) view.facts.add(fact);
  }
  if (line.tree) addVersion(line.tree, index);
  view.versionAt.push(view.versions.length - 1);
  view.lines.push(line);
}

function addVersion(rows, index) {
  const byUid = new Map(), children = new Map();
  let root = 0;
  for (const [uid, parent, kind, name] of rows) {
    byUid.set(uid, {uid, parent, kind, name});
    children.set(uid, []);
    if (parent === 0) root = uid; else if (children.has(parent)) children.get(parent).push(uid);
    if (!view.grownAt.has(uid)) view.grownAt.set(uid, index);
  }
  view.versions.push({rows, byUid, children, root, from: index});
}

function factsAt(index) {
  const facts = new Set(view.checkpoints[Math.floor(index / CHECKPOINT)]);
  for (let i = index - (index % CHECKPOINT); i <= index; i++) {
    const line = view.lines[i];
    if (line.base) { facts.clear(); for (const f of line.facts_at_start) facts.add(f); }
    if (!line.facts) continue;
    for (const fact of line.facts.removed) facts.delete(fact);
    for (const fact of line.facts.added) facts.add(fact);
  }
  return facts;
}

async function fetchLines() {
  const response = await fetch(`lines?from=${view.lines.length}`, {cache: "no-store"});
  const text = await response.text();
  let added = 0;
  for (const raw of text.split("\n")) {
    if (!raw.trim()) continue;
    addLine(JSON.parse(raw));
    added++;
  }
  return added;
}

// --- layout and drawing ------------------------------------------------------------------

function label(node) {
  if (LEAVES.has(node.kind)) return node.name || node.kind;
  const symbol = SYMBOLS[node.kind];
  return symbol || node.kind;
}

function visibleChildren(version, uid) {
  return view.collapsed.has(uid) ? [] : version.children.get(uid) || [];
}

// Left to right: one row per visible leaf, a parent centred on its children, one column
// per depth as wide as its widest label. Iterative, so that a deep tree cannot overflow
// the stack.
function layout(version) {
  const depthOf = new Map(), y = new Map(), widths = [];
  const order = [];
  const stack = [[version.root, 0]];
  while (stack.length) {
    const [uid, depth] = stack.pop();
    order.push(uid);
    depthOf.set(uid, depth);
    const node = version.byUid.get(uid);
    const text = label(node);
    const width = LEAVES.has(node.kind) ? text.length * CHAR + 24 : Math.max(28, text.length * 9 + 14);
    widths[depth] = Math.max(widths[depth] || 0, width);
    const kids = visibleChildren(version, uid);
    for (let i = kids.length - 1; i >= 0; i--) stack.push([kids[i], depth + 1]);
  }
  let row = 0;
  for (const uid of order) {  // leaves in depth-first order take the rows
    if (!visibleChildren(version, uid).length) y.set(uid, row++ * ROW + ROW / 2);
  }
  for (let i = order.length - 1; i >= 0; i--) {
    const uid = order[i];
    const kids = visibleChildren(version, uid);
    if (kids.length) y.set(uid, (y.get(kids[0]) + y.get(kids[kids.length - 1])) / 2);
  }
  const columns = [8];
  for (let d = 1; d <= widths.length; d++) columns[d] = columns[d - 1] + (widths[d - 1] || 0) + GAP;
  return {order, depthOf, y, widths, columns, height: row * ROW + 8, width: columns[widths.length] + 8};
}

function shape(node, width) {
  if (node.kind === "Condition") {
    const e = document.createElementNS(SVG, "ellipse");
    e.setAttribute("cx", width / 2); e.setAttribute("cy", 0);
    e.setAttribute("rx", width / 2); e.setAttribute("ry", 11);
    return e;
  }
  const r = document.createElementNS(SVG, "rect");
  r.setAttribute("x", 0); r.setAttribute("y", -11);
  r.setAttribute("width", width); r.setAttribute("height", 22);
  if (!LEAVES.has(node.kind)) r.setAttribute("rx", 3);
  return r;
}

function draw() {
  const version = view.versions[view.versionAt[view.at]];
  const svg = $("tree");
  const started = performance.now();
  svg.textContent = "";
  if (!version) return;
  const place = layout(version);
  svg.setAttribute("width", place.width);
  svg.setAttribute("height", place.height);
  const edges = document.createElementNS(SVG, "g");
  const nodes = document.createElementNS(SVG, "g");
  svg.append(edges, nodes);
  const elements = new Map(), boxes = new Map();
  let path = "";
  for (const uid of place.order) {
    const node = version.byUid.get(uid);
    const depth = place.depthOf.get(uid);
    const text = label(node);
    const leaf = LEAVES.has(node.kind);
    const width = leaf ? text.length * CHAR + 24 : Math.max(28, text.length * 9 + 14);
    const x = place.columns[depth], y = place.y.get(uid);
    boxes.set(uid, [x, y, width]);
    const g = document.createElementNS(SVG, "g");
    g.setAttribute("class", leaf ? "node" : "node control");
    g.setAttribute("transform", `translate(${x},${y})`);
    g.setAttribute("data-uid", uid);
    g.setAttribute("role", "treeitem");
    g.setAttribute("aria-label", `${node.kind} ${node.name}`.trim());
    const title = document.createElementNS(SVG, "title");
    title.textContent = `${node.kind}${node.name ? ": " + node.name : ""} (uid ${uid}, grown at tick ${view.lines[view.grownAt.get(uid)].tick})`;
    const t = document.createElementNS(SVG, "text");
    t.setAttribute("x", leaf ? 12 : width / 2);
    if (!leaf) t.setAttribute("text-anchor", "middle");
    t.textContent = text;
    g.append(title, shape(node, width), t);
    const hidden = view.collapsed.has(uid) ? (version.children.get(uid) || []).length : 0;
    if (hidden) {
      const fold = document.createElementNS(SVG, "text");
      fold.setAttribute("class", "fold"); fold.setAttribute("x", width + 4);
      fold.textContent = `+${countBelow(version, uid)}`;
      g.append(fold);
    }
    nodes.append(g);
    elements.set(uid, g);
    if (node.parent && boxes.has(node.parent)) {
      const [px, py, pw] = boxes.get(node.parent);
      const mid = px + pw + GAP / 2;
      path += `M${px + pw},${py}H${mid}V${y}H${x}`;
    }
  }
  const edge = document.createElementNS(SVG, "path");
  edge.setAttribute("class", "edge"); edge.setAttribute("d", path);
  edges.append(edge);
  view.drawn = {version, elements, place};
  paint();
  document.body.dataset.renderMs = String(Math.round(performance.now() - started));
}

function countBelow(version, uid) {
  let count = 0;
  const stack = [...(version.children.get(uid) || [])];
  while (stack.length) { const u = stack.pop(); count++; stack.push(...(version.children.get(u) || [])); }
  return count;
}

function statusesAt(index) {
  const out = new Map();
  for (const [uid, status] of view.lines[index].statuses || []) out.set(uid, status);
  return out;
}

function paint() {
  const {elements} = view.drawn;
  const statuses = statusesAt(view.at);
  for (const [uid, g] of elements) {
    const status = statuses.get(uid);
    if (status) g.setAttribute("data-status", status); else g.removeAttribute("data-status");
    g.classList.toggle("new", view.grownAt.get(uid) === view.at && view.at > 0);
    g.setAttribute("aria-description", status ? status.toLowerCase() : "not reached");
  }
  showPanel(statuses);
  if ($("follow").checked) follow(statuses);
}

function follow(statuses) {
  let deepest = null, depth = -1;
  for (const [uid, status] of statuses) {
    const d = view.drawn.place.depthOf.get(uid);
    if (status === "RUNNING" && d !== undefined && d > depth) { deepest = uid; depth = d; }
  }
  if (deepest !== null) reveal(deepest, false);
}

function reveal(uid, mark) {
  const g = view.drawn.elements.get(uid);
  if (!g) return;
  if (mark) {
    for (const other of document.querySelectorAll("#tree .current")) other.classList.remove("current");
    g.classList.add("current");
  }
  const place = view.drawn.place;
  const x = place.columns[place.depthOf.get(uid)], y = place.y.get(uid);
  const pane = $("tree-pane");
  pane.scrollTo({left: Math.max(0, x - pane.clientWidth / 3), top: Math.max(0, y - pane.clientHeight / 2)});
}

// --- the panel ---------------------------------------------------------------------------

function showPanel(statuses) {
  const line = view.lines[view.at];
  $("tick-head").textContent = `tick ${line.tick}: ${line.status || ""}${line.goal ? " (goal " + line.goal + ")" : ""}`;
  $("tick-label").textContent = `tick ${line.tick} of ${view.lines[view.lines.length - 1].tick}`;
  const picture = $("frame");
  if (view.frames && line.tick !== undefined) {
    picture.hidden = false;
    picture.src = `frame?tick=${line.tick}`;
  }
  const events = $("tick-events");
  events.textContent = "";
  const rows = [
    ["disturbed", (line.disturbances || []).map((d) => d.description)],
    ["grew", (line.expansions || []).map((e) => `${e.condition} \u2190 ${e.achievers.join(", ") || "no achiever"}`)],
    ["started", line.started || []], ["finished", line.finished || []],
    ["halted", line.halted || []], ["failed", line.failed || []],
  ];
  for (const [name, items] of rows) {
    if (!items.length) continue;
    const div = document.createElement("div");
    div.className = "event";
    const b = document.createElement("b");
    b.textContent = name;
    div.append(b, items.join("; "));
    events.append(div);
  }
  if (!events.childElementCount) events.textContent = "nothing started, finished or changed";
  const facts = factsAt(view.at);
  const added = new Set(line.facts ? line.facts.added : []);
  const list = $("facts");
  list.textContent = "";
  for (const fact of [...facts].sort()) {
    const li = document.createElement("li");
    li.textContent = fact;
    if (added.has(fact)) li.className = "added";
    list.append(li);
  }
  for (const fact of (line.facts ? line.facts.removed : [])) {
    const li = document.createElement("li");
    li.textContent = fact;
    li.className = "removed";
    list.append(li);
  }
}

function drawMarks() {
  const svg = $("marks");
  const count = view.lines.length;
  svg.setAttribute("viewBox", `0 0 ${Math.max(1, count)} 10`);
  svg.textContent = "";
  view.lines.forEach((line, i) => {
    const marks = [];
    if ((line.expansions || []).length) marks.push(["grew", 0]);
    if ((line.disturbances || []).length) marks.push(["disturbed", 5]);
    for (const [kind, y] of marks) {
      const r = document.createElementNS(SVG, "rect");
      r.setAttribute("class", kind); r.setAttribute("x", i); r.setAttribute("y", y);
      r.setAttribute("width", Math.max(1, count / 400)); r.setAttribute("height", 5);
      svg.append(r);
    }
  });
}

// --- moving through the ticks ------------------------------------------------------------

function show(index) {
  if (!view.lines.length) return;
  index = Math.max(0, Math.min(view.lines.length - 1, index));
  view.at = index;
  $("scrub").value = String(index);
  if (!view.drawn || view.drawn.version !== view.versions[view.versionAt[index]]) draw();
  else paint();
  document.body.dataset.tick = String(view.lines[index].tick);
}

function togglePlay() {
  if (view.playing) { clearInterval(view.playing); view.playing = null; $("play").textContent = "play"; return; }
  $("play").textContent = "pause";
  view.playing = setInterval(() => {
    if (view.at >= view.lines.length - 1) { if (!view.live || view.done) togglePlay(); return; }
    show(view.at + 1);
  }, 300);
}

function search(query, step) {
  const version = view.versions[view.versionAt[view.at]];
  if (!version) return;
  const wanted = query.trim().toLowerCase();
  for (const g of document.querySelectorAll("#tree .match")) g.classList.remove("match");
  if (!wanted) { view.matches = []; $("matches").textContent = ""; return; }
  if (step === 0) {
    view.matches = version.rows.filter(([, , kind, name]) => `${kind} ${name}`.toLowerCase().includes(wanted)).map(([uid]) => uid);
    view.matchAt = 0;
  } else if (view.matches.length) {
    view.matchAt = (view.matchAt + step + view.matches.length) % view.matches.length;
  }
  if (!view.matches.length) { $("matches").textContent = "no node"; return; }
  const target = view.matches[view.matchAt];
  let opened = false;  // a match inside a collapsed subtree: open its ancestors
  for (let p = version.byUid.get(target).parent; p; p = version.byUid.get(p).parent) {
    if (view.collapsed.delete(p)) opened = true;
  }
  if (opened) draw();
  for (const uid of view.matches) { const g = view.drawn.elements.get(uid); if (g) g.classList.add("match"); }
  $("matches").textContent = `${view.matchAt + 1} of ${view.matches.length}`;
  reveal(target, true);
}

function collapseQuiet() {
  const version = view.versions[view.versionAt[view.at]];
  const reached = statusesAt(view.at);
  const busy = new Set();
  for (const uid of reached.keys()) {
    for (let u = uid; u; u = version.byUid.get(u) ? version.byUid.get(u).parent : 0) busy.add(u);
  }
  view.collapsed.clear();
  for (const [uid] of version.rows) {
    if (!busy.has(uid) && (version.children.get(uid) || []).length) view.collapsed.add(uid);
  }
  draw();
}

// --- start ---------------------------------------------------------------------------------

async function poll() {
  if (view.polling) return;
  view.polling = true;
  try {
    const atEnd = view.at >= view.lines.length - 1;
    const added = await fetchLines();
    const info = await (await fetch("info", {cache: "no-store"})).json();
    view.done = info.done;
    if (added) {
      $("scrub").max = String(view.lines.length - 1);
      drawMarks();
      if (atEnd) show(view.lines.length - 1);
    }
    $("live").hidden = !(view.live && !view.done);
  } catch (error) {
    view.done = true;  // the run ended and its server with it
    $("live").hidden = true;
  } finally {
    view.polling = false;
  }
  if (!view.done) setTimeout(poll, POLL_MS);
}

async function start() {
  const info = await (await fetch("info", {cache: "no-store"})).json();
  document.title = `${info.title} - btplan view`;
  $("title").textContent = info.title;
  view.live = info.live; view.done = info.done; view.frames = info.frames;
  await fetchLines();
  $("scrub").max = String(Math.max(0, view.lines.length - 1));
  drawMarks();
  show(view.live ? view.lines.length - 1 : 0);
  $("live").hidden = !(view.live && !view.done);
  document.body.dataset.readyMs = String(Math.round(performance.now()));
  document.body.dataset.ready = "1";
  if (view.live && !view.done) setTimeout(poll, POLL_MS);
}

$("frame").addEventListener("error", () => { $("frame").hidden = true; });
$("scrub").addEventListener("input", (e) => show(Number(e.target.value)));
$("first").addEventListener("click", () => show(0));
$("prev").addEventListener("click", () => show(view.at - 1));
$("next").addEventListener("click", () => show(view.at + 1));
$("last").addEventListener("click", () => show(view.lines.length - 1));
$("play").addEventListener("click", togglePlay);
$("query").addEventListener("input", (e) => search(e.target.value, 0));
$("query").addEventListener("keydown", (e) => {
  if (e.key === "Enter") { e.preventDefault(); search(e.target.value, e.shiftKey ? -1 : 1); }
});
$("expand-all").addEventListener("click", () => { view.collapsed.clear(); draw(); });
$("collapse-quiet").addEventListener("click", collapseQuiet);
$("follow").addEventListener("change", () => paint());
$("tree").addEventListener("click", (e) => {
  const g = e.target.closest ? e.target.closest(".node.control") : null;
  if (!g) return;
  const uid = Number(g.getAttribute("data-uid"));
  if (!view.collapsed.delete(uid)) view.collapsed.add(uid);
  draw();
});
document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT" && e.target.type !== "range") return;
  if (e.key === "ArrowRight") { e.preventDefault(); show(view.at + 1); }
  else if (e.key === "ArrowLeft") { e.preventDefault(); show(view.at - 1); }
  else if (e.key === " ") { e.preventDefault(); togglePlay(); }
});
start();
