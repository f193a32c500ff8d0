// The HTTP API of `facectl serve` (docs/API.md): requests with the page's
// access token, and the server's {"error": ...} text on a refusal.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const token = new URLSearchParams(location.search).get("access_token");

  // An answer the server refused (4xx/5xx): carries its {"error"} text.
  class ApiError extends Error {
    constructor(method, path, status, text) {
      super(`${method} ${path}: ${status} ${text}`);
      this.status = status;
    }
  }

  const TIMEOUT_MS = 5000;  // a server that stops answering counts as gone

  async function request(method, path, body) {
    const headers = {};
    if (token) headers.Authorization = "Bearer " + token;
    const init = { method, headers, cache: "no-store", signal: AbortSignal.timeout(TIMEOUT_MS) };
    if (body !== undefined) {
      headers["Content-Type"] = "application/json";
      init.body = JSON.stringify(body);
    }
    const response = await fetch(path, init);  // a network failure throws TypeError
    const text = await response.text();
    let json = null;
    try { json = text ? JSON.parse(text) : {}; } catch (e) { json = null; }
    if (!response.ok) {
      const reason = json && typeof json.error === "string" ? json.error : text || response.statusText;
      throw new ApiError(method, path, response.status, reason);
    }
    return json;
  }

  // A URL for what cannot send a header (EventSource): the token as a query parameter.
  function urlWithToken(path) {
    if (!token) return path;
    return path + (path.includes("?") ? "&" : "?") + "access_token=" + encodeURIComponent(token);
  }

  ns.api = {
    ApiError,
    get: (path) => request("GET", path),
    // A resource the server may lack (404): null then.
    getIfPresent: (path) => request("GET", path).catch((error) => {
      if (error instanceof ApiError && error.status === 404) return null;
      throw error;
    }),
    // Commands send a JSON body ({} when there is nothing to say).
    post: (path, body) => request("POST", path, body === undefined ? {} : body),
    urlWithToken,
  };
})(window.FaceCtl);
