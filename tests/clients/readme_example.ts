// The README's /analyze example as a program author writes it in TypeScript, against the types
// that openapi-typescript generates from /api/v1/openapi.json (schema.d.ts, written by
// tests/server/test_generated_clients.py). Compiled with tsc --strict: no cast, no any; the
// answers of /analyze and /sweep are narrowed by their `kind`.
import type { components, paths } from "./schema";

type Analyze = paths["/api/v1/analyze"]["post"];
type AnalyzeRequest = Analyze["requestBody"]["content"]["application/json"];
type AnalyzeAnswer = Analyze["responses"][200]["content"]["application/json"];
type SweepAnswer = paths["/api/v1/sweep"]["post"]["responses"][200]["content"]["application/json"];
type Problem = components["schemas"]["Problem"];

export const request: AnalyzeRequest = {
  scene: {
    kind: "linkage",
    points: { A: [0, 0], B: [0, 1], C: [2, 1], D: [2.5, 0] },
    links: {
      ground: { points: ["A", "D"], ground: true },
      crank: { points: ["A", "B"] },
      coupler: { points: ["B", "C"] },
      rocker: { points: ["D", "C"] },
    },
    joints: [
      { type: "revolute", point: "A", links: ["ground", "crank"] },
      { type: "revolute", point: "B", links: ["crank", "coupler"] },
      { type: "revolute", point: "C", links: ["coupler", "rocker"] },
      { type: "revolute", point: "D", links: ["rocker", "ground"] },
    ],
    drivers: [{ link: "crank", omega: -1.0, alpha: -1.0 }],
  },
  quantities: ["velocity", "acceleration", "poles"],
};

/** The coupler's angular velocity (rad/s), or the problem's detail. */
export async function couplerOmega(base: string): Promise<number | string> {
  const response = await fetch(`${base}/api/v1/analyze`, {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(request),
  });
  if (!response.ok) {
    const problem: Problem = await response.json();
    return `${problem.code}: ${problem.detail}`;
  }
  const answer: AnalyzeAnswer = await response.json();
  // The answers are a union discriminated on `kind`: a linkage's has links.
  if (answer.kind !== "linkage") return `a ${answer.kind} has no coupler`;
  return answer.links?.["coupler"]?.omega ?? "no omega";
}

/** What a sweep's arrays run over: the driver's angle (rad) or time (s), narrowed by `kind`. */
export function abscissa(answer: SweepAnswer): number[] {
  switch (answer.kind) {
    case "linkage":
    case "cam":
      return answer.kind === "linkage" ? answer.driver_angle : answer.cam_angle;
    case "linkage_time":
    case "spatial_chain":
    case "gear_train":
      return answer.time;
  }
}
