// cgal_subdivide: runs one of CGAL's Subdivision_method_3 schemes on an OBJ file and writes the
// result as OBJ. Our own reference program for subsurf's tests (see DEVELOPERS.md, "Reference
// fixtures (CGAL)"); it only calls CGAL's public API.
//
//   cgal_subdivide --scheme catmull-clark|loop|doo-sabin|sqrt3 --levels N INPUT.obj [-o OUTPUT.obj]
//
// Input: `v x y z` and `f i j k ...` lines (indices 1-based or negative, `i/t/n` forms allowed);
// every other line is ignored. The faces go into a CGAL::Surface_mesh with double coordinates;
// a face that would make the mesh non-manifold is an error. The whole subdivision is one call
// with `number_of_iterations(N)` (this matters for sqrt3, which refines the border only on every
// second step of one call).
//
// Output: the vertices in the mesh's order after `collect_garbage()` as `v %.17g %.17g %.17g`,
// then every face as a 1-based `f` line starting at the target of the face's halfedge. The order
// is CGAL's own; tests compare order-independently.

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Simple_cartesian<double> Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;
typedef Mesh::Vertex_index Vertex;

namespace SM3 = CGAL::Subdivision_method_3;

static int usage(const char* message) {
    std::fprintf(stderr,
                 "cgal_subdivide: %s\n"
                 "usage: cgal_subdivide --scheme catmull-clark|loop|doo-sabin|sqrt3 --levels N "
                 "INPUT.obj [-o OUTPUT.obj]\n",
                 message);
    return 2;
}

// Reads the `v` and `f` lines of an OBJ file into `mesh`. Returns an error message or "".
static std::string read_obj(const char* path, Mesh& mesh) {
    std::ifstream in(path);
    if (!in) return std::string("cannot open ") + path;
    std::vector<Vertex> vertices;
    std::string line;
    std::size_t line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        std::istringstream words(line);
        std::string tag;
        if (!(words >> tag)) continue;
        if (tag == "v") {
            double x, y, z;
            if (!(words >> x >> y >> z))
                return "line " + std::to_string(line_number) + ": a v line needs x y z";
            vertices.push_back(mesh.add_vertex(Point(x, y, z)));
        } else if (tag == "f") {
            std::vector<Vertex> face;
            std::string corner;
            while (words >> corner) {
                long index = std::strtol(corner.c_str(), nullptr, 10);
                long resolved = index < 0 ? static_cast<long>(vertices.size()) + index : index - 1;
                if (index == 0 || resolved < 0 || resolved >= static_cast<long>(vertices.size()))
                    return "line " + std::to_string(line_number) + ": bad vertex index " + corner;
                face.push_back(vertices[resolved]);
            }
            if (face.size() < 3)
                return "line " + std::to_string(line_number) + ": a face needs 3 vertices";
            if (mesh.add_face(face) == Mesh::null_face())
                return "line " + std::to_string(line_number) +
                       ": Surface_mesh refused the face (non-manifold or repeated)";
        }
    }
    return "";
}

static void write_obj(std::FILE* out, Mesh& mesh) {
    mesh.collect_garbage();
    for (Vertex v : mesh.vertices()) {
        const Point& p = mesh.point(v);
        std::fprintf(out, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    }
    for (Mesh::Face_index f : mesh.faces()) {
        std::fputc('f', out);
        for (Vertex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
            std::fprintf(out, " %u", static_cast<unsigned>(v.idx()) + 1);
        std::fputc('\n', out);
    }
}

int main(int argc, char** argv) {
    std::string scheme, input, output;
    int levels = -1;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--scheme" && i + 1 < argc) {
            scheme = argv[++i];
        } else if (arg == "--levels" && i + 1 < argc) {
            levels = std::atoi(argv[++i]);
        } else if (arg == "-o" && i + 1 < argc) {
            output = argv[++i];
        } else if (!arg.empty() && arg[0] != '-' && input.empty()) {
            input = arg;
        } else {
            return usage(("unexpected argument " + arg).c_str());
        }
    }
    if (input.empty()) return usage("no input file");
    if (levels < 0) return usage("--levels N is required (N >= 0)");

    Mesh mesh;
    std::string error = read_obj(input.c_str(), mesh);
    if (!error.empty()) {
        std::fprintf(stderr, "cgal_subdivide: %s: %s\n", input.c_str(), error.c_str());
        return 1;
    }

    const auto np = CGAL::parameters::number_of_iterations(static_cast<unsigned>(levels));
    if (scheme == "catmull-clark") {
        SM3::CatmullClark_subdivision(mesh, np);
    } else if (scheme == "loop") {
        SM3::Loop_subdivision(mesh, np);
    } else if (scheme == "doo-sabin") {
        SM3::DooSabin_subdivision(mesh, np);
    } else if (scheme == "sqrt3") {
        SM3::Sqrt3_subdivision(mesh, np);
    } else {
        return usage(("unknown scheme '" + scheme + "'").c_str());
    }

    std::FILE* out = output.empty() ? stdout : std::fopen(output.c_str(), "w");
    if (!out) {
        std::fprintf(stderr, "cgal_subdivide: cannot write %s\n", output.c_str());
        return 1;
    }
    write_obj(out, mesh);
    if (out != stdout && std::fclose(out) != 0) {
        std::fprintf(stderr, "cgal_subdivide: error writing %s\n", output.c_str());
        return 1;
    }
    return 0;
}
