// velplan's interactive page: draws the records of the data block into the three SVG panels
// as the crank-angle slider moves and the step buttons build the plans. No network, no
// libraries. Coordinates are hundredths of a millimetre, y down (see velplan/html/records.py).
(function () {
  "use strict";
  var D = JSON.parse(document.getElementById("velplan-data").textContent);
  var W = D.words, LT = D.stroke, PL = D.plans;
  var NV = PL[0].steps, NA = PL[1].steps;
  var state = {pos: 0, cursor: 0, timer: null};
  var $ = function (id) { return document.getElementById(id); };

  function esc(s) {
    return String(s).replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;");
  }
  // text with the sheets' index marks (v_{BA}, 10^{−3}) as HTML: <sub>, <sup> (velplan.render.shapes)
  function marked(s) {
    return esc(s).replace(/_\{([^{}]*)\}/g, "<sub>$1</sub>").replace(/\^\{([^{}]*)\}/g, "<sup>$1</sup>");
  }
  // x to 4 significant figures, decimal comma in ru and uk, no exponent (velplan.views.base.number)
  function num(x, digits) {
    if (x === null || !isFinite(x)) return "—";
    digits = digits || 4;
    var t;
    if (x === 0) t = "0";
    else {
      var dec = Math.max(0, digits - 1 - Math.floor(Math.log10(Math.abs(x))));
      t = x.toFixed(Math.min(dec, 20));
      if (t.indexOf(".") >= 0) t = t.replace(/0+$/, "").replace(/\.$/, "");
    }
    if (t === "-0" || t === "") t = "0";
    return D.comma ? t.replace(".", ",") : t;
  }
  function pts(r, from) {
    var out = [];
    for (var j = from; j + 1 < r.length; j += 2) out.push(r[j] + "," + r[j + 1]);
    return out.join(" ");
  }
  // one record → SVG markup; attrs: extra attributes (class of the step, data-s)
  function draw(r, cls, attrs) {
    var c = "l" + r[1] + (cls ? " " + cls : "");
    var a = attrs || "";
    switch (r[0]) {
      case 0: return '<polyline class="' + c + '"' + a + ' points="' + pts(r, 2) + '"/>';
      case 1: return '<polygon class="' + c + " f" + r[2] + '"' + a + ' points="' + pts(r, 3) + '"/>';
      case 2: return '<circle class="' + c + " f" + r[2] + '"' + a + ' cx="' + r[3] + '" cy="' + r[4] +
        '" r="' + r[5] + '"/>';
      case 3: return arrow(r, c, a);
      case 4: {
        var anchor = ["start", "middle", "end"][r[5]];
        var rot = r[6] ? ' transform="rotate(' + r[6] + " " + r[2] + " " + r[3] + ')"' : "";
        return '<text class="t' + (cls ? " " + cls : "") + '"' + a + ' x="' + r[2] + '" y="' + r[3] +
          '" font-size="' + r[4] + '" text-anchor="' + anchor + '"' + rot + ">" + esc(r[7]) + "</text>";
      }
      case 5: {
        var d = [];
        for (var j = 2; j + 3 < r.length; j += 4) d.push("M" + r[j] + " " + r[j + 1] + "L" + r[j + 2] + " " + r[j + 3]);
        return '<path class="' + c + '"' + a + ' d="' + d.join("") + '"/>';
      }
    }
    return "";
  }
  // an arrow as the sheets draw it: the shaft stops at the base of a filled head
  function arrow(r, c, a) {
    var x0 = r[2], y0 = r[3], x1 = r[4], y1 = r[5];
    var dx = x1 - x0, dy = y1 - y0, span = Math.hypot(dx, dy);
    if (span === 0) return "";
    var head = LT[r[1]].head, len = head[0], wid = head[1];
    var ux = dx / span, uy = dy / span, k = Math.min(1, span / len);
    var bx = x1 - ux * len * k, by = y1 - uy * len * k;
    var hx = -uy * wid * k / 2, hy = ux * wid * k / 2;
    var out = "";
    if (Math.hypot(bx - x0, by - y0) > 1) {
      out += '<line class="' + c + '"' + a + ' x1="' + x0 + '" y1="' + y0 + '" x2="' + bx.toFixed(0) +
        '" y2="' + by.toFixed(0) + '"/>';
    }
    return out + '<polygon class="head ' + c + '"' + a + ' points="' + x1 + "," + y1 + " " +
      (bx + hx).toFixed(0) + "," + (by + hy).toFixed(0) + " " + (bx - hx).toFixed(0) + "," +
      (by - hy).toFixed(0) + '"/>';
  }

  // which steps of plan q are shown, and which one is the current one (0: none)
  function shown(q) {
    var c = state.cursor;
    if (c === 0) return {upto: PL[q].steps, now: 0};
    if (q === 0) return {upto: Math.min(c, NV), now: c <= NV ? c : 0};
    return {upto: Math.max(0, c - NV), now: c > NV ? c - NV : 0};
  }

  function drawScheme() {
    var frame = D.scheme.frames[state.pos], out = [];
    for (var j = 0; j < frame.length; j++) {
      var it = frame[j];
      out.push(draw(typeof it === "number" ? D.scheme.shared[it] : it));
    }
    $("scheme-now").innerHTML = out.join("");
  }

  function drawPlan(q) {
    var P = PL[q], items = P.items[state.pos], s = shown(q), out = [];
    if (items) {
      for (var j = 0; j < items.length; j++) {
        var it = items[j], step = it[0];
        if (step > s.upto) continue;
        out.push(draw(it.slice(1), step === s.now ? "now" : "", ' data-s="' + step + '"'));
      }
    }
    $("plan-" + P.kind).innerHTML = out.join("");
    var box = $("fixed").checked || !P.frames[state.pos] ? P.box : P.frames[state.pos];
    $("plan-" + P.kind + "-svg").setAttribute("viewBox", box.join(" "));
  }

  function sentence(q, k) {
    var row = PL[q].sentences[state.pos][k - 1];
    if (!row) return "";
    var pieces = PL[q].tpl[k - 1][row[0]].split("{}"), out = "";
    for (var j = 0; j < pieces.length; j++) out += pieces[j] + (j + 1 < row.length ? row[j + 1] : "");
    return out;
  }

  function drawCaption() {
    var c = state.cursor, cap = $("caption"), head = $("step-readout");
    if (!D.valid[state.pos]) { cap.textContent = W.not_assembled; }
    if (c === 0) {
      head.textContent = W.complete;
      if (D.valid[state.pos]) cap.textContent = W.complete_hint;
      return;
    }
    var q = c <= NV ? 0 : 1, k = q === 0 ? c : c - NV, P = PL[q];
    head.textContent = (q === 0 ? W.velocity_plan : W.acceleration_plan) + " · " + W.step + " " + k + "/" + P.steps;
    if (D.valid[state.pos]) cap.innerHTML = esc(W.step + " " + k + "/" + P.steps + ". ") + marked(sentence(q, k));
  }

  function drawValues() {
    var c = state.cursor, body = [], plans = c === 0 ? [0, 1] : [c <= NV ? 0 : 1];
    for (var n = 0; n < plans.length; n++) {
      var q = plans[n], P = PL[q], s = shown(q), vals = P.values[state.pos], at = 0;
      for (var k = 1; k <= P.steps; k++) {
        var rows = P.rows[k - 1];
        var cls = k === s.now ? ' class="now"' : "";
        var tag = (P.kind === "v" ? "v" : "a") + k;
        if (k <= s.upto && s.now && rows.length === 0 && k === s.now) {
          body.push("<tr" + cls + "><td>" + tag + '</td><td colspan="5" class="muted">' + esc(W.no_value) + "</td></tr>");
        }
        for (var j = 0; j < rows.length; j++, at += 2) {
          if (k > s.upto || !vals) continue;
          var a = vals[at], e = vals[at + 1];
          var d = a === null || e === null ? null : a + e;
          var rel = a !== null && Math.abs(a) > P.floor && e !== null ? 100 * e / a : null;
          body.push("<tr" + cls + "><td>" + tag + "</td><td>" + marked(rows[j]) + "</td><td>" + num(a) + "</td><td>" +
            num(d) + "</td><td>" + (e === null ? "—" : (e > 0 ? "+" : "") + num(e, 2)) + "</td><td>" +
            (rel === null ? "—" : (rel > 0 ? "+" : "") + num(rel, 2) + " %") + "</td></tr>");
        }
      }
    }
    $("values-body").innerHTML = body.join("");
  }

  function drawReadouts() {
    var i = state.pos;
    $("pos").value = String(i + 1);
    $("readout-pos").textContent = W.position + " " + (i + 1) + "/" + D.n;
    $("readout-phi").textContent = "φ = " + num(D.phi[i], 5) + "°";
    var parts = [];
    [["omega", "ω", D.units.omega], ["epsilon", "ε", D.units.epsilon]].forEach(function (spec) {
      var R = D.rates[spec[0]], v = R.values[i];
      for (var j = 0; j < R.links.length; j++) {
        parts.push(spec[1] + R.links[j].replace(/\d/g, function (d) { return "₀₁₂₃₄₅₆₇₈₉"[d]; }) +
          " = " + num(v[j]) + " " + spec[2]);
      }
    });
    $("rates").textContent = parts.join(" · ");
  }

  function render() {
    drawScheme(); drawPlan(0); drawPlan(1); drawCaption(); drawValues(); drawReadouts();
  }

  function go(pos) { state.pos = ((pos % D.n) + D.n) % D.n; render(); }
  function step(c) { state.cursor = Math.max(0, Math.min(NV + NA, c)); render(); }
  function play(on) {
    if (on && !state.timer) {
      state.timer = setInterval(function () { go(state.pos + 1); }, Math.max(16, Math.round(6000 / D.n)));
    } else if (!on && state.timer) { clearInterval(state.timer); state.timer = null; }
    $("play").textContent = state.timer ? "■ " + W.pause : "▶ " + W.play;
    $("play").setAttribute("aria-pressed", state.timer ? "true" : "false");
  }

  $("under").innerHTML = D.scheme.under.map(function (r) { return draw(r); }).join("");
  $("pos").addEventListener("input", function () { go(parseInt(this.value, 10) - 1); });
  $("play").addEventListener("click", function () { play(!state.timer); });
  $("first").addEventListener("click", function () { step(1); });
  $("prev").addEventListener("click", function () { step(state.cursor <= 1 ? (state.cursor === 0 ? NV + NA : 1) : state.cursor - 1); });
  $("next").addEventListener("click", function () { step(state.cursor === NV + NA ? NV + NA : state.cursor + 1); });
  $("fixed").addEventListener("change", function () { render(); });
  $("all").addEventListener("click", function () { step(0); });
  document.addEventListener("keydown", function (ev) {
    if (ev.target && ev.target.tagName === "INPUT") return;
    if (ev.key === "ArrowRight") step(state.cursor + 1);
    else if (ev.key === "ArrowLeft") step(Math.max(1, state.cursor - 1));
  });
  play(false);
  render();
})();
