// The tip-offset control: the cue ball's face, where the cue tip strikes it (right of
// centre along x, above centre along y, in fractions of the radius R), within the spin
// limit (dashed). A click puts the tip there; the arrow keys move it a tenth of a tip.

const SVG = "http://www.w3.org/2000/svg";
const STEP = 0.025;  // R: a tenth of a tip (a tip is a quarter of the radius)

function el(name, attributes = {}, parent = null) {
  const e = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (parent) parent.appendChild(e);
  return e;
}

export class TipDisc {
  // onChange({right, up}): the offset chosen, clamped to the limit.
  constructor(svg, { onChange }) {
    this.svg = svg;
    this.onChange = onChange;
    this.limit = 0.5;
    this.offset = { right: 0, up: 0 };
    const world = el("g", { transform: "scale(1,-1)" }, svg);
    this.world = world;
    el("circle", { cx: 0, cy: 0, r: 1, fill: "#fbfbf5", stroke: "#333", "stroke-width": 0.03 }, world);
    for (let r = 0.25; r < 1; r += 0.25)
      el("circle", { cx: 0, cy: 0, r, fill: "none", stroke: "#ccc", "stroke-width": 0.012 }, world);
    el("path", { d: "M-1 0 H1 M0 -1 V1", stroke: "#ccc", "stroke-width": 0.012 }, world);
    this.limitRing = el("circle", { cx: 0, cy: 0, r: this.limit, fill: "none", stroke: "#a4001d",
      "stroke-width": 0.025, "stroke-dasharray": "0.06 0.04" }, world);
    this.tip = el("circle", { r: 0.09, fill: "#0b5fa5", stroke: "#fff", "stroke-width": 0.025 }, world);
    svg.onclick = (e) => {
      const p = new DOMPoint(e.clientX, e.clientY).matrixTransform(world.getScreenCTM().inverse());
      this.choose({ right: p.x, up: p.y });
    };
    svg.onkeydown = (e) => {
      const step = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] }[e.key];
      if (!step) return;
      e.preventDefault();
      this.choose({ right: this.offset.right + STEP * step[0], up: this.offset.up + STEP * step[1] });
    };
    this.show(this.offset);
  }

  // The spin limit as a tip offset (R).
  setLimit(limit) {
    this.limit = limit;
    this.limitRing.setAttribute("r", limit);
  }

  choose({ right, up }) {
    const r = Math.hypot(right, up);
    const f = r > this.limit ? this.limit / r : 1;
    const round = (v) => Math.round(1000 * v * f) / 1000;
    this.show({ right: round(right), up: round(up) });
    this.onChange(this.offset);
  }

  // Shows an offset without reporting it.
  show(offset) {
    this.offset = offset;
    this.tip.setAttribute("cx", offset.right);
    this.tip.setAttribute("cy", offset.up);
    this.svg.setAttribute("aria-valuetext",
      `tip ${Math.abs(offset.right).toFixed(3)} R ${offset.right < 0 ? "left" : "right"} of centre, ` +
      `${Math.abs(offset.up).toFixed(3)} R ${offset.up < 0 ? "below" : "above"} centre`);
  }
}
