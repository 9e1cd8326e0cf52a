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

// GET (body undefined) or POST a JSON body; resolves to the answer's JSON. A 503 (all
// workers busy, or an impact table still being made) is asked again after the server's
// Retry-After, up to `retries` times; onWait(message, answer) says so meanwhile.
export async function call(path, body, { signal, onWait, retries = 60 } = {}) {
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
    if (response.status === 503 && attempt < retries) {
      const seconds = Number(response.headers.get("Retry-After")) || 1;
      onWait?.(message, answer);
      await sleep(seconds * 1000, signal);
      continue;
    }
    throw new ApiError(message, { status: response.status, field: answer?.field ?? null });
  }
}
