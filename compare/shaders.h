/* refray comparator: the GLSL 4.50 shaders of raster.c. Shared by every context back end.
 *
 * Data (std430 storage buffers, filled by raster.c):
 *   0 materials: 5 vec4 each: ka, kd, ks, emission, (shininess, 0, 0, 0)
 *   1 lights:    4 dvec4 each: (position, kind), (direction, falloff), (intensity, 0),
 *                (spot exponent, cos(spot cutoff), 0, 0); kind 0 point, 1 directional,
 *                2 spot; falloff 0 inverse square, 1 none
 *   2 triangles: 12 doubles each: p0, p1, p2, unit geometric normal (the tracer's: the fan
 *                triangle's (p1-p0)x(p2-p0), Newell's for a non-convex polygon)
 *   3 triangles: 9 floats each: vertex normals (unit)
 *   4 triangles: 4 ints each: material, flags (1 two-sided, 2 inside), smooth (1: interpolate
 *                the vertex normals), 0
 *   5 quadrics:  40 doubles each: [0, 8) in object space: sphere (centre, r); cone (base, rb,
 *                apex, ra); plane (n, offset); [8, 14) the world box lo, hi; [14, 26) to_object
 *                (rows 0-2 of M^-1); [26, 35) the normal matrix (M^-1)^T (row-major)
 *   6 quadrics:  4 ints each: type (0 sphere, 1 cone, 2 plane), flags, material, bits (1 full
 *                screen, 2 instanced: intersect in object space as the tracer, tracer.c hit_instance)
 *
 * Every fragment shader casts the tracer's primary ray through its pixel centre (in double) and
 * shades the point where that ray meets the primitive: the rasterizer decides coverage and
 * visibility (z-buffer), the ray gives the shading point, so shading matches the tracer to float
 * rounding wherever both see the same surface. Depth: reversed Z, depth = near / z_eye with a
 * 32-bit float buffer (glClipControl ZERO_TO_ONE), relative precision ~1e-7 at every distance. */
#ifndef RF_SHADERS_H
#define RF_SHADERS_H

static const char rf_glsl_common[] =
    "#version 450 core\n"
    "layout(std430, binding = 0) readonly buffer Mats { vec4 mats[]; };\n"
    "layout(std430, binding = 1) readonly buffer Lights { dvec4 lights[]; };\n"
    "layout(std430, binding = 2) readonly buffer TriD { double trid[]; };\n"
    "layout(std430, binding = 3) readonly buffer TriN { float trin[]; };\n"
    "layout(std430, binding = 4) readonly buffer TriI { int trii[]; };\n"
    "layout(std430, binding = 5) readonly buffer QuaD { double quad[]; };\n"
    "layout(std430, binding = 6) readonly buffer QuaI { int quai[]; };\n"
    "uniform dvec3 u_eye, u_u, u_v, u_w;\n"
    "uniform dvec4 u_win;\n"          /* l r b t */
    "uniform double u_d, u_near, u_hither;\n"
    "uniform vec2 u_size;\n"
    "uniform int u_light_count, u_mode;\n" /* mode 0 phong, 1 gouraud, 2 flat */
    "uniform vec3 u_ambient;\n"
    "const int TWO_SIDED = 1, INSIDE = 2;\n"
    /* the tracer's primary ray direction (camera.c rf_camera_ray) for window position frag */
    "dvec3 ray_dir(vec2 frag) {\n"
    "  double px = double(frag.x), py = double(u_size.y) - double(frag.y);\n"
    "  double l1 = u_win.x + (u_win.y - u_win.x) * px / double(u_size.x);\n"
    "  double l2 = u_win.w - (u_win.w - u_win.z) * py / double(u_size.y);\n"
    "  return normalize(u_u * l1 + u_v * l2 + u_w * (-u_d));\n"
    "}\n"
    /* eye space with reversed Z: clip z = near, clip w = -z_eye */
    "vec4 project(dvec3 p) {\n"
    "  dvec3 e = p - u_eye;\n"
    "  double x = dot(e, u_u), y = dot(e, u_v), wc = -dot(e, u_w);\n"
    "  double xc = 2.0 * u_d * x / (u_win.y - u_win.x) - (u_win.y + u_win.x) / (u_win.y - u_win.x) * wc;\n"
    "  double yc = 2.0 * u_d * y / (u_win.w - u_win.z) - (u_win.w + u_win.z) / (u_win.w - u_win.z) * wc;\n"
    "  return vec4(float(xc), float(yc), float(u_near), float(wc));\n"
    "}\n"
    /* tracer.c trace() with local_only: emission + ka ambient + per light diffuse + specular;
     * ng = geometric normal facing the viewer (decides whether a light is behind the surface),
     * ns = shading normal, V = unit vector to the viewer */
    "vec3 shade(int m, dvec3 p, dvec3 ng, dvec3 ns, dvec3 V) {\n"
    "  vec3 ka = mats[5 * m].rgb, kd = mats[5 * m + 1].rgb, ks = mats[5 * m + 2].rgb;\n"
    "  float shin = mats[5 * m + 4].x;\n"
    "  vec3 c = mats[5 * m + 3].rgb + ka * u_ambient;\n"
    "  for (int i = 0; i < u_light_count; i++) {\n"
    "    dvec4 a = lights[4 * i], b = lights[4 * i + 1], s = lights[4 * i + 3];\n"
    "    dvec3 I = lights[4 * i + 2].xyz, L;\n"
    "    int kind = int(a.w);\n"
    "    if (kind == 1) {\n"
    "      L = -b.xyz;\n"
    "    } else {\n"
    "      dvec3 to = a.xyz - p;\n"
    "      double dist = length(to);\n"
    "      if (!(dist > 0.0)) continue;\n"
    "      L = to / dist;\n"
    "      if (b.w == 0.0) I = I / (dist * dist);\n"
    "      if (kind == 2) {\n"
    /* theta <= cutoff as cos(theta) >= cos(cutoff), in double: GLSL has no double atan, and a
     * float angle would move the spot's edge by a pixel here and there */
    "        double ct = dot(b.xyz, -L);\n"
    "        I = I * (ct >= s.y ? double(pow(float(ct), float(s.x))) : 0.0);\n"
    "      }\n"
    "    }\n"
    "    if (max(I.r, max(I.g, I.b)) <= 0.0 || dot(ng, L) <= 0.0) continue;\n"
    "    double nl = dot(ns, L);\n"
    "    double rv = dot(ns * (2.0 * nl) - L, V);\n"
    "    double diff = nl > 0.0 ? nl : 0.0;\n"
    "    double spec = nl > 0.0 && rv > 0.0 ? double(pow(float(rv), shin)) : 0.0;\n"
    "    c += vec3(dvec3(kd) * I * diff + dvec3(ks) * I * spec);\n"
    "  }\n"
    "  return c;\n"
    "}\n"
    "dvec3 tri_p(int t, int k) { int o = 12 * t + 3 * k; return dvec3(trid[o], trid[o + 1], trid[o + 2]); }\n"
    "dvec3 tri_vn(int t, int k) { int o = 9 * t + 3 * k; return dvec3(trin[o], trin[o + 1], trin[o + 2]); }\n";

/* triangles: gl_VertexID / 3 is the triangle; Gouraud and flat modes light the vertices here */
static const char rf_glsl_tri_vs[] =
    "out vec3 v_color;\n"
    "flat out vec3 v_flat;\n"
    "void main() {\n"
    "  int t = gl_VertexID / 3, k = gl_VertexID % 3;\n"
    "  dvec3 p = tri_p(t, k), n = tri_p(t, 3);\n"
    "  gl_Position = project(p);\n"
    "  v_color = vec3(0.0); v_flat = vec3(0.0);\n"
    "  int m = trii[4 * t];\n"
    "  if (u_mode == 1) {\n"
    "    dvec3 V = normalize(u_eye - p), ng = dot(V, n) > 0.0 ? n : -n, ns = ng;\n"
    "    if (trii[4 * t + 2] != 0) { ns = tri_vn(t, k); if (dot(ns, ng) < 0.0) ns = -ns; }\n"
    "    v_color = shade(m, p, ng, ns, V);\n"
    "  } else if (u_mode == 2) {\n"
    "    dvec3 c = (tri_p(t, 0) + tri_p(t, 1) + tri_p(t, 2)) / 3.0;\n"
    "    dvec3 V = normalize(u_eye - c), ng = dot(V, n) > 0.0 ? n : -n;\n"
    "    v_flat = shade(m, c, ng, ng, V);\n"
    "  }\n"
    "}\n";

static const char rf_glsl_tri_fs[] =
    "in vec3 v_color;\n"
    "flat in vec3 v_flat;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out float o_depth;\n"
    "void main() {\n"
    "  int t = gl_PrimitiveID;\n"
    "  dvec3 d = ray_dir(gl_FragCoord.xy), p0 = tri_p(t, 0), n = tri_p(t, 3);\n"
    /* Moller-Trumbore for the hit distance and barycentric coordinates; coverage was decided by
     * the rasterizer, so the coordinates are used as they are, even a hair outside [0, 1] */
    "  dvec3 e1 = tri_p(t, 1) - p0, e2 = tri_p(t, 2) - p0, pv = cross(d, e2);\n"
    "  double det = dot(e1, pv), b1 = 1.0 / 3.0, b2 = 1.0 / 3.0, dist;\n"
    "  if (det != 0.0) {\n"
    "    dvec3 tv = u_eye - p0, qv = cross(tv, e1);\n"
    "    b1 = dot(tv, pv) / det; b2 = dot(d, qv) / det; dist = dot(e2, qv) / det;\n"
    "  } else {\n"
    "    dist = u_near / double(gl_FragCoord.z) / dot(d, -u_w);\n"
    "  }\n"
    "  if (dist < u_hither / dot(d, -u_w)) discard;\n"
    "  int flags = trii[4 * t + 1];\n"
    "  bool front = dot(d, n) < 0.0;\n"
    "  if ((flags & TWO_SIDED) == 0 && front == ((flags & INSIDE) != 0)) discard;\n"
    "  dvec3 ng = front ? n : -n, ns = ng, p = u_eye + d * dist;\n"
    "  if (trii[4 * t + 2] != 0) {\n"
    "    dvec3 s = tri_vn(t, 0) * (1.0 - b1 - b2) + tri_vn(t, 1) * b1 + tri_vn(t, 2) * b2;\n"
    "    double len = length(s);\n"
    "    if (len > 0.0) { ns = s / len; if (dot(ns, ng) < 0.0) ns = -ns; }\n"
    "  }\n"
    "  vec3 c = u_mode == 0 ? shade(trii[4 * t], p, ng, ns, -d) : (u_mode == 1 ? v_color : v_flat);\n"
    "  o_color = vec4(c, 1.0);\n"
    "  o_depth = float(dist * dot(d, -u_w));\n"
    "}\n";

/* quadric impostors: one instance per sphere/cone/plane, drawn as its bounding box (36
 * vertices), or as one full-screen triangle when the eye is near or inside the box (a box
 * clipped by the near plane would lose fragments) and for infinite planes */
static const char rf_glsl_quad_vs[] =
    "flat out int v_q;\n"
    "const int cube[36] = int[36](0,2,6, 0,6,4, 1,5,7, 1,7,3, 0,4,5, 0,5,1,\n"
    "                             2,3,7, 2,7,6, 0,1,3, 0,3,2, 4,6,7, 4,7,5);\n"
    "void main() {\n"
    "  int q = gl_InstanceID;\n"
    "  v_q = q;\n"
    "  if ((quai[4 * q + 3] & 1) != 0) {\n"
    "    vec2 c = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
    "    gl_Position = gl_VertexID < 3 ? vec4(c, 0.5, 1.0) : vec4(-1.0, -1.0, 0.5, 1.0);\n"
    "    return;\n"
    "  }\n"
    "  int o = 40 * q;\n"
    "  dvec3 lo = dvec3(quad[o + 8], quad[o + 9], quad[o + 10]), hi = dvec3(quad[o + 11], quad[o + 12], quad[o + 13]);\n"
    /* grow the box a little so that rounding never trims the silhouette */
    "  dvec3 pad = (hi - lo) * 1e-3 + 1e-6 * (abs(lo) + abs(hi)) + 1e-9;\n"
    "  lo -= pad; hi += pad;\n"
    "  int c = cube[gl_VertexID];\n"
    "  gl_Position = project(dvec3((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y,\n"
    "                              (c & 4) != 0 ? hi.z : lo.z));\n"
    "}\n";

static const char rf_glsl_quad_fs[] =
    "flat in int v_q;\n"
    "layout(location = 0) out vec4 o_color;\n"
    "layout(location = 1) out float o_depth;\n"
    /* intersect.c solve_quadratic: a t^2 + 2 bh t + c = 0, dq = bh^2 - a c */
    "bool solve(double a, double bh, double c, double dq, out double t0, out double t1) {\n"
    "  t0 = t1 = 0.0;\n"
    "  if (!(dq >= 0.0)) return false;\n"
    "  double q = -(bh + (bh < 0.0 ? -sqrt(dq) : sqrt(dq)));\n"
    "  if (q == 0.0) { return a != 0.0; }\n"
    "  if (a == 0.0) { t0 = t1 = c / q; return true; }\n"
    "  if (dq == 0.0) { t0 = t1 = q / a; return true; }\n"
    "  double r1 = q / a, r2 = c / q;\n"
    "  t0 = min(r1, r2); t1 = max(r1, r2);\n"
    "  return true;\n"
    "}\n"
    "dvec3 xf(int o, dvec3 x, double w) {\n"
    "  return dvec3(dot(dvec3(quad[o], quad[o + 1], quad[o + 2]), x) + w * quad[o + 3],\n"
    "               dot(dvec3(quad[o + 4], quad[o + 5], quad[o + 6]), x) + w * quad[o + 7],\n"
    "               dot(dvec3(quad[o + 8], quad[o + 9], quad[o + 10]), x) + w * quad[o + 11]);\n"
    "}\n"
    /* one-sided surfaces: seen from the front (outside), or only from the inside (INSIDE) */
    "bool visible(int flags, dvec3 d, dvec3 n) {\n"
    "  return (flags & TWO_SIDED) != 0 || (dot(d, n) < 0.0) != ((flags & INSIDE) != 0);\n"
    "}\n"
    "void main() {\n"
    "  int q = v_q, type = quai[4 * q], flags = quai[4 * q + 1], o = 40 * q;\n"
    "  bool inst = (quai[4 * q + 3] & 2) != 0;\n"
    /* d, e: the ray in the primitive's space (object space inside an instance, the direction not
     * normalised, so t is the world t); dw: the world direction */
    "  dvec3 dw = ray_dir(gl_FragCoord.xy), d = dw, e = u_eye, n;\n"
    "  if (inst) { e = xf(o + 14, u_eye, 1.0); d = xf(o + 14, dw, 0.0); }\n"
    "  dvec3 a = dvec3(quad[o], quad[o + 1], quad[o + 2]);\n"
    "  double t = -1.0, tmin = u_hither / dot(dw, -u_w);\n"
    "  if (type == 0) {\n"
    /* intersect.c RF_SPHERE_STABLE: the discriminant from the perpendicular distance */
    "    double r = quad[o + 3];\n"
    "    dvec3 f = e - a;\n"
    "    double aa = dot(d, d), bh = dot(f, d);\n"
    "    dvec3 v = f - d * (bh / aa);\n"
    "    double lv = length(v), t0, t1;\n"
    "    if (!solve(aa, bh, dot(f, f) - r * r, aa * (r - lv) * (r + lv), t0, t1)) discard;\n"
    /* the nearer root in range whose side is visible, else the farther (tracer.c hit_item) */
    "    for (int i = 0; i < 2 && t < 0.0; i++) {\n"
    "      double ti = i == 0 ? t0 : t1;\n"
    "      dvec3 ni = (f + d * ti) / r;\n"
    "      if (ti >= tmin && visible(flags, d, ni)) { t = ti; n = ni; }\n"
    "    }\n"
    "    if (t < 0.0) discard;\n"
    "  } else if (type == 1) {\n"
    /* intersect.c rf_intersect_cone: the nearest root in range whose axial position lies on
     * the frustum */
    "    dvec3 apex = dvec3(quad[o + 4], quad[o + 5], quad[o + 6]), axis = apex - a;\n"
    "    double rb = quad[o + 3], ra = quad[o + 7], h = length(axis);\n"
    "    dvec3 k = axis / h;\n"
    "    double m = (ra - rb) / h;\n"
    "    dvec3 oo = e - a;\n"
    "    double dz = dot(d, k), oz = dot(oo, k);\n"
    "    dvec3 dp = d - k * dz, op = oo - k * oz;\n"
    "    double r0 = rb + m * oz;\n"
    "    double qa = dot(dp, dp) - m * m * dz * dz, bh = dot(op, dp) - m * dz * r0;\n"
    "    double qc = dot(op, op) - r0 * r0, ts[2];\n"
    "    if (!solve(qa, bh, qc, bh * bh - qa * qc, ts[0], ts[1])) discard;\n"
    "    for (int i = 0; i < 2 && t < 0.0; i++) {\n"
    "      if (!(ts[i] >= tmin)) continue;\n"
    "      dvec3 qq = e + d * ts[i] - a;\n"
    "      double z = dot(qq, k);\n"
    "      if (!(z >= 0.0 && z <= h)) continue;\n"
    "      dvec3 radial = qq - k * z;\n"
    "      double rl = length(radial);\n"
    "      dvec3 ni = normalize(rl > 0.0 ? radial / rl - k * m : k * (m > 0.0 ? -1.0 : 1.0));\n"
    "      if (!visible(flags, d, ni)) continue;\n"
    "      n = ni;\n"
    "      t = ts[i];\n"
    "    }\n"
    "    if (t < 0.0) discard;\n"
    "  } else {\n"
    "    n = a;\n"
    "    double den = dot(d, n);\n"
    "    if (den == 0.0) discard;\n"
    "    t = (quad[o + 3] - dot(e, n)) / den;\n"
    "    if (!(t >= tmin)) discard;\n"
    "  }\n"
    "  if (!visible(flags, d, n)) discard;\n"
    "  if (inst) {\n"
    "    dvec3 m0 = dvec3(quad[o + 26], quad[o + 27], quad[o + 28]), m1 = dvec3(quad[o + 29], quad[o + 30], quad[o + 31]);\n"
    "    n = normalize(dvec3(dot(m0, n), dot(m1, n), dot(dvec3(quad[o + 32], quad[o + 33], quad[o + 34]), n)));\n"
    "  }\n"
    "  dvec3 ng = dot(dw, n) < 0.0 ? n : -n;\n"
    "  double z = t * dot(dw, -u_w);\n"
    "  o_color = vec4(shade(quai[4 * q + 2], u_eye + dw * t, ng, ng, -dw), 1.0);\n"
    "  o_depth = float(z);\n"
    "  gl_FragDepth = float(u_near / z);\n"
    "}\n";

#endif
