// The server's API (docs/web-api.md): JSON requests, 422 errors as ApiError with the one-line
// message and the failing field's path, and "latest wins" requests that abort their stale
// predecessor.

/** A request the server refused: `message` (one line), `path` ("bodies.0.mass", or "toml";
 * "" when no field is named) and the HTTP `status`. */
export class ApiError extends Error {
  constructor(message, path = "", status = 0) {
    super(message);
    this.path = path;
    this.status = status;
  }
}

/** "bodies.0.mass" from a 422 `loc` such as ["body", "system", "bodies", 0, "mass"]. */
export function fieldPath(loc) {
  const parts = [...(loc || [])];
  if (parts[0] === "body") parts.shift();
  if (parts[0] === "system") parts.shift();
  return parts.join(".");
}

/** "springs.0.ends" from a message about the whole system that names a part of it first
 * ("system: springs[0].ends: a spring cannot join 'hoop' to itself"); "" when it names none. */
export function pathInMessage(message) {
  const found = /^system: ((?:bodies|springs|anchors|forces)\[\d+\](?:\.[A-Za-z_]\w*|\[\d+\])*)[:\s]/
    .exec(message || "");
  return found ? found[1].replace(/\[(\d+)\]/g, ".$1").replace(/^\./, "") : "";
}

async function failure(response) {
  let body = null;
  try {
    body = await response.json();
  } catch {
    // not JSON: keep the status line
  }
  if (body && body.message) {
    const loc = Array.isArray(body.detail) && body.detail[0] ? body.detail[0].loc : [];
    return new ApiError(body.message, fieldPath(loc) || pathInMessage(body.message),
      response.status);
  }
  const detail = body && typeof body.detail === "string" ? body.detail : response.statusText;
  return new ApiError(`${response.status}: ${detail}`, "", response.status);
}

async function send(method, path, payload, signal) {
  const response = await fetch(path, {
    method,
    signal,
    headers: payload === undefined ? {} : { "Content-Type": "application/json" },
    body: payload === undefined ? undefined : JSON.stringify(payload),
  });
  if (!response.ok) throw await failure(response);
  return response;
}

export const getJson = async (path) => (await send("GET", path)).json();
export const postJson = async (path, payload, signal) =>
  (await send("POST", path, payload, signal)).json();
export const postBlob = async (path, payload) => (await send("POST", path, payload)).blob();

/** A POST endpoint where only the newest request matters: `call(payload)` aborts the previous
 * one still running, and resolves to null if itself is aborted by a newer call. */
export function latest(path) {
  let controller = null;
  return async (payload) => {
    if (controller) controller.abort();
    const mine = new AbortController();
    controller = mine;
    try {
      return await postJson(path, payload, mine.signal);
    } catch (error) {
      if (error.name === "AbortError") return null;
      throw error;
    } finally {
      if (controller === mine) controller = null;
    }
  };
}
