// The server's JSON API (apps/cueplan/serve_api.hpp): one call per request, errors as
// ApiError with the server's message and the field it names.

export class ApiError extends Error {
  constructor(message, { status = 0, field = null, aborted = false } = {}) {
    super(message);
    this.status = status;
    this.field = field;
    this.aborted = aborted;
  }
}

const sleep = (ms, signal) =>
  new Promise((resolve, reject) => {
    const timer = setTimeout(resolve, ms);
    signal?.addEventListener("abort", () => {
      clearTimeout(timer);
      reject(new ApiError("cancelled", { aborted: true }));
    });
  });

// GET (body undefined) or POST a JSON body; resolves to the answer's JSON. A 503 is
// asked again after the server's Retry-After: once when the server is busy (its queue
// full, or the wait beyond its budget), up to `tableRetries` times while an impact
// table is being made; onWait(message, answer, seconds) says so meanwhile.
export async function call(path, body, { signal, onWait, tableRetries = 60 } = {}) {
  let busyRetries = 0;
  for (let attempt = 0; ; ++attempt) {
    let response;
    try {
      response = await fetch(path, {
        method: body === undefined ? "GET" : "POST",
        headers: body === undefined ? {} : { "Content-Type": "application/json" },
        body: body === undefined ? undefined : JSON.stringify(body),
        signal,
      });
    } catch (e) {
      if (e.name === "AbortError") throw new ApiError("cancelled", { aborted: true });
      throw new ApiError("cannot reach the cueplan server (is `cueplan serve` still running?)");
    }
    let answer = null;
    try {
      answer = await response.json();
    } catch {
      answer = null;
    }
    if (response.ok && answer) return answer;
    const message = answer?.error ?? `the server answered HTTP ${response.status}`;
    const table = Boolean(answer?.impact_table);
    if (response.status === 503 && (table ? attempt < tableRetries : busyRetries++ < 1)) {
      const seconds = Number(response.headers.get("Retry-After")) || 1;
      onWait?.(message, answer, seconds);
      await sleep(seconds * 1000, signal);
      continue;
    }
    throw new ApiError(message, { status: response.status, field: answer?.field ?? null });
  }
}
