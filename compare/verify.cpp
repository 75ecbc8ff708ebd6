// refray-verify: the tracer's geometric decisions against exact arithmetic (issue 7,
// docs/verify.md). For each ray of a class: the tracer's answer (rf_tracer_intersect: hit or
// miss, nearest primitive, t) against the exact one (verify_oracle.cpp, CGAL Epeck); every
// disagreement is ambiguous (within kDelta * S of a boundary) or real. Also measured: shadow
// acne and light leaks over scene scales 1e-4 .. 1e6, the optics edge cases, and the
// invalid-sample count of stress renders. Exit status 1 on any real disagreement, 2 when a
// scene cannot be loaded or is outside the verifier's range (or on bad usage).
// This file: the driver (the options, the rows in processes, the table) and the small helpers
// the parts share (verify_run.hpp lists the parts).
#include "verify_run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdarg>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "../src/cli/exit_codes.h"
#include "../src/cli/opt.h"
#include "refray/scene_io.h"

namespace rv {

void example(Stats &st, const char *fmt, ...)
{
    if (st.n_examples >= 3)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st.examples[st.n_examples++], sizeof st.examples[0], fmt, ap);
    va_end(ap);
}

void not_representable(Stats &st, RfRay r, const char *why)
{
    st.rays++;
    st.skipped++;
    if (!st.skip_note[0])
        snprintf(st.skip_note, sizeof st.skip_note, "o=(%a,%a,%a) d=(%a,%a,%a): %s", r.origin.x, r.origin.y,
                 r.origin.z, r.dir.x, r.dir.y, r.dir.z, why);
}

void row_error(Stats &st, const char *fmt, ...)
{
    st.error = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st.error_msg, sizeof st.error_msg, fmt, ap);
    va_end(ap);
}

bool finite_ray(RfRay r)
{
    return std::isfinite(r.origin.x) && std::isfinite(r.origin.y) && std::isfinite(r.origin.z) &&
           std::isfinite(r.dir.x) && std::isfinite(r.dir.y) && std::isfinite(r.dir.z);
}

void frame(RfVec3 k, RfVec3 *u, RfVec3 *v)
{
    RfVec3 h = std::fabs(k.x) < 0.6 ? rf_vec3(1, 0, 0) : rf_vec3(0, 1, 0);
    *u = rf_vec3_normalize(rf_vec3_cross(k, h));
    *v = rf_vec3_cross(k, *u);
}

namespace {

const char *const kAllClasses[] = {"uniform",   "edges",  "grazing",  "parallel", "far",       "radii",
                                   "surface",   "acne",   "leak",     "optics",   "invalid",   "cones",
                                   "polygons",  "instances", "star-prisms"};

// ---- driver ------------------------------------------------------------------------------------

const char *const kFileClasses[] = {"uniform", "edges", "grazing", "parallel", "surface"};

// Loads a scene and prepares the oracle and the tracer. On failure *err says why: the loader's
// message (file:line:col), or the verifier's refusal of a scene outside its range with the
// primitive's position (RfPrimitive.loc: its statement in the scene or in the mesh file it
// includes).
// *code (may be null): RF_EXIT_FILE when the scene cannot be read, RF_EXIT_FAIL when the oracle
// cannot take it
bool load_world(const char *path, World &w, std::string *err, int *code = nullptr)
{
    char msg[1024];
    rf_scene_free(&w.sc);
    rf_scene_init(&w.sc);
    if (code)
        *code = RF_EXIT_FILE;
    if (rf_scene_load(path, nullptr, &w.sc, msg, sizeof msg) != RF_OK) {
        *err = msg;
        return false;
    }
    if (code)
        *code = RF_EXIT_FAIL;
    // the exact oracle expands every placement: a graph with more paths than it can hold (a DAG
    // of groups placing their child twice has 2^levels) is refused before the expansion
    RfTriangleCount tc = rf_scene_triangle_count(&w.sc);
    if (tc.instances_rendered > 1000000) {
        snprintf(msg, sizeof msg,
                 "%s: the scene graph expands to %zu placements, more than the exact oracle holds (1000000); scene refused",
                 path, tc.instances_rendered);
        *err = msg;
        return false;
    }
    w.prim_mesh.assign(w.sc.prim_count, -1);
    rf_scene_bounds(&w.sc, &w.bounds.lo, &w.bounds.hi);
    try {
        w.finish();
    } catch (const SceneError &e) {
        if (e.loc.line > 0)
            snprintf(msg, sizeof msg, "%s:%d:%d: %s; scene refused", path, e.loc.line, e.loc.col, e.what());
        else
            snprintf(msg, sizeof msg, "%s: %s; scene refused", path, e.what());
        *err = msg;
        return false;
    } catch (const std::exception &e) {
        snprintf(msg, sizeof msg, "%s: the exact oracle cannot represent this scene (%s); scene refused", path, e.what());
        *err = msg;
        return false;
    }
    return true;
}

void run_class_body(const char *cls, const Opts &o, World *file_world, Stats &st)
{
    std::string c = cls;
    if (c.compare(0, 6, "scene:") == 0) { // a scene file: every file class, one row
        const char *path = cls + 6;
        World w;
        Opts so = o;
        so.rays = o.scene_rays;
        std::string err;
        if (!load_world(path, w, &err))
            row_error(st, "%s", err.c_str());
        else
            for (const char *fc : kFileClasses)
                run_file(fc, so, w, st);
    } else if (file_world)
        run_file(cls, o, *file_world, st);
    else if (c == "acne")
        run_acne(o, st);
    else if (c == "leak")
        run_leak(o, st);
    else if (c == "optics")
        run_optics(o, st);
    else if (c == "invalid")
        run_invalid(o, st);
    else
        run_rays(cls, o, st);
}

Stats run_class(const char *cls, const Opts &o, World *file_world)
{
    Stats st;
    memset(&st, 0, sizeof st);
    snprintf(st.name, sizeof st.name, "%s", cls);
    if (strncmp(cls, "scene:", 6) == 0) {
        const char *base = strrchr(cls + 6, '/');
        snprintf(st.name, sizeof st.name, "%s", base ? base + 1 : cls + 6);
    }
    auto t0 = std::chrono::steady_clock::now();
    // anything the oracle throws outside a ray (a built-in scene it refuses, the allocator)
    // ends the row with a message instead of the process
    try {
        run_class_body(cls, o, file_world, st);
    } catch (const SceneError &e) {
        row_error(st, "%s: %s", cls, e.what());
    } catch (const std::exception &e) {
        row_error(st, "%s: %s", cls, e.what());
    }
    st.secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return st;
}

void print_table(const std::vector<Stats> &rows, FILE *f)
{
    fprintf(f, "%-13s %10s %10s %10s %6s %11s %8s %12s %8s\n", "class", "rays", "agree", "ambiguous", "real",
            "edge misses", "skipped", "acne share", "seconds");
    Stats tot;
    memset(&tot, 0, sizeof tot);
    for (const Stats &s : rows) {
        char acne[32] = "-";
        if (s.acne_d)
            snprintf(acne, sizeof acne, "%ld/%ld", s.acne_n, s.acne_d);
        if (s.error)
            fprintf(f, "%-13s %10s\n", s.name, "error");
        else
            fprintf(f, "%-13s %10ld %10ld %10ld %6ld %11ld %8ld %12s %8.1f\n", s.name, s.rays, s.agree, s.amb,
                    s.real, s.edge_miss, s.skipped, acne, s.secs);
        tot.rays += s.rays, tot.agree += s.agree, tot.amb += s.amb, tot.real += s.real;
        tot.edge_miss += s.edge_miss, tot.skipped += s.skipped, tot.acne_n += s.acne_n, tot.acne_d += s.acne_d;
        tot.secs += s.secs;
    }
    char acne[32] = "-";
    if (tot.acne_d)
        snprintf(acne, sizeof acne, "%ld/%ld", tot.acne_n, tot.acne_d);
    fprintf(f, "%-13s %10ld %10ld %10ld %6ld %11ld %8ld %12s %8.1f\n", "total", tot.rays, tot.agree, tot.amb, tot.real,
            tot.edge_miss, tot.skipped, acne, tot.secs);
    for (const Stats &s : rows)
        for (int i = 0; i < s.n_examples; i++)
            fprintf(f, "real (%s): %s\n", s.name, s.examples[i]);
    for (const Stats &s : rows)
        if (s.skipped)
            fprintf(f, "skipped (not representable) (%s): %ld rays; the first: %s\n", s.name, s.skipped, s.skip_note);
}

// Runs the classes, up to `jobs` at once in child processes (no shared state: each child
// builds its own scenes and sends its Stats back through a pipe).
std::vector<Stats> run_all(const std::vector<std::string> &classes, const Opts &o, int jobs, World *fw)
{
    std::vector<Stats> rows(classes.size());
    if (jobs <= 1 || fw) {
        for (size_t i = 0; i < classes.size(); i++)
            rows[i] = run_class(classes[i].c_str(), o, fw);
        return rows;
    }
    // the longest rows first (measured at CI size), so that no long row starts last; the table
    // keeps the given order
    auto cost = [](const std::string &c) {
        return c == "instances" ? 5 : c == "edges" ? 4 : c == "cones" ? 3 : c == "grazing" || c == "parallel" || c == "radii" || c == "polygons" ? 1 : 0;
    };
    std::vector<size_t> order(classes.size());
    for (size_t i = 0; i < order.size(); i++)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost(classes[a]) > cost(classes[b]); });
    size_t next = 0, done = 0;
    std::map<pid_t, std::pair<size_t, int>> running;
    while (done < classes.size()) {
        while ((int)running.size() < jobs && next < classes.size()) {
            size_t row = order[next];
            int fd[2];
            if (pipe(fd) != 0) {
                perror("pipe");
                exit(2);
            }
            fflush(nullptr);
            pid_t pid = fork();
            if (pid == 0) {
                close(fd[0]);
                Stats st = run_class(classes[row].c_str(), o, nullptr);
                ssize_t wr = write(fd[1], &st, sizeof st);
                _exit(wr == (ssize_t)sizeof st ? 0 : 3);
            }
            close(fd[1]);
            running[pid] = {row, fd[0]};
            next++;
        }
        int status;
        pid_t pid = wait(&status);
        auto it = running.find(pid);
        if (it == running.end())
            continue;
        Stats st;
        size_t got = 0;
        while (got < sizeof st) {
            ssize_t k = read(it->second.second, (char *)&st + got, sizeof st - got);
            if (k <= 0)
                break;
            got += (size_t)k;
        }
        close(it->second.second);
        if (got != sizeof st || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            memset(&st, 0, sizeof st);
            snprintf(st.name, sizeof st.name, "%s", classes[it->second.first].c_str());
            row_error(st, "class %s crashed (%s %d)", classes[it->second.first].c_str(),
                      WIFSIGNALED(status) ? "signal" : "exit status",
                      WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status));
        }
        rows[it->second.first] = st;
        running.erase(it);
        done++;
    }
    return rows;
}

enum { OPT_RAYS = RF_OPT_ID, OPT_SEED, OPT_JOBS, OPT_CLASS, OPT_STRESS, OPT_SCENE_RAYS, OPT_TRIANGLE, OPT_SPHERE,
       OPT_CONE_BOUND, OPT_FIXED_OFFSET };

const RfOpt verify_opts[] = {
    {"rays", OPT_RAYS, "N", "rays per class (default 100000)", "an integer >= 0"},
    {"class", OPT_CLASS, "CLASS", "one class of rays (repeatable; default: all); see below", nullptr},
    {"seed", OPT_SEED, "S", "the rays' random seed (default 1)", "an integer >= 0"},
    {"jobs", OPT_JOBS, "J", "classes run in J processes at once (default 1)", "an integer >= 1"},
    {"stress", OPT_STRESS, nullptr, "every class, the table of make stress", nullptr},
    {"scene-rays", OPT_SCENE_RAYS, "N", "rays per class in a scene's row (default rays/50)", "an integer >= 1"},
    {"triangle", OPT_TRIANGLE, "watertight|moller|script", "test the §3.5 triangle kernel with this method",
     "watertight, moller or script"},
    {"sphere", OPT_SPHERE, "stable|script", "test the §3.5 sphere kernel with this method", "stable or script"},
    {"fixed-offset", OPT_FIXED_OFFSET, "EPS", "replace the self-intersection policy by a fixed absolute offset",
     "a number >= 0"},
    {"cone-bound", OPT_CONE_BOUND, "kernel|geometric", "cones judged by the cone kernel's bound (default) or the geometric one",
     "kernel or geometric"},
    {nullptr, 0, nullptr, nullptr, nullptr},
};

const RfOpt *const verify_tables[] = {verify_opts, nullptr};

const RfCommand verify_cmd = {
    "refray-verify",
    "refray-verify [options] [SCENE...]\n",
    "The tracer's intersection decisions against CGAL's exact arithmetic. SCENE: an .nff/.rf/.obj\n"
    "scene: rays of the classes uniform, edges, grazing, parallel, surface over its primitives, a\n"
    "row per class (default: every class on scenes built in code); several scenes or --stress:\n"
    "one row per scene with --scene-rays rays per class.\n",
    verify_tables,
    "classes: uniform edges grazing parallel far radii surface acne leak optics invalid cones\n"
    "polygons instances star-prisms. The spheres' geometric cone bound is one the unstabilised\n"
    "cone kernel does not meet.\n"
    "exit: 0 no real disagreement, 2 a real disagreement (a planted bug found) or a row that could\n"
    "not run (a scene outside the verifier's range), 4 a scene cannot be read, 5 usage\n"
    "(README: Exit codes). docs/verify.md\n",
};

int verify_main(int argc, char **argv)
{
    Opts o;
    if (const char *f = getenv("REFRAY_VERIFY_FAULT"))
        o.fault_every = std::atol(f);
    std::vector<std::string> classes;
    std::vector<const char *> scenes;
    bool stress = false;
    int jobs = 1;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &verify_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        char *end = nullptr;
        bool ok = true;
        switch (key) {
        case RF_OPT_EXIT: return p.exit_code;
        case OPT_RAYS: o.rays = std::strtol(v, &end, 10), ok = *end == 0 && *v && o.rays >= 0; break;
        case OPT_SEED: o.seed = std::strtoull(v, &end, 10), ok = *end == 0 && *v && *v != '-'; break;
        case OPT_JOBS: jobs = (int)std::strtol(v, &end, 10), ok = *end == 0 && *v && jobs >= 1; break;
        case OPT_CLASS: classes.push_back(v); break;
        case OPT_STRESS: stress = true; break;
        case OPT_SCENE_RAYS: o.scene_rays = std::strtol(v, &end, 10), ok = *end == 0 && *v && o.scene_rays >= 1; break;
        case OPT_TRIANGLE: {
            std::string m = v;
            o.kernel = true;
            o.tri = m == "moller" ? RF_TRIANGLE_MOLLER : m == "script" ? RF_TRIANGLE_SCRIPT : RF_TRIANGLE_WATERTIGHT;
            ok = m == "moller" || m == "script" || m == "watertight";
            break;
        }
        case OPT_SPHERE:
            o.kernel = true;
            o.sph = std::string(v) == "script" ? RF_SPHERE_SCRIPT : RF_SPHERE_STABLE;
            ok = std::string(v) == "script" || std::string(v) == "stable";
            break;
        case OPT_CONE_BOUND:
            o.cone_geometric = std::string(v) == "geometric";
            ok = o.cone_geometric || std::string(v) == "kernel";
            break;
        case OPT_FIXED_OFFSET: o.fixed_offset = std::strtod(v, &end), ok = *end == 0 && *v && o.fixed_offset >= 0; break;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    char **ops;
    int nops = rf_opt_operands(&p, &ops);
    for (int i = 0; i < nops; i++)
        scenes.push_back(ops[i]);
    for (const std::string &c : classes)
        if (std::find(std::begin(kAllClasses), std::end(kAllClasses), c) == std::end(kAllClasses) &&
            c.compare(0, 6, "scene:") != 0) {
            return rf_opt_usage_error(&verify_cmd, "unknown class '%s'", c.c_str());
        }
    if (o.scene_rays <= 0)
        o.scene_rays = std::max(1L, o.rays / 50);
    std::unique_ptr<World> fw;
    if (scenes.size() == 1 && !stress) { // one scene: a row per class over it
        o.scene = scenes[0];
        fw.reset(new World);
        std::string err;
        int code = RF_EXIT_FILE;
        if (!load_world(o.scene, *fw, &err, &code)) {
            fprintf(stderr, "refray-verify: %s\n", err.c_str());
            return code;
        }
        if (classes.empty())
            classes.assign(std::begin(kFileClasses), std::end(kFileClasses));
        for (const std::string &c : classes)
            if (std::find(std::begin(kFileClasses), std::end(kFileClasses), c) == std::end(kFileClasses)) {
                return rf_opt_usage_error(&verify_cmd, "class '%s' runs on built-in scenes only", c.c_str());
            }
    } else {
        if (stress || (classes.empty() && scenes.empty()))
            classes.assign(std::begin(kAllClasses), std::end(kAllClasses));
        for (const char *sc : scenes) // several scenes, or --stress: one aggregated row each
            classes.push_back(std::string("scene:") + sc);
    }
    std::vector<Stats> rows = run_all(classes, o, jobs, fw.get());
    printf("refray-verify: %s, %ld rays per class (%ld per class in scene rows), seed %llu%s\n",
           o.scene ? o.scene : "built-in scenes", o.rays, o.scene_rays, (unsigned long long)o.seed,
           o.kernel ? " (kernel mode: planted methods)" : "");
    if (o.fixed_offset > 0)
        printf("planted: fixed self-intersection offset %g\n", o.fixed_offset);
    if (o.cone_geometric)
        printf("cones judged by the geometric bound (--cone-bound geometric)\n");
    print_table(rows, stdout);
    long real = 0;
    int errors = 0;
    for (const Stats &s : rows) {
        real += s.real;
        if (s.error) {
            errors++;
            fprintf(stderr, "refray-verify: %s\n", s.error_msg);
        }
    }
    if (real)
        printf("FAIL: real disagreements\n");
    else if (errors)
        printf("ERROR: %d row%s could not run (see above)\n", errors, errors > 1 ? "s" : "");
    else
        printf("OK: no real disagreement\n");
    return real || errors ? RF_EXIT_FAIL : RF_EXIT_OK;
}

} // namespace
} // namespace rv

int main(int argc, char **argv)
{
    // the last line of defence: no exception ends the process with an abort
    try {
        return rv::verify_main(argc, argv);
    } catch (const std::bad_alloc &) {
        fprintf(stderr, "refray-verify: out of memory\n");
    } catch (const std::exception &e) {
        fprintf(stderr, "refray-verify: internal error: %s\n", e.what());
    }
    return 2;
}
