// The table seen from above, to scale, as SVG in the page: drawn in metres in the table
// frame (origin where the cushion noses x = 0 and y = 0 meet, x along the length, y up
// the width), with the markings of its kind, the pockets' capture circles, the balls
// (draggable with the mouse, or with the arrow keys once focused) and the target zone,
// and ball paths drawn exactly from the simulator's path segments.
//
// Balls are whatever the scene lists: the cue ball, `obstacles` and, when problems
// carry them, `balls` ({name, position}) - each drawn and moved the same way, in the
// look its name gives it (colours.js ballLook: pool's numbers, 9-15 striped). Over the
// cloth, a position-play field may be shaded with its zone outlined (setField), and a
// run's shots numbered where each starts (setPaths with `number`).

import { BALL_COLOURS, ballLook, viridis } from "./colours.js";

const SVG = "http://www.w3.org/2000/svg";
const SNOOKER_LENGTH = 3.569;  // m, the table the snooker markings are given for
const FONT = 0.052;            // m: text scales with the drawing

export const SLIDING = "#D55E00";
export const ROLLING = "#0072B2";
// A path's dashes while the ball slides; a rolling ball's path is solid.
export const SLIDING_DASH = "0.035 0.02";
// Pockets as players say them: "top-right corner", "bottom middle" (pool players say
// "side"; the page says "middle" for every game).
export function pocketWords(name) {
  const [side, where] = String(name ?? "").split("_");
  if (!where) return String(name ?? "pocket");
  return where === "middle" ? `${side} middle pocket` : `${side}-${where} corner`;
}
const TARGET = "#009E73";
const CLOTH = { snooker: "#1f7a3f", pool: "#2a6aa8", carom: "#2f5f9e" };
const CUSHION = { snooker: "#145a2c", pool: "#1f4f7e", carom: "#234a78" };
const OBSTACLE = BALL_COLOURS.red;
// The next pot's field over the cloth (as `cueplan zone` shades it): viridis laid over the
// cloth at this opacity, the zone outlined in white on a dark edge.
const FIELD_OPACITY = 0.7;

function el(name, attributes = {}, parent = null) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

// A ball drawn at (cx, cy) of radius r as its look says ({colour, number, striped}, as
// colours.js ballLook gives): its circle (class "ring", the one focus and errors outline),
// a stripe's band, a pool ball's number on a white disc. Returns the circle.
export function drawBall(parent, cx, cy, r, look, attributes = {}) {
  const ring = el("circle", { class: "ring", cx, cy, r, fill: look.striped ? "#ffffff" : look.colour,
    stroke: "#222", "stroke-width": 0.004, ...attributes }, parent);
  if (look.striped) {
    // The band: the ball between y = cy - h and cy + h, its sides the ball's own edge.
    const h = 0.55 * r, w = Math.sqrt(r * r - h * h);
    el("path", { class: "stripe", fill: look.colour, d: `M${cx - w} ${cy - h} L${cx + w} ${cy - h} ` +
      `A${r} ${r} 0 0 1 ${cx + w} ${cy + h} L${cx - w} ${cy + h} A${r} ${r} 0 0 1 ${cx - w} ${cy - h} Z` }, parent);
    el("circle", { cx, cy, r, fill: "none", stroke: "#222", "stroke-width": 0.004, "pointer-events": "none" }, parent);
  }
  if (look.number > 0) {
    el("circle", { class: "number-disc", cx, cy, r: 0.52 * r, fill: "#ffffff" }, parent);
    const t = el("text", { class: "ball-number", x: cx, y: -cy, transform: "scale(1,-1)", "text-anchor": "middle",
      "dominant-baseline": "central", "font-size": (look.number >= 10 ? 0.62 : 0.78) * r, "font-weight": "bold",
      fill: "#1a1a1a", "pointer-events": "none" }, parent);
    t.textContent = String(look.number);
  }
  return ring;
}

const mm = (v) => (1000 * v).toFixed(0);
const metres = (v) => v.toFixed(3);

// Where a path segment is at time t0 + tau: p0 + v0 tau + a tau^2 / 2.
function at(segment, tau) {
  return [
    segment.p0[0] + segment.v0[0] * tau + 0.5 * segment.accel[0] * tau * tau,
    segment.p0[1] + segment.v0[1] * tau + 0.5 * segment.accel[1] * tau * tau,
  ];
}

export class TableView {
  // onMove(kind, index, [x, y], done): a ball or the target was moved (done: the move ended).
  // onPointer(text): where the pointer is on the cloth, in words.
  constructor(svg, { onMove, onPointer }) {
    this.svg = svg;
    this.onMove = onMove;
    this.onPointer = onPointer;
    this.scene = null;
    this.balls = [];  // {kind, index, group}
  }

  // Draws the table of a scene (as /api/examples gives it) and its balls.
  setScene(scene) {
    this.scene = scene;
    const s = scene;
    const band = 0.075 * Math.max(s.length / SNOOKER_LENGTH, 0.6);
    const left = band + 0.16, bottom = band + 0.12, pad = band + 0.03;
    this.svg.setAttribute("viewBox",
      `${-left} ${-(s.width + pad)} ${s.length + left + pad} ${s.width + pad + bottom}`);
    this.svg.replaceChildren();
    const defs = el("defs", {}, this.svg);
    const ghost = el("pattern", { id: "ghost-fill", width: 0.01, height: 0.01, patternUnits: "userSpaceOnUse" }, defs);
    el("rect", { width: 0.01, height: 0.01, fill: "rgba(255,255,255,0.15)" }, ghost);

    // Everything in table coordinates (y up) goes in `world`; text stays outside it.
    this.world = el("g", { transform: "scale(1,-1)" }, this.svg);
    const w = this.world;
    const kind = CLOTH[s.kind] ? s.kind : "snooker";
    el("rect", { x: -band, y: -band, width: s.length + 2 * band, height: s.width + 2 * band,
      rx: 0.03, fill: "#6b4423" }, w);
    const cushion = 0.6 * band;
    el("rect", { x: -cushion, y: -cushion, width: s.length + 2 * cushion,
      height: s.width + 2 * cushion, fill: CUSHION[kind] }, w);
    this.cloth = el("rect", { x: 0, y: 0, width: s.length, height: s.width, fill: CLOTH[kind] }, w);
    this.drawMarkings(w, s, band, cushion);
    for (const p of s.pockets) {
      const g = el("g", {}, w);
      const j = p.jaws;
      if (j) {
        // The jaws as they are: the cushion cut back along the facings from the rounded
        // points, the hole beyond the shelf, the points and facings outlined.
        const far = 2 * band;
        const out = (f) => {
          const dx = f.end[0] - f.start[0], dy = f.end[1] - f.start[1], n = Math.hypot(dx, dy) || 1;
          return [f.end[0] + far * dx / n, f.end[1] + far * dy / n];
        };
        const pts = [j.nose_ends[0], j.corners[0], out(j.facings[0]), out(j.facings[1]), j.corners[1], j.nose_ends[1]];
        el("path", { d: "M" + pts.map((q) => `${q[0]} ${q[1]}`).join(" L") + " Z", fill: CLOTH[kind] }, g);
        el("circle", { cx: j.hole_centre[0], cy: j.hole_centre[1], r: j.hole_radius, fill: "#050505" }, g);
        const edge = { stroke: "#1d3b2a", "stroke-width": 0.003, fill: "none" };
        for (const f of j.facings) el("line", { x1: f.start[0], y1: f.start[1], x2: f.end[0], y2: f.end[1], ...edge }, g);
        for (const c of j.point_centres) el("circle", { cx: c[0], cy: c[1], r: Math.max(j.point_radius, 0.001), ...edge }, g);
        el("title", {}, g).textContent =
          `${p.name} pocket: mouth ${mm(j.mouth)} mm, facings at ${j.wall_angle_deg} deg, shelf ${mm(j.shelf)} mm; ` +
          `a ball whose centre enters the ${mm(j.hole_radius)} mm hole drops`;
        continue;
      }
      el("circle", { cx: p.centre[0], cy: p.centre[1], r: p.radius, fill: "#050505" }, g);
      el("title", {}, g).textContent =
        `${pocketWords(p.name)}: a ball whose centre comes within ${mm(p.radius)} mm of (${metres(p.centre[0])}, ${metres(p.centre[1])}) m drops`;
    }
    this.aimLine = el("line", { stroke: "#ffffff", "stroke-width": 0.006, "stroke-dasharray": "0.03 0.02",
      opacity: 0.8, visibility: "hidden" }, w);
    // The field stays on the cloth (its last cells reach past the cushion's nose).
    const clip = el("clipPath", { id: "cloth-clip" }, defs);
    el("rect", { x: 0, y: 0, width: s.length, height: s.width }, clip);
    this.fieldLayer = el("g", { class: "field", "clip-path": "url(#cloth-clip)" }, w);
    this.targetGroup = el("g", { class: "ball target", tabindex: 0, role: "button" }, w);
    this.pathLayer = el("g", { "stroke-linecap": "round", fill: "none" }, w);
    this.markLayer = el("g", {}, w);
    this.ballLayer = el("g", {}, w);
    this.animLayer = el("g", { class: "anim" }, w);
    this.drawTicks(s, band);
    this.bindPointer();
    this.setPositions(s);
  }

  drawMarkings(w, s, band, cushion) {
    const mark = { stroke: "#ffffff", "stroke-width": 0.005, fill: "none", opacity: 0.8 };
    const spot = (x, y) => el("circle", { cx: x, cy: y, r: 0.008, fill: "#ffffff", opacity: 0.85 }, w);
    const diamond = (x, y) => {
      const d = 0.011;
      el("path", { d: `M${x - d} ${y} L${x} ${y + d} L${x + d} ${y} L${x} ${y - d} Z`, fill: "#f4ecd8" }, w);
    };
    const railMid = cushion + 0.5 * (band - cushion);
    if (s.kind === "snooker") {
      // Baulk line 737 mm from the baulk cushion (x = 0), the D of radius 292 mm, and the
      // spots, scaled with the table's length.
      const k = s.length / SNOOKER_LENGTH;
      const baulk = 0.737 * k, r = 0.292 * k, mid = s.width / 2;
      el("line", { x1: baulk, y1: 0, x2: baulk, y2: s.width, ...mark }, w);
      el("path", { d: `M${baulk} ${mid + r} A${r} ${r} 0 0 1 ${baulk} ${mid - r}`, ...mark }, w);
      for (const [x, y] of [[baulk, mid - r], [baulk, mid], [baulk, mid + r], [s.length / 2, mid],
        [0.75 * s.length, mid], [s.length - 0.324 * k, mid]]) spot(x, y);
    } else {
      // Diamonds on the rails: eighths of the length, quarters of the width; spots on the
      // long axis (head and foot spots of pool, the three spots of carom).
      for (let i = 1; i < 8; ++i) {
        if (i === 4 && s.pockets.length > 0) continue;  // the middle pockets
        diamond((i * s.length) / 8, -railMid);
        diamond((i * s.length) / 8, s.width + railMid);
      }
      for (let j = 1; j < 4; ++j) {
        diamond(-railMid, (j * s.width) / 4);
        diamond(s.length + railMid, (j * s.width) / 4);
      }
      const spots = s.kind === "pool" ? [0.25, 0.75] : [0.25, 0.5, 0.75];
      for (const f of spots) spot(f * s.length, s.width / 2);
      if (s.kind === "pool")
        el("line", { x1: s.length / 4, y1: 0, x2: s.length / 4, y2: s.width, ...mark,
          "stroke-dasharray": "0.02 0.02" }, w);
    }
  }

  // Metre labels along the bottom and the left, outside the rails.
  drawTicks(s, band) {
    const g = el("g", { fill: "#444", "font-size": FONT }, this.svg);
    const step = s.length > 2 ? 0.5 : 0.25;
    for (let x = 0; x <= s.length + 1e-9; x += step)
      el("text", { x, y: band + 1.2 * FONT, "text-anchor": "middle" }, g).textContent = x.toFixed(1);
    el("text", { x: s.length, y: band + 2.3 * FONT, "text-anchor": "end" }, g).textContent = "x (m)";
    for (let y = 0; y <= s.width + 1e-9; y += step)
      el("text", { x: -band - 0.02, y: -y + 0.35 * FONT, "text-anchor": "end" }, g).textContent = y.toFixed(1);
    el("text", { x: -band - 0.02, y: -s.width - band + FONT, "text-anchor": "end" }, g).textContent = "y (m)";
  }

  // The balls' and the target's places: {cue_ball, target, tolerance, obstacles, balls}.
  setPositions(p) {
    const s = this.scene;
    this.positions = p;
    this.ballLayer.replaceChildren();
    this.balls = [];
    // The target zone: its tolerance circle and a cross.
    const t = this.targetGroup;
    t.replaceChildren();
    t.toggleAttribute("hidden", !p.target);
    if (p.target) {
    el("circle", { class: "ring", cx: p.target[0], cy: p.target[1], r: p.tolerance,
      fill: "rgba(0,158,115,0.35)", stroke: TARGET, "stroke-width": 0.006 }, t);
    const c = 0.5 * Math.max(p.tolerance, 0.03);
    el("path", { d: `M${p.target[0] - c} ${p.target[1]} H${p.target[0] + c} M${p.target[0]} ${p.target[1] - c} V${p.target[1] + c}`,
      stroke: "#ffffff", "stroke-width": 0.004 }, t);
    t.setAttribute("aria-label", `target: x = ${metres(p.target[0])} m, y = ${metres(p.target[1])} m, ` +
      `tolerance ${mm(p.tolerance)} mm; arrow keys move it`);
    this.balls.push({ kind: "target", index: 0, group: t });
    }

    const ball = (kind, index, centre, look, label) => {
      const g = el("g", { class: "ball", tabindex: 0, role: "button",
        "aria-label": `${label}: x = ${metres(centre[0])} m, y = ${metres(centre[1])} m; arrow keys move it` }, this.ballLayer);
      drawBall(g, centre[0], centre[1], s.ball_radius, look);
      el("title", {}, g).textContent = `${label} (${metres(centre[0])}, ${metres(centre[1])}) m`;
      this.balls.push({ kind, index, group: g });
      return g;
    };
    const plain = (colour) => ({ colour, number: 0, striped: false });
    (p.obstacles ?? []).forEach((o, i) => ball("obstacles", i, o, plain(OBSTACLE), `obstacle ball ${i + 1}`));
    // An entry may say which of the problem's balls it is (`index`): a run's step shows
    // the balls left on the table.
    (p.balls ?? []).forEach((b, i) =>
      ball("balls", b.index ?? i, b.position, ballLook(b.name), `${b.name ?? "object"} ball`));
    ball("cue_ball", 0, p.cue_ball, ballLook("cue ball"), "cue ball");
    this.setAim(this.aimDeg);
  }

  // The aim as a dashed line from the cue ball (undefined hides it).
  setAim(aimDeg) {
    this.aimDeg = aimDeg;
    if (!this.positions || aimDeg === undefined || !Number.isFinite(aimDeg)) {
      this.aimLine?.setAttribute("visibility", "hidden");
      return;
    }
    const [x, y] = this.positions.cue_ball;
    const a = (aimDeg * Math.PI) / 180, len = 0.35;
    Object.entries({ x1: x, y1: y, x2: x + len * Math.cos(a), y2: y + len * Math.sin(a), visibility: "visible" })
      .forEach(([k, v]) => this.aimLine.setAttribute(k, v));
  }

  // Marks the ball an error is about ("problem.cue_ball", "problem.obstacles[1]", ...).
  flag(field) {
    for (const b of this.balls) {
      const name = b.kind === "target" ? "problem.target" : b.kind === "cue_ball" ? "problem.cue_ball"
        : `problem.${b.kind}[${b.index}]`;
      b.group.classList.toggle("flagged", !!field && (field === name || field.startsWith(name + ".")));
    }
  }

  // Paths: [{shot: simulate's JSON, style: "main" | "faint" | "hover", number?}], drawn
  // in order; a number (a run's shot) is written in a dark badge where the cue ball starts.
  setPaths(paths) {
    this.stopAnimation();
    this.pathLayer.replaceChildren();
    this.markLayer.replaceChildren();
    for (const { shot, style } of paths) this.drawPath(shot, style);
    for (const { shot, style, number } of paths)
      if (number && shot.path?.length) this.drawBadge(shot.path[0].p0, number, style);
  }

  // A shot's number beside where its cue ball starts (off the ball, towards the table's
  // middle, so that the ball stays in sight).
  drawBadge([x, y], number, style) {
    const s = this.scene, r = 0.032;
    const dx = s.length / 2 - x, dy = s.width / 2 - y, n = Math.hypot(dx, dy) || 1;
    const off = s.ball_radius + r + 0.006;
    const cx = x + (off * dx) / n, cy = y + (off * dy) / n;
    const g = el("g", { class: `shot-badge ${style}`, "data-shot": number, opacity: style === "faint" ? 0.6 : 1 },
      this.markLayer);
    el("circle", { cx, cy, r, fill: style === "faint" ? "#555" : "#1a1a1a", stroke: "#ffffff", "stroke-width": 0.004 }, g);
    const t = el("text", { x: cx, y: -cy, transform: "scale(1,-1)", "text-anchor": "middle",
      "dominant-baseline": "central", "font-size": 0.04, "font-weight": "bold", fill: "#ffffff" }, g);
    t.textContent = String(number);
    el("title", {}, g).textContent = `shot ${number}: the cue ball starts at (${metres(x)}, ${metres(y)}) m`;
  }

  // The next pot's field (/api/solve's `zone`): each cell shaded by its value (viridis
  // over the cloth), the zone (values at least zone.threshold) outlined; null clears it.
  setField(zone) {
    this.fieldLayer.replaceChildren();
    this.zone = zone ?? null;
    if (!zone) return;
    const { columns, rows, cell, values } = zone;
    // The shade as an image of one pixel a cell, smoothed when scaled.
    const canvas = document.createElement("canvas");
    canvas.width = columns;
    canvas.height = rows;
    const g2 = canvas.getContext("2d");
    const image = g2.createImageData(columns, rows);
    for (let j = 0; j < rows; ++j)
      for (let i = 0; i < columns; ++i) {
        const v = values[j * columns + i];
        const hex = viridis(v);
        const k = 4 * ((rows - 1 - j) * columns + i);  // the image's rows run from the top
        image.data[k] = parseInt(hex.slice(1, 3), 16);
        image.data[k + 1] = parseInt(hex.slice(3, 5), 16);
        image.data[k + 2] = parseInt(hex.slice(5, 7), 16);
        image.data[k + 3] = v > 0 ? Math.round(255 * FIELD_OPACITY) : 0;
      }
    g2.putImageData(image, 0, 0);
    // The world is flipped (y up): the image is drawn flipped back about its own middle.
    const w = columns * cell, h = rows * cell;
    el("image", { class: "field-shade", href: canvas.toDataURL(), x: 0, y: -h, width: w, height: h,
      transform: "scale(1,-1)", preserveAspectRatio: "none" }, this.fieldLayer);
    // The zone's outline: the cell edges between cells in it and cells out of it.
    const inside = (i, j) => i >= 0 && j >= 0 && i < columns && j < rows && values[j * columns + i] >= zone.threshold;
    let d = "";
    for (let j = 0; j <= rows; ++j)
      for (let i = 0; i <= columns; ++i) {
        if (i < columns && inside(i, j) !== inside(i, j - 1)) d += `M${i * cell} ${j * cell}h${cell}`;
        if (j < rows && inside(i, j) !== inside(i - 1, j)) d += `M${i * cell} ${j * cell}v${cell}`;
      }
    el("path", { d, stroke: "rgba(0,0,0,0.6)", "stroke-width": 0.009, fill: "none", "stroke-linecap": "square" },
      this.fieldLayer);
    el("path", { class: "zone-outline", d, stroke: "#ffffff", "stroke-width": 0.004, fill: "none",
      "stroke-linecap": "square" }, this.fieldLayer);
    const [bx, by] = zone.best;
    el("path", { class: "zone-best", d: `M${bx - 0.02} ${by} H${bx + 0.02} M${bx} ${by - 0.02} V${by + 0.02}`,
      stroke: "#ffffff", "stroke-width": 0.005 }, this.fieldLayer);
  }

  // A ball's colour on the table and on its path.
  colourOf(name) {
    return ballLook(name || "cue ball").colour;
  }

  // A shot's paths: the cue ball's, then each object ball's that moved (`balls` of the
  // simulate reply, the cue ball first), each ending in a ghost where it stops; each in
  // its ball's colour, dashed while it slides. Where the cue ball first strikes a ball,
  // the ghost ball (the cue ball at contact) is drawn.
  drawPath(shot, style) {
    this.drawBallPath(shot, style, BALL_COLOURS.white, "cue ball");
    for (const b of (shot.balls ?? []).slice(1))
      if (b.path?.length) this.drawBallPath(b, style, this.colourOf(b.name), b.name);
    if (style === "faint") return;
    const contact = (shot.events ?? []).find((e) => e.type === "ball_contact");
    if (contact) {
      const [x, y] = contact.position;
      const g = el("g", { class: "ghost-ball" }, this.markLayer);
      el("circle", { cx: x, cy: y, r: this.scene.ball_radius, fill: "rgba(255,255,255,0.25)",
        stroke: "#ffffff", "stroke-width": 0.005, "stroke-dasharray": "0.012 0.008" }, g);
      el("title", {}, g).textContent = `ghost ball: the cue ball where it strikes (${metres(x)}, ${metres(y)}) m`;
    }
  }

  // One ball's movement: {path, events, final_position}.
  drawBallPath(shot, style, colour = BALL_COLOURS.white, name = "cue ball") {
    const width = style === "faint" ? 0.006 : style === "hover" ? 0.009 : 0.012;
    const g = el("g", { class: `path ${style}`, opacity: style === "faint" ? 0.55 : 1,
      "data-ball": name }, this.pathLayer);
    // Consecutive segments of one motion make one SVG path of quadratic Bezier pieces
    // (exact: the ball moves on parabolas between events).
    let d = "", motion = null;
    const flush = () => {
      if (!d) return;
      const stroke = style === "faint" ? "#dcdcdc" : colour;
      const attributes = { d, stroke, "stroke-width": width, "data-motion": motion };
      if (motion === "sliding") attributes["stroke-dasharray"] = SLIDING_DASH;
      // A dark edge keeps a white or yellow line readable on the cloth.
      if (style !== "faint")
        el("path", { d, stroke: "rgba(0,0,0,0.45)", "stroke-width": width * 1.7,
          "stroke-dasharray": attributes["stroke-dasharray"] ?? "none" }, g);
      el("path", attributes, g);
      d = "";
    };
    for (const seg of shot.path) {
      if (seg.motion !== motion) flush();
      motion = seg.motion;
      const T = seg.t1 - seg.t0;
      const c = [seg.p0[0] + 0.5 * seg.v0[0] * T, seg.p0[1] + 0.5 * seg.v0[1] * T];
      const end = at(seg, T);
      d += `${d ? "" : `M${seg.p0[0]} ${seg.p0[1]}`} Q${c[0]} ${c[1]} ${end[0]} ${end[1]}`;
    }
    flush();
    if (style === "faint") return;
    // Cushion contacts numbered in order, and where the ball ends.
    let n = 0;
    for (const e of shot.events) {
      if (e.type !== "cushion") continue;
      el("circle", { cx: e.position[0], cy: e.position[1], r: 0.016, fill: "#fff", stroke: "#222",
        "stroke-width": 0.003 }, this.markLayer);
      const label = el("text", { x: e.position[0], y: -e.position[1] + 0.011, "font-size": 0.03,
        "text-anchor": "middle", transform: "scale(1,-1)", fill: "#222" }, this.markLayer);
      label.textContent = String(++n);
    }
    const [x, y] = shot.final_position;
    el("circle", { cx: x, cy: y, r: this.scene.ball_radius, fill: "url(#ghost-fill)", stroke: "#ffffff",
      "stroke-width": 0.004, "stroke-dasharray": "0.01 0.006", class: "rest" }, this.markLayer);
  }

  // Moves the balls along a shot's paths (simulate's JSON) at `rate` times real time;
  // onTick(t, duration) after each frame. The moving balls are drawn over the table's
  // own, which keep their places; the last frame leaves each where it stops.
  animate(shot, rate, onTick) {
    this.stopAnimation();
    const moving = [{ name: "cue ball", path: shot.path }];
    for (const b of (shot.balls ?? []).slice(1))
      if (b.path?.length) moving.push({ name: b.name, path: b.path });
    const duration = Math.max(...moving.map((m) => m.path.at(-1)?.t1 ?? 0));
    // Each moving ball: its circle (which carries its place in cx, cy) and, for a pool
    // ball, its band and number drawn at the origin and moved with it.
    const circles = moving.map((m) => {
      const look = ballLook(m.name);
      const circle = el("circle", { r: this.scene.ball_radius, fill: look.striped ? "#ffffff" : look.colour,
        stroke: "#000", "stroke-width": 0.004, "data-ball": m.name }, this.animLayer);
      if (look.number > 0) {
        const g = el("g", { "pointer-events": "none" }, this.animLayer);
        drawBall(g, 0, 0, this.scene.ball_radius, look, { class: "" });
        g.firstChild.remove();  // the circle above is the ball's
        circle.decor = g;
      }
      return circle;
    });
    const place = (t) => moving.forEach((m, i) => {
      const path = m.path;
      let p = path[0].p0;
      if (t >= path.at(-1).t1) p = at(path.at(-1), path.at(-1).t1 - path.at(-1).t0);
      else for (const seg of path) if (t >= seg.t0 && t <= seg.t1) { p = at(seg, t - seg.t0); break; }
      circles[i].setAttribute("cx", p[0]);
      circles[i].setAttribute("cy", p[1]);
      circles[i].decor?.setAttribute("transform", `translate(${p[0]} ${p[1]})`);
    });
    const started = performance.now();
    this.svg.dataset.anim = "running";
    const frame = (now) => {
      const t = Math.min(duration, ((now - started) / 1000) * rate);
      place(t);
      this.svg.dataset.animT = t.toFixed(3);
      onTick?.(t, duration);
      if (t < duration) this.animFrame = requestAnimationFrame(frame);
      else this.svg.dataset.anim = "done";
    };
    place(0);
    this.animFrame = requestAnimationFrame(frame);
  }

  stopAnimation() {
    if (this.animFrame) cancelAnimationFrame(this.animFrame);
    this.animFrame = null;
    this.animLayer?.replaceChildren();
    if (this.svg.dataset.anim) this.svg.dataset.anim = "stopped";
  }

  // Table coordinates of a pointer event.
  toTable(event) {
    const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(
      this.world.getScreenCTM().inverse());
    return [point.x, point.y];
  }

  // Inside the cushions (at least 1 mm clear of where a ball's centre meets one), to the
  // millimetre.
  clamp([x, y]) {
    const s = this.scene;
    const lo = Math.ceil(1000 * s.contact_offset + 1) / 1000;
    const hi = (size) => Math.floor(1000 * (size - s.contact_offset) - 1) / 1000;
    const round = (v, top) => Math.min(Math.max(Math.round(1000 * v) / 1000, lo), top);
    return [round(x, hi(s.length)), round(y, hi(s.width))];
  }

  bindPointer() {
    const svg = this.svg;
    let drag = null;
    const ballOf = (target) => this.balls.find((b) => b.group.contains(target));
    svg.onpointerdown = (event) => {
      const b = ballOf(event.target);
      if (b) {
        drag = { ball: b, moved: false };
        b.group.classList.add("dragging");
        b.group.focus({ preventScroll: true });
        svg.setPointerCapture(event.pointerId);
        event.preventDefault();
      } else if (event.target === this.cloth || this.world.contains(event.target)) {
        drag = { ball: null, moved: false };
      }
    };
    svg.onpointermove = (event) => {
      const p = this.toTable(event);
      const s = this.scene;
      if (p[0] >= 0 && p[0] <= s.length && p[1] >= 0 && p[1] <= s.width)
        this.onPointer?.(`pointer at x = ${metres(p[0])} m, y = ${metres(p[1])} m`);
      else this.onPointer?.("");
      if (!drag?.ball) return;
      drag.moved = true;
      this.onMove(drag.ball.kind, drag.ball.index, this.clamp(p), false);
    };
    svg.onpointerup = (event) => {
      if (!drag) return;
      const p = this.clamp(this.toTable(event));
      if (drag.ball) {
        drag.ball.group.classList.remove("dragging");
        if (drag.moved) this.onMove(drag.ball.kind, drag.ball.index, p, true);
      } else {
        const raw = this.toTable(event);
        const s = this.scene;
        if (raw[0] >= 0 && raw[0] <= s.length && raw[1] >= 0 && raw[1] <= s.width)
          this.onMove("target", 0, p, true);  // a click on the cloth puts the target there
      }
      drag = null;
    };
    svg.onpointerleave = () => this.onPointer?.("");
    svg.onkeydown = (event) => {
      const b = ballOf(event.target);
      const step = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] }[event.key];
      if (!b || !step) return;
      event.preventDefault();
      const d = event.shiftKey ? 0.1 : 0.01;
      const from = this.positionOf(b);
      this.onMove(b.kind, b.index, this.clamp([from[0] + d * step[0], from[1] + d * step[1]]), true);
    };
  }

  positionOf(b) {
    const p = this.positions;
    if (b.kind === "target") return p.target;
    if (b.kind === "cue_ball") return p.cue_ball;
    if (b.kind === "balls") return (p.balls.find((x) => x.index === b.index) ?? p.balls[b.index]).position;
    return p[b.kind][b.index];
  }

  // Focus a ball again after a redraw (keyboard moves redraw the balls).
  focusBall(kind, index) {
    this.balls.find((b) => b.kind === kind && b.index === index)?.group.focus({ preventScroll: true });
  }
}
