// The spin map's colours, as `cueplan spinmap` draws them (draw/src/spin_map.cpp:
// MissColourScale, classify, cell_colour): a log scale of the miss distance from the
// problem's tolerance to the next 1-2-5 value at or above the largest coloured miss,
// viridis with the target's end bright; fixed colours for the other outcomes.

// Viridis (matplotlib) at eleven evenly spaced points; linear in between.
const VIRIDIS = [
  [68, 1, 84], [72, 36, 117], [65, 68, 135], [53, 95, 141], [42, 120, 142], [33, 145, 140],
  [34, 168, 132], [68, 191, 112], [122, 209, 81], [189, 223, 38], [253, 231, 37],
];

export const KIND_COLOURS = {
  at_rest_other_cushions: "#c6c6c6",
  hit_obstacle: "#7a7a7a",
  no_outcome: "#f0f0f0",
  no_pot: "#d6604d",  // a pot problem: no aim pots the ball with this spin
  pocketed: "#ffffff",  // drawn hatched in #3a3a3a
};
export const HATCH = "#3a3a3a";
export const OUTLINE = "#000000";

const hex2 = (v) => Math.round(v).toString(16).padStart(2, "0");

export function viridis(t) {
  t = Math.min(Math.max(t, 0), 1) * 10;
  const i = Math.min(9, Math.floor(t));
  const f = t - i;
  const a = VIRIDIS[i];
  const b = VIRIDIS[i + 1];
  return "#" + [0, 1, 2].map((c) => hex2(a[c] + f * (b[c] - a[c]))).join("");
}

// The scale for a map: cells as /api/spinmap gives them, tolerance in m.
export function missScale(cells, tolerance) {
  const nearMm = 1000 * tolerance;
  let largest = 0;
  for (const c of cells)
    if (c.kind === "at_rest_allowed_cushions") largest = Math.max(largest, 1000 * c.miss_distance);
  largest = Math.max(largest, 10 * nearMm);
  // The next 1-2-5 value up.
  const decade = Math.pow(10, Math.floor(Math.log10(largest)));
  let farMm = 10 * decade;
  for (const m of [1, 2, 5])
    if (m * decade >= largest * (1 - 1e-12)) {
      farMm = m * decade;
      break;
    }
  const position = (mm) =>
    !(mm > nearMm) ? 0 : Math.min(Math.max(Math.log(mm / nearMm) / Math.log(farMm / nearMm), 0), 1);
  return {
    nearMm,
    farMm,
    position,
    colour: (missM) => viridis(1 - position(1000 * missM)),
    // 1-2-5 values from the tolerance to the far end, as the command's colour bar.
    ticks() {
      const ticks = [nearMm];
      for (let d = Math.pow(10, Math.floor(Math.log10(nearMm))); d <= farMm; d *= 10)
        for (const m of [1, 2, 5]) {
          const v = m * d;
          if (v > nearMm * 1.6 && v <= farMm * (1 + 1e-9)) ticks.push(v);
        }
      return ticks;
    },
  };
}

// A cell's fill.
export function cellColour(cell, scale) {
  if (cell.kind === "at_rest_allowed_cushions") return scale.colour(cell.miss_distance);
  return KIND_COLOURS[cell.kind] ?? KIND_COLOURS.no_outcome;
}

// ---------------------------------------------------------------------------
// Balls as the pictures draw them (draw/src/table.cpp: ball_colour, named_ball; the names
// as problems/src/ball_names.cpp reads them): snooker's colours by name, also numbered
// ("red3", "red_12"), pool's "1" to "15" (or "ball9") with the number on a white disc,
// 9-15 striped (a white ball with a band of 1-7's colour).

export const BALL_COLOURS = {
  "cue ball": "#fbfbf5", white: "#fbfbf5", red: "#c8102e", yellow: "#f4d000", green: "#1f7a3a",
  brown: "#7b4a21", blue: "#1f4fbf", pink: "#f28cb5", black: "#151515",
};
const POOL_COLOURS = ["#f4d000", "#1f4fbf", "#c8102e", "#5b2a86", "#f07c00", "#1f7a3a", "#7b1e1e", "#151515"];
export const OTHER_BALL = "#e8d9b0";  // a name no game gives a colour (ivory)

// {colour, number (pool 1-15, else 0), striped} of a ball by its name.
export function ballLook(name) {
  name = String(name ?? "");
  if (name === "cue ball" || name === "cue_ball") return { colour: BALL_COLOURS["cue ball"], number: 0, striped: false };
  if (name in BALL_COLOURS) return { colour: BALL_COLOURS[name], number: 0, striped: false };
  const pool = /^(?:ball)?([1-9]\d?)$/.exec(name);
  if (pool && Number(pool[1]) <= 15) {
    const n = Number(pool[1]);
    return { colour: POOL_COLOURS[n > 8 ? n - 9 : n - 1], number: n, striped: n > 8 };
  }
  // A colour numbered to tell balls of one colour apart: "red1", "red_12", "red 3".
  const numbered = /^([a-z]+)[_ -]?\d+$/.exec(name);
  if (numbered && numbered[1] in BALL_COLOURS) return { colour: BALL_COLOURS[numbered[1]], number: 0, striped: false };
  return { colour: OTHER_BALL, number: 0, striped: false };
}
