// refray-make-mesh: the `mesh` benchmark's triangles (shared/bench/SCENES.md §1), made
// reproducibly from Debian's libcgal-demo: the closed bunny data/meshes/bunny00.off (75,408
// triangles) with two levels of Loop subdivision by CGAL (1,206,528 triangles, 603,266
// vertices), written as a plain OBJ (`v x y z` with 6 decimals, `f a b c`, `s off`: flat).
// Usage: refray-make-mesh IN.off OUT.obj [levels]. Writes OUT.obj atomically (temporary + rename).
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

typedef CGAL::Simple_cartesian<double> Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Mesh;

int main(int argc, char **argv)
{
    if (argc < 3 || argc > 4) {
        std::fprintf(stderr, "usage: refray-make-mesh IN.off OUT.obj [levels, default 2]\n");
        return 2;
    }
    int levels = argc == 4 ? std::atoi(argv[3]) : 2;
    Mesh mesh;
    std::ifstream in(argv[1]);
    if (!in || !CGAL::IO::read_OFF(in, mesh) || mesh.is_empty() || !CGAL::is_triangle_mesh(mesh)) {
        std::fprintf(stderr, "refray-make-mesh: %s: cannot read a triangle mesh (OFF)\n", argv[1]);
        return 1;
    }
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(levels));
    std::string tmp = std::string(argv[2]) + ".tmp";
    std::FILE *f = std::fopen(tmp.c_str(), "w");
    if (!f) {
        std::perror(tmp.c_str());
        return 1;
    }
    std::fprintf(f, "# %s with %d levels of Loop subdivision (CGAL), by refray-make-mesh\n"
                    "# %zu vertices, %zu triangles\ns off\n",
                 argv[1], levels, (size_t)mesh.number_of_vertices(), (size_t)mesh.number_of_faces());
    // Surface_mesh indices are dense after subdivision (no removed elements)
    for (Mesh::Vertex_index v : mesh.vertices()) {
        const Kernel::Point_3 &p = mesh.point(v);
        std::fprintf(f, "v %.6f %.6f %.6f\n", p.x(), p.y(), p.z());
    }
    for (Mesh::Face_index fc : mesh.faces()) {
        std::fputc('f', f);
        for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(fc), mesh))
            std::fprintf(f, " %u", (unsigned)v + 1);
        std::fputc('\n', f);
    }
    if (std::fclose(f) != 0 || std::rename(tmp.c_str(), argv[2]) != 0) {
        std::perror(argv[2]);
        std::remove(tmp.c_str());
        return 1;
    }
    return 0;
}
