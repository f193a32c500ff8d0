// The expression library (GET /api/v1/expressions): a hold button each, at a chosen weight.
"use strict";
window.FaceCtl = window.FaceCtl || {};

(function (ns) {
  const { el, command } = ns.ui;

  class ExpressionsPanel {
    constructor() {
      this.list = document.getElementById("expression-list");
      this.weight = document.getElementById("expr-weight");
      const shown = document.getElementById("expr-weight-value");
      this.weight.oninput = () => { shown.textContent = Number(this.weight.value).toFixed(2); };
    }

    setExpressions(names) {
      this.list.replaceChildren(...names.map((name) => el("button", {
        type: "button", "aria-label": `hold ${name}`, text: name,
        onclick: () => command("/api/v1/expression/hold", { name, weight: Number(this.weight.value) }),
      })));
      if (names.length === 0) this.list.append(el("p", { text: "the expression library is empty" }));
    }

    render(state) {
      const source = (state && state.source) || {};
      for (const button of this.list.querySelectorAll("button")) {
        button.classList.toggle("active", source.kind === "expression" && source.name === button.textContent);
      }
    }
  }

  ns.ExpressionsPanel = ExpressionsPanel;
})(window.FaceCtl);
