// osd_refine: uniform refinement of an OBJ mesh with OpenSubdiv's Far layer, written as OBJ.
//
// Our own reference tool for subsurf's fixtures (see DEVELOPERS.md, "Reference fixtures").
// It reads `v` and `f` lines (any of the v, v/vt, v//vn, v/vt/vn forms, negative indices too) and
// OpenSubdiv regression `t` tag lines (`t NAME nint/nfloat/nstring ints floats strings`), builds a
// Far::TopologyRefiner from a Far::TopologyDescriptor, refines it uniformly, interpolates the
// positions level by level in double precision with Far::PrimvarRefinerReal<double>, and writes the last
// level: every vertex (`v`, %.17g) and every face that is not a hole (`f`, 1-based), both in
// OpenSubdiv's own order.
//
//   osd_refine [--scheme catmark|loop|bilinear] [--levels N]
//              [--boundary edge-and-corner|edge-only|none] [--ignore-tags]
//              [--fvar-linear MODE] [--no-positions] [--varying] [--limit] [--no-normals]
//              [--time REPEATS] [--color] [--no-output] [--quiet] INPUT.obj [-o OUTPUT.obj]
//
// Face-varying data: with --fvar-linear MODE (our kebab-case names of Sdc::Options::
// FVarLinearInterpolation: none, corners-only, corners-plus1, corners-plus2, boundaries, all) the
// file's `vt` lines (u v) and the vt index of every face corner (`v/vt`, `v/vt/vn`, negative
// indices too) become face-varying channel 0, refined level by level with
// PrimvarRefinerReal<double>::InterpolateFaceVarying; the output then has `vt` lines (%.10g, ten
// digits, as the tests compare to 1e-5: the last level's values in OpenSubdiv's order) and `f v/vt` corners. --no-positions leaves out the
// `v` lines (the face-varying fixtures carry only what the position fixtures do not). The
// shapes' own facevaryinginterpolateboundary and facevaryingpropagatecorners tags are ignored:
// MODE decides.
//
// Boundary interpolation: --boundary wins; otherwise the file's `interpolateboundary` tag
// (0 none, 1 edge-and-corner, 2 edge-only); otherwise edge-only, the default of OpenSubdiv's
// regression suite (regression/common/far_utils.h, GetSdcOptions), for which these shapes were
// written. --ignore-tags drops crease, corner, hole, creasemethod and smoothtriangles tags; it
// keeps interpolateboundary (which --boundary overrides anyway).
//
// --varying interpolates the positions as varying data (PrimvarRefinerReal<double>::
// InterpolateVarying): linearly on the scheme's topology, each child vertex of a vertex at the
// vertex, of an edge at its midpoint, of a face at its centroid, whatever the sharpness. With
// --scheme loop that is midpoint subdivision (Loop's topology, linear positions), which
// OpenSubdiv has no scheme of its own for.
//
// --limit evaluates the last level at the limit: after the interpolation,
// PrimvarRefinerReal<double>::Limit(src, dstPos, dstTan1, dstTan2) on the last level's positions;
// the `v` lines are then the limit positions (%.9g: the tests compare to 1e-5 of the size) and
// each vertex gets a `vn` line (%.6g): the
// cross product tan1 x tan2, normalised, or `vn 0 0 0` where the tangents are degenerate (zero,
// or |tan1 x tan2| < 1e-6 |tan1| |tan2|: no plane). With --fvar-linear MODE too, the last level's
// face-varying values are also taken to the limit (PrimvarRefinerReal<double>::LimitFaceVarying)
// and those are the `vt` lines (same order, same count, same `f v/vt` corners). --no-normals
// leaves out the `vn` lines (the face-varying limit fixtures: the limit fixtures have the normals).
// --limit with --varying is refused.
//
// --time R refines and interpolates R times and prints, to stderr, the best and median wall
// time of RefineUniform, of all PrimvarRefiner::Interpolate calls (with the allocation of the
// per-level position arrays), and of the two together; the refiner's construction from the
// descriptor (TopologyRefinerFactory::Create) is timed separately, last run only. --no-output skips writing the result (for timing).
// With --fvar-linear, the timed interpolation includes InterpolateFaceVarying of the `vt` values,
// and --color adds to the timed runs a vertex-varying channel of three floats per vertex
// ((i mod 7) / 7, as subsurf's attribute benchmark makes it) interpolated after the positions: the two channels of
// subsurf's uv + colour target (benches/table.rs), so that OpenSubdiv's own cost for them can be
// set beside ours. Each run's create, refine and interpolation are timed, and their sum.

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/version.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

// The precision of the positions and of PrimvarRefiner's weights: double for the fixtures;
// built with -DOSD_REAL=float (tools/osd/build.sh FLOAT=1) to see what OpenSubdiv's float path
// gives, as a renderer would run it.
#ifndef OSD_REAL
#define OSD_REAL double
#endif
using Real = OSD_REAL;

// A position, as PrimvarRefiner's interface wants it.
struct Point3 {
    Real p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(Point3 const & src, Real weight) {
        p[0] += weight * src.p[0];
        p[1] += weight * src.p[1];
        p[2] += weight * src.p[2];
    }
};

// A face-varying value (u, v) in double precision.
struct Point2 {
    double p[2];
    void Clear(void * = nullptr) { p[0] = p[1] = 0.0; }
    void AddWithWeight(Point2 const & src, double weight) {
        p[0] += weight * src.p[0];
        p[1] += weight * src.p[1];
    }
};

struct Tag {
    std::string name;
    std::vector<int> ints;
    std::vector<float> floats;
    std::vector<std::string> strings;
    int line;
};

struct Mesh {
    std::vector<double> positions;  // x y z per vertex
    std::vector<int> faceSizes;
    std::vector<int> faceIndices;   // 0-based
    std::vector<double> uvs;        // u v per vt line
    std::vector<int> uvIndices;     // 0-based, one per face corner; -1 where a corner has none
    std::vector<Tag> tags;
};

[[noreturn]] void fail(std::string const & message) {
    std::fprintf(stderr, "osd_refine: %s\n", message.c_str());
    std::exit(1);
}

std::string at(std::string const & path, int line) {
    return path + ":" + std::to_string(line) + ": ";
}

Mesh readObj(std::string const & path) {
    std::ifstream in(path);
    if (!in) fail("cannot open '" + path + "'");
    Mesh mesh;
    std::string raw;
    int lineNo = 0;
    while (std::getline(in, raw)) {
        ++lineNo;
        std::string line = raw.substr(0, raw.find('#'));
        std::istringstream words(line);
        std::string kind;
        if (!(words >> kind)) continue;
        if (kind == "v") {
            double xyz[3];
            for (double & c : xyz) {
                std::string w;
                if (!(words >> w)) fail(at(path, lineNo) + "'v' needs x y z");
                char * end = nullptr;
                c = std::strtod(w.c_str(), &end);
                if (*end != 0) fail(at(path, lineNo) + "'" + w + "' is not a number");
            }
            mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
        } else if (kind == "f") {
            int count = 0;
            std::string w;
            int numVertices = (int)mesh.positions.size() / 3;
            while (words >> w) {
                std::string first = w.substr(0, w.find('/'));
                char * end = nullptr;
                long v = std::strtol(first.c_str(), &end, 10);
                if (first.empty() || *end != 0 || v == 0)
                    fail(at(path, lineNo) + "'" + w + "' is not a face index");
                long index = v > 0 ? v - 1 : numVertices + v;
                if (index < 0) fail(at(path, lineNo) + "relative index reaches before vertex 1");
                mesh.faceIndices.push_back((int)index);
                size_t slash = w.find('/');
                std::string second = slash == std::string::npos ? "" : w.substr(slash + 1);
                second = second.substr(0, second.find('/'));
                if (second.empty()) {
                    mesh.uvIndices.push_back(-1);
                } else {
                    long t = std::strtol(second.c_str(), &end, 10);
                    if (*end != 0 || t == 0) fail(at(path, lineNo) + "'" + w + "' has a bad vt index");
                    long numUvs = (long)mesh.uvs.size() / 2;
                    long uv = t > 0 ? t - 1 : numUvs + t;
                    if (uv < 0) fail(at(path, lineNo) + "relative vt index reaches before vt 1");
                    mesh.uvIndices.push_back((int)uv);
                }
                ++count;
            }
            if (count < 3) fail(at(path, lineNo) + "a face needs at least 3 vertices");
            mesh.faceSizes.push_back(count);
        } else if (kind == "vt") {
            double uv[2];
            for (double & c : uv) {
                std::string w;
                if (!(words >> w)) fail(at(path, lineNo) + "'vt' needs u v");
                char * end = nullptr;
                c = std::strtod(w.c_str(), &end);
                if (*end != 0) fail(at(path, lineNo) + "'" + w + "' is not a number");
            }
            mesh.uvs.insert(mesh.uvs.end(), uv, uv + 2);
        } else if (kind == "t") {
            Tag tag;
            tag.line = lineNo;
            std::string counts;
            if (!(words >> tag.name >> counts)) fail(at(path, lineNo) + "bad 't' line");
            int ni = 0, nf = 0, ns = 0;
            if (std::sscanf(counts.c_str(), "%d/%d/%d", &ni, &nf, &ns) != 3)
                fail(at(path, lineNo) + "tag counts '" + counts + "' are not nint/nfloat/nstring");
            for (int i = 0; i < ni; ++i) {
                int x;
                if (!(words >> x)) fail(at(path, lineNo) + "tag has too few integers");
                tag.ints.push_back(x);
            }
            for (int i = 0; i < nf; ++i) {
                float x;
                if (!(words >> x)) fail(at(path, lineNo) + "tag has too few floats");
                tag.floats.push_back(x);
            }
            for (int i = 0; i < ns; ++i) {
                std::string x;
                if (!(words >> x)) fail(at(path, lineNo) + "tag has too few strings");
                tag.strings.push_back(x);
            }
            mesh.tags.push_back(tag);
        }
    }
    int numVertices = (int)mesh.positions.size() / 3;
    if (numVertices == 0) fail(path + ": no vertices");
    if (mesh.faceSizes.empty()) fail(path + ": no faces");
    for (int v : mesh.faceIndices)
        if (v >= numVertices) fail(path + ": a face refers to vertex " + std::to_string(v + 1) +
                                   " of " + std::to_string(numVertices));
    int numUvs = (int)mesh.uvs.size() / 2;
    for (int t : mesh.uvIndices)
        if (t >= numUvs) fail(path + ": a face refers to vt " + std::to_string(t + 1) + " of " +
                              std::to_string(numUvs));
    return mesh;
}

// One sharpness per item, or one for all (the regression shapes' convention).
float weightOf(Tag const & tag, size_t item) {
    if (tag.floats.empty()) return 0.0f;
    float w = tag.floats.size() > 1 ? tag.floats[std::min(item, tag.floats.size() - 1)] : tag.floats[0];
    return std::max(0.0f, w);
}

void usage(int code) {
    std::fprintf(code ? stderr : stdout,
                 "usage: osd_refine [--scheme catmark|loop|bilinear] [--levels N]\n"
                 "                  [--boundary edge-and-corner|edge-only|none] [--ignore-tags]\n"
                 "                  [--fvar-linear none|corners-only|corners-plus1|corners-plus2|boundaries|all]\n"
                 "                  [--no-positions] [--varying] [--limit] [--no-normals]\n"
                 "                  [--time REPEATS] [--color] [--no-output] [--quiet] INPUT.obj [-o OUTPUT.obj]\n");
    std::exit(code);
}

}  // namespace

int main(int argc, char ** argv) {
    Sdc::SchemeType scheme = Sdc::SCHEME_CATMARK;
    int levels = 1;
    int boundaryOverride = -1;  // Sdc::Options::VtxBoundaryInterpolation, or -1
    bool ignoreTags = false, quiet = false, noOutput = false, noPositions = false, varying = false;
    bool limit = false, noNormals = false, color = false;
    int fvarMode = -1;  // Sdc::Options::FVarLinearInterpolation, or -1 for no face-varying data
    int repeats = 0;
    std::string input, output;

    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) fail(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--scheme") {
            std::string s = value();
            if (s == "catmark") scheme = Sdc::SCHEME_CATMARK;
            else if (s == "loop") scheme = Sdc::SCHEME_LOOP;
            else if (s == "bilinear") scheme = Sdc::SCHEME_BILINEAR;
            else fail("unknown scheme '" + s + "'");
        } else if (arg == "--levels") {
            levels = std::atoi(value().c_str());
            if (levels < 0 || levels > 15) fail("--levels must be 0..15");
        } else if (arg == "--boundary") {
            std::string s = value();
            if (s == "edge-and-corner") boundaryOverride = Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER;
            else if (s == "edge-only") boundaryOverride = Sdc::Options::VTX_BOUNDARY_EDGE_ONLY;
            else if (s == "none") boundaryOverride = Sdc::Options::VTX_BOUNDARY_NONE;
            else fail("unknown boundary '" + s + "'");
        } else if (arg == "--fvar-linear") {
            std::string s = value();
            if (s == "none") fvarMode = Sdc::Options::FVAR_LINEAR_NONE;
            else if (s == "corners-only") fvarMode = Sdc::Options::FVAR_LINEAR_CORNERS_ONLY;
            else if (s == "corners-plus1") fvarMode = Sdc::Options::FVAR_LINEAR_CORNERS_PLUS1;
            else if (s == "corners-plus2") fvarMode = Sdc::Options::FVAR_LINEAR_CORNERS_PLUS2;
            else if (s == "boundaries") fvarMode = Sdc::Options::FVAR_LINEAR_BOUNDARIES;
            else if (s == "all") fvarMode = Sdc::Options::FVAR_LINEAR_ALL;
            else fail("unknown --fvar-linear mode '" + s + "'");
        } else if (arg == "--no-positions") {
            noPositions = true;
        } else if (arg == "--varying") {
            varying = true;
        } else if (arg == "--limit") {
            limit = true;
        } else if (arg == "--no-normals") {
            noNormals = true;
        } else if (arg == "--ignore-tags") {
            ignoreTags = true;
        } else if (arg == "--time") {
            repeats = std::max(1, std::atoi(value().c_str()));
        } else if (arg == "--color") {
            color = true;
        } else if (arg == "--no-output") {
            noOutput = true;
        } else if (arg == "--quiet") {
            quiet = true;
        } else if (arg == "-o" || arg == "--output") {
            output = value();
        } else if (arg == "-h" || arg == "--help") {
            usage(0);
        } else if (arg.size() > 1 && arg[0] == '-') {
            std::fprintf(stderr, "osd_refine: unknown option '%s'\n", arg.c_str());
            usage(2);
        } else {
            if (!input.empty()) fail("more than one input file");
            input = arg;
        }
    }
    if (input.empty()) usage(2);
    if (limit && varying) fail("--limit does not go with --varying");

    Mesh mesh = readObj(input);

    Sdc::Options sdcOptions;
    sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdcOptions.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
    sdcOptions.SetTriangleSubdivision(Sdc::Options::TRI_SUB_CATMARK);

    std::vector<Far::Index> creasePairs, corners, holes;
    std::vector<float> creaseWeights, cornerWeights;
    int numVertices = (int)mesh.positions.size() / 3;
    int numFaces = (int)mesh.faceSizes.size();
    for (Tag const & t : mesh.tags) {
        std::string where = at(input, t.line);
        if (t.name == "vertexedit" || t.name == "edgeedit" || t.name == "faceedit") {
            if (!quiet) std::fprintf(stderr, "osd_refine: warning: %shierarchical edit '%s' ignored (Far has none)\n",
                                     where.c_str(), t.name.c_str());
            continue;
        }
        if (t.name == "facevaryinginterpolateboundary" || t.name == "facevaryingpropagatecorners") {
            continue;  // --fvar-linear decides the face-varying rules
        }
        if (t.name == "interpolateboundary") {
            if (t.ints.size() != 1) fail(where + "interpolateboundary needs one integer");
            switch (t.ints[0]) {
                case 0: sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE); break;
                case 1: sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER); break;
                case 2: sdcOptions.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY); break;
                default: fail(where + "interpolateboundary must be 0, 1 or 2");
            }
        } else if (t.name == "crease") {
            if (ignoreTags) continue;
            if (t.ints.size() % 2) fail(where + "crease needs vertex pairs");
            for (size_t j = 0; j + 1 < t.ints.size(); j += 2) {
                if (t.ints[j] < 0 || t.ints[j] >= numVertices || t.ints[j + 1] < 0 || t.ints[j + 1] >= numVertices)
                    fail(where + "crease vertex out of range");
                creasePairs.push_back(t.ints[j]);
                creasePairs.push_back(t.ints[j + 1]);
                creaseWeights.push_back(weightOf(t, j / 2));
            }
        } else if (t.name == "corner") {
            if (ignoreTags) continue;
            for (size_t j = 0; j < t.ints.size(); ++j) {
                if (t.ints[j] < 0 || t.ints[j] >= numVertices) fail(where + "corner vertex out of range");
                corners.push_back(t.ints[j]);
                cornerWeights.push_back(weightOf(t, j));
            }
        } else if (t.name == "hole") {
            if (ignoreTags) continue;
            for (int f : t.ints) {
                if (f < 0 || f >= numFaces) fail(where + "hole face out of range");
                holes.push_back(f);
            }
        } else if (t.name == "creasemethod") {
            if (ignoreTags) continue;
            if (t.strings.size() != 1) fail(where + "creasemethod needs one string");
            if (t.strings[0] == "normal") sdcOptions.SetCreasingMethod(Sdc::Options::CREASE_UNIFORM);
            else if (t.strings[0] == "chaikin") sdcOptions.SetCreasingMethod(Sdc::Options::CREASE_CHAIKIN);
            else fail(where + "creasemethod must be normal or chaikin");
        } else if (t.name == "smoothtriangles") {
            if (ignoreTags) continue;
            if (t.strings.size() != 1) fail(where + "smoothtriangles needs one string");
            if (t.strings[0] == "catmark") sdcOptions.SetTriangleSubdivision(Sdc::Options::TRI_SUB_CATMARK);
            else if (t.strings[0] == "smooth") sdcOptions.SetTriangleSubdivision(Sdc::Options::TRI_SUB_SMOOTH);
            else fail(where + "smoothtriangles must be catmark or smooth");
        } else if (!quiet) {
            std::fprintf(stderr, "osd_refine: warning: %sunknown tag '%s' ignored\n", where.c_str(), t.name.c_str());
        }
    }
    if (boundaryOverride >= 0)
        sdcOptions.SetVtxBoundaryInterpolation((Sdc::Options::VtxBoundaryInterpolation)boundaryOverride);
    bool fvar = fvarMode >= 0;
    if (fvar) {
        if (mesh.uvs.empty()) fail(input + ": --fvar-linear needs vt lines");
        for (int t : mesh.uvIndices)
            if (t < 0) fail(input + ": --fvar-linear needs a vt index on every face corner");
        sdcOptions.SetFVarLinearInterpolation((Sdc::Options::FVarLinearInterpolation)fvarMode);
    }

    Far::TopologyDescriptor desc;
    desc.numVertices = numVertices;
    desc.numFaces = numFaces;
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.faceIndices.data();
    desc.numCreases = (int)creaseWeights.size();
    desc.creaseVertexIndexPairs = creasePairs.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = (int)corners.size();
    desc.cornerVertexIndices = corners.data();
    desc.cornerWeights = cornerWeights.data();
    desc.numHoles = (int)holes.size();
    desc.holeIndices = holes.data();
    Far::TopologyDescriptor::FVarChannel uvChannel;
    if (fvar) {
        uvChannel.numValues = (int)mesh.uvs.size() / 2;
        uvChannel.valueIndices = mesh.uvIndices.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &uvChannel;
    }

    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    typedef std::chrono::steady_clock Clock;
    auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };

    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<std::vector<Point3>> perLevel;
    std::vector<double> refineTimes, interpolateTimes, totalTimes, wholeTimes;
    double buildTime = 0;
    // The face-varying values, level by level, with a PrimvarRefiner of either precision: in the
    // timed runs (with --time) and for the output.
    std::vector<std::vector<Point2>> uvLevels;
    auto interpolateUvs = [&](auto const & primvar) {
        uvLevels.assign(levels + 1, std::vector<Point2>());
        uvLevels[0].resize(mesh.uvs.size() / 2);
        for (size_t t = 0; t < uvLevels[0].size(); ++t)
            for (int k = 0; k < 2; ++k) uvLevels[0][t].p[k] = mesh.uvs[2 * t + k];
        for (int level = 1; level <= levels; ++level) {
            uvLevels[level].resize(refiner->GetLevel(level).GetNumFVarValues(0));
            Point2 const * src = uvLevels[level - 1].data();
            Point2 * dst = uvLevels[level].data();
            primvar.InterpolateFaceVarying(level, src, dst, 0);
        }
    };
    std::vector<std::vector<Point3>> colorLevels;  // --color, in the timed runs
    for (int run = 0; run < std::max(1, repeats); ++run) {
        Clock::time_point t0 = Clock::now();
        refiner.reset(Factory::Create(desc, Factory::Options(scheme, sdcOptions)));
        if (!refiner) fail(input + ": OpenSubdiv refused the mesh (see its message above)");
        Clock::time_point t1 = Clock::now();

        Far::TopologyRefiner::UniformOptions uniform(levels);
        uniform.fullTopologyInLastLevel = limit;  // Limit needs the last level's vertex edges
        refiner->RefineUniform(uniform);
        Clock::time_point t2 = Clock::now();
        perLevel.assign(levels + 1, std::vector<Point3>());
        perLevel[0].resize(numVertices);
        for (int v = 0; v < numVertices; ++v)
            for (int k = 0; k < 3; ++k) perLevel[0][v].p[k] = mesh.positions[3 * v + k];
        Far::PrimvarRefinerReal<Real> primvar(*refiner);  // the weights in that precision too
        for (int level = 1; level <= levels; ++level) {
            perLevel[level].resize(refiner->GetLevel(level).GetNumVertices());
            Point3 const * src = perLevel[level - 1].data();
            Point3 * dst = perLevel[level].data();
            if (varying) {
                primvar.InterpolateVarying(level, src, dst);
            } else {
                primvar.Interpolate(level, src, dst);
            }
        }
        if (repeats > 0 && color) {
            colorLevels.assign(levels + 1, std::vector<Point3>());
            colorLevels[0].resize(numVertices);
            for (int v = 0; v < numVertices; ++v)
                for (int k = 0; k < 3; ++k) colorLevels[0][v].p[k] = (Real)((3 * v + k) % 7) / 7;
            for (int level = 1; level <= levels; ++level) {
                colorLevels[level].resize(refiner->GetLevel(level).GetNumVertices());
                Point3 const * src = colorLevels[level - 1].data();
                Point3 * dst = colorLevels[level].data();
                primvar.Interpolate(level, src, dst);
            }
        }
        if (repeats > 0 && fvar) interpolateUvs(primvar);
        Clock::time_point t3 = Clock::now();
        buildTime = seconds(t1 - t0);
        wholeTimes.push_back(seconds(t3 - t0));
        refineTimes.push_back(seconds(t2 - t1));
        interpolateTimes.push_back(seconds(t3 - t2));
        totalTimes.push_back(seconds(t3 - t1));
    }
    if (repeats > 0) {
        auto best = [](std::vector<double> v) { return *std::min_element(v.begin(), v.end()); };
        auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        Far::TopologyLevel const & last = refiner->GetLevel(levels);
        std::fprintf(stderr,
                     "osd_refine: %s level %d: %d vertices, %d faces; %d runs, best (median) seconds:\n"
                     "  create (TopologyRefinerFactory::Create) %.6f\n"
                     "  refine (RefineUniform)                  %.6f (%.6f)\n"
                     "  interpolate (PrimvarRefiner, %-6s)    %.6f (%.6f)\n"
                     "  refine + interpolate                    %.6f (%.6f)\n"
                     "  create + refine + interpolate           %.6f (%.6f)\n",
                     input.c_str(), levels, last.GetNumVertices(), last.GetNumFaces(), (int)totalTimes.size(),
                     buildTime, best(refineTimes), median(refineTimes), sizeof(Real) == 4 ? "float" : "double",
                     best(interpolateTimes),
                     median(interpolateTimes), best(totalTimes), median(totalTimes), best(wholeTimes),
                     median(wholeTimes));
    }

    // The output's face-varying values in double whatever the positions' precision (as the
    // fixtures always were), again after any timed runs.
    if (fvar) interpolateUvs(Far::PrimvarRefinerReal<double>(*refiner));

    // The limit of the last level (after any timing too).
    std::vector<Point3> limitPoints, tan1, tan2;
    if (limit) {
        size_t n = perLevel[levels].size();
        limitPoints.resize(n);
        tan1.resize(n);
        tan2.resize(n);
        Far::PrimvarRefinerReal<Real> primvar(*refiner);
        primvar.Limit(perLevel[levels].data(), limitPoints, tan1, tan2);
        if (fvar) {
            // LimitFaceVarying must not read what it writes: a separate destination.
            std::vector<Point2> limitUvs(uvLevels[levels].size());
            primvar.LimitFaceVarying(uvLevels[levels].data(), limitUvs, 0);
            uvLevels[levels].swap(limitUvs);
        }
    }

    if (noOutput) return 0;
    Far::TopologyLevel const & last = refiner->GetLevel(levels);
    std::vector<Point3> const & points = limit ? limitPoints : perLevel[levels];
    std::FILE * out = stdout;
    if (!output.empty() && output != "-") {
        out = std::fopen(output.c_str(), "w");
        if (!out) fail("cannot write '" + output + "'");
    }
    std::vector<char> buffer(1 << 20);
    std::setvbuf(out, buffer.data(), _IOFBF, buffer.size());
    if (!noPositions)
        for (Point3 const & p : points)
            std::fprintf(out, limit ? "v %.9g %.9g %.9g\n" : "v %.17g %.17g %.17g\n", p.p[0], p.p[1], p.p[2]);
    for (size_t v = 0; !noNormals && v < tan1.size(); ++v) {
        Real const * a = tan1[v].p;
        Real const * b = tan2[v].p;
        double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        if (!(length > 0.0) || length < 1e-6 * la * lb) {
            std::fprintf(out, "vn 0 0 0\n");
        } else {
            std::fprintf(out, "vn %.6g %.6g %.6g\n", n[0] / length, n[1] / length, n[2] / length);
        }
    }
    if (fvar)
        for (Point2 const & t : uvLevels[levels]) std::fprintf(out, "vt %.10g %.10g\n", t.p[0], t.p[1]);
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        std::fputc('f', out);
        if (fvar) {
            Far::ConstIndexArray ft = last.GetFaceFVarValues(f, 0);
            for (int k = 0; k < fv.size(); ++k) std::fprintf(out, " %d/%d", fv[k] + 1, ft[k] + 1);
        } else {
            for (int k = 0; k < fv.size(); ++k) std::fprintf(out, " %d", fv[k] + 1);
        }
        std::fputc('\n', out);
    }
    if (std::fflush(out) != 0 || (out != stdout && std::fclose(out) != 0)) fail("write failed");
    return 0;
}
