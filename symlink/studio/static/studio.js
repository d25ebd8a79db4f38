/* symlink studio: draw a linkage by its joints, read its structure and equations, watch it move.
 *
 * The page keeps the design (joints, links, ground, driver, sliders) and asks the server what it is
 * (/api/structure), its equations (/api/derive) and its generated solver (/api/solver).  The motion is the
 * generated JavaScript solver's: this file places joints where the solver says, and writes no kinematics.
 * In a self-contained page (symlink studio --html) the same script runs on the embedded data, offline.
 */
(function () {
  "use strict";

  var SVGNS = "http://www.w3.org/2000/svg";
  var STORE = "symlink-studio-design";
  var SNAP = 10;               // joints snap to a grid of 1/SNAP drawing units (k / 10 exactly, as typed)
  var SAMPLES = 360;           // samples of the input's range for the reach strip and traces
  var embedded = window.SYMLINK_EMBEDDED || null;

  var params = new URLSearchParams(window.location.search);
  var token = params.get("token") || "";

  var el = function (id) { return document.getElementById(id); };
  var svg = el("canvas");

  var state = {
    design: emptyDesign(),
    undo: [], redo: [],
    selected: [],
    view: { scale: 80, ox: 200, oy: 400 },
    structure: null, derivation: null, solverInfo: null, solver: null,
    error: null, motionError: null,
    input: null,       // the input's value (radians or drawing units) when posed, else null
    branches: {},
    pose: null,        // joint -> [x, y] from the solver, or null
    assembled: true,
    reach: null, traces: {},
    analysis: null, analysisError: null, analysing: 0,
    targets: [], targeting: false,     // clicked target points (drawing units), and whether clicks add them
    synthesis: null, job: null,        // the applied synthesis result; the running job {id, status, elapsed}
    band: null, bandMessage: "", bandError: false, bandPoint: null,
    synthMessage: "", synthError: false, synthSeconds: null, synthPoint: null,
    pending: 0, generation: 0, playing: false
  };

  function emptyDesign() { return { name: "drawing", joints: [], links: [], driver: null, sliders: [] }; }
  function clone(x) { return JSON.parse(JSON.stringify(x)); }

  // ---- persistence: local storage and the URL hash ------------------------------------------------
  function encodeHash(design) {
    var bytes = new TextEncoder().encode(JSON.stringify(design));
    var text = "";
    bytes.forEach(function (b) { text += String.fromCharCode(b); });
    return btoa(text).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
  }
  function decodeHash(hash) {
    var text = atob(hash.replace(/-/g, "+").replace(/_/g, "/"));
    var bytes = new Uint8Array(text.length);
    for (var i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
    return JSON.parse(new TextDecoder().decode(bytes));
  }
  function designFromHash() {
    var match = /^#d=([A-Za-z0-9_-]+)$/.exec(window.location.hash);
    if (!match) return null;
    try { return validDesign(decodeHash(match[1])); } catch (e) { return null; }
  }
  function validDesign(d) {
    if (!d || typeof d !== "object" || !Array.isArray(d.joints) || !Array.isArray(d.links)) return null;
    d.sliders = Array.isArray(d.sliders) ? d.sliders : [];
    d.driver = d.driver || null;
    d.name = typeof d.name === "string" ? d.name : "drawing";
    return d;
  }
  function save() {
    if (embedded) return;
    try { localStorage.setItem(STORE, JSON.stringify(state.design)); } catch (e) { /* private mode */ }
    var url = window.location.pathname + window.location.search + "#d=" + encodeHash(state.design);
    history.replaceState(null, "", url);
  }
  function shareLink() {
    return window.location.origin + window.location.pathname + window.location.search + "#d=" + encodeHash(state.design);
  }

  // ---- the view: drawing units <-> SVG pixels (y up) --------------------------------------------
  function toScreen(x, y) { return [state.view.ox + x * state.view.scale, state.view.oy - y * state.view.scale]; }
  function toWorld(px, py) { return [(px - state.view.ox) / state.view.scale, (state.view.oy - py) / state.view.scale]; }
  function snap(v) { return Math.round(v * SNAP) / SNAP; }
  function clientToSvg(event) {
    var box = svg.getBoundingClientRect();
    return [event.clientX - box.left, event.clientY - box.top];
  }
  function fitView() {
    var box = svg.getBoundingClientRect();
    var joints = state.design.joints;
    if (!joints.length || box.width === 0) {
      state.view = { scale: 80, ox: Math.round(box.width * 0.25) || 200, oy: Math.round(box.height * 0.7) || 400 };
      return;
    }
    var xs = joints.map(function (j) { return j.x; }), ys = joints.map(function (j) { return j.y; });
    state.targets.forEach(function (t) { xs.push(t[0]); ys.push(t[1]); });
    Object.keys(state.traces).forEach(function (k) {
      state.traces[k].forEach(function (p) { xs.push(p[0]); ys.push(p[1]); });
    });
    var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
    var y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
    var span = Math.max(x1 - x0, y1 - y0, 1e-9);
    var scale = 0.6 * Math.min(box.width, box.height) / span;
    state.view = { scale: scale, ox: box.width / 2 - scale * (x0 + x1) / 2, oy: box.height / 2 + scale * (y0 + y1) / 2 };
  }

  // ---- editing -------------------------------------------------------------------------------
  function commit(change) {
    state.undo.push(clone(state.design));
    if (state.undo.length > 200) state.undo.shift();
    state.redo = [];
    change(state.design);
    state.synthesis = null; state.synthMessage = ""; state.synthError = false;
    state.band = null; state.bandMessage = ""; state.bandError = false;
    changed();
  }
  function changed() {
    state.input = null; state.pose = null; state.assembled = true;
    save();
    render();
    schedule();
  }
  function undo() {
    if (!state.undo.length) return;
    state.redo.push(clone(state.design));
    state.design = state.undo.pop();
    state.selected = [];
    changed();
  }
  function redo() {
    if (!state.redo.length) return;
    state.undo.push(clone(state.design));
    state.design = state.redo.pop();
    state.selected = [];
    changed();
  }
  function nextName() {
    var used = {};
    state.design.joints.forEach(function (j) { used[j.name] = true; });
    var letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    for (var i = 0; i < letters.length; i++) if (!used[letters[i]]) return letters[i];
    for (var k = 1; ; k++) if (!used["J" + k]) return "J" + k;
  }
  function joint(name) {
    return state.design.joints.find(function (j) { return j.name === name; }) || null;
  }
  function addJoint(x, y) {
    var name = nextName();
    commit(function (d) { d.joints.push({ name: name, x: snap(x), y: snap(y) }); });
    state.selected = [];
    return name;
  }
  function joinSelected() {
    var chosen = state.selected.slice();
    if (chosen.length < 2) { showError("select two or more joints to join them into a link"); return; }
    state.selected = [];
    commit(function (d) { d.links.push(chosen); });
  }
  function groundSelected() {
    var chosen = state.selected.slice();
    if (!chosen.length) { showError("select the joints to put on the ground"); return; }
    state.selected = [];
    commit(function (d) {
      var on = !chosen.every(function (n) { return joint(n).ground; });
      d.joints.forEach(function (j) { if (chosen.indexOf(j.name) >= 0) j.ground = on; });
    });
  }
  function driveSelected() {
    if (state.selected.length !== 1) { showError("select the one joint to drive"); return; }
    var name = state.selected[0];
    state.selected = [];
    commit(function (d) { d.driver = { joint: name }; });
  }
  function sliderSelected() {
    if (state.selected.length !== 1) { showError("select the one joint that slides"); return; }
    var name = state.selected[0];
    state.selected = [];
    commit(function (d) {
      var at = d.sliders.findIndex(function (s) { return s.joint === name; });
      if (at >= 0) d.sliders.splice(at, 1);
      else d.sliders.push({ joint: name, guide: "ground", angle: 0 });
    });
  }
  function deleteSelected() {
    var chosen = state.selected.slice();
    if (!chosen.length) return;
    state.selected = [];
    commit(function (d) {
      d.joints = d.joints.filter(function (j) { return chosen.indexOf(j.name) < 0; });
      d.links = d.links.map(function (l) { return l.filter(function (n) { return chosen.indexOf(n) < 0; }); })
        .filter(function (l) { return l.length >= 2; });
      d.sliders = d.sliders.filter(function (s) { return chosen.indexOf(s.joint) < 0; });
      if (d.driver && chosen.indexOf(d.driver.joint) >= 0) d.driver = null;
    });
  }
  function toggleSelect(name) {
    var at = state.selected.indexOf(name);
    if (at >= 0) state.selected.splice(at, 1); else state.selected.push(name);
    render();
  }

  // ---- the server ------------------------------------------------------------------------------
  function post(path, body) {
    return fetch(path, {
      method: "POST", credentials: "same-origin",
      headers: { "Content-Type": "application/json", "X-Symlink-Token": token },
      body: JSON.stringify(body)
    }).catch(function () {
      throw new Error("the studio's server does not answer (was 'symlink studio' stopped?)");
    }).then(function (response) {
      return response.text().then(function (text) {
        var data;
        try { data = JSON.parse(text); } catch (e) { data = { error: "the server answered " + response.status }; }
        if (!response.ok) { var error = new Error(data.error || ("the server answered " + response.status)); error.data = data; throw error; }
        return data;
      });
    });
  }
  var timer = null;
  function schedule() {
    if (embedded) return;
    if (timer) clearTimeout(timer); else state.pending += 1;
    timer = setTimeout(function () { timer = null; state.pending -= 1; analyse(); }, 200);
  }
  function analyse() {
    var generation = ++state.generation;
    var design = clone(state.design);
    state.structure = null; state.derivation = null; state.solverInfo = null; state.solver = null;
    state.error = null; state.motionError = null; state.reach = null; state.traces = {};
    state.analysis = null; state.analysisError = null;
    if (!design.joints.length) { renderPanel(); return Promise.resolve(); }
    state.pending += 1;
    return post("api/structure", design).then(function (structure) {
      if (generation !== state.generation) return;
      state.structure = structure;
      renderPanel();
      requestAnalysis(design, generation);
      return Promise.all([
        post("api/derive", design).then(function (d) { if (generation === state.generation) state.derivation = d; })
          .catch(function (e) { if (generation === state.generation) state.error = e.message; }),
        post("api/solver", design).then(function (s) { if (generation === state.generation) loadSolver(s); })
          .catch(function (e) { if (generation === state.generation) state.motionError = e.message; })
      ]);
    }).catch(function (e) {
      if (generation === state.generation) state.error = e.message;
    }).then(function () {
      state.pending -= 1;
      if (generation === state.generation) { renderPanel(); render(); }
    });
  }

  function requestAnalysis(design, generation) {
    // the analysis takes seconds the first time (generated code): it does not hold up the rest of the page
    state.analysing += 1;
    renderAnalysis();
    return post("api/analyze", design).then(function (a) { if (generation === state.generation) state.analysis = a; })
      .catch(function (e) { if (generation === state.generation) state.analysisError = e.message; })
      .then(function () { state.analysing -= 1; if (generation === state.generation) renderAnalysis(); });
  }

  // ---- the generated solver ----------------------------------------------------------------------
  function evaluateUmd(source) {
    // The generated solver is one UMD expression: "return " + text gives the solver object itself.
    var found = new Function("return " + source)();  // the server's generated code, not the user's text
    if (!found || typeof found.solve !== "function") throw new Error("the generated solver defines no solve()");
    return found;
  }
  function loadSolver(info) {
    try {
      state.solver = evaluateUmd(info.source);
    } catch (e) {
      state.motionError = "the generated solver did not load: " + e.message;
      return;
    }
    state.solverInfo = info;
    state.branches = {};
    Object.keys(info.branches || {}).forEach(function (b) { state.branches[b] = info.branches[b]; });
    computeReach();
  }
  function inputName() { return state.solverInfo ? state.solverInfo.inputs[0] : null; }
  function isAngle() { var n = inputName(); return n !== null && !/^s_/.test(n); }
  function drawnInput() { return state.solverInfo ? state.solverInfo.defaults[inputName()] : 0; }
  function inputRange() {
    if (isAngle()) return [-Math.PI, Math.PI];
    var d = drawnInput(), span = Math.max(1, Math.abs(d)) * 2;
    return [d - span, d + span];
  }
  function solveAt(value) {
    // every argument the solver takes: its own defaults (rates 0), the drawing's values, the branch signs
    var values = Object.assign({}, state.solver.defaults || {}, state.solverInfo.defaults, state.branches);
    values[inputName()] = value;
    var out = state.solver.solve(values, {});
    var pose = {}, ok = !!out.assembled;
    (state.solver.points || []).forEach(function (p) {
      if (p.kind === "guide") return;
      var x = out[p.x], y = out[p.y];
      if (!(isFinite(x) && isFinite(y))) ok = false;
      pose[p.name] = [x, y];
    });
    return { pose: pose, assembled: ok };
  }
  function computeReach() {
    if (!state.solver) return;
    var range = inputRange(), reach = [], traces = {};
    var points = pointJoints();
    points.forEach(function (p) { traces[p] = []; });
    for (var k = 0; k <= SAMPLES; k++) {
      var v = range[0] + (range[1] - range[0]) * k / SAMPLES;
      var r;
      try { r = solveAt(v); } catch (e) { r = { assembled: false, pose: {} }; }
      reach.push(r.assembled);
      points.forEach(function (p) { if (r.assembled) traces[p].push(r.pose[p]); else if (traces[p].length && traces[p][traces[p].length - 1] !== null) traces[p].push(null); });
    }
    state.reach = reach;
    state.traces = traces;
  }
  function pointJoints() {
    // joints held by one moving link only (coupler points): their paths are drawn
    var count = {};
    state.design.links.forEach(function (l) { l.forEach(function (n) { count[n] = (count[n] || 0) + 1; }); });
    return state.design.joints.filter(function (j) { return count[j.name] === 1 && !j.ground; }).map(function (j) { return j.name; });
  }
  function setInput(value) {
    if (!state.solver) throw new Error("no solver loaded");
    state.input = value;
    var r = solveAt(value);
    state.assembled = r.assembled;
    state.pose = r.assembled ? r.pose : null;
    render();
    renderMotion();
    return state.pose;
  }
  function setBranch(name, sign) {
    if (!(name in state.branches)) throw new Error("no branch " + name);
    state.branches[name] = sign < 0 ? -1 : 1;
    computeReach();
    if (state.input !== null) setInput(state.input); else { render(); renderMotion(); }
  }

  // ---- drawing ----------------------------------------------------------------------------------
  function node(tag, attributes, parent) {
    var e = document.createElementNS(SVGNS, tag);
    Object.keys(attributes).forEach(function (k) { e.setAttribute(k, attributes[k]); });
    if (parent) parent.appendChild(e);
    return e;
  }
  function position(name) {
    if (state.input !== null && state.pose && state.pose[name]) return state.pose[name];
    var j = joint(name);
    return j ? [j.x, j.y] : null;
  }
  function render() {
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    var box = svg.getBoundingClientRect();
    var w = box.width || 800, h = box.height || 600, s = state.view.scale;
    var grid = node("g", {}, svg);
    var step = s >= 20 ? 1 : 10;
    var x0 = Math.floor(toWorld(0, 0)[0] / step) * step, x1 = toWorld(w, 0)[0];
    for (var x = x0; x <= x1; x += step) { var p = toScreen(x, 0)[0]; node("line", { x1: p, y1: 0, x2: p, y2: h, "class": Math.abs(x) < 1e-9 ? "axis" : "grid" }, grid); }
    var y0 = Math.floor(toWorld(0, h)[1] / step) * step, y1 = toWorld(0, 0)[1];
    for (var y = y0; y <= y1; y += step) { var q = toScreen(0, y)[1]; node("line", { x1: 0, y1: q, x2: w, y2: q, "class": Math.abs(y) < 1e-9 ? "axis" : "grid" }, grid); }
    var hidden = state.input !== null && !state.assembled;
    // traces of coupler points, when a solver is loaded
    Object.keys(state.traces).forEach(function (name) {
      var d = "", pen = false;
      state.traces[name].forEach(function (pt) {
        if (pt === null) { pen = false; return; }
        var sp = toScreen(pt[0], pt[1]);
        d += (pen ? "L" : "M") + sp[0].toFixed(1) + " " + sp[1].toFixed(1);
        pen = true;
      });
      if (d) node("path", { d: d, "class": "trace" }, svg);
    });
    if (state.band) {
      // each run of assembled samples: the outer edge forward, the inner edge back
      var runs = [], run = [];
      state.band.outer.forEach(function (o, k) {
        var i = state.band.inner[k];
        if (o && i) run.push([o, i]); else if (run.length) { runs.push(run); run = []; }
      });
      if (run.length) runs.push(run);
      var bd = "";
      runs.forEach(function (r) {
        if (r.length < 2) return;
        var pts = r.map(function (p) { return p[0]; }).concat(r.slice().reverse().map(function (p) { return p[1]; }));
        bd += "M" + pts.map(function (p) { var q = toScreen(p[0], p[1]); return q[0].toFixed(1) + " " + q[1].toFixed(1); }).join("L") + "Z";
      });
      if (bd) node("path", { d: bd, "class": "tol-band", "fill-rule": "nonzero" }, svg);
    }
    if (state.synthesis && state.synthesis.path) {
      var sd = "", spen = false;
      state.synthesis.path.forEach(function (pt) {
        if (pt === null) { spen = false; return; }
        var sp = toScreen(pt[0], pt[1]);
        sd += (spen ? "L" : "M") + sp[0].toFixed(1) + " " + sp[1].toFixed(1);
        spen = true;
      });
      if (sd) node("path", { d: sd, "class": "synth-path" }, svg);
    }
    state.targets.forEach(function (t, k) {
      var tp = toScreen(t[0], t[1]);
      node("path", { d: "M" + (tp[0] - 6) + " " + tp[1] + "h12M" + tp[0] + " " + (tp[1] - 6) + "v12", "class": "target", "data-target": k }, svg);
      var tl = node("text", { x: tp[0] + 6, y: tp[1] + 15, "class": "target-label" }, svg);
      tl.textContent = String(k + 1);
    });
    var design = state.design;
    var sliding = design.sliders.map(function (s) { return s.joint; });
    var grounded = design.joints.filter(function (j) { return j.ground && sliding.indexOf(j.name) < 0; })
      .map(function (j) { return j.name; });
    if (grounded.length >= 2) drawLink(grounded, true);
    if (!hidden) design.links.forEach(function (l) { drawLink(l, false); });
    design.sliders.forEach(function (sl) {
      var at = position(sl.joint);
      if (!at || sl.guide !== "ground") return;
      // the slot: along the slider's line through its drawn position, as long as the drawing is wide
      var c = Math.cos(sl.angle), sn = Math.sin(sl.angle), j = joint(sl.joint);
      var reach = 2 * Math.max.apply(null, design.joints.map(function (k) { return Math.hypot(k.x - j.x, k.y - j.y); }).concat([1]));
      var a = toScreen(j.x - reach * c, j.y - reach * sn), b = toScreen(j.x + reach * c, j.y + reach * sn);
      node("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], "class": "slot" }, svg);
    });
    design.joints.forEach(function (j) {
      if (hidden && !j.ground) return;
      var at = position(j.name); if (!at) return;
      var sp = toScreen(at[0], at[1]);
      var cls = "joint" + (j.ground && sliding.indexOf(j.name) < 0 ? " ground" : "") + (sliding.indexOf(j.name) >= 0 ? " slider" : "") + (design.driver && design.driver.joint === j.name ? " driver" : "")
        + (state.selected.indexOf(j.name) >= 0 ? " selected" : "");
      var c = node("circle", { cx: sp[0], cy: sp[1], r: 7, "class": cls, "data-joint": j.name }, svg);
      c.addEventListener("mousedown", function (event) { startDrag(event, j.name); });
      var t = node("text", { x: sp[0] + 9, y: sp[1] - 9, "class": "label" }, svg);
      t.textContent = j.name;
    });
    if (hidden) {
      var m = node("text", { x: 16, y: 28, "class": "unassembled" }, svg);
      m.textContent = "cannot be assembled here";
    }
  }
  function drawLink(names, ground) {
    var pts = names.map(position).filter(function (p) { return p; }).map(function (p) { return toScreen(p[0], p[1]); });
    if (pts.length < 2) return;
    var d = "M" + pts.map(function (p) { return p[0].toFixed(1) + " " + p[1].toFixed(1); }).join("L") + (pts.length > 2 ? "Z" : "");
    node("path", { d: d, "class": "link" + (ground ? " ground" : "") }, svg);
  }
  function typeset(target, latex) {
    var box = el(target);
    box.textContent = "";
    box.removeAttribute("data-latex");
    if (!latex) return;
    box.setAttribute("data-latex", latex);
    if (window.katex) {
      try { window.katex.render(latex, box, { displayMode: true, throwOnError: false, maxExpand: 10000 }); return; }
      catch (e) { /* shown as text below */ }
    }
    box.textContent = latex;
  }
  function renderPanel() {
    var message = el("structure-message");
    if (state.error) { message.textContent = state.error; message.className = "message error"; }
    else if (state.structure) {
      message.textContent = state.structure.message + (state.structure.notes.length ? " (" + state.structure.notes.join("; ") + ")" : "");
      message.className = "message ok";
    } else if (!state.design.joints.length) { message.textContent = "Draw a linkage: click to place joints."; message.className = "message"; }
    else { message.textContent = "…"; message.className = "message"; }
    el("plan").textContent = state.structure ? state.structure.plan : "";
    var d = state.derivation;
    typeset("equations", d ? d.equations : null);
    typeset("velocities", d ? d.velocities : null);
    typeset("accelerations", d ? d.accelerations : null);
    renderForms(d ? d.forms : null);
    renderMotion();
    renderAnalysis();
    renderDesign();
    renderBand();
  }
  function renderForms(forms) {
    var box = el("forms");
    if (!box) return;
    box.textContent = "";
    (forms || []).forEach(function (entry) {
      var title = document.createElement("h4");
      title.textContent = "Positions in the " + entry.title;  // text, never markup
      box.appendChild(title);
      var maths = document.createElement("div");
      maths.id = "form-" + entry.form;
      maths.className = "maths";
      box.appendChild(maths);
      typeset(maths.id, entry.latex);
    });
  }
  function degrees(v) { return v * 180 / Math.PI; }
  function deg(v) { return degrees(v).toFixed(2) + "°"; }
  function renderAnalysis() {
    var box = el("analysis");
    if (!box) return;
    box.textContent = "";
    var line = function (label, text, key) {
      var p = document.createElement("p");
      p.className = "analysis-line";
      if (key) p.setAttribute("data-key", key);
      var b = document.createElement("b"); b.textContent = label + ": "; p.appendChild(b);
      p.appendChild(document.createTextNode(text));
      box.appendChild(p);
      return p;
    };
    if (state.analysisError) { var m = line("cannot analyse", state.analysisError, "error"); m.className += " error"; return; }
    var a = state.analysis;
    if (!a) { if (state.analysing > 0 && state.structure) line("analysing", "…", "busy"); return; }
    var value = function (v) { return a.angle ? deg(v) : v.toFixed(4); };
    if (a.grashof) {
      var f = a.fourbar;
      line("Grashof", a.grashof.name + " (a " + f.a.toFixed(3) + ", b " + f.b.toFixed(3) + ", c " + f.c.toFixed(3) + ", d " + f.d.toFixed(3)
        + "; s + l = " + a.grashof.shortest_plus_longest.toFixed(3) + (a.grashof.name === "triple-rocker" ? " > " : " ≤ ") + "p + q = " + a.grashof.other_two.toFixed(3) + ")", "grashof");
    }
    line("Input " + a.input, a.reach.full_turn ? "turns fully" : "reaches " + a.reach.spans.map(function (s) { return value(s[0]) + " to " + value(s[1]); }).join(", "), "reach");
    if (a.reach.toggles.length) line("Toggles", a.reach.toggles.map(function (t) { return value(t.at) + (t.loop ? " (" + t.loop + ")" : ""); }).join(", "), "toggles");
    a.transmission.forEach(function (t) {
      line("Transmission " + t.loop + " at " + t.joint, deg(t.minimum) + " to " + deg(t.maximum) + " (at " + a.input + " = " + value(t.minimum_at) + ", " + value(t.maximum_at) + ")", "transmission-" + t.loop);
    });
    if (!a.transmission.length) line("Transmission", "no loop with two unknown angles", "transmission");
    a.limits.forEach(function (l) {
      var shown = function (v) { return l.angle ? deg(v) : v.toFixed(4); };
      var text = l.positions.map(function (p) { return p.kind + " " + shown(p.value) + " at " + a.input + " = " + value(p.at); }).join("; ");
      if (l.stroke !== null) text += "; stroke " + shown(l.stroke);
      if (l.time_ratio !== null) text += ", time ratio " + l.time_ratio.toFixed(4);
      line("Limits of " + l.output, text || "none", "limits-" + l.output);
    });
  }
  function renderMotion() {
    var ready = !!state.solver, slider = el("input"), play = el("play");
    slider.disabled = !ready; play.disabled = !ready;
    var message = el("motion-message");
    if (state.motionError) { message.textContent = state.motionError; message.className = "message error"; }
    else if (!ready) { message.textContent = state.structure ? "…" : ""; message.className = "message"; }
    else if (state.input !== null && !state.assembled) { message.textContent = "cannot be assembled here"; message.className = "message error"; }
    else { message.textContent = ""; message.className = "message"; }
    var branches = el("branches");
    if (ready && branches.childElementCount !== Object.keys(state.branches).length) {
      branches.textContent = "";
      Object.keys(state.branches).forEach(function (b) {
        var label = document.createElement("label");
        label.textContent = b + " ";
        var select = document.createElement("select");
        select.setAttribute("data-branch", b);
        [["1", "+1 (as drawn)"], ["-1", "−1 (the other assembly)"]].forEach(function (o) {
          var opt = document.createElement("option"); opt.value = o[0]; opt.textContent = o[1]; select.appendChild(opt);
        });
        select.addEventListener("change", function () { setBranch(b, Number(select.value)); });
        label.appendChild(select);
        branches.appendChild(label);
      });
    }
    if (!ready) branches.textContent = "";
    Array.prototype.forEach.call(branches.querySelectorAll("select"), function (s) { s.value = String(state.branches[s.getAttribute("data-branch")]); });
    if (ready) {
      var range = inputRange(), value = state.input !== null ? state.input : drawnInput();
      if (isAngle()) { slider.min = -180; slider.max = 180; slider.step = 0.5; slider.value = degrees(Math.atan2(Math.sin(value), Math.cos(value))); el("input-value").textContent = inputName() + " = " + degrees(value).toFixed(1) + "°"; }
      else { slider.min = range[0]; slider.max = range[1]; slider.step = (range[1] - range[0]) / 720; slider.value = value; el("input-value").textContent = inputName() + " = " + value.toFixed(3); }
    } else el("input-value").textContent = "";
    var canvas = el("reach"), ctx = canvas.getContext && canvas.getContext("2d");
    if (ctx) {
      ctx.clearRect(0, 0, canvas.width, canvas.height);
      if (state.reach) state.reach.forEach(function (ok, k) {
        ctx.fillStyle = ok ? "#7bb661" : "#d33";
        ctx.fillRect(k * canvas.width / state.reach.length, 0, canvas.width / state.reach.length + 1, canvas.height);
      });
    }
  }

  // ---- design: a path through clicked targets ------------------------------------------------------
  function setTargeting(on) {
    state.targeting = !!on;
    el("tool-targets").classList.toggle("active", state.targeting);
    svg.classList.toggle("targeting", state.targeting);
    if (state.targeting) state.selected = [];
    render();
    renderDesign();
  }
  function addTarget(x, y) {
    if (state.targets.length >= 40) { synthSay("at most 40 targets", true); return; }
    state.targets.push([x, y]);
    render();
    renderDesign();
  }
  function synthSay(text, error) { state.synthMessage = text; state.synthError = !!error; renderDesign(); }
  function movingJoints() {
    var ground = {};
    state.design.joints.forEach(function (j) { if (j.ground) ground[j.name] = true; });
    (state.design.sliders || []).forEach(function (s) { delete ground[s.joint]; });
    var held = {};
    state.design.links.forEach(function (l) { l.forEach(function (n) { held[n] = true; }); });
    return state.design.joints.filter(function (j) { return !ground[j.name] && held[j.name]; }).map(function (j) { return j.name; });
  }
  function renderDesign() {
    var select = el("synth-point");
    if (!select) return;
    var names = movingJoints();
    var points = pointJoints();
    if (Array.prototype.map.call(select.options, function (o) { return o.value; }).join() !== names.join()) {
      select.textContent = "";
      names.forEach(function (n) { var o = document.createElement("option"); o.value = n; o.textContent = n; select.appendChild(o); });
      // the user's choice if still there, else a coupler point (a joint on one link only), else the first
      select.value = state.synthPoint && names.indexOf(state.synthPoint) >= 0 ? state.synthPoint
        : (points.length ? points[points.length - 1] : (names[0] || ""));
    }
    var running = !!state.job;
    el("synthesize").disabled = running || state.targets.length < 3 || !state.structure;
    el("synth-cancel").disabled = !running;
    el("targets-clear").disabled = !state.targets.length || running;
    var message = el("synth-message");
    var text = state.synthMessage;
    if (!text) text = state.targets.length < 3 ? "Click Targets, then " + (3 - state.targets.length) + " or more points on the drawing (" + state.targets.length + " so far)." : state.targets.length + " targets: choose the joint and Synthesize.";
    message.textContent = text;
    message.className = "message" + (state.synthError ? " error" : "");
  }
  function renderBand() {
    var select = el("tol-point");
    if (!select) return;
    var names = movingJoints(), points = pointJoints();
    if (Array.prototype.map.call(select.options, function (o) { return o.value; }).join() !== names.join()) {
      select.textContent = "";
      names.forEach(function (n) { var o = document.createElement("option"); o.value = n; o.textContent = n; select.appendChild(o); });
      select.value = state.bandPoint && names.indexOf(state.bandPoint) >= 0 ? state.bandPoint
        : (points.length ? points[points.length - 1] : (names[0] || ""));
    }
    el("tolerance").disabled = !state.structure || !names.length;
    var message = el("tol-message");
    message.textContent = state.bandMessage;
    message.className = "message" + (state.bandError ? " error" : "");
  }
  function toleranceBand() {
    var band = Number(el("tol-band").value), point = el("tol-point").value;
    if (!(band > 0)) { state.bandMessage = "the tolerance is a number above 0"; state.bandError = true; renderBand(); return Promise.resolve(); }
    var generation = state.generation;
    state.bandMessage = "…"; state.bandError = false; renderBand();
    state.pending += 1;
    return post("api/tolerance", { drawing: clone(state.design), point: point, band: band }).then(function (b) {
      if (generation !== state.generation) return;
      state.band = b;
      var name = b.input, angle = !/^s_/.test(name);
      state.bandMessage = "every length ± " + band + ": " + point + " strays at most " + (b.worst === null ? "?" : b.worst.toPrecision(3))
        + " across its path (worst case, first order), at " + name + " = " + (b.worst_at === null ? "?" : angle ? degrees(b.worst_at).toFixed(1) + "°" : b.worst_at.toFixed(3));
      render();
    }).catch(function (e) { if (generation === state.generation) { state.bandMessage = e.message; state.bandError = true; } })
      .then(function () { state.pending -= 1; renderBand(); });
  }
  function request(method, path) {
    return fetch(path, { method: method, credentials: "same-origin", headers: { "X-Symlink-Token": token } })
      .catch(function () { throw new Error("the studio's server does not answer"); })
      .then(function (response) {
        return response.json().catch(function () { return { error: "the server answered " + response.status }; }).then(function (data) {
          if (!response.ok) throw new Error(data.error || ("the server answered " + response.status));
          return data;
        });
      });
  }
  function synthesize() {
    if (state.job) return Promise.resolve();
    var point = el("synth-point").value;
    var starts = Number(el("synth-starts").value);
    if (state.targets.length < 3) { synthSay("click at least 3 targets first", true); return Promise.resolve(); }
    if (!point) { synthSay("the drawing has no moving joint to trace the path", true); return Promise.resolve(); }
    if (!(starts >= 1 && starts <= 64 && Math.floor(starts) === starts)) { synthSay("starts is a whole number from 1 to 64", true); return Promise.resolve(); }
    var began = performance.now();
    var body = { drawing: clone(state.design), point: point, targets: clone(state.targets), starts: starts };
    state.job = { id: null, status: "starting", elapsed: 0 };
    state.synthSeconds = null;
    synthSay("starting…");
    return post("api/synthesize", body).then(function (job) {
      state.job = job;
      return new Promise(function (resolve) {
        function poll() {
          if (!state.job || state.job.id !== job.id) { resolve(); return; }
          request("GET", "api/synthesize/" + job.id).then(function (now) {
            if (!state.job || state.job.id !== job.id) { resolve(); return; }
            state.job = now;
            if (now.status === "done") { state.job = null; applySynthesis(now.result, body, (performance.now() - began) / 1000, now.elapsed); resolve(); }
            else if (now.status === "failed" || now.status === "cancelled") { state.job = null; synthSay(now.status === "cancelled" ? "cancelled" : now.error, now.status !== "cancelled"); resolve(); }
            else { synthSay(now.status + "… " + now.elapsed.toFixed(1) + " s"); setTimeout(poll, 300); }
          }).catch(function (e) { state.job = null; synthSay(e.message, true); resolve(); });
        }
        poll();
      });
    }).catch(function (e) { state.job = null; synthSay(e.message, true); });
  }
  function cancelSynthesis() {
    var job = state.job;
    if (!job || !job.id) return Promise.resolve();
    state.job = null;
    return request("DELETE", "api/synthesize/" + job.id).then(function () { synthSay("cancelled"); })
      .catch(function (e) { synthSay(e.message, true); });
  }
  function applySynthesis(result, body, seconds, elapsed) {
    state.synthSeconds = seconds;
    if (!result.assembled || !result.drawing) {
      synthSay("no design through the targets was found: " + (result.why || "error " + result.error.toExponential(2) + " of their size") + ". Try more starts, or targets a linkage can reach.", true);
      return;
    }
    commit(function (design) { Object.keys(result.drawing).forEach(function (k) { design[k] = clone(result.drawing[k]); }); });
    state.synthesis = result;
    fitView(); render();
    var worst = Math.max.apply(null, result.distances.map(function (d) { return d === null ? Infinity : d; }));
    if (result.exact) synthSay(result.point + " passes through the " + result.targets.length + " targets (largest distance " + worst.toExponential(1)
      + ") in " + seconds.toFixed(1) + " s; Undo restores the drawing.");
    else synthSay("no design through the targets was found: the closest one, drawn, misses them by up to " + worst.toPrecision(3)
      + " (" + result.error.toExponential(1) + " of their size) in " + seconds.toFixed(1) + " s. Try more starts, other targets, or Undo.", true);
  }

  // ---- mouse and keys ----------------------------------------------------------------------------
  var drag = null;
  function startDrag(event, name) {
    if (embedded) return;
    event.stopPropagation();
    event.preventDefault();
    drag = { name: name, start: clientToSvg(event), moved: false, before: clone(state.design) };
  }
  svg.addEventListener("mousemove", function (event) {
    if (!drag) return;
    var at = clientToSvg(event);
    if (!drag.moved && Math.hypot(at[0] - drag.start[0], at[1] - drag.start[1]) < 4) return;
    drag.moved = true;
    state.input = null; state.pose = null;
    var w = toWorld(at[0], at[1]), j = joint(drag.name);
    j.x = snap(w[0]); j.y = snap(w[1]);
    render();
  });
  window.addEventListener("mouseup", function () {
    if (!drag) return;
    var d = drag; drag = null;
    if (d.moved) {
      state.undo.push(d.before); state.redo = [];
      changed();
    } else toggleSelect(d.name);
  });
  svg.addEventListener("click", function (event) {
    if (embedded || event.target.getAttribute("data-joint")) return;
    var at = clientToSvg(event), w = toWorld(at[0], at[1]);
    if (state.targeting) { addTarget(w[0], w[1]); return; }
    if (state.selected.length) { state.selected = []; render(); return; }
    addJoint(w[0], w[1]);
  });
  document.addEventListener("keydown", function (event) {
    if (embedded || /INPUT|TEXTAREA|SELECT/.test(event.target.tagName)) return;
    var key = event.key.toLowerCase();
    if ((event.ctrlKey || event.metaKey) && key === "z") { event.preventDefault(); if (event.shiftKey) redo(); else undo(); }
    else if ((event.ctrlKey || event.metaKey) && key === "y") { event.preventDefault(); redo(); }
    else if (event.ctrlKey || event.metaKey || event.altKey) return;
    else if (key === "l") joinSelected();
    else if (key === "g") groundSelected();
    else if (key === "m") driveSelected();
    else if (key === "s") sliderSelected();
    else if (key === "delete" || key === "backspace") deleteSelected();
    else if (key === "t") setTargeting(!state.targeting);
    else if (key === "escape") { state.selected = []; setTargeting(false); }
  });
  function showError(text) { var m = el("structure-message"); m.textContent = text; m.className = "message error"; }

  el("tool-link").onclick = joinSelected;
  el("tool-targets").onclick = function () { setTargeting(!state.targeting); };
  el("targets-clear").onclick = function () { state.targets = []; state.synthesis = null; state.synthMessage = ""; render(); renderDesign(); };
  el("synthesize").onclick = function () { synthesize(); };
  el("tolerance").onclick = function () { toleranceBand(); };
  el("tol-point").addEventListener("change", function () { state.bandPoint = el("tol-point").value; });
  el("synth-point").addEventListener("change", function () { state.synthPoint = el("synth-point").value; });
  el("synth-cancel").onclick = function () { cancelSynthesis(); };
  el("tool-ground").onclick = groundSelected;
  el("tool-driver").onclick = driveSelected;
  el("tool-slider").onclick = sliderSelected;
  el("tool-delete").onclick = deleteSelected;
  el("tool-undo").onclick = undo;
  el("tool-redo").onclick = redo;
  el("tool-clear").onclick = function () { commit(function (d) { var e = emptyDesign(); Object.keys(e).forEach(function (k) { d[k] = e[k]; }); }); };
  el("tool-open").onclick = function () { openSource(el("open-source").value); };
  el("tool-share").onclick = function () {
    var link = shareLink();
    if (navigator.clipboard) navigator.clipboard.writeText(link).catch(function () {});
    el("structure-message").textContent = "Link copied: " + link.slice(0, 60) + "…";
  };
  el("tool-export").onclick = function () {
    var format = el("export-format").value;
    fetch("api/export?format=" + encodeURIComponent(format), {
      method: "POST", credentials: "same-origin",
      headers: { "Content-Type": "application/json", "X-Symlink-Token": token }, body: JSON.stringify(state.design)
    }).then(function (response) {
      if (!response.ok) return response.json().then(function (d) { throw new Error(d.error); });
      var name = (/filename="([^"]+)"/.exec(response.headers.get("Content-Disposition") || "") || [])[1] || "export";
      return response.blob().then(function (blob) {
        var a = document.createElement("a"); a.href = URL.createObjectURL(blob); a.download = name; a.click();
        setTimeout(function () { URL.revokeObjectURL(a.href); }, 1000);
      });
    }).catch(function (e) { showError(e.message); });
  };
  function openSource(source) {
    if (!source || !source.trim()) { showError("type a catalog name (fourbar), atlas:NAME, or paste a file's text"); return Promise.resolve(); }
    state.pending += 1;
    return post("api/open", { source: source }).then(function (d) {
      commit(function (design) { Object.keys(d).forEach(function (k) { design[k] = d[k]; }); });
      state.traces = {}; fitView(); render();
    }).catch(function (e) { showError(e.message); }).then(function () { state.pending -= 1; });
  }
  el("input").addEventListener("input", function () {
    var v = Number(el("input").value);
    setInput(isAngle() ? v * Math.PI / 180 : v);
  });
  el("play").onclick = function () {
    state.playing = !state.playing;
    el("play").textContent = state.playing ? "Pause" : "Play";
    var last = null;
    function frame(time) {
      if (!state.playing || !state.solver) { state.playing = false; el("play").textContent = "Play"; return; }
      var dt = last === null ? 0 : Math.min(0.1, (time - last) / 1000);
      last = time;
      var range = inputRange(), v = state.input !== null ? state.input : drawnInput();
      v += dt * (range[1] - range[0]) / 4;        // a full range in four seconds
      if (v > range[1]) v = range[0] + (v - range[1]);
      setInput(v);
      requestAnimationFrame(frame);
    }
    if (state.playing) requestAnimationFrame(frame);
  };
  window.addEventListener("resize", function () { render(); });

  // ---- start ---------------------------------------------------------------------------------------
  function start() {
    if (embedded) {
      document.body.classList.add("embedded");
      state.design = validDesign(embedded.drawing) || emptyDesign();
      state.structure = embedded.structure; state.derivation = embedded.derivation;
      if (embedded.solver) loadSolver(embedded.solver);
      else state.motionError = embedded.solverError || "no solver";
      fitView(); render(); renderPanel();
      return Promise.resolve();
    }
    var fromHash = designFromHash();
    var stored = null;
    try { stored = validDesign(JSON.parse(localStorage.getItem(STORE) || "null")); } catch (e) { stored = null; }
    state.pending += 1;
    var initial = fromHash ? Promise.resolve(null) : fetch("api/initial", { credentials: "same-origin", headers: { "X-Symlink-Token": token } })
      .then(function (r) { return r.ok ? r.json() : { drawing: null }; }).then(function (d) { return d.drawing; }).catch(function () { return null; });
    return initial.then(function (given) {
      state.design = fromHash || validDesign(given) || stored || emptyDesign();
      fitView();
      save(); render(); renderPanel();
      state.pending -= 1;
      return analyse();
    });
  }

  window.studio = {
    state: state,
    design: function () { return clone(state.design); },
    setDesign: function (d) { commit(function (design) { var v = validDesign(clone(d)); Object.keys(v).forEach(function (k) { design[k] = v[k]; }); }); fitView(); render(); },
    toScreen: function (x, y) { var p = toScreen(x, y), box = svg.getBoundingClientRect(); return [p[0] + box.left, p[1] + box.top]; },
    setView: function (scale, ox, oy) { state.view = { scale: scale, ox: ox, oy: oy }; render(); },
    idle: function () { return state.pending === 0 && timer === null; },
    solverReady: function () { return !!state.solver; },
    targets: function () { return clone(state.targets); },
    synthesis: function () { return state.synthesis ? clone(state.synthesis) : null; },
    synthesizing: function () { return !!state.job; },
    synthesisSeconds: function () { return state.synthSeconds; },
    synthesize: synthesize,
    band: function () { return state.band ? clone(state.band) : null; },
    analysisDone: function () { return state.analysing === 0 && (state.analysis !== null || state.analysisError !== null); },
    analysis: function () { return state.analysis ? clone(state.analysis) : null; },
    setInput: setInput,
    setBranch: setBranch,
    positions: function () { return state.pose ? clone(state.pose) : null; },
    assembled: function () { return state.assembled; },
    latex: function () { return state.derivation ? clone(state.derivation) : null; },
    shareLink: shareLink,
    open: openSource,
    undo: undo, redo: redo,
    started: null
  };
  window.studio.started = start();
})();
