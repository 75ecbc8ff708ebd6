/* Tests of issue 6: the OBJ and MTL readers, vertex normals (§3.6.3), the scene graph of
 * refray's format (§4.8) and instancing with transformed normals (§4.9). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "refray/render.h"
#include "refray/scene.h"
#include "refray/scene_io.h"
#include "refray/transform.h"
#include "rf_test.h"
#include "../fuzz/fuzz_common.h" /* rf_fuzz_same_scene */
#include "../src/scene/reader.h"

/* A scene a reader accepted passes the whole check too (the readers check each primitive as
 * they add it and leave that part of rf_scene_validate out). */
static RfStatus validated(RfStatus st, const RfScene *s)
{
    char err[512];
    if (st == RF_OK)
        RF_CHECK_EQ_INT(rf_scene_validate(s, "t", err, sizeof err), RF_OK);
    return st;
}

static RfStatus read_obj(const char *text, RfScene *s, char *err, size_t errsz)
{
    return validated(rf_scene_read_obj("t.obj", text, strlen(text), NULL, s, err, errsz), s);
}

static RfStatus read_rf(const char *text, RfScene *s, char *err, size_t errsz)
{
    return validated(rf_scene_read_rf("t.rf", text, strlen(text), s, err, errsz), s);
}

/* A fresh temporary folder with the given files (name, text pairs, NULL-terminated); dir gets
 * its path. */
static int write_files(char *dir, size_t n, const char *const *files)
{
    char tmpl[] = "/tmp/rf-mesh-test-XXXXXX";
    if (!mkdtemp(tmpl))
        return 0;
    snprintf(dir, n, "%s", tmpl);
    for (; files[0]; files += 2) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, files[0]);
        FILE *f = fopen(path, "wb");
        if (!f)
            return 0;
        fputs(files[1], f);
        fclose(f);
    }
    return 1;
}

static void remove_files(const char *dir, const char *const *files)
{
    for (; files[0]; files += 2) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, files[0]);
        remove(path);
    }
    rmdir(dir);
}

/* ---- OBJ: index forms, polygons, smoothing ------------------------------------------------- */

/* Every index form on one quad split in two triangles: v, v/vt, v//vn, v/vt/vn, and the same
 * with negative indices; they must give the same vertices. */
static void test_obj_index_forms(void)
{
    static const char *const forms[] = {
        "f 1 2 3\nf 1 3 4\n",
        "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
        "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n",
        "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n",
        "f -4 -3 -2\nf -4 -2 -1\n",
        "f -4/-4/-1 -3/-3/-1 -2/-2/-1\nf -4/-4/-1 -2/-2/-1 -1/-1/-1\n",
        "f -4//-1 -3//-1 -2//-1\nf -4//-1 -2//-1 -1//-1\n",
        "f -4/-4 -3/-3 -2/-2\nf -4/-4 -2/-2 -1/-1\n",
    };
    const char *head = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 3\n";
    for (size_t k = 0; k < sizeof forms / sizeof forms[0]; k++) {
        char text[512], err[256];
        RfScene s;
        snprintf(text, sizeof text, "%s%s", head, forms[k]);
        RF_CHECK_EQ_INT(read_obj(text, &s, err, sizeof err), RF_OK);
        RF_CHECK_EQ_INT(s.prim_count, 2);
        if (s.prim_count != 2)
            continue;
        const RfPrimitive *p = &s.prims[1];
        RF_CHECK_EQ_INT(p->type, RF_PRIM_TRIANGLE);
        RfVec3 v2 = s.vertices[p->u.poly.first + 1]; /* corner 3 of the quad */
        RF_CHECK(v2.x == 2 && v2.y == 1 && v2.z == 0);
        RF_CHECK(p->flags & RF_PRIM_VERTEX_NORMALS);
        /* a given vn is used as given (normalised); without vn the flat quad's computed
         * normals are its face normal: +z either way */
        RfVec3 n = s.normals[p->u.poly.nfirst + 2];
        RF_CHECK(n.x == 0 && n.y == 0 && n.z == 1);
        rf_scene_free(&s);
    }
}

static void test_obj_polygons(void)
{
    char err[256];
    RfScene s;
    /* a convex pentagon stays one polygon (the tracer fans it); a concave planar L is kept as
     * one polygon marked non-convex; a zero-area face is dropped */
    const char *text = "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\n"
                       "f 1 2 3 4 5\n"
                       "v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n"
                       "f 6 7 8 9 10 11\n"
                       "v 5 5 5\nv 6 6 6\nv 7 7 7\nf -1 -2 -3\n";
    RF_CHECK_EQ_INT(read_obj(text, &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(s.prim_count, 2);
    if (s.prim_count == 2) {
        RF_CHECK_EQ_INT(s.prims[0].type, RF_PRIM_POLYGON);
        RF_CHECK_EQ_INT(s.prims[0].u.poly.count, 5);
        RF_CHECK(!(s.prims[0].flags & RF_PRIM_NONCONVEX));
        RF_CHECK(s.prims[1].flags & RF_PRIM_NONCONVEX);
    }
    RfTriangleCount tc = rf_scene_triangle_count(&s);
    RF_CHECK_EQ_INT(tc.stored, 3 + 1);
    rf_scene_free(&s);
}

/* §3.6.3: a vertex shared by a large face (normal +z, area 8) and a small one (normal
 * (1,0,1)/sqrt2, area 2 sqrt2) gets normalise(sum of the cross products) = normalise(4,0,20),
 * not the count-weighted normalise(n1 + n2); with a crease angle under 45 degrees each face
 * keeps its own normal there; `s off` shades flat. */
static void test_obj_vertex_normals(void)
{
    const char *mesh = "v 0 0 0\nv 4 0 0\nv 0 4 0\nv -1 0 1\n"
                       "%s"
                       "f 1 2 3\nf 1 3 4\n";
    char text[256], err[256];
    RfScene s;
    snprintf(text, sizeof text, mesh, "");
    RF_CHECK_EQ_INT(read_obj(text, &s, err, sizeof err), RF_OK);
    if (s.prim_count == 2) {
        RfVec3 n = s.normals[s.prims[0].u.poly.nfirst]; /* corner 1 of the large face */
        RfVec3 area = rf_vec3_normalize(rf_vec3(4, 0, 20));
        RfVec3 count = rf_vec3_normalize(rf_vec3(1.0 / sqrt(2.0), 0, 1 + 1.0 / sqrt(2.0)));
        RF_CHECK_NEAR(n.x, area.x, 1e-15, 1e-15);
        RF_CHECK_NEAR(n.y, area.y, 0, 0);
        RF_CHECK_NEAR(n.z, area.z, 1e-15, 1e-15);
        /* the two weightings differ by about 11 degrees here */
        RF_CHECK(acos(rf_vec3_dot(area, count)) > 0.19);
        RF_CHECK(rf_vec3_dot(n, s.normals[s.prims[1].u.poly.nfirst]) > 1 - 1e-15); /* shared */
        /* corner 2 of the large face (4 0 0) touches only that face */
        RfVec3 n2 = s.normals[s.prims[0].u.poly.nfirst + 1];
        RF_CHECK(n2.x == 0 && n2.y == 0 && n2.z == 1);
    }
    rf_scene_free(&s);

    RfLoadOptions opt = rf_load_options_default();
    opt.crease_angle = 30.0; /* the faces meet at 45 degrees: a crease */
    RF_CHECK_EQ_INT(rf_scene_read_obj("t.obj", text, strlen(text), &opt, &s, err, sizeof err), RF_OK);
    if (s.prim_count == 2) {
        RfVec3 a = s.normals[s.prims[0].u.poly.nfirst], b = s.normals[s.prims[1].u.poly.nfirst];
        RF_CHECK(a.x == 0 && a.z == 1);
        RF_CHECK_NEAR(b.x, 1 / sqrt(2.0), 1e-15, 0);
        RF_CHECK_NEAR(b.z, 1 / sqrt(2.0), 1e-15, 0);
    }
    rf_scene_free(&s);

    snprintf(text, sizeof text, mesh, "s off\n");
    RF_CHECK_EQ_INT(read_obj(text, &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(s.normal_count, 0);
    for (size_t i = 0; i < s.prim_count; i++)
        RF_CHECK(!(s.prims[i].flags & RF_PRIM_VERTEX_NORMALS));
    rf_scene_free(&s);

    /* separate smoothing groups do not share normals */
    snprintf(text, sizeof text, "v 0 0 0\nv 4 0 0\nv 0 4 0\nv -1 0 1\ns 1\nf 1 2 3\ns 2\nf 1 3 4\n");
    RF_CHECK_EQ_INT(read_obj(text, &s, err, sizeof err), RF_OK);
    if (s.prim_count == 2)
        RF_CHECK(s.normals[s.prims[0].u.poly.nfirst].z == 1);
    rf_scene_free(&s);
}

/* ---- MTL ------------------------------------------------------------------------------------ */

static void test_mtl_illum(void)
{
    const char *text = "newmtl m0\nKd 0.5 0.25 0.125\nKe 0.1\nillum 0\n"
                       "newmtl m1\nKa 0.2\nKd 0.5\nKs 0.7\nillum 1\n"
                       "newmtl m2\nKd 0.5\nKs 0.7\nNs 30\n" /* illum 2 is the default */
                       "newmtl m3\nKs 0.6 0.5 0.4\nillum 3\n"
                       "newmtl m4\nKs 0.3\nd 0.25\nNi 1.5\nillum 4\n"
                       "newmtl m5\nKs 0.8\nillum 5\n"
                       "newmtl m6\nKs 0.25\nTf 1 0.5 0\nNi 1.33\nillum 6\n"
                       "newmtl m7\nKs 0.5\nTf 0.8\nNi 1.5\nillum 7\n"
                       "newmtl m8\nKs 0.5\nillum 8\nmap_Kd x.png\nTr 0.5\n";
    char err[256];
    RfScene s;
    rf_scene_init(&s);
    RF_CHECK_EQ_INT(rf_scene_read_mtl("t.mtl", text, strlen(text), &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(s.material_count, 9);
    if (s.material_count != 9) {
        rf_scene_free(&s);
        return;
    }
    const RfMaterial *m = s.materials;
    /* 0: constant colour Kd (+ Ke), no lighting */
    RF_CHECK(m[0].emission.r == 0.6 && m[0].emission.g == 0.35 && m[0].kd.r == 0 && m[0].ks.r == 0);
    /* 1: Lambert only */
    RF_CHECK(m[1].ka.r == 0.2 && m[1].kd.r == 0.5 && m[1].ks.r == 0 && m[1].kr.r == 0);
    /* 2: + Phong highlight, no rays */
    RF_CHECK(m[2].ks.r == 0.7 && m[2].shininess == 30 && m[2].kr.r == 0 && m[2].kt.r == 0);
    /* 3: the mirror ray with weight Ks */
    RF_CHECK(m[3].kr.r == 0.6 && m[3].kr.b == 0.4 && m[3].kt.r == 0 && !(m[3].flags & RF_MAT_FRESNEL));
    /* 4: glass without bending: kt = 1 - d, ior 1 */
    RF_CHECK(m[4].kr.r == 0.3 && m[4].kt.r == 0.75 && m[4].ior == 1.0);
    /* 5: Fresnel reflection; no Ni given: 1.5 */
    RF_CHECK(m[5].kr.r == 0.8 && (m[5].flags & RF_MAT_FRESNEL) && m[5].ior == 1.5 && m[5].kt.r == 0);
    /* 6: refraction without Fresnel, kt = (1 - Ks) Tf */
    RF_CHECK(m[6].kr.r == 0.25 && m[6].kt.r == 0.75 && m[6].kt.g == 0.375 && m[6].kt.b == 0 &&
             m[6].ior == 1.33 && !(m[6].flags & RF_MAT_FRESNEL));
    /* 7: refraction with Fresnel */
    RF_CHECK(m[7].kr.r == 0.5 && m[7].kt.r == 0.4 && m[7].ior == 1.5 && (m[7].flags & RF_MAT_FRESNEL));
    /* 8: ray tracing off: as 2; maps and Tr ignored */
    RF_CHECK(m[8].ks.r == 0.5 && m[8].kr.r == 0);
    RF_CHECK_STR(m[7].name, "m7");
    rf_scene_free(&s);
}

/* ---- errors with file:line:col -------------------------------------------------------------- */

typedef struct {
    int rf; /* 1: refray format, 0: OBJ, 2: MTL */
    const char *text, *err;
} ErrCase;

static void test_mesh_errors(void)
{
    static const char cam[] = "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\n";
    static const ErrCase cases[] = {
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "t.obj:4:7: vertex index 4 out of range in '4' (3 defined so far)"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "t.obj:4:7: vertex index -4 out of range in '-4' (3 defined so far)"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "t.obj:4:3: vertex index 0 in '0': OBJ indices start at 1"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n", "t.obj:4:3: texture index 1 out of range in '1/1' (0 defined so far)"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n", "t.obj:5:13: normal index 2 out of range in '3//2' (1 defined so far)"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3\n", "t.obj:5:8: face corner '2' is v, the first corner was v//vn: one form per face"},
        {0, "v 0 0 0\nv 1 0 0\nf 1 2\n", "t.obj:3:1: a face needs at least 3 vertices, found 2"},
        {0, "v 0 0 0\nv 1 x 0\n", "t.obj:2:5: expected vertex coordinate (a number), found 'x'"},
        {0, "v 0 0\nf 1 1 1\n", "t.obj:1:6: missing number: expected vertex coordinate"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2/ 3\n", "t.obj:4:5: malformed face corner '2/' (v, v/vt, v//vn or v/vt/vn)"},
        {0, "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n", "t.obj:4:8: unknown material 'red' (not in any mtllib read so far)"},
        {0, "mtllib missing.mtl\n", "t.obj:1:8: material library 'missing.mtl': No such file or directory"},
        {0, "v 0 0 0\nfoo 1\n", "t.obj:2:1: unknown OBJ keyword 'foo'"},
        {0, "vn 0 0 1 1\n", "t.obj:1:10: too many values for 'vn'"},
        {0, "v 0 0 0\n", "t.obj:1:1: the OBJ file has no faces"},
        {2, "Kd 1 1 1\n", "t.mtl:1:1: 'Kd' before the first 'newmtl'"},
        {2, "newmtl a\nKd spectral x.rfl\n", "t.mtl:2:4: Kd: the 'spectral' form is not supported (give r g b)"},
        {2, "newmtl a\nillum 11\n", "t.mtl:2:7: illum must be an integer in [0, 10], found '11'"},
        {2, "newmtl a\nillum 10\n", "t.mtl:2:7: illum 10 (shadow matte) is not supported: refray maps 0-9"},
        {2, "newmtl a\nd 1.5\n", "t.mtl:2:3: d must be in [0, 1], found 1.5"},
        {2, "newmtl a\nNs -1\n", "t.mtl:2:4: Ns must be >= 0, found -1"},
        {1, "object a\ninstance b\nend\nobject b\ninstance a scale 2\nend\n",
         "t.rf:6:1: cycle in the scene graph: 'a' -> 'b' -> 'a' (an object cannot contain itself)"},
        {1, "object a\nsphere 0 0 0 1\ninstance a\nend\n",
         "t.rf:4:1: cycle in the scene graph: 'a' -> 'a' (an object cannot contain itself)"},
        {1, "instance nothing translate 1 2 3\n", "t.rf:2:10: unknown object 'nothing'"},
        {1, "object a\nsphere 0 0 0 1\n", "t.rf:2:1: object 'a' has no 'end'"},
        {1, "object a\nobject b\n", "t.rf:3:1: 'object' inside object 'a': blocks do not nest (close it with 'end'; place objects in objects with 'instance')"},
        {1, "end\n", "t.rf:2:1: 'end' without an 'object' or 'group'"},
        {1, "object a\nend\ngroup a\nend\n", "t.rf:4:7: object 'a' is defined twice"},
        {1, "object a\nend\ninstance a scale 1 0 1\n", "t.rf:4:12: scale factors must be non-zero"},
        {1, "object a\nend\ninstance a matrix 1 0 0 0  0 1 0 0  1 1 0 0\n", "t.rf:4:1: instance transform is singular (a zero scale?)"},
        {1, "object a\nend\ninstance a rotate w 30\n", "t.rf:4:19: rotate needs an axis x, y or z, found 'w'"},
        {1, "object a\nend\ninstance a euler abc 1 2 3\n", "t.rf:4:18: unknown Euler order 'abc' (zyx, xyz, zxz, zyz)"},
        {1, "object a\nend\ninstance a axis-angle 0 0 0 30\n", "t.rf:4:12: axis-angle: the axis has zero length"},
        {1, "object a\nend\ninstance a shear 1\n", "t.rf:4:12: unknown attribute 'shear' for 'instance'"},
        {1, "mesh missing.obj\n", "t.rf:2:6: mesh 'missing.obj': No such file or directory"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char err[512], text[1024];
        RfScene s;
        RfStatus st;
        err[0] = 0;
        if (cases[i].rf == 1) {
            snprintf(text, sizeof text, "%s%s", cam, cases[i].text);
            st = read_rf(text, &s, err, sizeof err);
        } else if (cases[i].rf == 0) {
            st = read_obj(cases[i].text, &s, err, sizeof err);
        } else {
            rf_scene_init(&s);
            st = rf_scene_read_mtl("t.mtl", cases[i].text, strlen(cases[i].text), &s, err, sizeof err);
        }
        RF_CHECK(st != RF_OK);
        RF_CHECK_STR(err, cases[i].err);
        rf_scene_free(&s);
    }
}

/* ---- the scene graph ------------------------------------------------------------------------ */

/* Transforms compose in the order written (each acts after the ones before it), and every form
 * of a rotation gives the library's matrix (§4.3). */
static void test_graph_transforms(void)
{
    const char *text = "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
                       "instance a  scale 2  rotate z 90  translate 1 0 0\n"
                       "instance a  axis-angle 0 0 1 90\n"
                       "instance a  euler zyx 10 20 30\n"
                       "instance a  matrix 1 2 3 4  0 1 0 5  0 0 2 6\n"
                       "object a\nsphere 0 0 0 1\nend\n"
                       "group g\ninstance a scale 1 2 3\ninstance a\nend\n"
                       "instance g\ninstance g translate 0 5 0\n";
    char err[256];
    RfScene s;
    RF_CHECK_EQ_INT(read_rf(text, &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(s.instance_count, 8);
    RF_CHECK_EQ_INT(s.object_count, 2);
    if (s.instance_count == 8) {
        RfVec3 y;
        rf_transform_point(s.instances[0].to_world, rf_vec3(1, 0, 0), &y);
        /* (1,0,0) -> scale (2,0,0) -> rotate z 90 (0,2,0) -> translate (1,2,0) */
        RF_CHECK_NEAR(y.x, 1, 0, 1e-15);
        RF_CHECK_NEAR(y.y, 2, 0, 1e-15);
        RF_CHECK_NEAR(y.z, 0, 0, 1e-15);
        RfMat4 rz = rf_mat4_rotate(RF_AXIS_Z, RF_PI / 2);
        RfMat3 e = rf_mat3_euler(RF_EULER_ZYX, 10 * RF_PI / 180, 20 * RF_PI / 180, 30 * RF_PI / 180);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                RF_CHECK_NEAR(s.instances[1].to_world.m[i][j], rz.m[i][j], 0, 1e-15);
                RF_CHECK(s.instances[2].to_world.m[i][j] == e.m[i][j]);
            }
        RF_CHECK(s.instances[3].to_world.m[0][1] == 2 && s.instances[3].to_world.m[1][3] == 5 &&
                 s.instances[3].to_world.m[3][3] == 1);
        /* the normal matrix is the inverse transpose of the linear part (§4.9) */
        RfMat3 n = s.instances[4].normal_to_world; /* scale 1 2 3 */
        RF_CHECK_NEAR(n.m[1][1], 0.5, 1e-15, 0);
        RF_CHECK_NEAR(n.m[2][2], 1.0 / 3.0, 1e-15, 0);
    }
    /* 4 direct placements of a, 2 of g with 2 each */
    RfTriangleCount tc = rf_scene_triangle_count(&s);
    RF_CHECK_EQ_INT(tc.instances_rendered, 4 + 2 + 2 * 2);
    RfVec3 lo, hi;
    RF_CHECK(rf_scene_bounds(&s, &lo, &hi));
    RF_CHECK_NEAR(hi.y, 5 + 2, 0, 1e-12); /* g translated by 5 holds a scaled by 2 in y */
    rf_scene_free(&s);
}

/* §4.9 under a non-uniform scale: a unit sphere placed by M = T R S is the ellipsoid
 * |S^-1 R^T (x - c)| = 1; its outward normal at x is R S^-2 R^T (x - c), normalised. Rays from
 * many directions must hit on the ellipsoid and return that normal. */
static void test_ellipsoid_normal(void)
{
    const char *text = "camera eye 0 0 10 target 0 0 0 up 0 1 0 fov 40\n"
                       "object ball\nsphere 0 0 0 1\nend\n"
                       "instance ball  scale 2 0.5 1.25  rotate z 30  translate 0.3 -0.2 0.1\n";
    char err[256];
    RfScene s;
    RfTracer *t = NULL;
    RF_CHECK_EQ_INT(read_rf(text, &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_tracer_create(&s, &t), RF_OK);
    if (!t) {
        rf_scene_free(&s);
        return;
    }
    RfMat3 r = rf_mat3_rotate(RF_AXIS_Z, RF_PI / 6);
    RfVec3 c = rf_vec3(0.3, -0.2, 0.1), sc = rf_vec3(2, 0.5, 1.25);
    RfTestRng rng = {6};
    int hits = 0;
    double worst_n = 0, worst_p = 0;
    for (int k = 0; k < 2000; k++) {
        RfVec3 o = rf_vec3(rf_test_uniform(&rng, -1, 1), rf_test_uniform(&rng, -1, 1),
                           rf_test_uniform(&rng, -1, 1));
        if (rf_vec3_length(o) < 0.1)
            continue;
        o = rf_vec3_scale(rf_vec3_normalize(o), 8.0);
        RfVec3 aim = rf_vec3_add(c, rf_vec3(rf_test_uniform(&rng, -0.8, 0.8),
                                            rf_test_uniform(&rng, -0.3, 0.3),
                                            rf_test_uniform(&rng, -0.5, 0.5)));
        RfSurfaceHit h;
        if (rf_tracer_intersect(t, &(RfRay){o, rf_vec3_sub(aim, o)}, 0, HUGE_VAL, &h) < 0)
            continue;
        hits++;
        RfVec3 local = rf_mat3_mul_vec(rf_mat3_transpose(r), rf_vec3_sub(h.point, c));
        RfVec3 q = rf_vec3(local.x / sc.x, local.y / sc.y, local.z / sc.z);
        worst_p = fmax(worst_p, fabs(rf_vec3_length(q) - 1.0));
        RfVec3 want = rf_vec3_normalize(rf_mat3_mul_vec(
            r, rf_vec3(local.x / (sc.x * sc.x), local.y / (sc.y * sc.y), local.z / (sc.z * sc.z))));
        RfVec3 got = h.front ? h.normal : rf_vec3_neg(h.normal);
        worst_n = fmax(worst_n, rf_vec3_length(rf_vec3_sub(got, want)));
        RF_CHECK(rf_vec3_length(rf_vec3_sub(h.shading_normal, h.normal)) < 1e-15);
    }
    RF_CHECK(hits > 1000);
    RF_CHECK(worst_p < 1e-12);
    RF_CHECK(worst_n < 1e-12);
    if (worst_n >= 1e-12 || worst_p >= 1e-12)
        fprintf(stderr, "ellipsoid: worst point %g, worst normal %g\n", worst_p, worst_n);
    rf_tracer_free(t);
    rf_scene_free(&s);
}

/* The same mesh instanced (rays into object space, normals back by (M^-1)^T) and flattened
 * (the vertices and normals transformed once) must render the same image. Smooth shading only
 * under similarities: under a non-uniform scale normalising the transformed vertex normals
 * before the interpolation (flat) is not the same as after it (instanced), so those instances
 * use a flat material. Per channel
 * |a - b| <= 1e-6 everywhere except pixels where rounding moves a silhouette or shadow edge
 * across the pixel centre (at most 0.2% of the pixels). */
static void test_instanced_vs_flattened(void)
{
    static const char *const files[] = {
        "m.obj",
        "v -1 0 -1\nv 1 0 -1\nv 1 0.3 1\nv -1 0.2 1\nv 0 1.2 0\nv 0 -0.8 0.2\n"
        "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 2 1 6\nf 3 2 6\nf 4 3 6\nf 1 4 6\n",
        "s.rf",
        "camera eye 0.5 3 9  target 0 0.5 0  up 0 1 0  fov 40\n"
        "resolution 96 72\nambient 0.1\nbackground 0.1 0.1 0.2\n"
        "light point -4 6 5 intensity 80\n"
        "material ground kd 0.5 ka 0.5 kr 0.2\nplane 0 -1 0  0 1 0\n"
        "material m kd 0.7 0.3 0.2 ka 0.7 0.3 0.2 ks 0.6 shininess 40\n"
        "object gem\nmesh m.obj\nend\n"
        "material f kd 0.2 0.6 0.3 ka 0.2 0.6 0.3 ks 0.6 shininess 40 flat\n"
        "object facets\nmesh m.obj\nend\n"
        "group two\ninstance facets translate -1 0 0\ninstance gem scale -1 1 1 translate 1 0 0\nend\n"
        "instance two rotate y 20\n"
        "instance facets euler zyx 10 40 -20 scale 0.7 1.4 0.9 translate 2.5 0.2 -1\n"
        "instance gem axis-angle 1 1 0 70 scale 0.8 translate -2.6 0 -0.5\n"
        "instance facets scale 1 1.5 0.6 translate 0 0 -2\n"
        "material glass kr 1 kt 1 ior 1.5 fresnel\n"
        "object ball\nsphere 0 0 0 1\nend\n"
        "instance ball scale 0.6 rotate x 30 translate 0 0.4 2\n",
        NULL};
    char dir[256], path[512], err[512];
    RF_CHECK(write_files(dir, sizeof dir, files));
    snprintf(path, sizeof path, "%s/s.rf", dir);
    RfScene s, flat;
    RfStatus st = rf_scene_load(path, NULL, &s, err, sizeof err);
    RF_CHECK_EQ_INT(st, RF_OK);
    if (st) {
        fprintf(stderr, "%s\n", err);
        remove_files(dir, files);
        return;
    }
    RF_CHECK_EQ_INT(rf_scene_flatten(&s, 0, &flat, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(flat.instance_count, 0);
    RfTriangleCount a = rf_scene_triangle_count(&s), b = rf_scene_triangle_count(&flat);
    RF_CHECK_EQ_INT(a.rendered, 8 * 5);
    RF_CHECK_EQ_INT(b.stored, a.rendered);
    RfRenderOptions opt = rf_render_options_default();
    opt.threads = 2;
    RfImage ia, ib;
    RfRenderStats sa, sb;
    RF_CHECK_EQ_INT(rf_render(&s, &opt, &ia, &sa), RF_OK);
    RF_CHECK_EQ_INT(rf_render(&flat, &opt, &ib, &sb), RF_OK);
    size_t n = (size_t)ia.width * (size_t)ia.height, off = 0;
    double worst = 0;
    for (size_t i = 0; i < n; i++) {
        double d = 0;
        for (int ch = 0; ch < 3; ch++)
            d = fmax(d, fabs((double)ia.data[3 * i + ch] - (double)ib.data[3 * i + ch]));
        if (d > 1e-6)
            off++;
        else
            worst = fmax(worst, d);
    }
    RF_CHECK(off * 500 <= n);
    if (off * 500 > n)
        fprintf(stderr, "instanced vs flattened: %zu of %zu pixels differ\n", off, n);
    RF_CHECK(worst <= 1e-6);
    rf_image_free(&ia);
    rf_image_free(&ib);
    rf_scene_free(&flat);

    /* a non-uniformly scaled sphere has no flat form */
    const char *ell = "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\nresolution 48 36\n"
                      "light point 2 3 4  intensity 20\nmaterial m kd 0.6 0.3 0.2  ks 0.5  shininess 30\n"
                      "object b\nsphere 0 0 0 1\nend\ninstance b scale 1 2 1  rotate z 30  translate 0.2 0 0\n";
    RfScene e;
    RF_CHECK_EQ_INT(read_rf(ell, &e, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_scene_flatten(&e, 0, &flat, err, sizeof err), RF_ERR_DOMAIN);
    /* ... but it stays placed for the exporters (RF_FLATTEN_PLACED_QUADRICS): one object holding the
     * sphere, one instance with the same matrix, and the same image bit for bit */
    RF_CHECK_EQ_INT(rf_scene_flatten(&e, RF_FLATTEN_PLACED_QUADRICS, &flat, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(flat.object_count, 1);
    RF_CHECK_EQ_INT(flat.instance_count, 1);
    RF_CHECK_EQ_INT(flat.prim_count, 2);
    if (flat.instance_count == 1 && e.instance_count == 1) {
        RF_CHECK(memcmp(&flat.instances[0].to_world, &e.instances[0].to_world, sizeof(RfMat4)) == 0);
        RF_CHECK_EQ_INT(rf_render(&e, &opt, &ia, &sa), RF_OK);
        RF_CHECK_EQ_INT(rf_render(&flat, &opt, &ib, &sb), RF_OK);
        RF_CHECK(ia.width == ib.width && ia.height == ib.height &&
                 memcmp(ia.data, ib.data, sizeof(float) * 3 * (size_t)ia.width * (size_t)ia.height) == 0);
        RF_CHECK(ia.data[3 * ((size_t)ia.width * (size_t)(ia.height / 2) + (size_t)(ia.width / 2))] > 0.05f); /* lit */
        rf_image_free(&ia);
        rf_image_free(&ib);
    }
    rf_scene_free(&flat);
    rf_scene_free(&e);
    rf_scene_free(&s);
    remove_files(dir, files);
}

/* An OBJ with its MTL through `mesh` inside an object, and mtllib relative to the OBJ. */
static void test_mesh_statement(void)
{
    static const char *const files[] = {
        "sub/a.mtl", "newmtl shiny\nKd 0.2 0.4 0.6\nKs 0.5\nNs 20\nillum 3\n",
        "sub/a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                     "f 1 2 3\nusemtl shiny\nf 2 4 3\n",
        "s.rf", "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\n"
                "material base kd 1\nobject o\nmesh sub/a.obj crease 30\nend\ninstance o\ninstance o translate 2 0 0\n",
        NULL};
    char dir[256], path[512], err[512];
    snprintf(dir, sizeof dir, "/tmp/rf-mesh-sub-XXXXXX");
    RF_CHECK(mkdtemp(dir) != NULL);
    snprintf(path, sizeof path, "%s/sub", dir);
    RF_CHECK(mkdir(path, 0700) == 0);
    for (const char *const *f = files; f[0]; f += 2) {
        snprintf(path, sizeof path, "%s/%s", dir, f[0]);
        FILE *fp = fopen(path, "wb");
        if (fp) {
            fputs(f[1], fp);
            fclose(fp);
        }
    }
    snprintf(path, sizeof path, "%s/s.rf", dir);
    RfScene s;
    RfStatus st = rf_scene_load(path, NULL, &s, err, sizeof err);
    RF_CHECK_EQ_INT(st, RF_OK);
    if (st == RF_OK) {
        RF_CHECK_EQ_INT(s.object_count, 1);
        RF_CHECK_EQ_INT(s.objects[0].count, 2);
        RF_CHECK_EQ_INT(s.material_count, 2);
        RF_CHECK(s.prims[0].flags & RF_PRIM_IN_OBJECT);
        RF_CHECK_STR(s.materials[s.prims[0].material].name, "base"); /* before usemtl */
        RF_CHECK_STR(s.materials[s.prims[1].material].name, "shiny");
        RF_CHECK(s.materials[1].kr.r == 0.5);
        RfTriangleCount tc = rf_scene_triangle_count(&s);
        RF_CHECK_EQ_INT(tc.stored, 2);
        RF_CHECK_EQ_INT(tc.rendered, 4);
        rf_scene_free(&s);
    } else {
        fprintf(stderr, "%s\n", err);
    }
    for (const char *const *f = files; f[0]; f += 2) {
        snprintf(path, sizeof path, "%s/%s", dir, f[0]);
        remove(path);
    }
    snprintf(path, sizeof path, "%s/sub", dir);
    rmdir(path);
    rmdir(dir);
}

/* The shipped scenes load, and `refray info` shows the graph. */
static void test_mesh_scenes(void)
{
    static const char *const paths[] = {"scenes/mesh.rf", "scenes/instances.rf",
                                        "scenes/ellipsoid.rf", "scenes/gem.obj"};
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
        RfScene s;
        char err[512];
        RfStatus st = rf_scene_load(paths[i], NULL, &s, err, sizeof err);
        RF_CHECK_EQ_INT(st, RF_OK);
        if (st)
            fprintf(stderr, "%s\n", err);
        rf_scene_free(&s);
    }
    char cmd[512];
    int code;
    snprintf(cmd, sizeof cmd, "%s info scenes/instances.rf", rf_test_bin());
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    /* 144 clusters x (2 chains x 2 rings + 1) + 60 rings = 780 rings of 2304 triangles */
    RF_CHECK(strstr(out, "triangles 6912 stored, 1797120 rendered after instancing") != NULL);
    RF_CHECK(strstr(out, "  cluster      group: 0 primitives (0 triangles), 3 instances of chain, chain, ring_blue") != NULL);
}

/* A random decimal number in one of the spellings OBJ files use (and a few they should not):
 * digits before and after the point, leading zeros and signs, exponents, up to 20 significant
 * digits; most take the reader's fast decimal path, the rest strtod. */
static void random_number(RfTestRng *r, char *buf, size_t n)
{
    char mant[32];
    int k = 0, digits = 1 + (int)rf_test_uniform(r, 0, 20), point = (int)rf_test_uniform(r, -1, digits + 1);
    int sign = (int)rf_test_uniform(r, 0, 3), form = (int)rf_test_uniform(r, 0, 6);
    if (sign == 1)
        mant[k++] = '-';
    else if (sign == 2 && form == 0)
        mant[k++] = '+';
    if (form == 1)
        mant[k++] = '0';
    for (int i = 0; i < digits; i++) {
        if (i == point)
            mant[k++] = '.';
        mant[k++] = (char)('0' + (int)rf_test_uniform(r, 0, 10));
    }
    if (point == digits)
        mant[k++] = '.';
    mant[k] = 0;
    if (form >= 4)
        snprintf(buf, n, "%s%c%d", mant, form == 4 ? 'e' : 'E', (int)rf_test_uniform(r, -30, 31));
    else
        snprintf(buf, n, "%s", mant);
}

/* The OBJ reader's fast path (plain v and f lines, its own decimal conversion) against the
 * statement readers (the same file with every line indented) and against strtod: the same
 * doubles bit for bit, the same faces. */
static void test_obj_fast_path(void)
{
    RfTestRng r = {2024};
    enum { NV = 3000 };
    size_t cap = NV * 120 + 4096;
    char *fast = malloc(cap), *slow = malloc(cap + NV * 4);
    double *want = malloc(sizeof *want * NV * 3);
    size_t nf = 0, ns = 0;
    for (int i = 0; i < NV; i++) {
        char num[3][64], line[256];
        for (int k = 0; k < 3; k++) {
            random_number(&r, num[k], sizeof num[k]);
            want[3 * i + k] = strtod(num[k], NULL);
        }
        snprintf(line, sizeof line, "v %s %s%s\t%s%s\n", num[0], num[1], i % 5 ? "" : "  ", num[2], i % 7 ? "" : " # note");
        nf += (size_t)snprintf(fast + nf, cap - nf, "%s", line);
        ns += (size_t)snprintf(slow + ns, cap + NV * 4 - ns, " %s", line);
    }
    /* texture coordinates and a normal, the faces in every form, then one face per vertex triple
     * (a nearly degenerate one may be dropped: the same ones both ways) */
    static const char *const faces[] = {"vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n", "f 1 2 3\n", "f 4/1 5/2 6/3\n",
                                        "f 7//1 8//1 9//1\n", "f 10/1/1 11/2/1 12/3/1 13/1/1\n",
                                        "f 14 15 16 # a comment\r\n", "f -3 -2 -1\n"};
    for (int i = 0; i < 7; i++) {
        nf += (size_t)snprintf(fast + nf, cap - nf, "%s", faces[i]);
        ns += (size_t)snprintf(slow + ns, cap + NV * 4 - ns, "%s%s", i ? " " : "", faces[i]);
    }
    int first_face_line = NV + 4 + 7;
    for (int i = 0; i < NV / 3; i++) {
        nf += (size_t)snprintf(fast + nf, cap - nf, "f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
        ns += (size_t)snprintf(slow + ns, cap + NV * 4 - ns, " f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    RfScene a, b;
    char err[512];
    RfStatus sa = read_obj(fast, &a, err, sizeof err), sb = read_obj(slow, &b, err, sizeof err);
    RF_CHECK_EQ_INT(sa, RF_OK);
    RF_CHECK_EQ_INT(sb, RF_OK);
    if (sa == RF_OK && sb == RF_OK) {
        RF_CHECK(a.prim_count > NV / 6); /* wild magnitudes make many triangles "collinear" */
        RF_CHECK_EQ_INT(a.prim_count, b.prim_count);
        RF_CHECK_EQ_INT(a.vertex_count, b.vertex_count);
        RF_CHECK(memcmp(a.vertices, b.vertices, sizeof *a.vertices * a.vertex_count) == 0);
        int same = 1, checked = 0;
        for (size_t p = 0; p < a.prim_count; p++) {
            int tri = a.prims[p].loc.line - first_face_line;
            same &= a.prims[p].loc.line == b.prims[p].loc.line;
            if (tri < 0)
                continue;
            for (int k = 0; k < 3; k++) {
                RfVec3 v = a.vertices[a.prims[p].u.poly.first + (size_t)k];
                const double *w = &want[3 * (3 * tri + k)];
                same &= v.x == w[0] && v.y == w[1] && v.z == w[2];
                checked++;
            }
        }
        RF_CHECK(same);
        RF_CHECK(checked > NV / 2);
        rf_scene_free(&a);
        rf_scene_free(&b);
    }
    free(fast);
    free(slow);
    free(want);
}

/* The fast path's vn and vt lines against the statement readers (the same lines indented) and
 * against strtod: normals of 1 to 17 significant digits (beyond 15 the fast path leaves them to
 * the statement readers) and texture coordinates of one to three numbers; each face takes one
 * normal, which the scene keeps normalised. */
static void test_obj_fast_normals(void)
{
    RfTestRng r = {77};
    enum { NN = 600 };
    size_t cap = (size_t)NN * 200 + 256;
    char *text[2] = {malloc(cap), malloc(cap)};
    RfVec3 *want = malloc(sizeof *want * NN);
    size_t len[2] = {0, 0};
    for (int k = 0; k < 2; k++)
        len[k] += (size_t)snprintf(text[k] + len[k], cap - len[k], "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (int i = 0; i < NN; i++) {
        double c[3];
        char line[200];
        int digits = 1 + i % 17;
        for (int a = 0; a < 3; a++) {
            char num[64];
            snprintf(num, sizeof num, "%.*g", digits, rf_test_uniform(&r, -10.0, 10.0) + (a == 2 ? 20.0 : 0.0));
            c[a] = strtod(num, NULL);
            snprintf(line + (a ? strlen(line) : 0), sizeof line - (a ? strlen(line) : 0), "%s%s", a ? " " : "vn ", num);
        }
        want[i] = rf_vec3_normalize(rf_vec3(c[0], c[1], c[2]));
        for (int k = 0; k < 2; k++)
            len[k] += (size_t)snprintf(text[k] + len[k], cap - len[k], "%s%s%s\nvt%s%s\n", k ? " " : "", line,
                                       i % 3 ? "" : " # n", k ? " " : "", i % 3 == 0 ? " 0.5" : i % 3 == 1 ? " 0.5 0.25" : " 0.5 0.25 0");
    }
    for (int i = 0; i < NN; i++)
        for (int k = 0; k < 2; k++)
            len[k] += (size_t)snprintf(text[k] + len[k], cap - len[k], "f 1/%d/%d 2/%d/%d 3/%d/%d\n", i + 1, i + 1,
                                       i + 1, i + 1, i + 1, i + 1);
    RfScene sc[2];
    char err[512];
    for (int k = 0; k < 2; k++)
        RF_CHECK_EQ_INT(read_obj(text[k], &sc[k], err, sizeof err), RF_OK);
    RF_CHECK(rf_fuzz_same_scene(&sc[0], &sc[1]));
    RF_CHECK_EQ_INT(sc[0].normal_count, 3 * NN);
    int exact = 1;
    for (size_t n = 0; n < sc[0].normal_count && n < 3 * NN; n++)
        exact &= sc[0].normals[n].x == want[n / 3].x && sc[0].normals[n].y == want[n / 3].y &&
                 sc[0].normals[n].z == want[n / 3].z;
    RF_CHECK(exact);
    for (int k = 0; k < 2; k++) {
        rf_scene_free(&sc[k]);
        free(text[k]);
    }
    free(want);
}

/* The faces go into the scene in chunks of 16,384 on the load's threads (obj.c, emit_faces):
 * 40,000 faces (three chunks) of every kind the reader knows, loaded on 1, 2 and 3 threads,
 * make the same scene, and one face after another as the file lists them; the first failing
 * face in the file is the one reported, whichever thread met it first. */
enum { TF_ROWS = 200, TF_COLS = 100, TF_FACES = 40000 };

/* OBJ text: a TF_ROWS x TF_COLS grid of vertices (z a function of x and y), faces over it in
 * turn: flat triangles, smooth triangles, quads with their own normals, triangles of no area
 * (dropped); bad_a and bad_b (face numbers, or -1) use a zero-length normal. */
static char *threads_obj(int bad_a, int bad_b, int *bad_line)
{
    size_t cap = (size_t)64 * (TF_ROWS * TF_COLS + TF_FACES + 16), len = 0;
    char *t = malloc(cap);
    int line = 1;
    len += (size_t)snprintf(t + len, cap - len, "vn 0 0 1\nvn 0.6 0 0.8\nvn 0 0 0\n");
    line += 3;
    for (int r = 0; r < TF_ROWS; r++)
        for (int c = 0; c < TF_COLS; c++, line++)
            len += (size_t)snprintf(t + len, cap - len, "v %d %d %.17g\n", c, r, 0.01 * (c % 7) * (r % 5));
    for (int f = 0; f < TF_FACES; f++) {
        int cell = f % ((TF_ROWS - 1) * (TF_COLS - 1)), r = cell / (TF_COLS - 1), c = cell % (TF_COLS - 1);
        int a = r * TF_COLS + c + 1, b = a + 1, d = a + TF_COLS, e = d + 1;
        if (f % 4000 == 0) {
            len += (size_t)snprintf(t + len, cap - len, "s %s\n", (f / 4000) % 2 ? "off" : "1");
            line++;
        }
        if (f == bad_a || f == bad_b) {
            if (f == bad_a)
                *bad_line = line;
            len += (size_t)snprintf(t + len, cap - len, "f %d//3 %d//1 %d//1\n", a, b, e);
        } else if (f % 5 == 3) {
            len += (size_t)snprintf(t + len, cap - len, "f %d//1 %d//2 %d//1 %d//2\n", a, b, e, d);
        } else if (f % 11 == 7) {
            len += (size_t)snprintf(t + len, cap - len, "f %d %d %d\n", a, b, a); /* no area */
        } else {
            len += (size_t)snprintf(t + len, cap - len, "f %d %d %d\n", a, b, e);
        }
        line++;
    }
    return t;
}

static void test_obj_threads(void)
{
    int bad_line = -1;
    char *text = threads_obj(-1, -1, &bad_line);
    RfScene sc[3];
    char err[512];
    for (int k = 0; k < 3; k++) {
        RfLoadOptions opt = rf_load_options_default();
        opt.threads = k + 1;
        RF_CHECK_EQ_INT(rf_scene_read_obj("t.obj", text, strlen(text), &opt, &sc[k], err, sizeof err), RF_OK);
    }
    /* independently: every face but those of no area (f % 11 == 7 but not a quad) */
    size_t want = 0;
    for (int f = 0; f < TF_FACES; f++)
        want += !(f % 5 != 3 && f % 11 == 7);
    RF_CHECK(sc[0].prim_count == want);
    int in_order = 1;
    for (int k = 1; k < 3; k++)
        RF_CHECK(rf_fuzz_same_scene(&sc[k], &sc[0]));
    size_t smooth = 0, quads = 0;
    for (size_t p = 0; p < sc[0].prim_count; p++) {
        const RfPrimitive *a = &sc[0].prims[p];
        in_order &= p == 0 || a->loc.line > sc[0].prims[p - 1].loc.line;
        in_order &= a->u.poly.first == (p ? sc[0].prims[p - 1].u.poly.first + (size_t)sc[0].prims[p - 1].u.poly.count : 0);
        smooth += (a->flags & RF_PRIM_VERTEX_NORMALS) != 0;
        quads += a->type == RF_PRIM_POLYGON;
    }
    RF_CHECK(in_order);
    RF_CHECK(quads == TF_FACES / 5);
    RF_CHECK(smooth > quads && smooth < sc[0].prim_count);
    for (int k = 0; k < 3; k++)
        rf_scene_free(&sc[k]);
    free(text);
    /* two bad faces, in the second and third chunk: the earlier one is reported */
    text = threads_obj(20000, 36000, &bad_line);
    char want_at[64];
    snprintf(want_at, sizeof want_at, "t.obj:%d:1: ", bad_line);
    for (int k = 0; k < 3; k++) {
        RfLoadOptions opt = rf_load_options_default();
        opt.threads = k + 1;
        RfScene s;
        RF_CHECK(rf_scene_read_obj("t.obj", text, strlen(text), &opt, &s, err, sizeof err) != RF_OK);
        RF_CHECK(strncmp(err, want_at, strlen(want_at)) == 0 && strstr(err, "zero length"));
    }
    free(text);
}

/* The parse in chunks on several threads (obj.c, parse_chunks) against the parse line by line:
 * an OBJ of ~1 MB (some sixty chunks) with every kind of line the chunks take (v, vn, vt, f in
 * all four forms and as quads, comments after faces, empty lines and comments, CRLF ends,
 * mtllib, usemtl, s, o, g) gives the same scene on 1, 2 and 3 threads, with the materials and
 * smoothing the file says (counted here). Lines the fast path leaves to the statement readers
 * (17 digits, negative indices, v with w) are read in their chunk; a line of another kind (l)
 * or a failing v or f line makes the file read line by line; errors are the file's first. */
enum { PC_GRID = 120, PC_FACES = 30000 };
enum { PC_CLEAN, PC_NEGATIVE, PC_VERTEX_W, PC_LINE, PC_BAD_MTL_THEN_FACE, PC_BAD_FACE, PC_BAD_FACE_THEN_MTL,
       PC_BARE_S, PC_BAD_MTL, PC_VARIANTS };

typedef struct {
    size_t blue, flat; /* faces with the material blue; without normals (s off, no vn) */
    int err_line;      /* the first error's line, 0 for none */
} ChunksWant;

static char *chunks_obj(int variant, ChunksWant *w)
{
    size_t cap = (size_t)96 * (PC_GRID * PC_GRID + 2 * PC_FACES), len = 0;
    char *t = malloc(cap);
    int line = 1, blue = 0, flat = 0;
    memset(w, 0, sizeof *w);
#define PC_PUT(...) (len += (size_t)snprintf(t + len, cap - len, __VA_ARGS__), line++)
    PC_PUT("# chunks test\r\n");
    PC_PUT("mtllib m.mtl\n");
    PC_PUT("o body\n");
    PC_PUT("vt 0 0\n");
    PC_PUT("vt 1 0 0.5\n");
    PC_PUT("vt 0.5 1\n");
    PC_PUT("vn 0 0 1\n");
    PC_PUT("vn 0 0.6 0.8\n");
    for (int i = 0; i < PC_GRID * PC_GRID; i++) {
        PC_PUT("v %d %d %.17g%s", i % PC_GRID, i / PC_GRID, 0.01 * (i % 7) * (i % 5), i % 7 == 3 ? "\r\n" : "\n");
        if (i % 50 == 49) {
            PC_PUT("\n");
            PC_PUT("# row %d\n", i);
        }
    }
    for (int f = 0; f < PC_FACES; f++) {
        int cell = f % ((PC_GRID - 1) * (PC_GRID - 1)), r = cell / (PC_GRID - 1), c = cell % (PC_GRID - 1);
        int a = r * PC_GRID + c + 1, b = a + 1, d = a + PC_GRID, e = d + 1;
        if (f % 3000 == 0) {
            blue = (f / 3000) % 2;
            PC_PUT("usemtl %s\n", blue ? "blue" : "red");
        }
        if (f % 4500 == 0) {
            flat = (f / 4500) % 2 == 0;
            PC_PUT("s %s\n", flat ? "off" : "3");
        }
        if (f % 7000 == 0)
            PC_PUT("g part%d\n", f);
        if ((variant == PC_NEGATIVE && f == 20000) || (variant == PC_VERTEX_W && f == 15000) ||
            (variant == PC_LINE && f == 10000)) {
            PC_PUT("%s\n", variant == PC_NEGATIVE ? "f -1 -2 -121" : variant == PC_VERTEX_W ? "v 0.5 0.5 0.5 1" : "l 1 2");
            w->blue += variant == PC_NEGATIVE && blue;
            w->flat += variant == PC_NEGATIVE && flat;
        }
        if ((f == 8000 && variant == PC_BAD_MTL_THEN_FACE) || (f == 26000 && variant == PC_BAD_FACE_THEN_MTL) ||
            (f == 27000 && variant == PC_BAD_MTL)) {
            if (!w->err_line)
                w->err_line = line;
            PC_PUT("usemtl green\n");
        }
        if ((f == 25000 && (variant == PC_BAD_MTL_THEN_FACE || variant == PC_BAD_FACE)) ||
            (f == 12000 && variant == PC_BAD_FACE_THEN_MTL)) {
            if (!w->err_line)
                w->err_line = line;
            PC_PUT("%s\n", f == 12000 ? "f 0 1 2" : "f 1 2 99999");
        }
        if (f == 22000 && variant == PC_BARE_S) {
            w->err_line = line;
            PC_PUT("s\n");
        }
        switch (f % 4) {
        case 0: PC_PUT("f %d %d %d%s\n", a, b, e, f % 13 == 0 ? " # note" : ""); break;
        case 1: PC_PUT("f %d/1 %d/2 %d/3\n", a, b, e); break;
        case 2: PC_PUT("f %d//1 %d//2 %d//1\n", a, b, e); break;
        default: PC_PUT("f %d/1/1 %d/2/2 %d/3/1 %d/1/2\n", a, b, e, d);
        }
        w->blue += blue;
        w->flat += flat && (f % 4 == 0 || f % 4 == 1);
    }
#undef PC_PUT
    return t;
}

static void test_obj_parse_chunks(void)
{
    static const char *const files[] = {"m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n", NULL};
    static const int chunked_want[PC_VARIANTS] = {1, 1, 1, 0, 0, 0, 0, 1, 1};
    char dir[256], name[512];
    RF_CHECK(write_files(dir, sizeof dir, files));
    snprintf(name, sizeof name, "%s/t.obj", dir);
    for (int v = 0; v < PC_VARIANTS; v++) {
        ChunksWant w;
        char *text = chunks_obj(v, &w);
        size_t len = strlen(text);
        RF_CHECK(len > 16 * 16384);
        RfScene sc[3];
        RfStatus st[3];
        char err[3][512];
        for (int k = 0; k < 3; k++) {
            RfObjPlacement pl = {60.0, -1, 0u, k + 1, NULL};
            int chunked = -1;
            pl.chunked = &chunked;
            rf_scene_init(&sc[k]);
            st[k] = rf__obj_read(name, text, len, &pl, &sc[k], err[k], sizeof err[k]);
            RF_CHECK_EQ_INT(chunked, k == 0 ? 0 : chunked_want[v]);
        }
        for (int k = 1; k < 3; k++) {
            RF_CHECK_EQ_INT(st[k], st[0]);
            if (st[0] == RF_OK)
                RF_CHECK(rf_fuzz_same_scene(&sc[k], &sc[0]));
            else
                RF_CHECK_STR(err[k], err[0]);
        }
        if (w.err_line) {
            char at[600];
            snprintf(at, sizeof at, "%s:%d:", name, w.err_line);
            RF_CHECK(st[0] != RF_OK && strncmp(err[0], at, strlen(at)) == 0);
        } else {
            RF_CHECK_EQ_INT(st[0], RF_OK);
            size_t blue = 0, flat = 0;
            for (size_t p = 0; p < sc[0].prim_count; p++) {
                blue += strcmp(sc[0].materials[sc[0].prims[p].material].name, "blue") == 0;
                flat += !(sc[0].prims[p].flags & RF_PRIM_VERTEX_NORMALS);
            }
            RF_CHECK_EQ_INT(sc[0].prim_count, PC_FACES + (v == PC_NEGATIVE));
            RF_CHECK_EQ_INT(blue, w.blue);
            RF_CHECK_EQ_INT(flat, w.flat);
        }
        if (st[0] != RF_OK && !w.err_line)
            printf("  %s\n", err[0]);
        for (int k = 0; k < 3; k++)
            rf_scene_free(&sc[k]);
        free(text);
    }
    remove_files(dir, files);
}

/* The definition rf_lex_decimal keeps (lexer.h), digit by digit: the test's reference for the
 * reader's faster loops (eight fraction digits at a time). */
static const char *decimal_definition(const char *s, const char *end, double *out)
{
    static const double pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                     1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    int neg = 0, digits = 0, sig = 0, scale = 0, frac = 0;
    uint64_t m = 0;
    if (s < end && (*s == '+' || *s == '-'))
        neg = *s++ == '-';
    for (;;) {
        for (; s < end && *s >= '0' && *s <= '9'; s++, digits++) {
            scale -= frac;
            if (m || *s != '0') {
                if (++sig > 15)
                    return NULL;
                m = m * 10 + (uint64_t)(*s - '0');
            }
        }
        if (frac || !(s < end && *s == '.'))
            break;
        s++, frac = 1;
    }
    if (digits == 0)
        return NULL;
    if (s < end && (*s == 'e' || *s == 'E')) {
        int eneg = 0, e = 0, ed = 0;
        s++;
        if (s < end && (*s == '+' || *s == '-'))
            eneg = *s++ == '-';
        for (; s < end && *s >= '0' && *s <= '9'; s++, ed++)
            if ((e = e * 10 + (*s - '0')) > 400)
                return NULL;
        if (ed == 0)
            return NULL;
        scale += eneg ? -e : e;
    }
    if (scale < -22 || scale > 22)
        return NULL;
    double v = scale < 0 ? (double)m / pow10[-scale] : (double)m * pow10[scale];
    *out = neg ? -v : v;
    return s;
}

static void test_lex_numbers(void)
{
    RfTestRng r = {2026};
    uint64_t st = 0x9E3779B97F4A7C15ULL;
    int bad8 = 0, bad = 0, accepted = 0;
    /* rf_lex_digits8 against a loop: every run length, zeros first, bytes of every value after */
    for (int it = 0; it < 200000; it++) {
        char b[16];
        for (int i = 0; i < 16; i++) {
            st = st * 6364136223846793005ULL + 1442695040888963407ULL;
            unsigned x = (unsigned)(st >> 33);
            b[i] = (char)(x % 4 ? '0' + (int)(x % 10) : (int)(x >> 8) % 256);
        }
        for (int i = 0; i < it % 9; i++)
            b[i] = '0';
        uint64_t v = 0;
        int z = 0, n = rf_lex_digits8(b, b + 8 + it % 9, &v, &z), m = 0, zz = 0;
        uint64_t w = 0;
        for (; m < 8 && b[m] >= '0' && b[m] <= '9'; m++) {
            w = w * 10 + (uint64_t)(b[m] - '0');
            zz += w == 0;
        }
        bad8 += n >= 0 && (n != m || v != w || z != zz);
    }
    /* rf_lex_decimal against its definition and strtod: signs, leading zeros, long fractions,
     * exponents, other bytes after, and every cut of the text */
    for (int it = 0; it < 100000; it++) {
        char buf[96];
        int k = 0;
        unsigned x = (unsigned)rf_test_uniform(&r, 0, 1e9);
        if (x % 3 == 0)
            buf[k++] = x % 2 ? '-' : '+';
        for (int i = 0; i < (int)(x / 3 % 4); i++)
            buf[k++] = '0';
        for (int i = 0, n = (int)rf_test_uniform(&r, 0, 19); i < n; i++)
            buf[k++] = (char)('0' + (int)rf_test_uniform(&r, 0, 10));
        if (x / 12 % 2) {
            buf[k++] = '.';
            for (int i = 0, n = (int)rf_test_uniform(&r, 0, 3); i < n; i++)
                buf[k++] = '0';
            for (int i = 0, n = (int)rf_test_uniform(&r, 0, 21); i < n; i++)
                buf[k++] = (char)('0' + (int)rf_test_uniform(&r, 0, 10));
        }
        if (x / 24 % 5 == 0) {
            buf[k++] = 'e';
            if (x / 120 % 2)
                buf[k++] = '-';
            for (int i = 0, n = (int)rf_test_uniform(&r, 0, 4); i < n; i++)
                buf[k++] = (char)('0' + (int)rf_test_uniform(&r, 0, 10));
        }
        for (int i = 0, n = (int)rf_test_uniform(&r, 0, 12); i < n && k < 95; i++)
            buf[k++] = " .e-/#9\r"[(int)rf_test_uniform(&r, 0, 8)];
        int len = x / 600 % 2 ? k : (int)rf_test_uniform(&r, 0, k + 1);
        double v1 = 0.0, v2 = 0.0;
        const char *e1 = decimal_definition(buf, buf + len, &v1), *e2 = rf_lex_decimal(buf, buf + len, &v2);
        int same = e1 == e2 && (!e1 || memcmp(&v1, &v2, sizeof v1) == 0);
        if (e1) { /* and strtod agrees on what was read */
            char tmp[100];
            memcpy(tmp, buf, (size_t)(e1 - buf));
            tmp[e1 - buf] = 0;
            same &= strtod(tmp, NULL) == v1;
            accepted++;
        }
        if (!same && bad++ < 3)
            printf("  '%.*s': definition %d %.17g, rf_lex_decimal %d %.17g\n", len, buf, e1 ? (int)(e1 - buf) : -1, v1,
                   e2 ? (int)(e2 - buf) : -1, v2);
    }
    RF_CHECK_EQ_INT(bad8, 0);
    RF_CHECK_EQ_INT(bad, 0);
    RF_CHECK(accepted > 20000);
    /* face indices of 1 to 12 digits (zeros before them), the fast path's eight at a time and the
     * rest one by one: the scene of the plain indices */
    char *text[2] = {malloc(8192), malloc(8192)};
    size_t len[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        len[k] += (size_t)snprintf(text[k] + len[k], 8192 - len[k], "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n");
        for (int d = 1; d <= 12; d++)
            len[k] += (size_t)snprintf(text[k] + len[k], 8192 - len[k], "f %0*d//1 %0*d//%d %0*d//1\n", k ? d : 1, 1,
                                       k ? d : 1, 2, 1, k ? d : 1, d % 2 ? 3 : 4);
    }
    RfScene sc[2];
    char err[512];
    for (int k = 0; k < 2; k++)
        RF_CHECK_EQ_INT(read_obj(text[k], &sc[k], err, sizeof err), RF_OK);
    RF_CHECK(rf_fuzz_same_scene(&sc[0], &sc[1]));
    RF_CHECK_EQ_INT(sc[1].prim_count, 12);
    for (int k = 0; k < 2; k++) {
        rf_scene_free(&sc[k]);
        free(text[k]);
    }
}

const RfTest rf_tests_mesh[] = {
    {"mesh_obj_threads_same_scene", test_obj_threads},
    {"mesh_obj_parse_chunks", test_obj_parse_chunks},
    {"mesh_obj_fast_path", test_obj_fast_path},
    {"mesh_obj_fast_normals", test_obj_fast_normals},
    {"mesh_lex_numbers", test_lex_numbers},
    {"mesh_obj_index_forms", test_obj_index_forms},
    {"mesh_obj_polygons", test_obj_polygons},
    {"mesh_obj_vertex_normals", test_obj_vertex_normals},
    {"mesh_mtl_illum", test_mtl_illum},
    {"mesh_errors", test_mesh_errors},
    {"mesh_graph_transforms", test_graph_transforms},
    {"mesh_ellipsoid_normal", test_ellipsoid_normal},
    {"mesh_instanced_vs_flattened", test_instanced_vs_flattened},
    {"mesh_statement", test_mesh_statement},
    {"mesh_scenes", test_mesh_scenes},
    RF_TEST_END,
};
