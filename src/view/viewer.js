// SPDX-License-Identifier: GPL-3.0-or-later
// The viewer of subfab's view.html (embedded by write_view_html.cpp): reads
// the scene from the JSON block #subfab-scene and draws it with three.js
// r111 (inlined before this script). Geometry arrives as base64
// little-endian float32 / uint32 arrays; planar polygons are triangulated
// here with THREE.ShapeUtils on their 2D copy. Mouse: drag to rotate,
// right-drag or shift-drag to pan, wheel to zoom, click a part for its
// details. The page's state is in window.subfabStatus for the tests:
// frames drawn, errors seen (script errors, console.error, blocked loads).
// The part of the address after '#' may hold, separated by '&':
//   explode=N    the explode slider at N % (0..100)
//   eye=X,Y,Z    the initial view direction (from the model to the eye)
//   check        each object in the flat colour idColor(i) (hexahedral
//                cells: in their own colours, unlit), fully exploded unless
//                explode= says otherwise, on black, without the panel (what
//                the browser test reads back)
//   cut=A,T      hexahedral cells: keep those whose centre is at most T %
//                along axis A (x, y or z) of their extent
//   filter=T     hexahedral cells: keep those whose value is at most T % of
//                the way from the smallest to the largest value
// Hexahedral cells (an object with `hex`) are drawn as the faces of the kept
// cells that no other kept cell covers, so a cut or a filter shows the
// inside cell by cell; a click names the cell and its value.
(function () {
  'use strict';
  var status = (window.subfabStatus = { frames: 0, errors: [], objects: 0, ready: false });
  function fail(message) {
    status.errors.push(String(message));
    var box = document.getElementById('errors');
    if (box) {
      box.textContent = status.errors.join('\n');
      box.style.display = 'block';
    }
  }
  window.addEventListener('error', function (ev) { fail(ev.message || 'script error'); });
  window.addEventListener('unhandledrejection', function (ev) { fail('unhandled rejection: ' + ev.reason); });
  document.addEventListener('securitypolicyviolation', function (ev) {
    fail('blocked by the page policy (no network): ' + ev.blockedURI);
  });
  var consoleError = console.error;
  console.error = function () {
    fail(Array.prototype.join.call(arguments, ' '));
    consoleError.apply(console, arguments);
  };

  var options = {};
  window.location.hash.replace(/^#/, '').split('&').forEach(function (part) {
    var kv = part.split('=');
    if (kv[0]) options[kv[0]] = kv.length > 1 ? decodeURIComponent(kv[1]) : true;
  });
  var check = !!options.check;
  if (typeof THREE === 'undefined') {
    fail('three.js is missing from the page');
    return;
  }

  // All browsers are little-endian, as the arrays are.
  function buffer(b64) {
    var s = atob(b64), n = s.length, u = new Uint8Array(n);
    for (var i = 0; i < n; ++i) u[i] = s.charCodeAt(i);
    return u.buffer;
  }
  function float32(b64) { return new Float32Array(buffer(b64)); }
  function uint32(b64) { return new Uint32Array(buffer(b64)); }
  function idColor(i) {
    return [16 + 15 * (i % 16), 16 + 15 * (Math.floor(i / 16) % 16), 16 + 15 * (Math.floor(i / 256) % 16)];
  }
  function color(rgb) { return new THREE.Color(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255); }

  function geometryOf(o) {
    var positions, indices;
    if (o.positions) {
      positions = float32(o.positions);
      indices = uint32(o.indices);
    } else {
      var p = [], t = [];
      o.polygons.forEach(function (poly) {
        var p2 = float32(poly.p2), p3 = float32(poly.p3), base = p.length / 3, k = 0, contour = null, holes = [];
        poly.loops.forEach(function (n, l) {
          var loop = [];
          for (var i = 0; i < n; ++i, ++k) loop.push(new THREE.Vector2(p2[2 * k], p2[2 * k + 1]));
          if (l === 0) contour = loop; else holes.push(loop);
        });
        for (var j = 0; j < p3.length; ++j) p.push(p3[j]);
        THREE.ShapeUtils.triangulateShape(contour, holes).forEach(function (f) {
          t.push(base + f[0], base + f[1], base + f[2]);
        });
      });
      positions = new Float32Array(p);
      indices = new Uint32Array(t);
    }
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    g.setIndex(new THREE.BufferAttribute(indices, 1));
    g.computeBoundingSphere();
    return g;
  }

  var data = JSON.parse(document.getElementById('subfab-scene').textContent);
  var canvas = document.getElementById('view');
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: !check });
  } catch (e) {
    fail('WebGL is not available in this browser: ' + e.message);
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  var scene = new THREE.Scene();
  scene.background = check ? new THREE.Color(0, 0, 0) : new THREE.Color(0.94, 0.945, 0.95);
  var camera = new THREE.PerspectiveCamera(35, 1, 0.1, 1000);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.42));
  var headlight = new THREE.DirectionalLight(0xffffff, 0.5);
  headlight.position.set(0.3, 0.6, 1);
  camera.add(headlight);
  var sky = new THREE.DirectionalLight(0xffffff, 0.22);
  sky.position.set(0.2, 1, 0.4);
  scene.add(sky);

  // Hexahedral cells: the faces of the kept cells that no kept cell covers.
  var HEX_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
  var HEX_EDGES = [0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7];
  function HexCells(h) {
    this.points = float32(h.points);
    this.cells = uint32(h.cells);
    this.neighbors = uint32(h.neighbors);
    this.colors = uint32(h.colors);
    this.values = float32(h.values);
    this.label = h.label;
    var n = (this.n = this.values.length);
    this.centre = new Float32Array(3 * n);
    this.lo = [Infinity, Infinity, Infinity];
    this.hi = [-Infinity, -Infinity, -Infinity];
    this.vmin = Infinity;
    this.vmax = -Infinity;
    for (var c = 0; c < n; ++c) {
      for (var k = 0; k < 3; ++k) {
        var sum = 0;
        for (var j = 0; j < 8; ++j) sum += this.points[3 * this.cells[8 * c + j] + k];
        this.centre[3 * c + k] = sum / 8;
        this.lo[k] = Math.min(this.lo[k], sum / 8);
        this.hi[k] = Math.max(this.hi[k], sum / 8);
      }
      this.vmin = Math.min(this.vmin, this.values[c]);
      this.vmax = Math.max(this.vmax, this.values[c]);
    }
    this.kept = new Uint8Array(n);
    this.shown = 0;
    this.faceCell = new Uint32Array(0);
  }
  // Keeps the cells whose centre is at most cutT (0..1) along axis cutAxis
  // of the centres' extent and whose value is at most valueMax; returns the geometry.
  HexCells.prototype.geometry = function (cutAxis, cutT, valueMax) {
    var n = this.n, cut = this.lo[cutAxis] + (this.hi[cutAxis] - this.lo[cutAxis]) * cutT, faces = 0, c, f;
    this.shown = 0;
    for (c = 0; c < n; ++c) {
      this.kept[c] = this.centre[3 * c + cutAxis] <= cut * (1 + 1e-7) + 1e-12 && this.values[c] <= valueMax ? 1 : 0;
      this.shown += this.kept[c];
    }
    for (c = 0; c < n; ++c) {
      if (!this.kept[c]) continue;
      for (f = 0; f < 6; ++f) {
        var d = this.neighbors[6 * c + f];
        if (d === 0xffffffff || !this.kept[d]) ++faces;
      }
    }
    var position = new Float32Array(18 * faces), colour = new Float32Array(18 * faces), at = 0;
    this.faceCell = new Uint32Array(2 * faces);
    for (c = 0; c < n; ++c) {
      if (!this.kept[c]) continue;
      var rgb = this.colors[c], r = ((rgb >> 16) & 255) / 255, g = ((rgb >> 8) & 255) / 255, b = (rgb & 255) / 255;
      for (f = 0; f < 6; ++f) {
        var e = this.neighbors[6 * c + f];
        if (e !== 0xffffffff && this.kept[e]) continue;
        this.faceCell[at / 9] = this.faceCell[at / 9 + 1] = c;
        [0, 1, 2, 0, 2, 3].forEach(function (corner) {
          var v = this.cells[8 * c + HEX_FACES[f][corner]];
          position[at] = this.points[3 * v];
          position[at + 1] = this.points[3 * v + 1];
          position[at + 2] = this.points[3 * v + 2];
          colour[at] = r;
          colour[at + 1] = g;
          colour[at + 2] = b;
          at += 3;
        }, this);
      }
    }
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colour, 3));
    geometry.computeBoundingSphere();
    return geometry;
  };
  // The twelve edges of cell c, as line segments.
  HexCells.prototype.edges = function (c) {
    var p = new Float32Array(72);
    for (var i = 0; i < 24; ++i)
      for (var k = 0; k < 3; ++k) p[3 * i + k] = this.points[3 * this.cells[8 * c + HEX_EDGES[i]] + k];
    var geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(p, 3));
    return geometry;
  };

  var solids = [], ghosts = [], hexes = [];
  data.objects.forEach(function (o, i) {
    var ghost = o.style === 'ghost';
    if (check && ghost) return;
    var material;
    if (o.hex) {
      material = check ? new THREE.MeshBasicMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide })
                       : new THREE.MeshPhongMaterial({ vertexColors: THREE.VertexColors, flatShading: true,
                                                       side: THREE.DoubleSide, specular: 0, shininess: 0 });
      var cells = new HexCells(o.hex);
      var hexMesh = new THREE.Mesh(cells.geometry(0, 1, Infinity), material);
      hexMesh.userData = { object: o, cells: cells, offset: new THREE.Vector3(o.offset[0], o.offset[1], o.offset[2]) };
      solids.push(hexMesh);
      hexes.push(hexMesh);
      scene.add(hexMesh);
      return;
    }
    if (check) {
      material = new THREE.MeshBasicMaterial({ color: color(idColor(solids.length)), side: THREE.DoubleSide });
    } else if (ghost) {
      material = new THREE.MeshPhongMaterial({
        color: color(o.color), flatShading: true, side: THREE.DoubleSide, specular: 0, shininess: 0,
        transparent: true, opacity: 0.2, depthWrite: false,
        polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 4
      });
    } else {
      material = new THREE.MeshPhongMaterial({
        color: color(o.color), flatShading: true, side: THREE.DoubleSide, specular: 0, shininess: 0
      });
    }
    var mesh = new THREE.Mesh(geometryOf(o), material);
    mesh.userData = { object: o, offset: new THREE.Vector3(o.offset[0], o.offset[1], o.offset[2]) };
    if (ghost) {
      mesh.renderOrder = 1;
      ghosts.push(mesh);
    } else {
      solids.push(mesh);
    }
    scene.add(mesh);
  });
  status.objects = solids.length;

  // Cut and filter of hexahedral cells.
  var cutAxis = document.getElementById('cut-axis'), cutSlider = document.getElementById('cut');
  var filterSlider = document.getElementById('filter');
  if (typeof options.cut === 'string') {
    var cutParts = options.cut.split(',');
    cutAxis.value = cutParts[0];
    cutSlider.value = Number(cutParts[1]);
  }
  if (options.filter !== undefined) filterSlider.value = Number(options.filter);
  function fmt(x) { return Math.abs(x) >= 1e4 || (x !== 0 && Math.abs(x) < 1e-3) ? x.toExponential(2) : String(+x.toFixed(3)); }
  function cutCells() {
    if (hexes.length === 0) return;
    var axis = Math.max(0, ['x', 'y', 'z'].indexOf(cutAxis.value)), t = cutSlider.value / 100, shown = 0, total = 0;
    hexes.forEach(function (m) {
      var cells = m.userData.cells, valueMax = cells.vmin + (cells.vmax - cells.vmin) * filterSlider.value / 100;
      if (filterSlider.value >= 100) valueMax = Infinity;
      m.geometry.dispose();
      m.geometry = cells.geometry(axis, t, valueMax);
      shown += cells.shown;
      total += cells.n;
      document.getElementById('filter-label').textContent = cells.label;
      document.getElementById('filter-text').textContent = fmt(Math.min(valueMax, cells.vmax));
      var lo = cells.lo[axis], hi = cells.hi[axis];
      document.getElementById('cut-text').textContent = '(cell centres up to ' + fmt(lo + (hi - lo) * t) + ')';
    });
    document.getElementById('cells-count').textContent = shown + ' of ' + total + ' cells shown';
    status.cellsShown = shown;
    if (picked && picked.userData.cells) showPicked(null);
    requestRender();
  }
  if (hexes.length) {
    document.getElementById('cells-row').style.display = 'block';
    [cutAxis, cutSlider, filterSlider].forEach(function (el) { el.addEventListener('input', cutCells); });
  }

  // Explode slider.
  var slider = document.getElementById('explode');
  if (options.explode !== undefined) slider.value = Number(options.explode);
  else if (check) slider.value = 100;
  function explode() {
    var t = slider.value / 100;
    solids.concat(ghosts).forEach(function (m) { m.position.copy(m.userData.offset).multiplyScalar(t); });
    requestRender();
  }
  slider.addEventListener('input', explode);
  var ghostBox = document.getElementById('ghost');
  if (ghosts.length === 0) document.getElementById('ghost-row').style.display = 'none';
  ghostBox.addEventListener('change', function () {
    ghosts.forEach(function (m) { m.visible = ghostBox.checked; });
    requestRender();
  });
  if (check) document.getElementById('panel').style.display = 'none';
  if (data.objects.every(function (o) { return !o.offset[0] && !o.offset[1] && !o.offset[2]; }))
    document.getElementById('explode-row').style.display = 'none';

  // Camera: orbit around a target (spherical angles), y up.
  var eyeOption = typeof options.eye === 'string' ? options.eye.split(',').map(Number) : null;
  var eye = new THREE.Vector3().fromArray(eyeOption && eyeOption.length === 3 && eyeOption.every(isFinite) ? eyeOption
                                                                                                          : data.eye).normalize();
  var target = new THREE.Vector3(), radius = 1, theta = Math.atan2(eye.x, eye.z), phi = Math.acos(eye.y);
  var theta0 = theta, phi0 = phi;
  function placeCamera() {
    camera.position.set(target.x + radius * Math.sin(phi) * Math.sin(theta), target.y + radius * Math.cos(phi),
                        target.z + radius * Math.sin(phi) * Math.cos(theta));
    camera.lookAt(target);
    camera.near = radius / 200;
    camera.far = radius * 50;
    camera.updateProjectionMatrix();
    requestRender();
  }
  function fit() {
    theta = theta0;
    phi = phi0;
    var box = new THREE.Box3();
    solids.forEach(function (m) { box.expandByObject(m); });
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    var sphere = box.getBoundingSphere(new THREE.Sphere());
    target.copy(sphere.center);
    var half = (camera.fov * Math.PI / 360);
    var aspect = (window.innerWidth - panelWidth()) / Math.max(1, window.innerHeight);
    var fitHalf = aspect < 1 ? Math.atan(Math.tan(half) * aspect) : half;
    radius = Math.max(sphere.radius, 1e-9) / Math.sin(fitHalf) * 1.02;
    placeCamera();
  }
  // On a wide window the scene is centred right of the panel.
  function panelWidth() {
    return check || window.innerWidth < 700 ? 0 : document.getElementById('panel').offsetWidth + 24;
  }
  function resize() {
    var w = window.innerWidth, h = window.innerHeight;
    renderer.setSize(w, h, false);
    canvas.style.width = w + 'px';
    canvas.style.height = h + 'px';
    camera.aspect = w / Math.max(1, h);
    if (panelWidth() > 0) camera.setViewOffset(w, h, -panelWidth() / 2, 0, w, h);
    else camera.clearViewOffset();
    camera.updateProjectionMatrix();
    requestRender();
  }
  window.addEventListener('resize', resize);
  document.getElementById('reset').addEventListener('click', fit);

  var down = null;
  canvas.addEventListener('contextmenu', function (ev) { ev.preventDefault(); });
  canvas.addEventListener('pointerdown', function (ev) {
    down = { x: ev.clientX, y: ev.clientY, lastX: ev.clientX, lastY: ev.clientY, pan: ev.button === 2 || ev.shiftKey };
    canvas.setPointerCapture(ev.pointerId);
  });
  canvas.addEventListener('pointermove', function (ev) {
    if (!down) return;
    var dx = ev.clientX - down.lastX, dy = ev.clientY - down.lastY;
    down.lastX = ev.clientX;
    down.lastY = ev.clientY;
    if (down.pan) {
      var scale = 2 * radius * Math.tan((camera.fov * Math.PI / 360)) / window.innerHeight;
      var right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
      var up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
      target.addScaledVector(right, -dx * scale).addScaledVector(up, dy * scale);
    } else {
      theta -= dx * 0.008;
      phi = Math.min(Math.PI - 0.01, Math.max(0.01, phi - dy * 0.008));
    }
    placeCamera();
  });
  canvas.addEventListener('pointerup', function (ev) {
    if (down && Math.abs(ev.clientX - down.x) + Math.abs(ev.clientY - down.y) < 4) pick(ev);
    down = null;
  });
  canvas.addEventListener('wheel', function (ev) {
    ev.preventDefault();
    radius *= Math.exp(ev.deltaY * 0.001);
    placeCamera();
  }, { passive: false });

  // Click: the object under the pointer, highlighted, its lines in the info box.
  // A click on cells: the cell outlined, its number and value shown.
  var raycaster = new THREE.Raycaster(), picked = null, outline = null;
  function pick(ev) {
    var rect = canvas.getBoundingClientRect();
    var ndc = new THREE.Vector2((ev.clientX - rect.left) / rect.width * 2 - 1, -(ev.clientY - rect.top) / rect.height * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    var hits = raycaster.intersectObjects(solids.filter(function (m) { return m.visible; }));
    showPicked(hits.length ? hits[0] : null);
  }
  function showPicked(hit) {
    if (picked && picked.material.emissive && !picked.userData.cells) picked.material.emissive.setRGB(0, 0, 0);
    if (outline) {
      scene.remove(outline);
      outline.geometry.dispose();
      outline = null;
    }
    picked = hit ? hit.object : null;
    var box = document.getElementById('info');
    box.textContent = '';
    if (picked) {
      var o = picked.userData.object, h = document.createElement('h2'), table = document.createElement('table');
      var lines = o.info;
      h.textContent = o.name;
      if (picked.userData.cells) {
        var cells = picked.userData.cells, c = cells.faceCell[hit.faceIndex];
        outline = new THREE.LineSegments(cells.edges(c), new THREE.LineBasicMaterial({ color: 0x000000 }));
        outline.position.copy(picked.position);
        scene.add(outline);
        h.textContent = 'cell ' + c;
        lines = [['Cell', c + ' (from 0, as in the .vtk file; the .mesh file counts from 1)'],
                 [cells.label, cells.values[c].toFixed(3)]].concat(o.info);
        status.pickedCell = c;
      } else if (picked.material.emissive) {
        picked.material.emissive.setRGB(0.25, 0.25, 0.25);
      }
      lines.forEach(function (line) {
        var tr = table.insertRow(), th = document.createElement('th');
        th.textContent = line[0];
        tr.appendChild(th);
        tr.insertCell().textContent = line[1];
      });
      box.appendChild(h);
      box.appendChild(table);
    } else {
      box.textContent = 'Click a part to see its details.';
    }
    requestRender();
  }

  var pending = false;
  function requestRender() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(function () {
      pending = false;
      renderer.render(scene, camera);
      status.frames++;
    });
  }

  resize();
  cutCells();
  explode();
  fit();
  status.ready = true;
})();
