/* symlink's LinkageWidget in a notebook (anywidget's front end): the drawing, its sliders and its equations.
 *
 * The model (symlink/studio/widget.py) holds:
 *   values     {name: number}  the inputs and parameters (synced both ways);
 *   branch     {name: +1|-1}   the branch signs (synced both ways);
 *   _solver    the generated JavaScript solver's text (symlink.codegen.javascript.javascript_geometry);
 *   _ranges    {name: [min, max, step]}  each slider's range;
 *   _lengths   the names whose value must stay positive;
 *   _equations the linkage's equations as LaTeX (typeset with the vendored KaTeX, `katex` below).
 * Every joint is placed where the generated solver says: this file writes no kinematics.  Names are
 * written with textContent and attributes, never as HTML.
 */

var SVG = "http://www.w3.org/2000/svg";
var SAMPLES = 120;

function node(tag, attributes, parent) {
  var made = document.createElementNS(SVG, tag);
  Object.keys(attributes || {}).forEach(function (k) { made.setAttribute(k, String(attributes[k])); });
  if (parent) parent.appendChild(made);
  return made;
}

function element(tag, className, parent) {
  var made = document.createElement(tag);
  if (className) made.className = className;
  if (parent) parent.appendChild(made);
  return made;
}

function loadSolver(source) {
  // The generated solver is one UMD expression: "return " + text gives the solver object itself.
  var found = new Function("return " + source)();  // symlink's generated code, not the user's text
  if (!found || typeof found.solve !== "function") throw new Error("the generated solver defines no solve()");
  return found;
}

function render(context) {
  var model = context.model, root = context.el;
  root.classList.add("symlink-widget");
  var solver = null, failure = null;
  try { solver = loadSolver(model.get("_solver")); } catch (e) { failure = e.message; }

  var figure = element("div", "symlink-figure", root);
  var svg = node("svg", { "class": "symlink-drawing", width: 480, height: 360, viewBox: "0 0 480 360" }, figure);
  var message = element("div", "symlink-message", figure);
  var controls = element("div", "symlink-controls", root);
  var equations = element("div", "symlink-equations", root);
  var inputs = {};   // name -> <input type=range>
  var readouts = {};  // name -> <span>
  var branchBox = {};  // name -> <select>
  var playing = false, frame = null, view = null;

  function current() {
    return Object.assign({}, (solver && solver.defaults) || {}, model.get("values") || {}, model.get("branch") || {});
  }

  function solveAt(values) {
    var out;
    try { out = solver.solve(values, {}); } catch (e) { return { assembled: false, pose: {}, error: e.message }; }
    var pose = {}, guides = {}, ok = !!out.assembled;
    solver.points.forEach(function (p) {
      var x = out[p.x], y = out[p.y];
      if (!(isFinite(x) && isFinite(y))) ok = false;
      (p.kind === "guide" ? guides : pose)[p.name] = [x, y];
    });
    // each slider's guide: a point on its line (the solver's guide point) and the line's angle
    var slots = (solver.sliders || []).map(function (s) {
      var at = pose[s.name], through = guides[s.guide], angle = out[s.direction];
      if (typeof angle !== "number" && at && through) angle = Math.atan2(at[1] - through[1], at[0] - through[0]);
      return { name: s.name, at: at, through: through, angle: angle };
    }).filter(function (s) { return s.at && s.through && isFinite(s.angle); });
    return { assembled: ok, pose: pose, slots: slots, error: null };
  }

  function frameView() {
    // the drawing's box over the input's whole range at the present lengths: the scale holds while it moves
    var values = current(), name = solver.inputs[0], range = model.get("_ranges")[name];
    var xs = [], ys = [];
    for (var k = 0; k <= SAMPLES; k++) {
      values[name] = range[0] + (range[1] - range[0]) * k / SAMPLES;
      var r = solveAt(values);
      if (!r.assembled) continue;
      Object.keys(r.pose).forEach(function (p) { xs.push(r.pose[p][0]); ys.push(r.pose[p][1]); });
    }
    var here = solveAt(current());
    Object.keys(here.pose).forEach(function (p) {
      if (isFinite(here.pose[p][0])) { xs.push(here.pose[p][0]); ys.push(here.pose[p][1]); }
    });
    if (!xs.length) { view = { x0: -1, y0: -1, scale: 100 }; return; }
    var x0 = Math.min.apply(null, xs), x1 = Math.max.apply(null, xs);
    var y0 = Math.min.apply(null, ys), y1 = Math.max.apply(null, ys);
    var span = Math.max(x1 - x0, y1 - y0, 1e-9);
    var scale = Math.min(400 / Math.max(x1 - x0, span * 0.1), 290 / Math.max(y1 - y0, span * 0.1));
    view = { x0: (x0 + x1) / 2, y0: (y0 + y1) / 2, scale: scale };
  }

  function screen(point) {
    return [240 + (point[0] - view.x0) * view.scale, 180 - (point[1] - view.y0) * view.scale];
  }

  function draw() {
    while (svg.firstChild) svg.removeChild(svg.firstChild);
    if (!solver) { message.textContent = "the generated solver did not load: " + failure; return; }
    var r = solveAt(current());
    svg.setAttribute("data-assembled", r.assembled ? "true" : "false");
    if (!r.assembled) {
      message.textContent = r.error ? r.error : "cannot be assembled here";
      message.className = "symlink-message symlink-error";
      return;
    }
    message.textContent = "";
    message.className = "symlink-message";
    var grounded = {};
    r.slots.forEach(function (slot) {
      // the guide's line from its point past the slider, and the block on it
      var u = [Math.cos(slot.angle), Math.sin(slot.angle)];
      var t = (slot.at[0] - slot.through[0]) * u[0] + (slot.at[1] - slot.through[1]) * u[1];
      var margin = 0.25 * Math.abs(t) + 24 / view.scale;
      var from = screen([slot.through[0] + (Math.min(0, t) - margin) * u[0], slot.through[1] + (Math.min(0, t) - margin) * u[1]]);
      var to = screen([slot.through[0] + (Math.max(0, t) + margin) * u[0], slot.through[1] + (Math.max(0, t) + margin) * u[1]]);
      var line = node("line", { x1: from[0], y1: from[1], x2: to[0], y2: to[1], "class": "symlink-guide" }, svg);
      line.setAttribute("data-slider", slot.name);
      line.setAttribute("data-angle", String(slot.angle));
      var c = screen(slot.at), degrees = -slot.angle * 180 / Math.PI;
      node("rect", { x: c[0] - 11, y: c[1] - 7, width: 22, height: 14, "class": "symlink-block",
        transform: "rotate(" + degrees + " " + c[0] + " " + c[1] + ")" }, svg);
    });
    solver.bodies.forEach(function (body) {
      var ground = body.name === "ground";
      // a moving body joins its joints and points (a slider's block to its pin); the ground, its fixed points
      var held = ground ? body.points : body.joints.concat(body.points.filter(function (p) {
        return body.joints.indexOf(p) < 0;
      }));
      var places = held.filter(function (p) { return p in r.pose; }).map(function (p) {
        if (ground) grounded[p] = true;
        return screen(r.pose[p]);
      });
      if (places.length < 2) return;
      var shape = node(places.length > 2 ? "polygon" : "polyline", {
        points: places.map(function (s) { return s[0] + "," + s[1]; }).join(" "),
        "class": ground ? "symlink-ground" : "symlink-link"
      }, svg);
      shape.setAttribute("data-body", body.name);
    });
    Object.keys(r.pose).forEach(function (p) {
      var s = screen(r.pose[p]);
      if (grounded[p]) {
        node("polygon", { points: [s[0], s[1], s[0] - 7, s[1] + 11, s[0] + 7, s[1] + 11].join(","),
          "class": "symlink-pivot" }, svg);
      }
      var joint = node("circle", { cx: s[0], cy: s[1], r: 4.5, "class": "symlink-joint" }, svg);
      // the solver's numbers exactly (String() of a double reads back to the same double)
      joint.setAttribute("data-joint", p);
      joint.setAttribute("data-x", String(r.pose[p][0]));
      joint.setAttribute("data-y", String(r.pose[p][1]));
      var tag = node("text", { x: s[0] + 7, y: s[1] - 7, "class": "symlink-label" }, svg);
      tag.textContent = p;
    });
  }

  function showValues() {
    var values = model.get("values") || {}, ranges = model.get("_ranges");
    Object.keys(inputs).forEach(function (name) {
      var v = values[name], slider = inputs[name];
      if (typeof v !== "number") return;
      // a value set from Python past the slider's end widens the slider
      if (v < Number(slider.min)) slider.min = String(v);
      if (v > Number(slider.max)) slider.max = String(v);
      slider.value = String(v);
      readouts[name].textContent = Number(v.toPrecision(6)).toString();
    });
    var branch = model.get("branch") || {};
    Object.keys(branchBox).forEach(function (b) { branchBox[b].value = String(branch[b] < 0 ? -1 : 1); });
    void ranges;
  }

  function setValue(name, value) {
    var values = Object.assign({}, model.get("values"));
    values[name] = value;
    model.set("values", values);
    model.save_changes();
  }

  function addSlider(name, kind) {
    var range = model.get("_ranges")[name];
    var row = element("label", "symlink-row", controls);
    var caption = element("span", "symlink-name", row);
    caption.textContent = name;
    var slider = element("input", "symlink-slider", row);
    slider.type = "range";
    slider.min = String(range[0]);
    slider.max = String(range[1]);
    slider.step = String(range[2]);
    slider.setAttribute("data-name", name);
    slider.setAttribute("data-kind", kind);
    readouts[name] = element("span", "symlink-value", row);
    slider.addEventListener("input", function () {
      var v = Number(slider.value);
      if (!isFinite(v)) return;
      if (kind === "length" && !(v > 0)) return;
      setValue(name, v);
    });
    inputs[name] = slider;
  }

  function play() {
    var name = solver.inputs[0], range = model.get("_ranges")[name];
    var step = (range[1] - range[0]) / 240;
    var values = Object.assign({}, model.get("values"));
    var v = values[name] + step;
    if (v > range[1]) v = range[0];
    values[name] = v;
    model.set("values", values);  // the page moves; Python hears of it when the motion stops
    frame = window.requestAnimationFrame(function () { if (playing) play(); });
  }

  if (solver) {
    var name = solver.inputs[0];
    addSlider(name, "input");
    var button = element("button", "symlink-play", controls);
    button.type = "button";
    button.textContent = "Play";
    button.addEventListener("click", function () {
      playing = !playing;
      button.textContent = playing ? "Stop" : "Play";
      if (playing) play();
      else { if (frame !== null) window.cancelAnimationFrame(frame); model.save_changes(); }
    });
    var lengths = model.get("_lengths") || [];
    solver.parameters.forEach(function (p) { addSlider(p, lengths.indexOf(p) >= 0 ? "length" : "parameter"); });
    solver.branches.forEach(function (b) {
      var row = element("label", "symlink-row", controls);
      var caption = element("span", "symlink-name", row);
      caption.textContent = b;
      var select = element("select", "symlink-branch", row);
      select.setAttribute("data-branch", b);
      [1, -1].forEach(function (sign) {
        var option = element("option", null, select);
        option.value = String(sign);
        option.textContent = sign > 0 ? "+1" : "-1";
      });
      select.addEventListener("change", function () {
        var branch = Object.assign({}, model.get("branch"));
        branch[b] = Number(select.value);
        model.set("branch", branch);
        model.save_changes();
      });
      branchBox[b] = select;
    });
    frameView();
  }

  var typeset = model.get("_equations") || "";
  if (typeset) {
    try {
      katex.render(typeset, equations, { displayMode: true, throwOnError: false, trust: false });
    } catch (e) {
      equations.textContent = typeset;
    }
  }

  var lastParameters = null;
  function onValues() {
    if (!solver) return;
    // the view is framed again when a length changes, not while the input turns
    var values = model.get("values") || {}, key = JSON.stringify(solver.parameters.map(function (p) { return values[p]; }))
      + JSON.stringify(model.get("branch"));
    if (key !== lastParameters) { lastParameters = key; frameView(); }
    showValues();
    draw();
  }
  model.on("change:values", onValues);
  model.on("change:branch", onValues);
  onValues();
  return function () {
    playing = false;
    if (frame !== null) window.cancelAnimationFrame(frame);
    model.off("change:values", onValues);
    model.off("change:branch", onValues);
  };
}

export default { render: render };
