// The spin map as a disc of tip offsets (tip right of centre along x, above centre along
// y, as fractions of the ball radius R), one cell per grid spin of /api/spinmap's
// `cells`, coloured as `cueplan spinmap` colours them (colours.js), the landing spins
// outlined. Hovering a cell or moving to it with the arrow keys reports it; a click or
// Enter selects it.

import { cellColour, HATCH, missScale, OUTLINE, viridis } from "./colours.js";

const SVG = "http://www.w3.org/2000/svg";
const SPIN_PER_TIP = 2.5;  // k = 2.5 d / R
const PLANNED = "#e6007e";
const PENDING = "#e4e4e4";  // a spin whose success under noise is not estimated yet

function el(name, attributes = {}, parent = null) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

const trim = (v) => String(Number(v.toFixed(3)));

export class SpinDisc {
  // onHover(cell or null), onSelect(cell): cells as /api/spinmap gives them.
  constructor(svg, legend, { onHover, onSelect }) {
    this.svg = svg;
    this.legend = legend;
    this.onHover = onHover;
    this.onSelect = onSelect;
    this.map = null;
    this.cursor = null;  // index of the cell under the pointer or the keyboard's cursor
    this.bind();
  }

  // Draws a map; `planned` (a stroke {topspin_k, sidespin_k}) is ringed when given;
  // `cushions` says what the problem allows, e.g. " after 1 cushion".
  draw(map, { planned = null, cushions = "" } = {}) {
    this.map = map;
    this.scale = missScale(map.cells, map.tolerance);
    this.radius = map.spin_max / SPIN_PER_TIP;
    this.half = (map.grid - 1) / 2;
    this.cellSize = (2 * this.radius) / (map.grid - 1);
    this.showSuccess = map.cells.some((c) => "success" in c) || this.successMode === true;
    this.byGrid = new Map();
    map.cells.forEach((c, i) => this.byGrid.set(`${this.rowOf(c)},${this.colOf(c)}`, i));

    const r = this.radius, h = this.cellSize;
    const left = 0.3 * r, bottom = 0.3 * r, pad = 0.04 * r + h;
    this.svg.setAttribute("viewBox", `${-r - pad - left} ${-r - pad} ${2 * r + 2 * pad + left} ${2 * r + 2 * pad + bottom}`);
    this.svg.replaceChildren();
    const defs = el("defs", {}, this.svg);
    const hatch = el("pattern", { id: "hatch", width: h / 2, height: h / 2, patternUnits: "userSpaceOnUse",
      patternTransform: "rotate(45)" }, defs);
    el("rect", { width: h / 2, height: h / 2, fill: "#ffffff" }, hatch);
    el("line", { x1: 0, y1: 0, x2: 0, y2: h / 2, stroke: HATCH, "stroke-width": h / 6 }, hatch);

    const world = el("g", { transform: "scale(1,-1)" }, this.svg);
    this.world = world;
    el("circle", { cx: 0, cy: 0, r: r + h / 2, fill: "#fafafa", stroke: "#bbb", "stroke-width": h / 10 }, world);
    const cells = el("g", { "shape-rendering": "crispEdges" }, world);
    this.rects = map.cells.map((c) =>
      el("rect", { x: c.tip_right - h / 2, y: c.tip_up - h / 2, width: h, height: h,
        fill: this.fillOf(c), "data-kind": c.kind,
        "data-miss": c.miss_distance ?? "" }, cells));
    const outlines = el("g", { fill: "none", stroke: OUTLINE, "stroke-width": h / 7 }, world);
    for (const c of map.cells)
      if (c.lands) el("rect", { x: c.tip_right - h / 2, y: c.tip_up - h / 2, width: h, height: h }, outlines);
    el("circle", { cx: 0, cy: 0, r, fill: "none", stroke: "#333", "stroke-width": h / 8,
      "stroke-dasharray": `${h / 2} ${h / 3}` }, world);
    el("line", { x1: -r - h, y1: 0, x2: r + h, y2: 0, stroke: "#666", "stroke-width": h / 14, opacity: 0.6 }, world);
    el("line", { x1: 0, y1: -r - h, x2: 0, y2: r + h, stroke: "#666", "stroke-width": h / 14, opacity: 0.6 }, world);
    if (planned) {
      el("circle", { cx: planned.sidespin_k / SPIN_PER_TIP, cy: planned.topspin_k / SPIN_PER_TIP,
        r: 1.3 * h, fill: "none", stroke: PLANNED, "stroke-width": h / 4, class: "planned" }, world);
    }
    this.hoverMark = el("rect", { width: h, height: h, fill: "none", stroke: "#ffffff",
      "stroke-width": h / 4, visibility: "hidden", class: "hover" }, world);
    this.selectMark = el("rect", { width: h, height: h, fill: "none", stroke: "#f0b400",
      "stroke-width": h / 4, visibility: "hidden", class: "selected" }, world);

    // Axes in tip offset (fractions of R), outside the flipped group so text reads upright.
    const font = 0.075 * r;
    const text = el("g", { "font-size": font, fill: "#333" }, this.svg);
    for (const t of [-r, -r / 2, 0, r / 2, r]) {
      el("text", { x: t, y: r + pad + 0.9 * font, "text-anchor": "middle" }, text).textContent = trim(t);
      el("text", { x: -r - pad - 0.05 * r, y: -t + 0.35 * font, "text-anchor": "end" }, text).textContent = trim(t);
    }
    el("text", { x: 0, y: r + pad + 2.1 * font, "text-anchor": "middle" }, text).textContent =
      "tip right of centre (R)";
    el("text", { x: -r - pad - 0.2 * r, y: 0, "text-anchor": "middle",
      transform: `rotate(-90 ${-r - pad - 0.2 * r} 0)` }, text).textContent = "tip above centre (R)";
    this.planned = planned;
    this.cushions = cushions;
    this.drawLegend(map, planned, cushions);
    this.cursor = null;
  }

  // A cell's fill: by where it stops, or, showing how forgiving each spin is, by its
  // success under noise (a light grey until it is estimated).
  fillOf(c) {
    if (this.showSuccess) return "success" in c ? viridis(c.success) : PENDING;
    return c.kind === "pocketed" ? "url(#hatch)" : cellColour(c, this.scale);
  }

  // Shows the success under noise (on) or where the spins stop (off); `map.cells` may
  // gain `success` a part at a time: call again to shade what has arrived.
  setSuccess(on) {
    this.successMode = on;
    if (!this.map) return;
    const was = this.showSuccess;
    this.showSuccess = on;
    this.map.cells.forEach((c, i) => {
      this.rects[i].setAttribute("fill", this.fillOf(c));
      if ("success" in c) this.rects[i].setAttribute("data-success", c.success);
      else this.rects[i].removeAttribute("data-success");
    });
    if (was !== on) this.drawLegend(this.map, this.planned, this.cushions);
  }

  rowOf(c) { return Math.round((c.topspin_k / this.map.spin_max) * this.half + this.half); }
  colOf(c) { return Math.round((c.sidespin_k / this.map.spin_max) * this.half + this.half); }

  // The colour bar (log scale, mm) and a line for each outcome the map has.
  drawLegend(map, planned, cushions) {
    const scale = this.scale;
    this.legend.replaceChildren();
    if (this.showSuccess) return this.drawSuccessLegend(map, planned);
    const bar = el("svg", { viewBox: "0 0 300 44", role: "img",
      "aria-label": `colour scale: miss distance from ${scale.nearMm} mm to ${scale.farMm} mm, log scale` }, null);
    const grad = el("linearGradient", { id: "miss-gradient" }, el("defs", {}, bar));
    for (let i = 0; i <= 20; ++i)
      el("stop", { offset: i / 20, "stop-color": viridis(1 - i / 20) }, grad);
    el("rect", { x: 10, y: 4, width: 280, height: 12, fill: "url(#miss-gradient)", stroke: "#888", "stroke-width": 0.5 }, bar);
    for (const t of scale.ticks()) {
      const x = 10 + 280 * scale.position(t);
      el("line", { x1: x, y1: 16, x2: x, y2: 20, stroke: "#444" }, bar);
      el("text", { x, y: 30, "font-size": 10, "text-anchor": "middle", fill: "#333" }, bar).textContent =
        t >= 1000 ? `${t / 1000} m` : `${Number(t.toPrecision(4))}`;
    }
    el("text", { x: 150, y: 42, "font-size": 10, "text-anchor": "middle", fill: "#555" }, bar).textContent =
      "miss distance from the target (mm, log scale)";
    this.legend.appendChild(bar);

    const o = map.outcomes;
    const rows = [
      ["land", `lands: at rest within ${Number((1000 * map.tolerance).toPrecision(4))} mm${cushions} (${map.landing} spins)`],
      o.at_rest_other_cushions > 0 && ["wrong", `at rest after a cushion count not allowed (${o.at_rest_other_cushions})`],
      o.pocketed > 0 && ["pocketed", `pocketed (${o.pocketed})`],
      o.hit_obstacle > 0 && ["obstacle", `stops against an obstacle ball (${o.hit_obstacle})`],
      o.no_pot > 0 && ["no-pot", `no aim pots the ${map.pot_ball ?? "object ball"} with this spin (${o.no_pot})`],
      o.no_outcome > 0 && ["none", `no outcome: the simulation gave no result (${o.no_outcome})`],
      planned && ["planned", "the planner's spin"],
    ].filter(Boolean);
    for (const [kind, words] of rows) {
      const row = document.createElement("div");
      row.className = "row";
      const box = document.createElement("span");
      box.className = `box ${kind}`;
      const label = document.createElement("span");
      label.textContent = words;
      row.append(box, label);
      this.legend.appendChild(row);
    }
  }

  // The colour bar of the success under noise (0 % dark to 100 % bright).
  drawSuccessLegend(map, planned) {
    const bar = el("svg", { viewBox: "0 0 300 44", role: "img", id: "success-scale",
      "aria-label": "colour scale: success under noise, 0 to 100 %" }, null);
    const grad = el("linearGradient", { id: "success-gradient" }, el("defs", {}, bar));
    for (let i = 0; i <= 20; ++i) el("stop", { offset: i / 20, "stop-color": viridis(i / 20) }, grad);
    el("rect", { x: 10, y: 4, width: 280, height: 12, fill: "url(#success-gradient)", stroke: "#888", "stroke-width": 0.5 }, bar);
    for (let t = 0; t <= 100; t += 25) {
      const x = 10 + 2.8 * t;
      el("line", { x1: x, y1: 16, x2: x, y2: 20, stroke: "#444" }, bar);
      el("text", { x, y: 30, "font-size": 10, "text-anchor": "middle", fill: "#333" }, bar).textContent = `${t}`;
    }
    el("text", { x: 150, y: 42, "font-size": 10, "text-anchor": "middle", fill: "#555" }, bar).textContent =
      "success under noise, %";
    this.legend.appendChild(bar);
    const rows = [
      ["land", `outlined: lands when struck exactly (${map.landing} spins)`],
      ["pending", "not estimated yet"],
      planned && ["planned", "the planner's spin"],
    ].filter(Boolean);
    for (const [kind, words] of rows) {
      const row = document.createElement("div");
      row.className = "row";
      const box = document.createElement("span");
      box.className = `box ${kind}`;
      const label = document.createElement("span");
      label.textContent = words;
      row.append(box, label);
      this.legend.appendChild(row);
    }
  }

  cellAt(event) {
    const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(this.world.getScreenCTM().inverse());
    const col = Math.round((p.x / this.radius) * this.half + this.half);
    const row = Math.round((p.y / this.radius) * this.half + this.half);
    const i = this.byGrid.get(`${row},${col}`);
    return i === undefined ? null : i;
  }

  mark(rect, i) {
    if (i === null || i === undefined) {
      rect.setAttribute("visibility", "hidden");
      return;
    }
    const c = this.map.cells[i], h = this.cellSize;
    rect.setAttribute("x", c.tip_right - h / 2);
    rect.setAttribute("y", c.tip_up - h / 2);
    rect.setAttribute("visibility", "visible");
  }

  hover(i) {
    if (i === this.cursor) return;
    this.cursor = i;
    this.mark(this.hoverMark, i);
    this.onHover(i === null ? null : this.map.cells[i]);
  }

  select(i) {
    if (i === null) return;
    this.mark(this.selectMark, i);
    this.onSelect(this.map.cells[i]);
  }

  bind() {
    this.svg.onpointermove = (e) => this.map && this.hover(this.cellAt(e));
    this.svg.onpointerleave = () => this.map && this.hover(null);
    this.svg.onclick = (e) => this.map && this.select(this.cellAt(e));
    this.svg.onkeydown = (e) => {
      if (!this.map) return;
      if (e.key === "Enter" || e.key === " ") {
        e.preventDefault();
        this.select(this.cursor);
        return;
      }
      const step = { ArrowLeft: [0, -1], ArrowRight: [0, 1], ArrowUp: [1, 0], ArrowDown: [-1, 0] }[e.key];
      if (!step) return;
      e.preventDefault();
      let row = this.half, col = this.half;
      if (this.cursor !== null) {
        const c = this.map.cells[this.cursor];
        row = this.rowOf(c) + step[0];
        col = this.colOf(c) + step[1];
      }
      const i = this.byGrid.get(`${row},${col}`);
      if (i !== undefined) this.hover(i);
    };
  }
}
