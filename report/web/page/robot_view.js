// The 3D view of one plot problem (three.js): the scene's obstacles, every planner's TCP path in its
// colour, the robot's link meshes (arm, tool, sensor, gripper) placed at the link poses arcplan computed along the time-scaled
// trajectory, a time slider and play button, a choice of which planner's motion the arm shows, and
// one toggle per planner. Renders on demand (a frame per change), not continuously.
"use strict";

// A triangle mesh sent as base64 (positions: Float32 x, y, z; indices: Uint32 corners).
function meshGeometry(data) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(float32Array(data.positions), 3));
  geometry.setIndex(new THREE.BufferAttribute(uint32Array(data.indices), 1));
  geometry.computeVertexNormals();
  return geometry;
}

function obstacleGeometry(obstacle) {
  if (obstacle.shape === "sphere") return new THREE.SphereBufferGeometry(obstacle.radius, 32, 16);
  if (obstacle.shape === "box") return new THREE.BoxBufferGeometry(obstacle.size[0], obstacle.size[1], obstacle.size[2]);
  if (obstacle.shape === "cylinder") {
    const geometry = new THREE.CylinderBufferGeometry(obstacle.radius, obstacle.radius, obstacle.length, 32);
    geometry.rotateX(Math.PI / 2);  // three.js cylinders run along y, arcplan's along z
    return geometry;
  }
  if (obstacle.shape === "mesh" && obstacle.positions) return meshGeometry(obstacle);
  return null;  // a mesh from a campaign written before scene.json carried its triangles
}

function makeObstacle(obstacle) {
  const geometry = obstacleGeometry(obstacle);
  if (!geometry) return null;
  geometry.computeBoundingBox();
  // Small obstacles (the ones a path goes around) in red, large ones (tables, walls, shelves) neutral.
  const large = geometry.boundingBox.getSize(new THREE.Vector3()).toArray().some(extent => extent > 0.5);
  const material = new THREE.MeshLambertMaterial({color: large ? 0xc9bfb3 : 0xd9534f, transparent: true, opacity: large ? 0.45 : 0.7});
  const mesh = new THREE.Mesh(geometry, material);
  mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry, 30), new THREE.LineBasicMaterial({color: large ? 0x9c8f80 : 0xa02c2c})));
  const r = obstacle.rotation, p = obstacle.position;
  mesh.matrixAutoUpdate = false;
  mesh.matrix.set(r[0][0], r[0][1], r[0][2], p[0], r[1][0], r[1][1], r[1][2], p[1], r[2][0], r[2][1], r[2][2], p[2], 0, 0, 0, 1);
  mesh.name = "obstacle " + obstacle.name;
  return mesh;
}

function makeLinkMesh(link) {
  const mesh = new THREE.Mesh(meshGeometry(link), new THREE.MeshLambertMaterial({color: 0x8fa3b8}));
  mesh.name = link.link;
  return mesh;
}

function marker(position, colour, radius) {
  const mesh = new THREE.Mesh(new THREE.SphereBufferGeometry(radius, 16, 8), new THREE.MeshBasicMaterial({color: colour}));
  mesh.position.set(position[0], position[1], position[2]);
  return mesh;
}

// Linear interpolation of a planner's TCP position at time t (clamped to its motion).
function tcpAt(planner, t) {
  const times = planner.t;
  let i = 0;
  while (i + 1 < times.length - 1 && times[i + 1] < t) ++i;
  const j = Math.min(i + 1, times.length - 1);
  const s = times[j] > times[i] ? Math.min(1, Math.max(0, (t - times[i]) / (times[j] - times[i]))) : 0;
  const a = planner.tcp.slice(3 * i, 3 * i + 3), b = planner.tcp.slice(3 * j, 3 * j + 3);
  return [0, 1, 2].map(k => a[k] + s * (b[k] - a[k]));
}

// container: an empty element; problem: data.paths[name]; colours: planner -> colour.
function createRobotView(container, problemName, problem, robotData, colours) {
  const controlsBar = el("div", {class: "controls"});
  const viewer = el("div", {class: "viewer", id: "viewer-" + problemName.replace(/[^A-Za-z0-9]+/g, "-")});
  container.append(controlsBar, viewer);

  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (error) {
    viewer.appendChild(el("p", {class: "missing", text: "This browser cannot draw the 3D view (WebGL unavailable: " + error.message + ")."}));
    return null;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xfbfcfd);
  viewer.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 0.55));
  const sun = new THREE.DirectionalLight(0xffffff, 0.75);
  sun.position.set(2, -3, 4);
  scene.add(sun);
  const grid = new THREE.GridHelper(2, 20, 0xb0b8c2, 0xdde2e8);
  grid.rotateX(Math.PI / 2);  // three.js grids lie in x-z; the robot's floor is x-y
  scene.add(grid);
  scene.add(new THREE.AxesHelper(0.25));
  const obstacles = (problem.scene.obstacles || []).map(makeObstacle).filter(Boolean);
  obstacles.forEach(mesh => scene.add(mesh));
  if (problem.scene.start) scene.add(marker(problem.scene.start, 0x2e7d32, 0.018));
  if (problem.scene.goal) scene.add(marker(problem.scene.goal, 0x222222, 0.018));

  const planners = problem.planners;
  const paths = {}, tcpMarkers = {};
  for (const planner of planners) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(planner.tcp), 3));
    const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({color: colours[planner.name]}));
    line.name = "path " + planner.name;
    paths[planner.name] = line;
    tcpMarkers[planner.name] = marker(planner.tcp.slice(0, 3), colours[planner.name], 0.012);
    scene.add(line, tcpMarkers[planner.name]);
  }

  // The arm: one mesh per link; pose frames per planner, decoded once, and the start and goal
  // configurations (shown when chosen, and where no planner found a path).
  const animated = planners.filter(planner => planner.frames && robotData);
  const links = robotData ? robotData.meshes.map(makeLinkMesh) : [];
  links.forEach(link => scene.add(link));
  // Bodies the robot holds ride on their link (their pose is in its frame): three.js moves them with it.
  const held = [];
  for (const body of robotData ? problem.scene.attached || [] : []) {
    const link = links.find(mesh => mesh.name === body.link);
    const mesh = link && makeObstacle(body);
    if (!mesh) continue;
    mesh.material.color.set(0xe69f00);
    link.add(mesh);
    held.push(mesh);
  }
  const poses = {};
  for (const planner of animated) poses[planner.name] = {frames: planner.frames, values: float32Array(planner.frames.poses)};
  const armChoices = animated.map(planner => ({value: planner.name, label: planner.name}));
  if (robotData && problem.endpoints) {
    const values = float32Array(problem.endpoints.poses);
    poses["@start"] = {values, frame: 0};
    poses["@goal"] = {values, frame: 1};
    armChoices.push({value: "@start", label: "start configuration"}, {value: "@goal", label: "goal configuration"});
  }
  let armPlanner = armChoices.length ? armChoices[0].value : null;
  const duration = Math.max(0, ...planners.map(planner => planner.t[planner.t.length - 1]));
  let time = 0;

  // Look at the middle of the robot base, the start and goal, the paths and the obstacles near them (not a room-sized
  // wall or floor), from the front right, far enough to see all.
  const bounds = new THREE.Box3(new THREE.Vector3(-0.1, -0.1, 0), new THREE.Vector3(0.1, 0.1, 0.2));
  for (const planner of planners) {
    for (let i = 0; i < planner.tcp.length; i += 3) bounds.expandByPoint(new THREE.Vector3().fromArray(planner.tcp, i));
  }
  for (const end of [problem.scene.start, problem.scene.goal]) if (end) bounds.expandByPoint(new THREE.Vector3().fromArray(end));
  for (const mesh of obstacles) {
    mesh.updateMatrixWorld(true);
    const box = new THREE.Box3().setFromObject(mesh);
    if (box.getSize(new THREE.Vector3()).length() < 2.5) bounds.union(box);
  }
  const centre = bounds.getCenter(new THREE.Vector3());
  const radius = Math.max(0.4, bounds.getSize(new THREE.Vector3()).length() / 2);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 50);
  camera.up.set(0, 0, 1);
  camera.position.copy(centre).add(new THREE.Vector3(1.1, -1.9, 1.0).multiplyScalar(radius * 0.95));
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  controls.update();

  function render() { renderer.render(scene, camera); }
  controls.addEventListener("change", render);

  function resize() {
    const width = viewer.clientWidth, height = viewer.clientHeight;
    renderer.setSize(width, height);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    render();
  }
  window.addEventListener("resize", resize);

  function placeArm() {
    const shown = poses[armPlanner];
    links.forEach(link => { link.visible = Boolean(shown); });
    if (!shown) return;
    const frame = shown.frames ? Math.min(shown.frames.frames - 1, Math.round(time * shown.frames.rate_hz)) : shown.frame;
    links.forEach((link, index) => {
      const at = (frame * links.length + index) * 7;
      const v = shown.values;
      link.position.set(v[at], v[at + 1], v[at + 2]);
      link.quaternion.set(v[at + 3], v[at + 4], v[at + 5], v[at + 6]);
    });
  }

  const slider = el("input", {type: "range", class: "time-slider", min: 0, max: duration.toFixed(3), step: 0.01, value: 0,
                              "aria-label": "time along the trajectories (s)"});
  const timeLabel = el("span", {class: "time-label", text: "t = 0.00 s"});
  function setTime(t) {
    time = Math.min(duration, Math.max(0, t));
    slider.value = time;
    timeLabel.textContent = "t = " + time.toFixed(2) + " s of " + duration.toFixed(2) + " s";
    for (const planner of planners) tcpMarkers[planner.name].position.fromArray(tcpAt(planner, time));
    placeArm();
    render();
  }
  slider.addEventListener("input", () => { stop(); setTime(Number(slider.value)); });

  let playing = null;
  const playButton = el("button", {type: "button", text: "▶ play"});
  function stop() {
    if (playing !== null) cancelAnimationFrame(playing);
    playing = null;
    playButton.textContent = "▶ play";
  }
  playButton.addEventListener("click", () => {
    if (playing !== null) { stop(); return; }
    if (time >= duration) setTime(0);
    playButton.textContent = "❚❚ pause";
    let last = performance.now();
    const step = now => {
      setTime(time + (now - last) / 1000);
      last = now;
      if (time >= duration) stop(); else playing = requestAnimationFrame(step);
    };
    playing = requestAnimationFrame(step);
  });

  controlsBar.append(playButton, slider, timeLabel);
  if (armChoices.length) {
    controlsBar.appendChild(selectControl("arm shows", armChoices, value => { armPlanner = value; setTime(time); }));
  }
  if (!animated.length) {
    controlsBar.appendChild(el("span", {class: "missing", text: robotData && problem.endpoints
      ? "no planner's motion with joints: the arm at start or goal only" : "no joint data: paths only, no arm"}));
  }
  const toggles = el("div", {class: "controls planner-toggles"}, planners.map(planner => {
    const box = el("input", {type: "checkbox", checked: true, "data-planner": planner.name,
                             onchange: () => { paths[planner.name].visible = tcpMarkers[planner.name].visible = box.checked; render(); }});
    return el("label", {}, [box, el("span", {class: "swatch", style: "background:" + colours[planner.name]}), planner.name]);
  }));
  container.appendChild(toggles);

  resize();
  setTime(0);
  // For the browser tests and the curious: world positions of the arm's links now.
  return {
    problem: problemName, setTime, duration, render,
    canvas: renderer.domElement,
    linkPositions: () => links.map(link => link.position.toArray()),
    linkNames: () => links.map(link => link.name),
    obstacleCount: () => obstacles.length,
    obstacleShapes: () => obstacles.map(mesh => mesh.geometry.type),
    heldBodies: () => held.map(mesh => ({name: mesh.name, link: mesh.parent.name, position: mesh.getWorldPosition(new THREE.Vector3()).toArray()})),
    pathCount: () => planners.length,
    visiblePaths: () => planners.filter(planner => paths[planner.name].visible).length,
  };
}
