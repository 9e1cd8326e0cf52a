// The page of `cueplan serve`: pick an example, move the balls and the target, plan the
// stroke, play a stroke of your own, and see every spin that lands ("what spin lands
// here?"). The page keeps the problem as the problem file's fields (`problem`, sent with
// every request) and draws from the resolved `scene` /api/examples gives with it.

import { ApiError, call } from "./api.js";
import { viridis } from "./colours.js";
import { SpinDisc } from "./spin_disc.js";
import { TableView, pocketWords } from "./table_view.js";
import { TipDisc } from "./tip_disc.js";

const $ = (id) => document.getElementById(id);
const SPIN_PER_TIP = 2.5;       // k = 2.5 d / R
const MAP_DEBOUNCE_MS = 250;    // a speed slider redraws the map once it rests this long
const HOVER_DEBOUNCE_MS = 40;
const DEFAULT_EXAMPLE = "one_rail_position.yaml";
const SPIN_INTRO = document.getElementById("spin-intro").textContent;

const state = {
  examples: [],
  example: null,
  problem: null,   // the request's problem: the example's fields, balls where they are now
  scene: null,     // what to draw (the example's resolved scene), positions kept in step
  version: 0,      // counts changes to the problem, so stale answers are dropped
  plan: null,      // /api/solve's answer
  planShots: [],   // /api/simulate's answers for the plan's best and alternatives
  shown: 0,        // which of planShots is drawn in full (0: the best)
  map: null,       // /api/spinmap's answer
  strokeKnown: false,  // speed and aim set by a plan or by hand (else the map plans first)
  mapAbort: null,
  hoverAbort: null,
  shots: new Map(),  // simulate answers by request, for hovering back and forth
  selected: null,    // the simulate answer of the spin map cell last clicked
  exactStroke: null, // the last stroke put in the controls, unrounded
  asideTarget: null, // the problem's target, set aside while a next ball is chosen
  run: null,         // /api/run's answer and the shot shown ({answer, step}: 0 all shots)
};

const fixed = (v, digits) => (Number.isFinite(v) ? v.toFixed(digits) : "-");
// A tip offset in ball radii R, with the players' "tips" the plan's words count in (a
// tip is a quarter of R: planner/src/stroke_terms.cpp).
const TIPS_PER_R = 4;
const tipWords = (right, up) =>
  `${fixed(Math.abs(right), 3)} R (${fixed(TIPS_PER_R * Math.abs(right), 2)} tips) ${right < 0 ? "left" : "right"} of centre, ` +
  `${fixed(Math.abs(up), 3)} R (${fixed(TIPS_PER_R * Math.abs(up), 2)} tips) ${up < 0 ? "below" : "above"} centre`;
const cushionWord = (n) => `${n} cushion${n === 1 ? "" : "s"}`;

function allowedCushions(limits) {
  const [lo, hi] = limits.cushions;
  return lo === hi ? ` after ${cushionWord(lo)}` : ` after ${lo} to ${hi} cushions`;
}

// ---------------------------------------------------------------------------
// Views

const table = new TableView($("table"), {
  onMove: moveBall,
  onPointer: (text) => ($("pointer").textContent = text),
});
const tip = new TipDisc($("tip-disc"), { onChange: (offset) => setTip(offset, true) });
const disc = new SpinDisc($("spin-disc"), $("spin-legend"), { onHover: hoverCell, onSelect: selectCell });

// ---------------------------------------------------------------------------
// Busy, errors

let busyTimer = null;
function busy(text) {
  const started = performance.now();
  $("busy").hidden = false;
  const tick = () => ($("busy-text").textContent =
    `${text} ${((performance.now() - started) / 1000).toFixed(1)} s`);
  tick();
  clearInterval(busyTimer);
  busyTimer = setInterval(tick, 100);
  for (const id of ["plan", "play", "spinmap", "run"]) $(id).disabled = true;
  return (waitText) => {
    if (waitText) text = waitText;
  };
}
function idle() {
  clearInterval(busyTimer);
  $("busy").hidden = true;
  for (const id of ["plan", "play", "spinmap", "run"]) $(id).disabled = false;
}

function showError(e) {
  const box = $("error");
  box.replaceChildren();
  const message = document.createElement("span");
  message.textContent = e instanceof ApiError || e instanceof Error ? e.message : String(e);
  box.appendChild(message);
  if (e.field) {
    const field = document.createElement("span");
    field.className = "field-name";
    field.textContent = ` (field: ${e.field})`;
    box.appendChild(field);
  }
  box.hidden = false;
  table.flag(e.field ?? null);
}
function clearError() {
  $("error").hidden = true;
  table.flag(null);
}

// Runs one request with the progress line shown; errors land in the error box.
// What the progress line says while the server asks the page to come back (503).
function waitWords(message, answer, seconds) {
  if (!answer) return message;
  if (answer.impact_table)
    return "Waiting for the impact table of this cushion (made once; loading takes a second, " +
      "a first build about 30 s)...";
  return `The server is busy (${answer.error}); trying once more in ${seconds} s...`;
}

async function task(text, work) {
  clearError();
  const say = busy(text);
  try {
    await work((message, answer, seconds) => say(waitWords(message, answer, seconds)));
  } catch (e) {
    if (!e.aborted) showError(e);
  } finally {
    idle();
  }
}

// ---------------------------------------------------------------------------
// The problem and its balls

function positions() {
  const p = state.problem, s = state.scene;
  return {
    cue_ball: p.cue_ball,
    target: p.target ?? null,
    tolerance: s.tolerance,
    obstacles: p.obstacles ?? [],
    balls: objectBalls(p),
  };
}

// The problem's object balls as the file gives them (name -> [x, y]), in its order.
function objectBalls(p) {
  return Object.entries(p.balls ?? {}).map(([name, position]) => ({ name, position }));
}

function selectExample(index) {
  const e = state.examples[index];
  state.example = e;
  state.map = null;
  clearTimeout(mapTimer);  // a refresh of the old problem's map still waiting
  state.mapAbort?.abort();
  $("spin-disc").toggleAttribute("hidden", true);
  $("map-speed-field").hidden = true;
  $("spin-legend").replaceChildren();
  $("spin-cell").textContent = "";
  $("spin-intro").textContent = SPIN_INTRO;
  state.problem = structuredClone(e.problem);
  state.scene = structuredClone(e.scene);
  state.asideTarget = null;
  state.strokeKnown = false;
  table.setScene(state.scene);
  const limits = state.scene.limits;
  tip.setLimit(limits.spin / SPIN_PER_TIP);
  for (const id of ["speed-range", "map-speed-range"]) {
    $(id).min = limits.speed[0];
    $(id).max = limits.speed[1];
  }
  $("example-note").textContent =
    `${e.file}: ${state.scene.kind} table ${fixed(state.scene.length, 3)} x ${fixed(state.scene.width, 3)} m, ` +
    `target zone ${fixed(1000 * state.scene.tolerance, 0)} mm, ${allowedCushions(limits).trim()} allowed`;
  fillPot();
  changed();
}

// The pot's place: an object ball into a pocket, for problems that have object balls.
function fillPot() {
  const balls = objectBalls(state.problem);
  const pockets = state.scene.pockets;
  const ball = $("pot-ball"), pocket = $("pot-pocket");
  const none = new Option("no pot", "");
  ball.replaceChildren(...(balls.length ? [none, ...balls.map((b) => new Option(b.name, b.name))]
    : [new Option("none on this table", "")]));
  pocket.replaceChildren(...(pockets.length ? pockets.map((p) => new Option(pocketWords(p.name), p.name))
    : [new Option("no pockets on this table", "")]));
  ball.disabled = balls.length === 0;
  const pot = state.problem.pot;
  ball.value = pot?.ball ?? "";
  if (pot?.pocket) pocket.value = pot.pocket;
  pocket.disabled = !pot;
  fillNext();
  $("pot-note").textContent = !balls.length
    ? "This problem has no object balls: the plan leaves the cue ball on the target. Problems with object balls offer a pot here."
    : pot ? `Pot the ${pot.ball} in the ${pocketWords(pot.pocket)}; the cue ball must strike ` +
      `the ${state.problem.first_contact ?? pot.ball} first.`
    : "Choose a ball to pot and its pocket, or play for position only.";
}

// The first of the problem's next pots ({ball, pocket}), or null.
function firstNext(p) {
  const n = Array.isArray(p.next) ? p.next[0] : p.next;
  return n && n.ball ? n : null;
}

// The next ball: another object ball and its pocket, offered once a pot is chosen. The
// stroke is then ranked by P(pot now and pot next), and the table shades the next pot's
// zone when the plan comes back.
function fillNext() {
  const p = state.problem;
  const pot = p.pot;
  const others = objectBalls(p).filter((b) => b.name !== pot?.ball);
  const ball = $("next-ball"), pocket = $("next-pocket");
  ball.replaceChildren(new Option(pot ? (others.length ? "no next ball" : "no other ball") : "choose a pot first", ""),
    ...(pot ? others.map((b) => new Option(b.name, b.name)) : []));
  pocket.replaceChildren(...state.scene.pockets.map((q) => new Option(pocketWords(q.name), q.name)));
  const next = firstNext(p);
  ball.disabled = !pot || others.length === 0;
  ball.value = next?.ball ?? "";
  if (next?.pocket) pocket.value = next.pocket;
  pocket.disabled = !next;
  const rest = Array.isArray(p.next) ? p.next.slice(1) : [];
  $("next-note").textContent = !next
    ? (pot && others.length ? "Choose the ball to play after this one: the plan then leaves the cue ball " +
      "where that pot is easiest, and shades its zone on the table." : "")
    : `Then the ${next.ball} in the ${pocketWords(next.pocket)}` +
      (rest.length ? `, then ${rest.map((n) => `the ${n.ball} in the ${pocketWords(n.pocket)}`).join(", ")}` : "") +
      `: the plan is ranked by P(pot now and pot next)${p.target ? " and must also reach the target" : ""}.`;
}

// The next ball chosen in the controls becomes the problem's `next` (the target, if the
// problem has one, is set aside meanwhile: position is for the next ball).
function chooseNext() {
  const ball = $("next-ball").value, pocket = $("next-pocket").value;
  const p = state.problem;
  if (!ball) {
    delete p.next;
    if (state.asideTarget && !p.target) p.target = state.asideTarget;
    state.asideTarget = null;
  } else {
    const old = firstNext(p);
    const rest = Array.isArray(p.next) ? p.next.slice(1).filter((n) => n.ball !== ball) : [];
    const first = { ball, pocket: pocket || state.scene.pockets[0]?.name };
    p.next = old && old.ball === first.ball && old.pocket === first.pocket && rest.length ? [first, ...rest] : first;
    if (p.target) {
      state.asideTarget = p.target;
      delete p.target;
    }
  }
  fillNext();
  changed();
}

// The pot chosen in the controls becomes the problem's.
function choosePot() {
  const ball = $("pot-ball").value, pocket = $("pot-pocket").value;
  const p = state.problem;
  if (!ball) {
    delete p.pot;
    delete p.first_contact;
    if (p.next) {  // a next ball needs a pot
      delete p.next;
      if (state.asideTarget && !p.target) p.target = state.asideTarget;
      state.asideTarget = null;
    }
  } else {
    p.pot = { ball, pocket: pocket || state.scene.pockets[0]?.name };
    if (p.first_contact && !(p.first_contact in (p.balls ?? {}))) delete p.first_contact;
    if (firstNext(p)?.ball === ball) {
      delete p.next;
      if (state.asideTarget && !p.target) p.target = state.asideTarget;
      state.asideTarget = null;
    }
  }
  fillPot();
  changed();
}

// The problem changed: drop what was computed for the old one.
function changed() {
  state.version += 1;
  state.plan = null;
  state.planShots = [];
  state.shots.clear();
  state.selected = null;
  state.run = null;
  state.mapAbort?.abort();
  state.hoverAbort?.abort();
  table.setPositions(positions());
  table.setPaths([]);
  table.setField(null);
  animateShot(null);
  $("share").textContent = "Copy link";
  $("result").hidden = true;
  if (state.map) {
    // The map follows the balls; until it has, it is shown faded.
    $("spin-disc").classList.add("stale");
    $("spin-cell").textContent = "The balls moved: the map is being drawn again for their new places.";
    refreshMap();
  }
}

function moveBall(kind, index, place, done) {
  const p = state.problem;
  if (kind === "target" && !p.target) return;  // position for a next ball, or a pot alone
  if (state.run?.step && done) {
    // A run's step shows the balls where that shot finds them: a move starts from the
    // problem's own places again.
    state.run = null;
    table.setPositions(positions());
  }
  if (kind === "target") p.target = place;
  else if (kind === "cue_ball") p.cue_ball = place;
  else if (kind === "obstacles") p.obstacles[index] = place;
  else if (kind === "balls") p.balls[objectBalls(p)[index].name] = place;
  if (!done) {
    table.setPositions(positions());
    table.setPaths([]);
    return;
  }
  changed();
  table.focusBall(kind, index);
}

// ---------------------------------------------------------------------------
// The stroke controls

// The stroke in the controls. While they still show the stroke a plan (or a spin map
// cell) put there, its exact numbers: the controls round them for reading.
function readStroke() {
  const t = tip.offset;
  const shown = {
    speed: Number($("speed").value),
    aim_deg: Number($("aim").value),
    topspin_k: Math.round(1e6 * SPIN_PER_TIP * t.up) / 1e6,
    sidespin_k: Math.round(1e6 * SPIN_PER_TIP * t.right) / 1e6,
  };
  const exact = state.exactStroke;
  if (exact && JSON.stringify(rounded(exact)) === JSON.stringify(rounded(shown))) return { ...exact };
  return shown;
}

// A stroke as the controls show it.
function rounded(s) {
  const r = (v) => Math.round(1000 * v) / 1000;
  return [r(s.speed), r(s.aim_deg), r(s.topspin_k / SPIN_PER_TIP), r(s.sidespin_k / SPIN_PER_TIP)];
}

function setTip(offset, byHand) {
  if (!byHand) tip.show(offset);
  $("tip-right").value = offset.right;
  $("tip-up").value = offset.up;
  $("tip-spin").textContent =
    `${fixed(TIPS_PER_R * offset.right, 2)} tips right, ${fixed(TIPS_PER_R * offset.up, 2)} tips up; ` +
    `k_T = ${fixed(SPIN_PER_TIP * offset.up, 3)}, k_S = ${fixed(SPIN_PER_TIP * offset.right, 3)}`;
}

function setSpeed(speed) {
  const v = Math.round(1000 * speed) / 1000;
  $("speed").value = v;
  $("speed-range").value = v;
  $("map-speed-range").value = v;
  $("map-speed").textContent = `${fixed(v, 2)} m/s`;
}

// Puts a shot {speed, aim_deg, topspin_k, sidespin_k} in the controls.
function setStroke(shot) {
  setSpeed(shot.speed);
  $("aim").value = Math.round(1000 * shot.aim_deg) / 1000;
  const round = (v) => Math.round(1000 * v) / 1000;
  setTip({ right: round(shot.sidespin_k / SPIN_PER_TIP), up: round(shot.topspin_k / SPIN_PER_TIP) }, false);
  $("tip-spin").textContent =
    `${fixed(TIPS_PER_R * shot.sidespin_k / SPIN_PER_TIP, 2)} tips right, ` +
    `${fixed(TIPS_PER_R * shot.topspin_k / SPIN_PER_TIP, 2)} tips up; ` +
    `k_T = ${fixed(shot.topspin_k, 3)}, k_S = ${fixed(shot.sidespin_k, 3)}`;
  table.setAim(shot.aim_deg);
  state.strokeKnown = true;
  state.exactStroke = { speed: shot.speed, aim_deg: shot.aim_deg, topspin_k: shot.topspin_k,
    sidespin_k: shot.sidespin_k };
}

function plannerOptions() {
  const options = {};
  const number = (id) => ($(id).value === "" ? undefined : Number($(id).value));
  if (number("seed") !== undefined) options.seed = number("seed");
  if (number("max-time") !== undefined) options.max_time = number("max-time");
  if (number("noise") !== undefined) options.noise = number("noise");
  return options;
}

// ---------------------------------------------------------------------------
// Simulating one stroke (the plan's, your own, a spin map cell's)

// The stroke fields /api/simulate takes: a plan's shot also reports what the stroke does
// (its squirt), which is not sent back.
const STROKE_FIELDS = ["speed", "aim_deg", "topspin_k", "sidespin_k", "elevation_deg"];

async function simulate(planned, method, { signal, onWait } = {}) {
  const stroke = Object.fromEntries(
    STROKE_FIELDS.filter((k) => planned[k] !== undefined).map((k) => [k, planned[k]]));
  const body = { problem: state.problem, stroke, options: { method } };
  const key = JSON.stringify([state.version, stroke, method]);
  if (state.shots.has(key)) return state.shots.get(key);
  const shot = await call("/api/simulate", body, { signal, onWait });
  state.shots.set(key, shot);
  return shot;
}

function outcomeText(shot) {
  return cueOutcome(shot) + ballsOutcome(shot);
}

// What the cue ball did to the object balls: what it struck first, what dropped.
function ballsOutcome(shot) {
  if (!shot.balls || shot.balls.length < 2) return "";
  if (!shot.first_contact) return "; it strikes no object ball";
  const pots = shot.balls.slice(1).filter((b) => b.pocketed)
    .map((b) => `the ${b.name} in the ${pocketWords(b.pocket)}`);
  return `; it strikes the ${shot.first_contact} first and ${pots.length ? "pots " + pots.join(" and ") : "pots nothing"}`;
}

function cueOutcome(shot) {
  if (shot.status === "rest") {
    const miss = shot.miss_distance;
    return `stops at x = ${fixed(shot.final_position[0], 3)} m, y = ${fixed(shot.final_position[1], 3)} m ` +
      `after ${cushionWord(shot.cushion_hits)}, ${fixed(1000 * miss, 1)} mm from the target ` +
      `(${shot.in_target_zone ? "inside" : "outside"} the ${fixed(1000 * shot.tolerance, 0)} mm zone)`;
  }
  if (shot.status === "pocketed") return `is pocketed after ${cushionWord(shot.cushion_hits)}`;
  if (shot.status === "hit_obstacle") return `stops against an obstacle ball after ${cushionWord(shot.cushion_hits)}`;
  return `gives no outcome (${shot.status}: ${shot.message})`;
}

// ---------------------------------------------------------------------------
// The shot's animation: the balls move along the simulator's paths

function animateShot(shot) {
  state.animated = shot ?? null;
  $("replay").disabled = !shot;
  if (!shot) return;
  const rate = Number($("anim-rate").value) || 1;
  table.animate(shot, rate, (t, duration) => {
    $("anim-clock").textContent = `${fixed(t, 2)} of ${fixed(duration, 2)} s`;
  });
}

// ---------------------------------------------------------------------------
// Shareable links: the example, the balls, the stroke and the options in the address

const SHARE_KEY = "setup";

function shareState() {
  return {
    example: state.example.file,
    problem: state.problem,
    stroke: readStroke(),
    options: { seed: $("seed").value, max_time: $("max-time").value, noise: $("noise").value,
      grid: $("grid").value },
  };
}

function shareLink() {
  const url = new URL(window.location.href);
  url.hash = `${SHARE_KEY}=${encodeURIComponent(JSON.stringify(shareState()))}`;
  return url.toString();
}

async function copyLink() {
  const link = shareLink();
  history.replaceState(null, "", link);
  const box = $("share-url");
  box.value = link;
  box.hidden = false;
  box.select();
  try {
    await navigator.clipboard.writeText(link);
    $("share").textContent = "Link copied";
  } catch {
    $("share").textContent = "Copy the link below";
  }
}

// The set-up a link carries, or null (no link, or one that cannot be read).
function sharedSetup() {
  const hash = window.location.hash.slice(1);
  if (!hash.startsWith(`${SHARE_KEY}=`)) return null;
  try {
    const s = JSON.parse(decodeURIComponent(hash.slice(SHARE_KEY.length + 1)));
    if (typeof s !== "object" || typeof s.problem !== "object" || typeof s.example !== "string") return null;
    return s;
  } catch {
    return null;
  }
}

// Opens what a link carries: its example with its balls, its options and its stroke,
// played.
function restoreShared(setup) {
  const index = state.examples.findIndex((e) => e.file === setup.example);
  if (index < 0) {
    showError(new Error(`the link names an example this server does not have: ${setup.example}`));
    return false;
  }
  $("example").value = index;
  selectExample(index);
  state.problem = setup.problem;
  for (const [id, key] of [["seed", "seed"], ["max-time", "max_time"], ["noise", "noise"], ["grid", "grid"]])
    if (setup.options?.[key] !== undefined) $(id).value = setup.options[key];
  fillPot();
  changed();
  if (setup.stroke && Number.isFinite(setup.stroke.speed)) {
    setStroke(setup.stroke);
    play();
  }
  return true;
}

// ---------------------------------------------------------------------------
// Plan

function drawPlan() {
  const paths = state.planShots.map((shot, i) => ({ shot, style: i === state.shown ? "main" : "faint" }));
  // The one drawn in full goes last, on top.
  paths.push(paths.splice(state.shown, 1)[0]);
  table.setPaths(paths.filter(Boolean));
}

function dl(rows) {
  const list = document.createElement("dl");
  for (const [term, value] of rows) {
    const dt = document.createElement("dt");
    dt.textContent = term;
    const dd = document.createElement("dd");
    dd.textContent = value;
    list.append(dt, dd);
  }
  return list;
}

function legendLine() {
  const p = document.createElement("p");
  for (const [cls, words] of [["sliding", "sliding (dashed)"], ["rolling", "rolling (solid)"],
    ["cue", "cue ball"], ["object", "object ball: its own colour"], ["faint", "other ways (alternatives)"]]) {
    const item = document.createElement("span");
    item.className = "legend-line";
    const sw = document.createElement("span");
    sw.className = `swatch ${cls}`;
    item.append(sw, document.createTextNode(words));
    p.appendChild(item);
  }
  const note = document.createElement("span");
  note.className = "legend-line";
  note.textContent = "numbered dots: cushion contacts; dashed ball: where it stops, or the ghost " +
    "ball where the cue ball strikes";
  p.appendChild(note);
  return p;
}

// A planned stroke's chance of success in words: the estimate with its 95 % interval
// (`success.both`: it stops in the zone, and pots what the problem asks to be potted).
function successText(a, r) {
  if (!(r.options.samples > 0)) return "not estimated";
  const s = a.success?.both;
  if (!s) return `${fixed(100 * a.success_probability, 1)} %`;
  return `${fixed(100 * s.p, 1)} % of ${s.samples} noisy strokes (95 % interval ` +
    `${fixed(100 * s.low, 1)} to ${fixed(100 * s.high, 1)} %)`;
}

function renderPlan() {
  const r = state.plan;
  const shown = state.shown === 0 ? r : r.alternatives[state.shown - 1];
  const box = $("result");
  box.replaceChildren();
  const words = document.createElement("p");
  words.className = "words";
  const head = document.createElement("span");
  head.className = r.status === "solved" ? "status-solved" : "status-other";
  head.textContent = ({ solved: "Solved", no_solution_found: "No solution found",
    budget_exhausted: "Budget exhausted" }[r.status] ?? r.status) + ": ";
  const stroke = document.createElement("span");
  stroke.id = "stroke-words";
  stroke.textContent = `${shown.stroke}, aim ${fixed(shown.shot.aim_deg, 2)} deg` +
    (state.shown ? ` (alternative ${state.shown})` : "");
  words.append(head, stroke);
  const message = document.createElement("p");
  message.className = "note";
  message.textContent = r.message;
  const s = shown.shot;
  box.append(words, message, dl([
    ["speed", `${fixed(s.speed, 3)} m/s`],
    ["aim", `${fixed(s.aim_deg, 2)} deg`],
    ["tip offset", `${tipWords(shown.tip_offset.right, shown.tip_offset.up)} (k_T = ${fixed(s.topspin_k, 3)}, k_S = ${fixed(s.sidespin_k, 3)})`],
    ["stops", shown.final_position ? `x = ${fixed(shown.final_position[0], 3)} m, y = ${fixed(shown.final_position[1], 3)} m (${shown.outcome})` : "-"],
    ["miss", !state.problem.target ? (firstNext(state.problem)
      ? "no target: the pot and the position for the next ball judge the stroke"
      : "no target: the pot judges the stroke")
      : shown.miss_distance === null ? "none: not at rest on the table"
      : `${fixed(1000 * shown.miss_distance, 1)} mm (tolerance ${fixed(1000 * r.tolerance, 0)} mm)`],
    ["success", successText(shown, r)],
    ["route", shown.route_names.length ? `${cushionWord(shown.route_names.length)}: ${shown.route_names.join(", ")}` : "no cushion"],
    ["search", `${r.evaluations} shot simulations in ${fixed(r.time_s, 3)} s (seed ${r.options.seed}, ${r.options.method} impacts)`],
    ...nextRows(shown, r),
  ]));

  if (r.alternatives.length) {
    const t = document.createElement("table");
    const caption = document.createElement("caption");
    caption.className = "visually-hidden";
    caption.textContent = "The plan and the other ways to play it";
    t.appendChild(caption);
    const header = t.insertRow();
    for (const [text, num] of [["#", false], ["stroke", false], ["V (m/s)", true], ["aim (deg)", true],
      ["miss (mm)", true], ["success (%)", true], ["route", false], ["", false]]) {
      const th = document.createElement("th");
      th.textContent = text;
      if (num) th.className = "num";
      header.appendChild(th);
    }
    [r, ...r.alternatives].forEach((a, i) => {
      const row = t.insertRow();
      if (i === state.shown) row.className = "shown";
      const cells = [i === 0 ? "plan" : String(i), a.stroke, fixed(a.shot.speed, 3), fixed(a.shot.aim_deg, 2),
        a.miss_distance === null ? "-" : fixed(1000 * a.miss_distance, 1),
        r.options.samples > 0 ? fixed(100 * a.success_probability, 1) : "-",
        a.route_names.length ? a.route_names.join(", ") : "none"];
      cells.forEach((text, c) => {
        const td = row.insertCell();
        td.textContent = text;
        if (c >= 2 && c <= 5) td.className = "num";
        if (c === 1) td.className = "stroke";
      });
      const show = document.createElement("button");
      show.type = "button";
      show.className = "link";
      show.textContent = i === state.shown ? "shown" : "show";
      show.setAttribute("aria-label", `show ${i === 0 ? "the plan" : `alternative ${i}`} on the table`);
      show.onclick = () => {
        state.shown = i;
        setStroke(a.shot);
        drawPlan();
        renderPlan();
        animateShot(state.planShots[i]);
      };
      row.insertCell().appendChild(show);
    });
    box.appendChild(t);
  }
  box.appendChild(legendLine());
  if (r.zone) box.appendChild(zoneLegend(r.zone));
  box.hidden = false;
}

// Position play: what the plan leaves for the next ball, and its zone.
function nextRows(a, r) {
  const n = a.next;
  if (!n) return [];
  const rows = [["next", `the ${n.ball} in the ${pocketWords(n.pocket)}: ${n.words}`]];
  const s = a.success ?? {};
  const interval = (e) => `${fixed(100 * e.p, 0)} % (95 % interval ${fixed(100 * e.low, 0)} to ${fixed(100 * e.high, 0)} %)`;
  if (s.pot) rows.push(["P(pot now)", interval(s.pot)]);
  if (s.next) rows.push(["P(next pot)", interval(s.next)]);
  if (s.both) rows.push(["P(both)", interval(s.both)]);
  rows.push(["landing", `P(next pot) ${fixed(100 * n.p, 0)} % from where the cue ball stops, ` +
    `${n.in_zone ? "inside" : "outside"} the zone`]);
  if (r.zone)
    rows.push(["zone", `${fixed(1e4 * r.zone.area_m2, 0)} cm\u00b2 where P(next pot) is within 10 points ` +
      `of the best (${fixed(100 * r.zone.best_p, 0)} % at the white cross)`]);
  return rows;
}

// The zone's legend: the shade's colour bar and the outline.
function zoneLegend(zone) {
  const p = document.createElement("p");
  p.id = "zone-legend";
  p.className = "zone-legend";
  const bar = document.createElement("span");
  bar.className = "zone-bar";
  bar.style.background = `linear-gradient(90deg, ${[0, 0.25, 0.5, 0.75, 1].map((t) => viridis(t)).join(", ")})`;
  const outline = document.createElement("span");
  outline.className = "zone-box";
  p.append(document.createTextNode(`Shaded: P(next pot) on the ${zone.ball} into the ${pocketWords(zone.pocket)} ` +
    "from each cue-ball position, 0 "), bar, document.createTextNode(" 100 %; "), outline,
  document.createTextNode(" the zone, within 10 points of the best."));
  return p;
}

async function plan() {
  const version = state.version;
  const options = plannerOptions();
  await task(`Planning (search up to ${options.max_time ?? 10} s)...`, async (wait) => {
    const r = await call("/api/solve", { problem: state.problem, options }, { onWait: wait });
    if (version !== state.version) return;
    state.plan = r;
    state.shown = 0;
    table.setField(r.zone ?? null);
    setStroke(r.shot);
    // Paths, one stroke after another (the worker pool is small): the best first.
    wait("Drawing the paths...");
    state.planShots = [];
    for (const a of [r, ...r.alternatives]) {
      state.planShots.push(await simulate(a.shot, a.impact_method, { onWait: wait }));
      if (version !== state.version) return;
      drawPlan();
    }
    renderPlan();
    animateShot(state.planShots[0]);
    if (state.map) refreshMap();
  });
}

// ---------------------------------------------------------------------------
// Plan the run: every ball in turn, the pattern shot by shot (/api/run)

const RUN_SAMPLES = 20;

async function runOut() {
  const version = state.version;
  const options = { samples: RUN_SAMPLES, seed: Number($("seed").value) || 1,
    noise: Number($("noise").value) };
  await task(`Planning the run, then playing it ${RUN_SAMPLES} times under the noise...`, async (wait) => {
    const r = await call("/api/run", { problem: state.problem, options }, { onWait: wait });
    if (version !== state.version) return;
    state.run = { answer: r, step: 0 };
    table.setField(null);
    showRunStep();
  });
}

// The run's shots that were simulated (each from where the balls stood).
const runShots = (r) => r.plan.filter((s) => s.simulation);

// Where the balls stand before shot `step` (1-based): the cue ball where its path
// starts, the object balls left on the table where that shot's simulation starts them.
function positionsBefore(shot) {
  const sim = shot.simulation;
  const names = objectBalls(state.problem).map((b) => b.name);
  const balls = (sim.balls ?? []).slice(1).map((b) => ({
    name: b.name,
    index: names.indexOf(b.name),
    position: b.path?.length ? b.path[0].p0 : b.final_position,
  })).filter((b) => b.index >= 0);
  return { ...positions(), cue_ball: sim.path[0].p0, target: null, balls };
}

// The run on the table: all shots (step 0), each cue-ball path numbered, or one shot in
// full over the faint paths of the others, the balls where that shot finds them.
function showRunStep() {
  const { answer: r, step } = state.run;
  const shots = runShots(r);
  if (step === 0) {
    table.setPositions(positions());
    table.setPaths(shots.map((s, i) => ({ shot: s.simulation, style: "main", number: i + 1 })));
  } else {
    table.setPositions(positionsBefore(shots[step - 1]));
    const paths = shots.map((s, i) => ({ shot: s.simulation, style: i === step - 1 ? "main" : "faint", number: i + 1 }));
    paths.push(paths.splice(step - 1, 1)[0]);  // the one shown goes on top
    table.setPaths(paths);
  }
  renderRun();
  animateShot(step === 0 ? shots[0]?.simulation : shots[step - 1].simulation);
}

function renderRun() {
  const { answer: r, step } = state.run;
  const shots = runShots(r);
  const box = $("result");
  box.replaceChildren();
  const words = document.createElement("p");
  words.className = "words";
  words.id = "run-words";
  const p = r.runout;
  words.textContent = (r.plan_clears
    ? `The run clears the table in ${r.plan.length} shot${r.plan.length === 1 ? "" : "s"}`
    : `The run stops short after ${r.plan.length} shot${r.plan.length === 1 ? "" : "s"} (${r.plan_ended})`) +
    `; played ${p.samples} times under the noise it clears ${fixed(100 * p.p, 0)} % ` +
    `(95 % interval ${fixed(100 * p.low, 0)}-${fixed(100 * p.high, 0)} %).`;
  // Step through: all shots, or one at a time.
  const stepper = document.createElement("div");
  stepper.className = "stepper";
  stepper.setAttribute("role", "group");
  stepper.setAttribute("aria-label", "Step through the run");
  const button = (id, text, to, disabled) => {
    const b = document.createElement("button");
    b.type = "button";
    b.id = id;
    b.textContent = text;
    b.disabled = disabled;
    b.onclick = () => {
      state.run.step = to;
      showRunStep();
      $(id).focus();
    };
    return b;
  };
  const where = document.createElement("span");
  where.id = "run-step";
  where.className = "note";
  where.textContent = step === 0 ? `all ${shots.length} shots, numbered` : `shot ${step} of ${shots.length}`;
  stepper.append(button("run-all", "All shots", 0, step === 0),
    button("run-prev", "\u25c0 Previous", Math.max(step - 1, 1), step <= 1),
    button("run-next", "Next \u25b6", Math.min(step + 1, shots.length), step >= shots.length), where);
  const list = document.createElement("ol");
  list.id = "run-shots";
  r.plan.forEach((s, i) => {
    const item = document.createElement("li");
    if (i + 1 === step) item.className = "shown";
    const link = document.createElement("button");
    link.type = "button";
    link.className = "link";
    // A bank, kick or combination is named; a direct pot is not.
    link.textContent = `${s.ball} into ${pocketWords(s.pocket)}` +
      (s.route && s.route !== "direct" ? ` (${s.route})` : "");
    link.disabled = !s.simulation;
    link.onclick = () => {
      state.run.step = i + 1;
      showRunStep();
    };
    item.append(link, document.createTextNode(`: ${s.shot.stroke}; P(pot) ${fixed(100 * s.success.p, 0)} %` +
      (s.next ? `; then ${s.next.replace(/ into (\w+)$/, (m, q) => ` into the ${pocketWords(q)}`)}` : "")));
    list.appendChild(item);
  });
  const rows = [["mean potted", `${fixed(r.mean_potted, 2)} balls`]];
  for (const d of r.deaths.slice(0, 3))
    rows.push([`shot ${d.shot}`, `${d.reason} (${d.count} of ${p.samples} runs)`]);
  const note = document.createElement("p");
  note.className = "note";
  note.textContent = "Numbered badges: where the cue ball starts each shot. A shot shown alone has the " +
    "balls where it finds them; the others' paths are faint.";
  box.append(words, stepper, list, dl(rows), legendLine(), note);
  box.hidden = false;
}

// ---------------------------------------------------------------------------
// Play a stroke of your own

async function play() {
  const stroke = readStroke();
  state.strokeKnown = true;
  table.setAim(stroke.aim_deg);
  await task("Simulating...", async (wait) => {
    const shot = await simulate(stroke, "exact", { onWait: wait });
    table.setPaths([{ shot, style: "main" }]);
    animateShot(shot);
    const box = $("result");
    box.replaceChildren();
    const words = document.createElement("p");
    words.className = "words";
    words.id = "stroke-words";
    words.textContent = `Your stroke ${outcomeText(shot)}.`;
    const t = tip.offset;
    box.append(words, dl([
      ["stroke", `${fixed(stroke.speed, 3)} m/s at aim ${fixed(stroke.aim_deg, 2)} deg, tip ${tipWords(t.right, t.up)}`],
      ["solves the problem", shot.reaches_target ? "yes" : "no"],
      ["limits", shot.within_limits ? "within the problem's limits" : shot.limits_message],
      ["duration", `${fixed(shot.duration, 2)} s`],
      ["impacts", `${shot.method} method`],
    ]), legendLine());
    box.hidden = false;
  });
}

// ---------------------------------------------------------------------------
// What spin lands here?

async function requestMap() {
  state.mapAbort?.abort();
  const abort = new AbortController();
  state.mapAbort = abort;
  const body = { problem: state.problem, grid: Number($("grid").value), options: plannerOptions() };
  if (state.strokeKnown) {
    const s = readStroke();
    body.speed = s.speed;
    body.aim_deg = s.aim_deg;
  }
  const version = state.version;
  await task(state.strokeKnown ? "Simulating every spin..." : "Planning the stroke, then every spin...",
    async (wait) => {
      let map;
      try {
        map = await call("/api/spinmap", body, { signal: abort.signal, onWait: wait });
      } catch (e) {
        if (state.map && !e.aborted)
          $("spin-cell").textContent = "The map (faded) is for the balls' previous places: " +
            "this problem has no map until the error is mended.";
        throw e;
      }
      if (version !== state.version) return;
      showMap(map);
    });
}

function showMap(map) {
  state.map = map;
  $("forgiving-field").hidden = false;
  if (map.stroke_source === "planner") setStroke(map.planner.shot);
  // Ring the planned spin when the plan's speed and aim are the map's.
  let planned = map.stroke_source === "planner" ? map.planner.shot : null;
  const best = state.planShots.length ? state.plan : null;
  if (!planned && best && Math.abs(best.shot.speed - map.speed) < 1e-9 &&
      Math.abs(best.shot.aim_deg - map.aim_deg) < 1e-9)
    planned = best.shot;
  $("spin-intro").textContent =
    `At ${fixed(map.speed, 3)} m/s and aim ${fixed(map.aim_deg, 2)} deg, ${map.landing} of ${map.points} spins ` +
    `stop within ${fixed(1000 * map.tolerance, 0)} mm of the target${allowedCushions(state.scene.limits)}. ` +
    "Hover or click a cell to see that spin's path.";
  $("spin-disc").toggleAttribute("hidden", false);
  $("map-speed-field").hidden = false;
  $("map-speed").textContent = `${fixed(map.speed, 2)} m/s`;
  disc.draw(map, { planned, cushions: allowedCushions(state.scene.limits) });
  $("spin-disc").classList.remove("stale");
  $("spin-cell").textContent = "";
  if ($("forgiving").checked) requestForgiveness();
}

// How forgiving each spin is: the server estimates the success under noise of a part of
// the map's cells per request (at most max_success_strokes noisy strokes), and the page
// asks for the parts one after another, shading each as it arrives.
const SUCCESS_STROKES_PER_REQUEST = 40000;
async function requestForgiveness() {
  state.successAbort?.abort();
  const map = state.map;
  const on = $("forgiving").checked;
  disc.setSuccess(on);
  if (!on || !map) {
    $("forgiving-progress").textContent = "";
    return;
  }
  const samples = Number($("forgiving-samples").value);
  if (!Number.isInteger(samples) || samples < 1 || samples > 200) {
    $("forgiving-progress").textContent = "Noisy strokes a spin must be a whole number from 1 to 200.";
    return;
  }
  for (const c of map.cells) delete c.success;
  disc.setSuccess(true);
  const abort = new AbortController();
  state.successAbort = abort;
  const total = map.cells.length;
  // About ten parts, so that the progress moves, each within the server's bound.
  const part = Math.max(1, Math.min(Math.ceil(total / 10), Math.floor(SUCCESS_STROKES_PER_REQUEST / samples)));
  const say = (done) => {
    $("forgiving-progress").textContent = done < total
      ? `Estimating how forgiving each spin is: ${Math.round((100 * done) / total)} % ` +
        `(${done} of ${total} spins, ${samples} noisy strokes each)...`
      : `Success under noise: ${samples} noisy strokes for each of the ${total} spins ` +
        `(noise ${plannerOptions().noise ?? 1} times a club player's scatter).`;
  };
  say(0);
  for (let from = 0; from < total; from += part) {
    const body = { problem: state.problem, grid: map.grid, speed: map.speed, aim_deg: map.aim_deg,
      options: plannerOptions(), success: true, samples, success_from: from, success_count: part };
    let answer;
    try {
      answer = await call("/api/spinmap", body, { signal: abort.signal });
    } catch (e) {
      if (!e.aborted) $("forgiving-progress").textContent = `The estimate stopped: ${e.message ?? e}`;
      return;
    }
    if (state.map !== map || abort.signal.aborted) return;
    answer.cells.forEach((c, i) => { if ("success" in c) map.cells[i].success = c.success; });
    disc.setSuccess(true);
    say(Math.min(total, from + part));
  }
}

let mapTimer = null;
function refreshMap() {
  clearTimeout(mapTimer);
  // Only a map on show is refreshed (an example chosen since has none).
  mapTimer = setTimeout(() => state.map && requestMap(), MAP_DEBOUNCE_MS);
}

function cellText(cell) {
  const where = cell.kind === "pocketed" ? "is pocketed"
    : cell.kind === "hit_obstacle" ? "stops against an obstacle ball"
    : cell.kind === "no_outcome" ? "gives no outcome"
    : `stops ${fixed(1000 * cell.miss_distance, 1)} mm from the target after ${cushionWord(cell.cushion_hits)}` +
      (cell.kind === "at_rest_other_cushions" ? " (a cushion count the problem does not allow)" : "") +
      (cell.lands ? ": lands" : "");
  const success = "success" in cell ? ` Under noise it succeeds ${Math.round(100 * cell.success)} % of the time.` : "";
  return `Tip ${tipWords(cell.tip_right, cell.tip_up)} (k_T = ${fixed(cell.topspin_k, 3)}, ` +
    `k_S = ${fixed(cell.sidespin_k, 3)}) ${where}.${success}`;
}

const cellStroke = (cell) => ({ speed: state.map.speed, aim_deg: state.map.aim_deg,
  topspin_k: cell.topspin_k, sidespin_k: cell.sidespin_k });

let hoverTimer = null;
function hoverCell(cell) {
  clearTimeout(hoverTimer);
  if (!cell) {
    $("spin-cell").textContent = "";
    if (state.planShots.length) drawPlan();
    else table.setPaths(state.selected ? [{ shot: state.selected, style: "main" }] : []);
    return;
  }
  $("spin-cell").textContent = cellText(cell);
  hoverTimer = setTimeout(async () => {
    state.hoverAbort?.abort();
    const abort = new AbortController();
    state.hoverAbort = abort;
    try {
      const shot = await simulate(cellStroke(cell), state.map.method, { signal: abort.signal, retries: 3 });
      const behind = state.planShots.length ? [{ shot: state.planShots[state.shown], style: "faint" }] : [];
      table.setPaths([...behind, { shot, style: "hover" }]);
    } catch (e) {
      if (!e.aborted) showError(e);
    }
  }, HOVER_DEBOUNCE_MS);
}

async function selectCell(cell) {
  setStroke(cellStroke(cell));
  $("spin-cell").textContent = cellText(cell);
  await task("Simulating...", async (wait) => {
    const shot = await simulate(cellStroke(cell), state.map.method, { onWait: wait });
    state.selected = shot;
    table.setPaths([{ shot, style: "main" }]);
  });
}

// ---------------------------------------------------------------------------
// Health: the workers and the impact tables

async function pollHealth() {
  const line = $("health");
  try {
    const h = await call("/api/health");
    const tables = h.impact_tables;
    const ready = tables.filter((t) => t.state === "ready").length;
    line.className = "health" + (h.impact_tables_ready ? "" : " warn");
    line.textContent = `Server ${h.version}: ${h.workers} worker${h.workers === 1 ? "" : "s"}, ` +
      (h.default_method === "table"
        ? h.impact_tables_ready ? `impact tables ready (${ready})`
          : `impact tables: ${ready} of ${tables.length} ready, ${tables.find((t) => t.state !== "ready")?.note ?? ""}`
        : `${h.default_method} impacts`);
    if (!h.impact_tables_ready) setTimeout(pollHealth, 2000);
  } catch (e) {
    line.className = "health bad";
    line.textContent = e.message;
    setTimeout(pollHealth, 5000);
  }
}

// ---------------------------------------------------------------------------
// Start

function bindControls() {
  $("example").onchange = (e) => selectExample(Number(e.target.value));
  $("reset").onclick = () => selectExample(state.examples.indexOf(state.example));
  $("pot-ball").onchange = choosePot;
  $("pot-pocket").onchange = choosePot;
  $("next-ball").onchange = chooseNext;
  $("next-pocket").onchange = chooseNext;
  $("plan").onclick = plan;
  $("play").onclick = play;
  $("spinmap").onclick = requestMap;
  $("run").onclick = runOut;
$("forgiving").onchange = requestForgiveness;
$("forgiving-samples").onchange = () => $("forgiving").checked && requestForgiveness();
  $("speed-range").oninput = (e) => {
    setSpeed(Number(e.target.value));
    state.strokeKnown = true;
  };
  $("speed").onchange = (e) => {
    setSpeed(Number(e.target.value));
    state.strokeKnown = true;
  };
  $("map-speed-range").oninput = (e) => {
    setSpeed(Number(e.target.value));
    state.strokeKnown = true;
    refreshMap();
  };
  $("aim").onchange = (e) => {
    table.setAim(Number(e.target.value));
    state.strokeKnown = true;
  };
  const typedTip = () => {
    const offset = { right: Number($("tip-right").value), up: Number($("tip-up").value) };
    tip.choose(offset);
  };
  $("tip-right").onchange = typedTip;
  $("tip-up").onchange = typedTip;
  $("grid").onchange = () => state.map && refreshMap();
  $("replay").onclick = () => animateShot(state.animated);
  $("anim-rate").onchange = () => state.animated && animateShot(state.animated);
  $("share").onclick = copyLink;
}

async function start() {
  bindControls();
  setTip({ right: 0, up: 0 }, false);
  setSpeed(Number($("speed").value));
  pollHealth();
  try {
    const { examples } = await call("/api/examples");
    state.examples = examples;
    const picker = $("example");
    examples.forEach((e, i) => picker.appendChild(new Option(e.name, i)));
    const shared = sharedSetup();
    if (!shared || !restoreShared(shared)) {
      const first = Math.max(0, examples.findIndex((e) => e.file === DEFAULT_EXAMPLE));
      picker.value = first;
      selectExample(first);
    }
  } catch (e) {
    showError(e);
  }
}

start();
