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
//   check        each object in the flat colour idColor(i), fully exploded
//                unless explode= says otherwise, on black, without the
//                panel (what the browser test reads back)
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

  var solids = [], ghosts = [];
  data.objects.forEach(function (o, i) {
    var ghost = o.style === 'ghost';
    if (check && ghost) return;
    var material;
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
  var raycaster = new THREE.Raycaster(), picked = null;
  function pick(ev) {
    var rect = canvas.getBoundingClientRect();
    var ndc = new THREE.Vector2((ev.clientX - rect.left) / rect.width * 2 - 1, -(ev.clientY - rect.top) / rect.height * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    var hits = raycaster.intersectObjects(solids.filter(function (m) { return m.visible; }));
    if (picked && picked.material.emissive) picked.material.emissive.setRGB(0, 0, 0);
    picked = hits.length ? hits[0].object : null;
    var box = document.getElementById('info');
    box.textContent = '';
    if (picked) {
      if (picked.material.emissive) picked.material.emissive.setRGB(0.25, 0.25, 0.25);
      var o = picked.userData.object, h = document.createElement('h2'), table = document.createElement('table');
      h.textContent = o.name;
      o.info.forEach(function (line) {
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
  explode();
  fit();
  status.ready = true;
})();
