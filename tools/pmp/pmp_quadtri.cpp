// pmp_quadtri: runs pmp-library's quad_tri_subdivision on an OBJ file, for the reference
// fixtures of tests/pmp_agreement.rs (see DEVELOPERS.md, "Reference fixtures (pmp-library)").
//
//   pmp_quadtri [--levels N] [--preserve-boundary] INPUT.obj [-o OUTPUT.obj]
//
// Our own program: pmp's SurfaceMesh and quad_tri_subdivision are compiled from pmp-library's
// source (tools/pmp/make_fixtures.sh says which commit), nothing of pmp is in this file. The OBJ
// reading and writing are ours rather than pmp's io module, which would pull in most of the
// library: the mesh is built with add_vertex/add_face in file order, so pmp's vertex i is the
// file's vertex i, and the result is written in pmp's own vertex and face order.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pmp/surface_mesh.h"
#include "pmp/algorithms/subdivision.h"

namespace {

[[noreturn]] void fail(const std::string& message)
{
    std::cerr << "pmp_quadtri: " << message << "\n";
    std::exit(1);
}

// "i", "i/t", "i//n" or "i/t/n", 1-based or negative (relative to the vertices read so far).
size_t parse_index(const std::string& word, size_t vertices_so_far, size_t line)
{
    const std::string head = word.substr(0, word.find('/'));
    char* end = nullptr;
    const long value = std::strtol(head.c_str(), &end, 10);
    if (head.empty() || *end != '\0' || value == 0)
        fail("line " + std::to_string(line) + ": bad face index '" + word + "'");
    const long index = value > 0 ? value - 1 : static_cast<long>(vertices_so_far) + value;
    if (index < 0 || static_cast<size_t>(index) >= vertices_so_far)
        fail("line " + std::to_string(line) + ": face index '" + word + "' out of range");
    return static_cast<size_t>(index);
}

pmp::SurfaceMesh read_obj(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        fail("cannot read " + path);
    pmp::SurfaceMesh mesh;
    std::vector<pmp::Vertex> vertices;
    std::string text;
    size_t line = 0;
    while (std::getline(in, text))
    {
        ++line;
        std::istringstream words(text);
        std::string tag;
        words >> tag;
        if (tag == "v")
        {
            // Read as float, as pmp stores them (Scalar = float) and as our reader does.
            pmp::Scalar x, y, z;
            if (!(words >> x >> y >> z))
                fail("line " + std::to_string(line) + ": bad vertex");
            vertices.push_back(mesh.add_vertex(pmp::Point(x, y, z)));
        }
        else if (tag == "f")
        {
            std::vector<pmp::Vertex> face;
            std::string word;
            while (words >> word)
                face.push_back(vertices[parse_index(word, vertices.size(), line)]);
            if (face.size() < 3)
                fail("line " + std::to_string(line) + ": a face needs three vertices");
            try
            {
                mesh.add_face(face);
            }
            catch (const std::exception& e)
            {
                fail("line " + std::to_string(line) + ": " + e.what());
            }
        }
    }
    return mesh;
}

void write_obj(const pmp::SurfaceMesh& mesh, std::FILE* out)
{
    for (auto v : mesh.vertices())
    {
        const pmp::Point& p = mesh.position(v);
        std::fprintf(out, "v %.9g %.9g %.9g\n", p[0], p[1], p[2]);
    }
    for (auto f : mesh.faces())
    {
        std::fputc('f', out);
        for (auto v : mesh.vertices(f))
            std::fprintf(out, " %u", static_cast<unsigned>(v.idx()) + 1);
        std::fputc('\n', out);
    }
}

} // namespace

int main(int argc, char** argv)
{
    int levels = 1;
    auto boundary = pmp::BoundaryHandling::Interpolate;
    std::string input, output;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "--levels" && i + 1 < argc)
            levels = std::atoi(argv[++i]);
        else if (arg == "--preserve-boundary")
            boundary = pmp::BoundaryHandling::Preserve;
        else if (arg == "-o" && i + 1 < argc)
            output = argv[++i];
        else if (!arg.empty() && arg[0] != '-' && input.empty())
            input = arg;
        else
            fail("usage: pmp_quadtri [--levels N] [--preserve-boundary] INPUT.obj [-o OUTPUT.obj]");
    }
    if (input.empty() || levels < 0)
        fail("usage: pmp_quadtri [--levels N] [--preserve-boundary] INPUT.obj [-o OUTPUT.obj]");

    pmp::SurfaceMesh mesh = read_obj(input);
    for (int level = 0; level < levels; ++level)
        pmp::quad_tri_subdivision(mesh, boundary);

    std::FILE* out = output.empty() ? stdout : std::fopen(output.c_str(), "w");
    if (!out)
        fail("cannot write " + output);
    write_obj(mesh, out);
    if (out != stdout && std::fclose(out) != 0)
        fail("cannot write " + output);
    return 0;
}
