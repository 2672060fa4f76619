// The report page's interactive parts: the top in 3D (three.js), the interactive plots
// (uPlot) and the clickable stability explorer. Bundled by esbuild into one classic script
// (heavytop-report.js) because pages opened from file:// may not import ES modules; its data
// come from report-data.js (window.HEAVYTOP_REPORT), written by heavytop beside it. The
// explorer page (web/explore.js) inlines this same bundle and draws its own runs with the 3D
// view: window.heavytopView3D.show(data) with data from the core's report::view_data().
// Every number shown here was computed by heavytop (report/src/report.cpp); this file only
// draws them: the attitude is composed from the report's theta, phi, psi as SPEC section 2
// defines it, R = R_eta(theta) R_xi(phi) Rz(psi).
import {
  AmbientLight, Box3, BoxGeometry, BufferAttribute, BufferGeometry, Color, ConeGeometry, CylinderGeometry, DirectionalLight,
  DoubleSide, Float32BufferAttribute, GridHelper, Group, Line, LineBasicMaterial, LineDashedMaterial, Matrix4, Mesh,
  MeshBasicMaterial, MeshStandardMaterial, OrthographicCamera, PerspectiveCamera, PlaneGeometry, RingGeometry, Scene, SphereGeometry,
  TorusGeometry, Vector3, WebGLRenderer,
} from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { STLLoader } from "three/examples/jsm/loaders/STLLoader.js";
import { OBJLoader } from "three/examples/jsm/loaders/OBJLoader.js";
import { PLYLoader } from "three/examples/jsm/loaders/PLYLoader.js";
import { mergeGeometries } from "three/examples/jsm/utils/BufferGeometryUtils.js";
import uPlot from "uplot";
import uPlotCss from "uplot/dist/uPlot.min.css";

const $ = (id) => document.getElementById(id);

// One colour per model, as the static figures draw them (report/src/figures.cpp).
const COLORS = { nonlinear: "#000000", "first-order": "#1f77b4", "body-fixed": "#ff7f0e", linearized: "#2ca02c",
                 "lagrange-exact": "#9467bd" };

// x to `digits` significant digits, without trailing zeros after the point (400, 0.05, 1.5e-9).
function fmt(x, digits = 4) {
  if (x === null || x === undefined || !isFinite(x)) return "–";
  const [mantissa, exponent] = Number(x).toPrecision(digits).split("e");
  const m = mantissa.includes(".") ? mantissa.replace(/0+$/, "").replace(/\.$/, "") : mantissa;
  return exponent === undefined ? m : `${m}e${exponent.replace("+", "")}`;
}

// ---- the attitude: SPEC section 2 ------------------------------------------------------------
// Q(phi, theta) = R_eta(theta) R_xi(phi); three.js's rotations are the same active right-handed
// ones, in the fixed frame (x = xi, y = eta, z = zeta up).
const mY = new Matrix4(), mX = new Matrix4(), mZ = new Matrix4();
function attitude(theta, phi, psi, out) {
  return out.copy(mY.makeRotationY(theta)).multiply(mX.makeRotationX(phi)).multiply(mZ.makeRotationZ(psi));
}
const ez = new Vector3(0, 0, 1), tmpM = new Matrix4();
function axisOf(theta, phi, out) { return out.copy(ez).applyMatrix4(attitude(theta, phi, 0, tmpM)); }

// Linear interpolation in a sampled series at fractional index u.
function lerp(series, u) {
  const i = Math.min(Math.floor(u), series.length - 2), f = u - i;
  return series[i] + f * (series[i + 1] - series[i]);
}

// ---- the body as drawn ------------------------------------------------------------------------
// Each triangle painted by its azimuth about the spin axis: 12 sectors in a part's two tones,
// sector 0 red towards the rim, so that the spin shows on a body of revolution.
const TONES = [[[0.80, 0.62, 0.38], [0.62, 0.44, 0.24]],   // wood
               [[0.72, 0.75, 0.79], [0.55, 0.58, 0.63]],   // steel
               [[0.35, 0.55, 0.72], [0.25, 0.42, 0.58]],   // blue
               [[0.85, 0.72, 0.35], [0.70, 0.56, 0.22]]];  // ochre
const RED = [0.85, 0.1, 0.1];
function paintSectors(geometry, tones, rimRadius) {
  const g = geometry.index ? geometry.toNonIndexed() : geometry;
  const p = g.attributes.position, colours = new Float32Array(3 * p.count);
  for (let i = 0; i + 2 < p.count; i += 3) {
    const x = (p.getX(i) + p.getX(i + 1) + p.getX(i + 2)) / 3, y = (p.getY(i) + p.getY(i + 1) + p.getY(i + 2)) / 3;
    const sector = Math.floor(((Math.atan2(y, x) + Math.PI) / (2 * Math.PI)) * 12) % 12;
    const c = sector === 6 && Math.hypot(x, y) > 0.6 * rimRadius ? RED : tones[sector % 2];  // sector 6: azimuth 0, +x
    for (let k = 0; k < 3; k++) colours.set(c, 3 * (i + k));
  }
  g.setAttribute("color", new Float32BufferAttribute(colours, 3));
  return g;
}

// The triangles of a non-indexed geometry wound the other way (every attribute's second and
// third vertex swapped).
function flipTriangles(g) {
  for (const a of Object.values(g.attributes))
    for (let i = 0; i + 2 < a.count; i += 3)
      for (let k = 0; k < a.itemSize; k++) {
        const x = a.getComponent(i + 1, k);
        a.setComponent(i + 1, k, a.getComponent(i + 2, k));
        a.setComponent(i + 2, k, x);
      }
  return g;
}

// A mesh part from its own file's bytes (base64), parsed by three.js's loader for its format.
function meshGeometry(part) {
  const bytes = Uint8Array.from(atob(part.data), (ch) => ch.charCodeAt(0));
  let g;
  if (part.format === "stl") g = new STLLoader().parse(bytes.buffer);
  else if (part.format === "ply") g = new PLYLoader().parse(bytes.buffer);
  else if (part.format === "obj") {
    const pieces = [];
    new OBJLoader().parse(new TextDecoder().decode(bytes)).traverse((o) => {
      if (!o.isMesh) return;
      const piece = new BufferGeometry();
      piece.setAttribute("position", (o.geometry.index ? o.geometry.toNonIndexed() : o.geometry).attributes.position);
      pieces.push(piece);
    });
    g = mergeGeometries(pieces);
  } else throw new Error(`a mesh of format ${part.format}`);
  g = g.index ? g.toNonIndexed() : g;
  for (const name of Object.keys(g.attributes)) if (name !== "position") g.deleteAttribute(name);
  g.scale(part.scale, part.scale, part.scale);
  // Outward normals from the winding (SPEC 10 accepts a surface oriented inwards throughout).
  const p = g.attributes.position, a = new Vector3(), b = new Vector3(), c = new Vector3();
  let volume = 0;
  for (let i = 0; i + 2 < p.count; i += 3) {
    a.fromBufferAttribute(p, i); b.fromBufferAttribute(p, i + 1); c.fromBufferAttribute(p, i + 2);
    volume += a.dot(b.cross(c));
  }
  if (volume < 0) flipTriangles(g);
  g.computeVertexNormals();
  return g;
}

// A solid part of SPEC section 10 (body axes, z the spin axis, z0 its lowest point).
function solidGeometry(part) {
  const r = part.radius, h = part.height, z0 = part.z0, N = 96;
  switch (part.shape) {
    case "cylinder": return new CylinderGeometry(r, r, h, N).rotateX(Math.PI / 2).translate(0, 0, z0 + h / 2);
    case "cone":  // three.js's cone has its apex on +y
      return new ConeGeometry(r, h, N).rotateX(part.apex === "up" ? Math.PI / 2 : -Math.PI / 2).translate(0, 0, z0 + h / 2);
    case "sphere": return new SphereGeometry(r, N, N / 2).rotateX(Math.PI / 2).translate(0, 0, z0 + r);
    case "tube": {
      const ri = part.inner_radius;
      if (!(ri > 0)) return new CylinderGeometry(r, r, h, N).rotateX(Math.PI / 2).translate(0, 0, z0 + h / 2);
      const inner = flipTriangles(new CylinderGeometry(ri, ri, h, N, 1, true).toNonIndexed());  // it faces the hole
      const q = inner.attributes.normal;
      for (let i = 0; i < q.count; i++) q.setXYZ(i, -q.getX(i), -q.getY(i), -q.getZ(i));
      const ring = (y, up) => new RingGeometry(ri, r, N, 1).rotateX(up ? -Math.PI / 2 : Math.PI / 2).translate(0, y, 0).toNonIndexed();
      const outer = new CylinderGeometry(r, r, h, N, 1, true).toNonIndexed();
      const all = [outer, inner, ring(h / 2, true), ring(-h / 2, false)];
      for (const g of all) g.deleteAttribute("uv");
      return mergeGeometries(all).rotateX(Math.PI / 2).translate(0, 0, z0 + h / 2);
    }
  }
  throw new Error(`a part of shape ${part.shape}`);
}

// The body in its own axes: its parts as they are (SPEC section 10), or for a body given by its
// moments only the uniform ellipsoid with its mass and central moments, on a spindle. Returns
// the group, what it is made of (shapes, for a reader's console and the browser test), its size
// and the point on the axis whose path is traced.
function buildBody(D) {
  const group = new Group();
  const shapes = [];
  const material = (options) => new MeshStandardMaterial({ vertexColors: true, roughness: 0.65, ...options });
  if (D.parts && D.parts.length) {
    const geometries = D.parts.map((part) => (part.shape === "mesh" ? part.format === "box" ? null : meshGeometry(part) : solidGeometry(part)));
    let rim = 0, zMin = Infinity, zMax = -Infinity, reach = 0;
    for (const g of geometries) {
      if (!g) continue;
      const p = g.attributes.position;
      for (let i = 0; i < p.count; i++) {
        rim = Math.max(rim, Math.hypot(p.getX(i), p.getY(i)));
        zMin = Math.min(zMin, p.getZ(i)); zMax = Math.max(zMax, p.getZ(i));
        reach = Math.max(reach, Math.hypot(p.getX(i), p.getY(i), p.getZ(i)));
      }
    }
    D.parts.forEach((part, k) => {
      let mesh;
      if (part.format === "box") {  // a mesh too large to carry: its bounding box, translucent
        const [lo, hi] = [part.box.min, part.box.max];
        const g = new BoxGeometry(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]).translate((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
        mesh = new Mesh(g, new MeshStandardMaterial({ color: 0x9c7a50, transparent: true, opacity: 0.5 }));
        rim = Math.max(rim, Math.hypot(lo[0], lo[1]), Math.hypot(hi[0], hi[1]));
        zMin = Math.min(zMin, lo[2]); zMax = Math.max(zMax, hi[2]);
      } else {
        mesh = new Mesh(paintSectors(geometries[k], TONES[k % TONES.length], rim),
                        material(part.shape === "mesh" ? { side: DoubleSide } : {}));
      }
      mesh.userData.part = k;
      group.add(mesh);
      const box = new Box3().setFromBufferAttribute(mesh.geometry.attributes.position);
      shapes.push({ ...part, data: undefined, triangles: mesh.geometry.attributes.position.count / 3,
                    min: box.min.toArray(), max: box.max.toArray(), uuid: mesh.uuid });
    });
    const size = Math.max(reach, 1e-9);
    // The traced point: the axis at the body's top (a top) or its bottom (a hanging body).
    const zTrace = zMax > 0.2 * size || zMax >= -zMin ? zMax : zMin;
    // The red ball on the rim, at the widest height.
    let zRim = 0.5 * (zMin + zMax), best = -1;
    for (const g of geometries) {
      if (!g) continue;
      const p = g.attributes.position;
      for (let i = 0; i < p.count; i++) {
        const rr = Math.hypot(p.getX(i), p.getY(i));
        if (rr > best + 1e-9 * size) { best = rr; zRim = p.getZ(i); }
      }
    }
    const marker = new Mesh(new SphereGeometry(size / 30, 16, 8), new MeshStandardMaterial({ color: 0xd62728 }));
    marker.position.set(rim + size / 45, 0, zRim);
    group.add(marker);
    return { group, shapes, size, zTrace, spindle: false };
  }
  // The equivalent ellipsoid (D.shape: semi-axes, m, and its centre on z).
  const a = D.shape.semi_axes[0], b = D.shape.semi_axes[1], c = D.shape.semi_axes[2], zc = D.shape.centre;
  const size = Math.max(a, b, c, Math.abs(zc));
  // The spindle: from the tip at O (a top) through the body to a point above it, whose path is
  // traced; a hanging body's from below it up through O to a short stub above.
  const zTop = zc >= 0 ? zc + Math.max(1.5 * c, 0.45 * size) : 0.45 * size;
  const zBottom = zc >= 0 ? 0 : zc - Math.max(1.5 * c, 0.2 * size);
  const ell = paintSectors(new SphereGeometry(1, 96, 48).rotateX(Math.PI / 2).scale(a, b, c).translate(0, 0, zc), TONES[0], Math.max(a, b));
  group.add(new Mesh(ell, material({ roughness: 0.7 })));
  const rim = new Mesh(new TorusGeometry(1, 0.035, 12, 128).scale(a, b, a).translate(0, 0, zc), new MeshStandardMaterial({ color: 0x333333 }));
  group.add(rim);
  const marker = new Mesh(new SphereGeometry(size / 18, 16, 8), new MeshStandardMaterial({ color: 0xd62728 }));
  marker.position.set(a * 1.02, 0, zc);
  group.add(marker);
  // A top's spindle starts inside its point (a flat end at O would dip below it when tilted).
  const hPoint = Math.min(0.35 * zc, size / 3), zLow = zc > 0 ? 0.9 * hPoint : zBottom;
  const spindle = new Mesh(new CylinderGeometry(size / 40, size / 40, zTop - zLow, 16).rotateX(Math.PI / 2).translate(0, 0, 0.5 * (zTop + zLow)),
                           new MeshStandardMaterial({ color: 0x9aa3ab, metalness: 0.5, roughness: 0.35 }));
  group.add(spindle);
  if (zc > 0) {  // the top's own point, on O
    const h = hPoint;
    group.add(new Mesh(new ConeGeometry(h / 2.2, h, 32).rotateX(-Math.PI / 2).translate(0, 0, h / 2),
                       new MeshStandardMaterial({ color: 0x6b737a, metalness: 0.5, roughness: 0.4 })));
  }
  shapes.push({ shape: "ellipsoid", semi_axes: [a, b, c], centre: zc, uuid: group.children[0].uuid });
  return { group, shapes, size, zTrace: zTop, spindle: true };
}

// On a table (D.table, SPEC section 16) a body given by its moments is drawn as what touches
// the table: the rim (a disc of radius rho about the axis through O, thickened by the tip's
// radius r), or the tip's sphere (radius r about O): the whole body when the sphere is as large as
// the equivalent ellipsoid (a tippe top, its upper cap dark so that the axis shows), else under
// the ellipsoid and spindle (a top on its round point).
function buildTableBody(D) {
  const r = D.table.tip_radius, rho = D.table.rim_radius;
  const material = () => new MeshStandardMaterial({ vertexColors: true, roughness: 0.6 });
  if (rho > 0) {
    const group = new Group(), h = Math.max(2 * r, 0.08 * rho);
    group.add(new Mesh(paintSectors(new CylinderGeometry(rho + r, rho + r, h, 96).rotateX(Math.PI / 2), TONES[3], rho), material()));
    const tube = Math.max(r, 0.03 * rho);  // the rim's edge at rho + r, as the table meets it
    group.add(new Mesh(new TorusGeometry(rho + r - tube, tube, 12, 128), new MeshStandardMaterial({ color: 0x6b5a2a })));
    return { group, shapes: [{ shape: "rim", radius: rho, thickness: h, uuid: group.children[0].uuid }], size: rho + r, zTrace: rho, spindle: false };
  }
  const base = buildBody(D);
  if (!(r > 0)) return base;
  const ball = paintSectors(new SphereGeometry(r, 64, 32).rotateX(Math.PI / 2), TONES[1], r);
  if (r < 0.5 * base.size) {
    base.group.add(new Mesh(ball, material()));
    base.shapes.push({ shape: "tip", radius: r });
    return base;
  }
  const p = ball.attributes.position, c = ball.attributes.color;
  for (let i = 0; i < p.count; i++) if (p.getZ(i) > 0.72 * r) c.setXYZ(i, 0.22, 0.24, 0.28);
  const group = new Group();
  group.add(new Mesh(ball, material()));
  return { group, shapes: [{ shape: "ball", radius: r, uuid: group.children[0].uuid }], size: r, zTrace: r, spindle: false };
}

// Points of the body (its own axes), at most `most` of them, for its extent over the motion.
function bodyPoints(group, most) {
  const all = [];
  group.updateMatrixWorld(true);
  group.traverse((o) => {
    if (!o.isMesh) return;
    const p = o.geometry.attributes.position, v = new Vector3();
    for (let i = 0; i < p.count; i++) all.push(v.fromBufferAttribute(p, i).applyMatrix4(o.matrix).toArray());
  });
  const stride = Math.max(1, Math.ceil(all.length / most)), out = [];
  // Every stride-th, and the extremes along each axis (the lowest point above all).
  for (let i = 0; i < all.length; i += stride) out.push(all[i]);
  for (let k = 0; k < 3; k++) {
    let lo = 0, hi = 0;
    all.forEach((q, i) => { if (q[k] < all[lo][k]) lo = i; if (q[k] > all[hi][k]) hi = i; });
    out.push(all[lo], all[hi]);
  }
  return out;
}

// ---- the 3D view ---------------------------------------------------------------------------------
const EXAGGERATION = 10;
// The attitude drawn: the true one, or (exaggerated) its tilt from the vertical times 10, at most
// pi (upside down), about the same horizontal line, azimuth and spin unchanged.
const ex = new Matrix4(), exAxis = new Vector3();
function exaggerate(R) {
  const e = R.elements, kx = e[8], ky = e[9], kz = e[10];
  const tilt = Math.acos(Math.max(-1, Math.min(1, kz))), h = Math.hypot(kx, ky);
  if (!(h > 1e-12)) return R;
  const drawn = Math.min(EXAGGERATION * tilt, Math.PI);
  exAxis.set(-ky / h, kx / h, 0);
  return R.premultiply(ex.makeRotationAxis(exAxis, drawn - tilt));
}
function exaggerateAxis(k) {
  const tilt = Math.acos(Math.max(-1, Math.min(1, k.z))), h = Math.hypot(k.x, k.y);
  if (!(h > 1e-12)) return k;
  const drawn = Math.min(EXAGGERATION * tilt, Math.PI), s = Math.sin(drawn) / h;
  return k.set(k.x * s, k.y * s, Math.cos(drawn));
}

let keptRenderer = null, keptSize = "";
// The 3D view of `D` (the report's data, or report::view_data()'s) in the page's #scene with its
// controls (#play, #speed, #scrub, #exaggerate...). Returns its state; state.dispose() removes
// it (its listeners, its animation, its geometries; the renderer stays), so that another can be
// built in its place.
function buildView(D) {
  const host = $("scene");
  const lifetime = new AbortController(), signal = lifetime.signal;
  const t = D.t, n = t.length, T = t[n - 1];
  // On a table (SPEC section 16): O moves (D.table.origin, m, at the samples), the table is the
  // plane z = 0 and the contact point P leaves its track on it (D.table.track).
  const onTable = D.table || null;
  const body = onTable && !(D.parts && D.parts.length) ? buildTableBody(D) : buildBody(D);
  const { size, zTrace } = body;
  const originAt = (i, out) => (onTable ? out.set(onTable.origin.x[i], onTable.origin.y[i], onTable.origin.z[i]) : out.set(0, 0, 0));
  const originLerp = (u, out) => (onTable ? out.set(lerp(onTable.origin.x, u), lerp(onTable.origin.y, u), lerp(onTable.origin.z, u)) : out.set(0, 0, 0));
  const o = new Vector3();

  // One renderer (one WebGL context, its compiled shaders) for every view built in this page: a
  // new context for each of the explorer's runs took 0.3 to 1 s under SwiftShader.
  const renderer = keptRenderer || new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  keptRenderer = renderer;
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setClearColor(0xf4f6f8);
  renderer.autoClear = false;
  if (renderer.domElement.parentElement !== host) host.appendChild(renderer.domElement);
  renderer.domElement.id = "scene-canvas";

  const scene = new Scene();
  scene.add(new AmbientLight(0xffffff, 0.55));
  const sun = new DirectionalLight(0xffffff, 1.6);
  sun.position.set(2 * size, -3 * size, 5 * size);
  scene.add(sun);
  const fill = new DirectionalLight(0xffffff, 0.5);
  fill.position.set(-3 * size, 2 * size, -1 * size);
  scene.add(fill);

  const bodyGroup = body.group;
  bodyGroup.matrixAutoUpdate = false;
  scene.add(bodyGroup);

  // The body's extent over the motion, true and exaggerated: the floor goes below its lowest
  // point (at O for a top that stays above its tip), the camera frames all of it.
  const points = bodyPoints(bodyGroup, 4000);
  const R = new Matrix4(), v = new Vector3();
  const extentOf = (exaggerated) => {
    const lo = new Vector3(0, 0, 0), hi = new Vector3(0, 0, 0);
    for (let i = 0; i < n; i++) {
      attitude(D.nonlinear.theta[i], D.nonlinear.phi[i], D.nonlinear.psi[i], R);
      if (exaggerated) exaggerate(R);
      const e = R.elements;
      originAt(i, o);
      for (const q of points) {
        v.set(e[0] * q[0] + e[4] * q[1] + e[8] * q[2], e[1] * q[0] + e[5] * q[1] + e[9] * q[2], e[2] * q[0] + e[6] * q[1] + e[10] * q[2]).add(o);
        lo.min(v); hi.max(v);
      }
      axisOf(D.nonlinear.theta[i], D.nonlinear.phi[i], v);
      if (exaggerated) exaggerateAxis(v);
      v.multiplyScalar(zTrace).add(o);
      lo.min(v); hi.max(v);
    }
    return { lo, hi };
  };
  // A body never near the vertical (the horizontal gyroscope) would only be drawn upside down:
  // no exaggeration for it.
  let leastTilt = Math.PI;
  for (let i = 0; i < n; i++) leastTilt = Math.min(leastTilt, Math.acos(Math.max(-1, Math.min(1, axisOf(D.nonlinear.theta[i], D.nonlinear.phi[i], v).z))));
  const exaggerable = !onTable && EXAGGERATION * leastTilt < 0.9 * Math.PI;
  const truth = extentOf(false), extents = [truth, exaggerable ? extentOf(true) : truth];
  const floorOf = (ext) => (ext.lo.z >= -1e-3 * size ? 0 : ext.lo.z - 0.04 * size);
  const floors = onTable ? [0, 0] : extents.map(floorOf);

  // The fixed frame: the floor (a grid) below the body, a stand from it up to O when O is above
  // it, a mount above O for a hanging body, the vertical.
  const reachXY = Math.max(...extents.map((e) => Math.max(-e.lo.x, e.hi.x, -e.lo.y, e.hi.y)), 0.5 * size);
  const gridSide = onTable ? Math.max(...extents.map((e) => Math.max(e.hi.x - e.lo.x, e.hi.y - e.lo.y))) + 3 * size : 2.6 * reachXY;
  // On a table, a cell about the body's width (at most 200 a side).
  const grid = new GridHelper(gridSide, onTable ? Math.max(8, Math.min(200, Math.round(gridSide / (2 * size)))) : 12, 0xb0b8c0, 0xd5dade);
  grid.rotation.x = Math.PI / 2;
  scene.add(grid);
  let track = null;
  if (onTable) {  // the table: a plane under the grid, centred on the motion; P's track on it
    const cx = 0.5 * (extents[0].lo.x + extents[0].hi.x), cy = 0.5 * (extents[0].lo.y + extents[0].hi.y);
    grid.position.set(cx, cy, 0);
    const plane = new Mesh(new PlaneGeometry(gridSide, gridSide), new MeshStandardMaterial({ color: 0xeae3d6, roughness: 0.9, side: DoubleSide }));
    plane.position.set(cx, cy, -2e-3 * size);
    scene.add(plane);
    // Every computed sample of P (its small loops at the nutation's frequency would alias at the
    // display's samples).
    const m = onTable.track.t.length, pts = new Float32Array(3 * m);
    for (let i = 0; i < m; i++) pts.set([onTable.track.x[i], onTable.track.y[i], 2e-3 * size], 3 * i);
    const g = new BufferGeometry();
    g.setAttribute("position", new BufferAttribute(pts, 3));
    g.setDrawRange(0, 0);
    track = new Line(g, new LineBasicMaterial({ color: 0x000000 }));
    track.frustumCulled = false;
    scene.add(track);
  }
  const standMaterial = new MeshStandardMaterial({ color: 0x8a939b, metalness: 0.3, roughness: 0.5 });
  const stand = new Mesh(new CylinderGeometry(size / 70, size / 70, 1, 16).rotateX(Math.PI / 2).translate(0, 0, -0.5), standMaterial);
  const foot = new Mesh(new CylinderGeometry(size / 9, size / 8, size / 40, 48).rotateX(Math.PI / 2).translate(0, 0, size / 80), standMaterial);
  scene.add(stand, foot);
  const zHigh = Math.max(...extents.map((e) => e.hi.z), 0.3 * size);
  const vertical = new Line(new BufferGeometry().setFromPoints([new Vector3(0, 0, 0), new Vector3(0, 0, 1)]),
                            new LineDashedMaterial({ color: 0x555555, dashSize: size / 15, gapSize: size / 20 }));
  vertical.layers.enable(1);
  scene.add(vertical);
  const pivot = new Mesh(new SphereGeometry(size / 40, 24, 12), new MeshStandardMaterial({ color: 0x222222 }));
  scene.add(pivot);
  if (D.body.length < 0) {  // a hanging body hangs from a mount above O
    const h = size / 4;
    scene.add(new Mesh(new ConeGeometry(h / 2.2, h, 32).rotateX(-Math.PI / 2).translate(0, 0, h / 2), standMaterial));
  }
  const state = { time: 0, playing: true, speed: D.playback.speed, frames: 0, exaggerated: false, shapes: body.shapes };
  function placeFloor() {
    const z = floors[state.exaggerated ? 1 : 0];
    state.floor = z;
    state.lowest = extents[state.exaggerated ? 1 : 0].lo.z;
    grid.position.z = z;
    // A top whose body reaches below O stands on a post; a hanging body's mount needs none.
    stand.visible = foot.visible = !onTable && z < 0 && D.body.length >= 0;
    vertical.visible = pivot.visible = !onTable;
    stand.scale.set(1, 1, -z || 1);
    foot.position.z = z;
    vertical.geometry.setFromPoints([new Vector3(0, 0, z), new Vector3(0, 0, 1.25 * zHigh)]);
    vertical.computeLineDistances();
  }
  placeFloor();

  // The traced point: the axis at zTrace. Its past path, for the truth and each model, true and
  // exaggerated.
  const tip = (theta, phi, out) => {
    axisOf(theta, phi, out);
    if (state.exaggerated) exaggerateAxis(out);
    return out.multiplyScalar(zTrace);
  };
  const traces = [];
  function traceOf(theta, phi, color, until) {
    const pts = [new Float32Array(3 * n), new Float32Array(3 * n)], w = new Vector3();
    let m = 0;
    // Up to a divergence, or a gap (null: a model that stopped on a numerical failure).
    for (let i = 0; i < n && !(until !== null && t[i] > until) && theta[i] !== null && phi[i] !== null; i++, m++) {
      axisOf(theta[i], phi[i], w);
      pts[0].set([w.x * zTrace, w.y * zTrace, w.z * zTrace], 3 * i);
      exaggerateAxis(w).multiplyScalar(zTrace);
      pts[1].set([w.x, w.y, w.z], 3 * i);
    }
    const g = new BufferGeometry();
    const attributes = pts.map((p) => new BufferAttribute(p, 3));
    g.setAttribute("position", attributes[0]);
    g.setDrawRange(0, 0);
    const line = new Line(g, new LineBasicMaterial({ color }));
    line.frustumCulled = false;
    line.layers.enable(1);
    line.userData.count = m;
    line.userData.attributes = attributes;
    traces.push(line);
    return line;
  }
  const truthTrace = traceOf(D.nonlinear.theta, D.nonlinear.phi, 0x000000, null);
  scene.add(truthTrace);
  const tipMark = new Mesh(new SphereGeometry(size / 45, 16, 8), new MeshStandardMaterial({ color: 0x000000 }));
  scene.add(tipMark);
  if (onTable) {  // the axis's path only in the inset (about O, wherever O is); P's track in the view
    truthTrace.layers.set(1);
    tipMark.visible = false;
  }
  const overlays = D.models.map((m) => {
    const color = new Color(COLORS[m.name] || "#777777");
    const rod = new Line(new BufferGeometry().setFromPoints([new Vector3(), new Vector3(0, 0, zTrace)]),
                         new LineBasicMaterial({ color }));
    rod.matrixAutoUpdate = false;
    const end = new Mesh(new SphereGeometry(size / 50, 16, 8), new MeshStandardMaterial({ color }));
    const trace = traceOf(m.theta, m.phi, color, m.diverged_at);
    const g = new Group();
    g.add(rod, end, trace);
    g.visible = false;
    scene.add(g);
    return { model: m, group: g, rod, end, trace, dot: null };
  });

  // Cameras: an oblique view that a mouse can turn, framing the body over the whole motion (the
  // box of both the true and the exaggerated attitudes, the floor's centre and O); and an inset
  // from straight above on the tip (xi to the right, eta up: the static figure's "seen from above").
  const box = new Box3(new Vector3(0, 0, Math.min(...floors)), new Vector3(0, 0, D.body.length < 0 ? size / 4 : 0));
  for (const e of extents) box.expandByPoint(e.lo).expandByPoint(e.hi);
  const centre = box.getCenter(new Vector3()), radius = Math.max(0.5 * box.getSize(new Vector3()).length(), 1e-9);
  const camera = new PerspectiveCamera(35, 1, radius / 100, radius * 100);
  camera.up.set(0, 0, 1);
  const direction = new Vector3(2.3, -3.0, 1.3).normalize();
  // The nearest camera along `direction` that sees every corner of the box, left of the inset
  // (which covers the right quarter of the view's lower part).
  const cornersOf = (b) => [0, 1, 2, 3, 4, 5, 6, 7].map((c) => new Vector3(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z));
  // `b`: the box to frame (default: the whole motion's); the controls then turn about its centre.
  function fitCamera(b = box) {
    const centre = b.getCenter(new Vector3()), corners = cornersOf(b);
    const sees = (d) => {
      camera.position.copy(centre).addScaledVector(direction, d);
      camera.lookAt(centre);
      camera.updateMatrixWorld();
      return corners.every((c) => { const p = c.clone().project(camera); return Math.abs(p.z) < 1 && Math.abs(p.x) <= 0.5 && Math.abs(p.y) <= 0.86; });
    };
    let near = 0, far = 4 * radius;
    while (!sees(far) && far < 1e6 * radius) far *= 2;
    for (let k = 0; k < 40; k++) { const mid = 0.5 * (near + far); if (sees(mid)) far = mid; else near = mid; }
    sees(far);
    if (controls) controls.target.copy(centre);
  }
  let controls = null;
  // On a table the camera follows the body by default (a box of a few body sizes about O, moved
  // with O; the mouse still turns and zooms about it); unticked, it frames the whole track.
  const followBox = () => {
    const here = originLerp(Math.min((state.time / T) * (n - 1), n - 1 - 1e-9), new Vector3());
    return new Box3(new Vector3(here.x - 2.2 * size, here.y - 2.2 * size, 0), new Vector3(here.x + 2.2 * size, here.y + 2.2 * size, here.z + 2.2 * size));
  };
  const followFrom = new Vector3();
  state.follow = !!onTable;
  controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(centre);
  const top = new OrthographicCamera(-1, 1, 1, -1, size / 100, size * 100);
  top.up.set(0, 1, 0);
  top.layers.set(1);
  // The tip's largest distance from the vertical, for the inset's scale (true and exaggerated).
  const insetExtent = [false, true].map((exaggerated) => {
    let e = 0;
    const w = new Vector3();
    for (let i = 0; i < n; i++) {
      axisOf(D.nonlinear.theta[i], D.nonlinear.phi[i], w);
      if (exaggerated) exaggerateAxis(w);
      w.multiplyScalar(zTrace);
      e = Math.max(e, Math.hypot(w.x, w.y));
    }
    return Math.max(1.25 * e, 1e-6 * Math.abs(zTrace));
  });
  top.position.set(0, 0, Math.max(3 * Math.abs(zTrace), 3 * size, 2 * zHigh));
  top.lookAt(0, 0, 0);
  top.far = top.position.z - Math.min(...floors) + size;
  top.updateProjectionMatrix();
  // In the inset (layer 1 only): the tip as a dot at the inset's scale, each model's too, and a
  // cross where the vertical is; sized for the scale at hand.
  const dot = (color, r) => { const m = new Mesh(new SphereGeometry(r, 16, 8), new MeshBasicMaterial({ color })); m.layers.set(1); return m; };
  const tipDot = dot(0x000000, 1 / 28);
  scene.add(tipDot);
  for (const o of overlays) { o.dot = dot(new Color(COLORS[o.model.name] || "#777777"), 1 / 34); o.group.add(o.dot); }
  const cross = new Line(new BufferGeometry().setFromPoints([new Vector3(-1 / 12, 0, 0), new Vector3(1 / 12, 0, 0),
    new Vector3(0, 0, 0), new Vector3(0, 1 / 12, 0), new Vector3(0, -1 / 12, 0)]), new LineBasicMaterial({ color: 0x888888 }));
  cross.position.z = zTrace;
  cross.layers.set(1);
  scene.add(cross);
  const insetScale = () => insetExtent[state.exaggerated ? 1 : 0];
  function placeInset() {
    const e = insetScale();
    tipDot.scale.setScalar(e);
    for (const o of overlays) o.dot.scale.setScalar(e);
    cross.scale.set(e, e, 1);
    $("inset-scale").textContent = state.exaggerated
      ? `${fmt((e / Math.abs(zTrace)) * 1e3, 3)} mrad as drawn (tilt x${EXAGGERATION}, not to scale)`
      : `${fmt((e / Math.abs(zTrace)) * 1e3, 3)} mrad`;
  }

  // ---- playback ----
  const scrub = $("scrub"), speedInput = $("speed"), playButton = $("play"), readout = $("time");
  const speeds = D.playback.speeds;
  speedInput.max = speeds.length - 1;
  speedInput.value = speeds.indexOf(state.speed);
  const spinNote = $("spin-note");
  function describeSpeed() {
    $("speed-value").textContent = `${fmt(state.speed, 3)}× real time`;
    // The spin between two frames at 60 frames a second: beyond 30 degrees the eye cannot follow
    // it and the marker's apparent turning is aliased (a stroboscope), though its angle is true.
    const perFrame = (D.playback.spin_rate * state.speed) / 60;
    const faithful = (Math.PI / 6) * 60 / D.playback.spin_rate;
    if (perFrame > Math.PI / 6) {
      spinNote.hidden = false;
      spinNote.textContent = `At this speed the body turns ${fmt((perFrame * 180) / Math.PI, 3)}° between frames (spin ` +
        `${fmt(D.playback.spin_rate, 4)} rad/s): the red marker is drawn at its true angle in every frame, but ` +
        `its apparent turning is stroboscopic (aliased), not the real spin. Below ${fmt(faithful, 2)}× it turns faithfully.`;
    } else spinNote.hidden = true;
  }
  describeSpeed();
  speedInput.addEventListener("input", () => { state.speed = speeds[+speedInput.value]; describeSpeed(); }, { signal });
  playButton.textContent = "Pause";
  playButton.addEventListener("click", () => {
    state.playing = !state.playing;
    if (state.playing && state.time >= T) state.time = 0;
    playButton.textContent = state.playing ? "Pause" : "Play";
  }, { signal });
  scrub.addEventListener("input", () => { state.time = (T * scrub.value) / scrub.max; draw(); }, { signal });
  for (const o of overlays) {
    const box = $(`overlay-${o.model.name}`);
    if (box) box.addEventListener("change", () => { o.group.visible = box.checked; draw(); }, { signal });
  }
  const exaggerateBox = $("exaggerate");
  const oldWhy = $("exaggerate-off");
  if (oldWhy) oldWhy.remove();
  if (exaggerateBox) { exaggerateBox.disabled = false; exaggerateBox.checked = false; }
  function setExaggerated(on) {
    state.exaggerated = on;
    for (const line of traces) line.geometry.setAttribute("position", line.userData.attributes[on ? 1 : 0]);
    placeFloor();
    placeInset();
    draw();
  }
  if (exaggerateBox && !exaggerable) {
    exaggerateBox.disabled = true;
    const why = document.createElement("span");
    why.id = "exaggerate-off";
    why.textContent = ` Off for this body: its axis is never nearer the vertical than ${fmt((leastTilt * 180) / Math.PI, 3)} degrees, ` +
      `so ten times its tilt would only draw it upside down.`;
    exaggerateBox.parentElement.appendChild(why);
  } else if (exaggerateBox) exaggerateBox.addEventListener("change", () => setExaggerated(exaggerateBox.checked), { signal });
  placeInset();
  Object.defineProperty(state, "scene", { value: scene, enumerable: false });  // (the test looks for the parts in it)
  window.heavytopView = state;  // for a reader's console (and the browser test's logs)
  // The plots jump the view to a time clicked on them.
  state.seek = (time) => { state.time = Math.max(0, Math.min(T, time)); draw(); };

  function place(time) {
    const u = Math.min((time / T) * (n - 1), n - 1 - 1e-9);
    const i = Math.floor(u);
    const th = lerp(D.nonlinear.theta, u), ph = lerp(D.nonlinear.phi, u), ps = lerp(D.nonlinear.psi, u);
    attitude(th, ph, ps, R);
    state.tilt = Math.acos(Math.max(-1, Math.min(1, R.elements[10])));  // the true tilt, rad
    if (state.exaggerated) exaggerate(R);
    state.drawnTilt = Math.acos(Math.max(-1, Math.min(1, R.elements[10])));
    bodyGroup.matrix.copy(R);
    if (onTable) {
      originLerp(u, o);
      bodyGroup.matrix.setPosition(o);
      if (state.follow) {  // the camera and the point it turns about move with O
        const dx = o.x - followFrom.x, dy = o.y - followFrom.y;
        camera.position.x += dx; camera.position.y += dy;
        controls.target.x += dx; controls.target.y += dy;
        camera.updateMatrixWorld();
        followFrom.set(o.x, o.y, o.z);
      }
      state.origin = o.toArray();
      // P's samples up to this time (binary search: the last one may be an event's, off the grid).
      const tt = onTable.track.t;
      let lo = 0, hi = tt.length;
      while (lo < hi) { const mid = (lo + hi) >> 1; if (tt[mid] <= time) lo = mid + 1; else hi = mid; }
      track.geometry.setDrawRange(0, Math.max(lo, 1));
    }
    bodyGroup.matrixWorldNeedsUpdate = true;
    tip(th, ph, v);
    tipMark.position.copy(v);
    tipDot.position.copy(v);
    truthTrace.geometry.setDrawRange(0, i + 1);
    for (const o of overlays) {
      const m = o.model, mt = lerp(m.theta, u), mp = lerp(m.phi, u);
      const gone = (m.diverged_at !== null && time > m.diverged_at) || !isFinite(mt) || !isFinite(mp);
      o.rod.visible = o.end.visible = o.dot.visible = !gone;
      o.trace.geometry.setDrawRange(0, Math.min(i + 1, o.trace.userData.count));
      if (gone) continue;
      attitude(mt, mp, 0, o.rod.matrix);
      if (state.exaggerated) exaggerate(o.rod.matrix);
      o.rod.matrixWorldNeedsUpdate = true;
      tip(mt, mp, o.end.position);
      o.dot.position.copy(o.end.position);
    }
    readout.textContent = `t = ${time.toFixed(3)} s of ${fmt(T, 4)} s`;
    scrub.value = Math.round((time / T) * scrub.max);
  }

  function resize() {
    const w = host.clientWidth, h = Math.round(w * 0.56);
    // Only when it changed: a resize reallocates the drawing buffer (0.7 s under SwiftShader).
    if (keptSize !== `${w}x${h}`) renderer.setSize(w, h);
    keptSize = `${w}x${h}`;
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", () => { resize(); draw(); }, { signal });
  resize();
  fitCamera();
  if (state.follow) { fitCamera(followBox()); originLerp(0, followFrom); }
  controls.update();
  const followBox_ = $("follow");
  if (followBox_ && onTable) followBox_.addEventListener("change", () => {
    state.follow = followBox_.checked;
    if (state.follow) { fitCamera(followBox()); originLerp(Math.min((state.time / T) * (n - 1), n - 1 - 1e-9), followFrom); }
    else fitCamera();
    controls.update();
    draw();
  }, { signal });

  function draw() {
    place(state.time);
    const w = renderer.domElement.clientWidth, h = renderer.domElement.clientHeight;
    renderer.setScissorTest(false);
    renderer.setViewport(0, 0, w, h);
    renderer.clear();
    renderer.render(scene, camera);
    if (onTable) return;  // on a table no inset: the track of P on the table shows the motion
    // The inset, bottom right: straight down on the tip, its loops and cusps at true scale.
    const s = Math.round(h * 0.42), x0 = w - s - 8, y0 = 8;
    renderer.setScissorTest(true);
    renderer.setScissor(x0, y0, s, s);
    renderer.setViewport(x0, y0, s, s);
    renderer.setClearColor(0xffffff);
    renderer.clear();
    const e = insetScale();
    top.left = -e; top.right = e; top.top = e; top.bottom = -e;
    top.updateProjectionMatrix();
    renderer.render(scene, top);
    renderer.setClearColor(0xf4f6f8);
    renderer.setScissorTest(false);
  }

  // For the browser test: over `count` times of the motion, the body's lowest point (its drawn
  // triangles, exactly) against the floor, and whether all of it is inside the camera's view.
  state.measure = (count = 60) => {
    const saved = state.time, out = { lowest: Infinity, floor: state.floor, outside: 0, times: count };
    const b = new Box3(), corner = new Vector3();
    camera.updateMatrixWorld();
    for (let k = 0; k <= count; k++) {
      place((T * k) / count);
      bodyGroup.updateMatrixWorld(true);
      b.setFromObject(bodyGroup, true);
      out.lowest = Math.min(out.lowest, b.min.z);
      for (let c = 0; c < 8; c++) {
        corner.set(c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z).project(camera);
        if (Math.abs(corner.x) > 1 || Math.abs(corner.y) > 1) out.outside++;
      }
    }
    place(saved);
    return out;
  };

  let last = null, pending = 0;
  state.dispose = () => {
    lifetime.abort();
    cancelAnimationFrame(pending);
    controls.dispose();
    scene.traverse((o) => { if (o.geometry) o.geometry.dispose(); if (o.material) o.material.dispose(); });
    renderer.renderLists.dispose();  // the renderer and its canvas stay for the next view
    if (window.heavytopView === state) window.heavytopView = undefined;
  };
  function frame(now) {
    if (last !== null && state.playing) {
      state.time += (state.speed * Math.min(now - last, 100)) / 1000;
      if (state.time >= T) { state.time = T; state.playing = false; playButton.textContent = "Play"; }
    }
    last = now;
    draw();
    state.frames++;
    pending = requestAnimationFrame(frame);
  }
  controls.addEventListener("change", draw);
  pending = requestAnimationFrame(frame);
  return state;
}

// ---- interactive plots -----------------------------------------------------------------------------
function buildPlots(D) {
  const style = document.createElement("style");
  style.textContent = uPlotCss;
  document.head.appendChild(style);
  const t = D.t, scale = D.angle_scale, unit = D.angle_unit;
  const width = () => Math.min($("plots").clientWidth, 1100);
  const sync = uPlot.sync("heavytop");
  const charts = [];
  const series = (key) => {
    const s = [{ label: "t (s)" }], data = [t];
    // The truth last, so it is drawn on top of the others.
    for (const m of D.models) {
      s.push({ label: m.name, stroke: COLORS[m.name], width: 3.5, dash: m.name === "body-fixed" ? [6, 4] : undefined });
      data.push(m[key].map((x, i) => (x === null || (m.diverged_at !== null && t[i] > m.diverged_at) ? null : x * scale)));
    }
    s.push({ label: "nonlinear (truth)", stroke: COLORS.nonlinear, width: 1.2 });  // thin, on top: models show beneath
    // theta = atan2(k_xi, k_zeta) jumps by 2 pi when the axis passes below the horizontal: a gap there, not a wall.
    const truth = D.nonlinear[key];
    data.push(truth.map((x, i) => (i > 0 && Math.abs(x - truth[i - 1]) > Math.PI ? null : x * scale)));
    return { s, data };
  };
  const cursor = { sync: { key: sync.key }, drag: { x: true, y: true } };
  for (const [key, label] of [["theta", "theta"], ["phi", "phi"]]) {
    const { s, data } = series(key);
    const el = document.createElement("div");
    el.className = "plot";
    el.id = `plot-${key}`;
    $("plots").appendChild(el);
    charts.push(new uPlot({ title: `${label}(t): every model from the same start (${unit})`, width: width(), height: 300,
                            cursor, series: s, scales: { x: { time: false } },
                            axes: [{ label: "t (s)" }, { label: `${label} (${unit})`, size: 70 }] }, data, el));
  }
  // The error of each model against the truth, log scale (null where it is 0 or the model diverged).
  const s = [{ label: "t (s)" }], data = [t];
  for (const m of D.models) {
    s.push({ label: m.name, stroke: COLORS[m.name], width: 1.5 });
    data.push(m.error.map((x, i) => (x > 0 && !(m.diverged_at !== null && t[i] > m.diverged_at) ? x : null)));
  }
  const el = document.createElement("div");
  el.className = "plot";
  el.id = "plot-errors";
  $("plots").appendChild(el);
  charts.push(new uPlot({ title: "Angle error of each model against the nonlinear body (rad, log scale)", width: width(),
                          height: 300, cursor, series: s, scales: { x: { time: false }, y: { distr: 3, log: 10 } },
                          axes: [{ label: "t (s)" },
                                 // Decades only, as 1e-9: uPlot's own labels round tiny values to 0.
                                 { label: "max(|d theta|, |d phi|) (rad)", size: 70,
                                   splits: (u, ax, min, max) => {
                                     const out = [];
                                     for (let e = Math.ceil(Math.log10(min) - 1e-9); e <= Math.floor(Math.log10(max) + 1e-9); e++) out.push(10 ** e);
                                     return out;
                                   },
                                   values: (u, splits) => splits.map((v) => {
                                     const e = Math.round(Math.log10(v));
                                     return Math.abs(v / 10 ** e - 1) < 1e-6 ? `1e${e}` : "";
                                   }) }] }, data, el));
  window.addEventListener("resize", () => charts.forEach((c) => c.setSize({ width: width(), height: 300 })));
  // A click (not a drag, which zooms) shows that moment in the 3D view.
  for (const c of charts)
    c.over.addEventListener("click", () => {
      if (c.select.width > 2 || c.cursor.left === undefined || c.cursor.left < 0 || !window.heavytopView) return;
      window.heavytopView.seek(c.posToVal(c.cursor.left, "x"));
    });
}

// ---- the stability explorer: the map's grid and the diagram's nonlinear runs, clickable ------------
function buildExplorer(D) {
  const canvas = $("explorer"), info = $("explorer-info"), M = D.map;
  const nx = M.x.count, ny = M.y.count;
  const pad = { l: 70, r: 20, t: 20, b: 50 };
  const W = canvas.width, H = canvas.height, pw = W - pad.l - pad.r, ph = H - pad.t - pad.b;
  const X = (v) => pad.l + ((v - M.x.start) / (M.x.stop - M.x.start)) * pw;
  const Y = (v) => pad.t + ph - ((v - M.y.start) / (M.y.stop - M.y.start)) * ph;
  const ctx = canvas.getContext("2d");
  const palette = ["#d9d9d9", "#d62728", "#1f77b4", "#2ca02c"];  // as the static map
  const code = (i) => parseInt(M.verdicts[i], 16);
  const cw = pw / (nx - 1), chh = ph / (ny - 1);
  for (let i = 0; i < nx; i++)
    for (let j = 0; j < ny; j++) {
      const c = code(i * ny + j);
      ctx.fillStyle = palette[(c & 1) + ((c >> 2) & 1) * 2];
      ctx.fillRect(X(M.x.start + (i * (M.x.stop - M.x.start)) / (nx - 1)) - cw / 2, Y(M.y.start + (j * (M.y.stop - M.y.start)) / (ny - 1)) - chh / 2, cw + 1, chh + 1);
    }
  ctx.save();
  ctx.beginPath();
  ctx.rect(pad.l, pad.t, pw, ph);
  ctx.clip();
  for (const p of D.diagram.points) {
    const x = X(p[0]), y = Y(p[1]);
    ctx.lineWidth = 2;
    ctx.strokeStyle = p[2] ? "#ffffff" : "#000000";
    ctx.beginPath();
    if (p[2]) ctx.arc(x, y, 5, 0, 2 * Math.PI);
    else { ctx.moveTo(x - 5, y - 5); ctx.lineTo(x + 5, y + 5); ctx.moveTo(x + 5, y - 5); ctx.lineTo(x - 5, y + 5); }
    ctx.stroke();
  }
  const bx = X(D.body_point[0]), by = Y(D.body_point[1]);
  ctx.strokeStyle = "#000";
  ctx.lineWidth = 3;
  ctx.beginPath();
  ctx.moveTo(bx - 10, by); ctx.lineTo(bx + 10, by); ctx.moveTo(bx, by - 10); ctx.lineTo(bx, by + 10);
  ctx.stroke();
  ctx.restore();
  ctx.fillStyle = "#222";
  ctx.font = "14px DejaVu Sans, Arial, sans-serif";
  ctx.textAlign = "center";
  for (let k = 0; k <= 5; k++) {
    const v = M.x.start + (k * (M.x.stop - M.x.start)) / 5;
    ctx.fillText(fmt(v, 3), X(v), H - pad.b + 18);
  }
  ctx.fillText(M.x.label, pad.l + pw / 2, H - 10);
  ctx.textAlign = "right";
  for (let k = 0; k <= 5; k++) {
    const v = M.y.start + (k * (M.y.stop - M.y.start)) / 5;
    ctx.fillText(fmt(v, 3), pad.l - 6, Y(v) + 5);
  }
  ctx.save();
  ctx.translate(16, pad.t + ph / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = "center";
  ctx.fillText(M.y.label, 0, 0);
  ctx.restore();

  const word = (s) => `<b class="${s ? "ok" : "bad"}">${s ? "stable" : "unstable"}</b>`;
  canvas.addEventListener("click", (e) => {
    const r = canvas.getBoundingClientRect();
    const px = ((e.clientX - r.left) * W) / r.width, py = ((e.clientY - r.top) * H) / r.height;
    const fx = (px - pad.l) / pw, fy = (pad.t + ph - py) / ph;
    if (fx < -0.01 || fx > 1.01 || fy < -0.01 || fy > 1.01) return;
    const i = Math.max(0, Math.min(nx - 1, Math.round(fx * (nx - 1)))), j = Math.max(0, Math.min(ny - 1, Math.round(fy * (ny - 1))));
    const xv = M.x.start + (i * (M.x.stop - M.x.start)) / (nx - 1), yv = M.y.start + (j * (M.y.stop - M.y.start)) / (ny - 1);
    const c = code(i * ny + j), cert = D.certificates[parseInt(M.certificates[i * ny + j], 10)];
    let html = `<p><b>${M.x.key} = ${fmt(xv, 4)}, spin = ${fmt(yv, 4)} rad/s</b> (the grid point nearest the click)` +
      `<br>first-order (4): ${word(c & 1)}; body-fixed (5): ${word(c & 2)}; linearized (exact): ${word(c & 4)}` +
      `<br>Lyapunov (the real body): ${c & 8 ? '<b class="ok">proven stable</b>' : "<b>not proven stable</b>"} ` +
      `(certificate <code>${cert}</code>)</p>`;
    // The nearest of the nonlinear runs, if the click is on one.
    let best = null, bd = 1e9;
    for (const p of D.diagram.points) {
      const d = Math.hypot(X(p[0]) - px, Y(p[1]) - py);
      if (d < bd) { bd = d; best = p; }
    }
    if (best && bd < 12)
      html += `<p>Nonlinear run at ${M.x.key} = ${fmt(best[0], 4)}, spin = ${fmt(best[1], 4)} rad/s, started ` +
        `${D.diagram.start_tilt} rad off vertical: <b class="${best[2] ? "ok" : "bad"}">${best[2] ? D.diagram.up_word : D.diagram.down_word}</b> ` +
        `(tilt ${best[2] ? "stayed within" : "passed"} ${D.diagram.max_tilt} rad within ${fmt(D.diagram.horizon, 3)} s).</p>`;
    if (Math.abs(X(D.body_point[0]) - px) < 12 && Math.abs(Y(D.body_point[1]) - py) < 12)
      html += `<p>This is the body of this report: its motion is the one in the 3D view and the plots above.</p>`;
    else if (D.explorer) {
      // The explorer beside the report computes it: this point's body and spin, the report's start.
      const body = { ...D.body };
      if (M.x.key === "B/A") body.B = xv * D.body.A;
      const config = { body, motion: { spin: yv, ...D.start } };
      html += `<p>The report computed no motion for this point: <a id='explorer-point' href='explore.html#config=` +
        `${encodeURIComponent(JSON.stringify(config))}'>see it in the explorer</a> (computed there, in the page), or run ` +
        `<code>heavytop simulate --model nonlinear ${D.cli_body} ${M.x.key === "B/A" ? `--B ${fmt(xv * D.body.A, 6)}` : ""} ` +
        `--spin ${fmt(yv, 6)} ${D.cli_start}</code></p>`;
    } else
      html += `<p>The report computed no motion for this point; to see it: <code>heavytop simulate --model nonlinear ` +
        `${D.cli_body} ${M.x.key === "B/A" ? `--B ${fmt(xv * D.body.A, 6)}` : ""} --spin ${fmt(yv, 6)} ${D.cli_start}</code></p>`;
    info.innerHTML = html;
  });
}

function start() {
  const D = window.HEAVYTOP_REPORT;
  // On a table (D.table) the page has the 3D view only; its figures are static.
  const parts = D.table ? [["3D view", buildView]] : [["3D view", buildView], ["plots", buildPlots], ["stability explorer", buildExplorer]];
  for (const [name, build] of parts) {
    try {
      build(D);
    } catch (err) {
      // Say so on the page; the static figures below stay.
      const p = document.createElement("p");
      p.className = "note";
      p.textContent = `The ${name} could not be drawn in this browser (${err.message}); the static figures below show the same.`;
      $(name === "3D view" ? "interactive" : "interactive-plots").prepend(p);
      console.error(err);
    }
  }
}
window.heavytopView3D = Object.freeze({ show: buildView });
if (window.HEAVYTOP_REPORT) {
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", start);
  else start();
}
