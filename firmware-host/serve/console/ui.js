// Small DOM helpers shared by the panels, and the one place that sends a
// command and shows what the server said when it refused.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  function el(tag, attrs, ...children) {
    const node = document.createElement(tag);
    for (const [key, value] of Object.entries(attrs || {})) {
      if (key === "onclick" || key === "oninput" || key === "onchange") node[key] = value;
      else if (key === "text") node.textContent = value;
      else node.setAttribute(key, value);
    }
    for (const child of children) node.append(child);
    return node;
  }

  let messageTimer = null;
  function showMessage(text, isError) {
    const box = document.getElementById("message");
    box.textContent = text;
    box.className = isError ? "error" : "info";
    box.hidden = false;
    clearTimeout(messageTimer);
    messageTimer = setTimeout(() => { box.hidden = true; }, isError ? 12000 : 3000);
  }

  function describe(error) {
    if (error instanceof ns.api.ApiError) return error.message;
    return `${error.message || error} (is facectl serve running?)`;
  }

  // Sends one command; a refusal (4xx with {"error"}) or a lost connection is
  // shown to the operator. Returns the answer, or null when it failed.
  async function command(path, body) {
    try {
      const answer = await ns.api.post(path, body);
      if (ns.onCommandDone) ns.onCommandDone();
      return answer;
    } catch (error) {
      showMessage(describe(error), true);
      return null;
    }
  }

  // Writes only a change: a screen reader announces a live region on every write.
  function setText(node, text) {
    if (node.textContent !== text) node.textContent = text;
  }

  function format(value, digits) {
    return typeof value === "number" && isFinite(value) ? value.toFixed(digits) : "–";
  }

  ns.ui = { el, showMessage, describe, command, format, setText };
})(window.FaceCtl);
