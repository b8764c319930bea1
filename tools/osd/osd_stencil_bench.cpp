// osd_stencil_bench: what applying precomputed stencils costs in OpenSubdiv, as a reference for
// subsurf's stencil evaluation (see tools/osd/stencil_bench.sh).
//
//   osd_stencil_bench [--scheme catmark|loop] [--level N] [--repeats R] [--no-limit] MESH.obj
//
// Refined stencils: a Far::TopologyRefiner from the OBJ's `v` and `f` lines (no tags; boundary
// edge-and-corner), RefineUniform(N), then Far::StencilTableFactory::Create with
// interpolationMode vertex, generateIntermediateLevels = false and factorizeIntermediateLevels =
// true, so that every stencil maps the control points straight to one vertex of level N. Its
// application, Osd::CpuEvaluator::EvalStencils on plain float arrays (3 floats a vertex,
// Osd::BufferDescriptor(0, 3, 3); single-threaded), is timed R times after one warm-up run.
//
// Limit stencils (unless --no-limit): the limit position and first derivatives at every vertex of
// level N. OpenSubdiv evaluates the limit on patches, so a second refiner is refined adaptively
// (isolation level N) and Far::LimitStencilTableFactory::Create (which builds its own patch table,
// Gregory end caps) gets, for each level-N vertex, its ptex face and (s, t): found by following
// each level-N face back to its base face (a child vertex of a vertex sits where its parent does,
// of an edge at the edge's midpoint, of a face at its centroid, in (s, t)). EvalStencils with
// du and dv is timed the same way. As a check that the locations are right, the limit positions
// are compared with PrimvarRefiner::Limit on the uniformly refined level N (they agree to float
// rounding where the patches are exact, i.e. away from extraordinary vertices isolated less
// deeply than N; the worst difference is printed relative to the bounding-box diagonal).
//
// Output: one line per table on stdout, `key=value` fields separated by spaces:
//   table=refined|limit mesh= scheme= level= control_vertices= stencils= entries=
//   table_bytes= bytes_per_stencil= refine_ms= build_ms= eval_best_ms= eval_median_ms=
//   ns_per_stencil= [limit_check=]
// table_bytes counts the arrays as OpenSubdiv stores them: int sizes, int offsets, int indices and
// float weights (limit: and float du and dv weights). refine_ms is RefineUniform (refined) or
// RefineAdaptive (limit); build_ms the stencil factory alone; ns_per_stencil the median
// evaluation over the number of stencils.

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/osd/bufferDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

typedef std::chrono::steady_clock Clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

[[noreturn]] void fail(std::string const & message) {
    std::fprintf(stderr, "osd_stencil_bench: %s\n", message.c_str());
    std::exit(1);
}

struct Mesh {
    std::vector<float> positions;
    std::vector<int> faceSizes;
    std::vector<int> faceIndices;
};

Mesh readObj(std::string const & path) {
    std::ifstream in(path);
    if (!in) fail("cannot open '" + path + "'");
    Mesh mesh;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string kind;
        if (!(words >> kind)) continue;
        if (kind == "v") {
            float x, y, z;
            if (!(words >> x >> y >> z)) fail(path + ": bad 'v' line: " + line);
            mesh.positions.insert(mesh.positions.end(), {x, y, z});
        } else if (kind == "f") {
            int count = 0;
            std::string w;
            long numVertices = (long)mesh.positions.size() / 3;
            while (words >> w) {
                long v = std::strtol(w.c_str(), nullptr, 10);
                long index = v > 0 ? v - 1 : numVertices + v;
                if (v == 0 || index < 0 || index >= numVertices) fail(path + ": bad face index in: " + line);
                mesh.faceIndices.push_back((int)index);
                ++count;
            }
            if (count < 3) fail(path + ": a face needs 3 vertices: " + line);
            mesh.faceSizes.push_back(count);
        }
    }
    if (mesh.faceSizes.empty()) fail(path + ": no faces");
    return mesh;
}

Far::TopologyRefiner * makeRefiner(Mesh const & mesh, Sdc::SchemeType scheme) {
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    Far::TopologyDescriptor desc;
    desc.numVertices = (int)mesh.positions.size() / 3;
    desc.numFaces = (int)mesh.faceSizes.size();
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.faceIndices.data();
    typedef Far::TopologyRefinerFactory<Far::TopologyDescriptor> Factory;
    Far::TopologyRefiner * refiner = Factory::Create(desc, Factory::Options(scheme, options));
    if (!refiner) fail("OpenSubdiv refused the mesh");
    return refiner;
}

struct Timing {
    double best, median;
};

template <class F>
Timing timeRuns(int repeats, F run) {
    run();  // warm-up: page in the tables and the destination
    std::vector<double> ms;
    for (int r = 0; r < repeats; ++r) {
        Clock::time_point t0 = Clock::now();
        run();
        ms.push_back(msSince(t0));
    }
    std::sort(ms.begin(), ms.end());
    return Timing{ms.front(), ms[ms.size() / 2]};
}

// Where a vertex of the last level lies: ptex face and (s, t).
struct Location {
    int ptex = -1;
    double s = 0, t = 0;
};

// The ptex location of every vertex of the uniform refiner's last level. Locations are carried
// per face corner, level by level, because a vertex on a ptex boundary has one per ptex face.
std::vector<Location> lastLevelLocations(Far::TopologyRefiner const & refiner, bool catmark) {
    Far::PtexIndices ptex(refiner);
    int levels = refiner.GetMaxLevel();
    Far::TopologyLevel const & base = refiner.GetLevel(0);
    // corners[f] = the location of each corner of face f at the current level.
    std::vector<std::vector<Location>> corners(base.GetNumFaces());
    for (int f = 0; f < base.GetNumFaces(); ++f) {
        int n = base.GetFaceVertices(f).size();
        if (!catmark || n == 4) {
            static const double quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            static const double tri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
            if (n != (catmark ? 4 : 3)) fail("loop needs triangles");
            for (int k = 0; k < n; ++k) {
                double const * st = catmark ? quad[k] : tri[k];
                corners[f].push_back(Location{ptex.GetFaceId(f), st[0], st[1]});
            }
        }
    }
    for (int level = 1; level <= levels; ++level) {
        Far::TopologyLevel const & parent = refiner.GetLevel(level - 1);
        Far::TopologyLevel const & child = refiner.GetLevel(level);
        std::vector<std::vector<Location>> next(child.GetNumFaces());
        for (int f = 0; f < parent.GetNumFaces(); ++f) {
            Far::ConstIndexArray fv = parent.GetFaceVertices(f);
            Far::ConstIndexArray fe = parent.GetFaceEdges(f);
            Far::ConstIndexArray kids = parent.GetFaceChildFaces(f);
            int n = fv.size();
            bool subFaces = corners[f].empty();  // a non-quad base face under Catmull-Clark
            for (int c = 0; c < kids.size(); ++c) {
                Far::ConstIndexArray cv = child.GetFaceVertices(kids[c]);
                for (int m = 0; m < cv.size(); ++m) {
                    Location at;
                    int v = cv[m];
                    if (subFaces) {
                        // Ptex sub-face c of an n-gon: its corner at (0, 0), the midpoint of the
                        // edge to the next corner at (1, 0), the centroid at (1, 1).
                        at.ptex = ptex.GetFaceId(f) + c;
                        if (v == parent.GetVertexChildVertex(fv[c])) {
                        } else if (v == parent.GetEdgeChildVertex(fe[c])) {
                            at.s = 1;
                        } else if (v == parent.GetFaceChildVertex(f)) {
                            at.s = at.t = 1;
                        } else if (v == parent.GetEdgeChildVertex(fe[(c + n - 1) % n])) {
                            at.t = 1;
                        } else {
                            fail("a child face of an n-gon has a vertex of no known origin");
                        }
                    } else {
                        std::vector<Location> const & p = corners[f];
                        at.ptex = p[0].ptex;
                        bool found = false;
                        for (int k = 0; k < n && !found; ++k) {
                            Location const & a = p[k];
                            Location const & b = p[(k + 1) % n];
                            if (v == parent.GetVertexChildVertex(fv[k])) {
                                at.s = a.s, at.t = a.t, found = true;
                            } else if (v == parent.GetEdgeChildVertex(fe[k])) {
                                at.s = (a.s + b.s) / 2, at.t = (a.t + b.t) / 2, found = true;
                            }
                        }
                        if (!found && catmark && v == parent.GetFaceChildVertex(f)) {
                            for (Location const & a : p) at.s += a.s / n, at.t += a.t / n;
                            found = true;
                        }
                        if (!found) fail("a child face has a vertex of no known origin");
                    }
                    next[kids[c]].push_back(at);
                }
            }
        }
        corners.swap(next);
    }
    Far::TopologyLevel const & last = refiner.GetLevel(levels);
    std::vector<Location> at(last.GetNumVertices());
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        Far::ConstIndexArray fv = last.GetFaceVertices(f);
        if (corners[f].size() != (size_t)fv.size()) fail("level 0 needs the limit of n-gons, unsupported");
        for (int k = 0; k < fv.size(); ++k)
            if (at[fv[k]].ptex < 0) at[fv[k]] = corners[f][k];
    }
    for (Location const & a : at)
        if (a.ptex < 0) fail("a last-level vertex is in no face");
    return at;
}

struct Point3 {
    float p[3];
    void Clear(void * = nullptr) { p[0] = p[1] = p[2] = 0.0f; }
    void AddWithWeight(Point3 const & src, float weight) {
        p[0] += weight * src.p[0];
        p[1] += weight * src.p[1];
        p[2] += weight * src.p[2];
    }
};

void usage() {
    std::fprintf(stderr, "usage: osd_stencil_bench [--scheme catmark|loop] [--level N] [--repeats R] [--no-limit] MESH.obj\n");
    std::exit(2);
}

}  // namespace

int main(int argc, char ** argv) {
    Sdc::SchemeType scheme = Sdc::SCHEME_CATMARK;
    std::string schemeName = "catmark", input;
    int level = 2, repeats = 20;
    bool limit = true;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage();
            return argv[++i];
        };
        if (arg == "--scheme") {
            schemeName = value();
            if (schemeName == "catmark") scheme = Sdc::SCHEME_CATMARK;
            else if (schemeName == "loop") scheme = Sdc::SCHEME_LOOP;
            else fail("unknown scheme '" + schemeName + "'");
        } else if (arg == "--level") {
            level = std::atoi(value().c_str());
            if (level < 1 || level > 8) fail("--level must be 1..8");
        } else if (arg == "--repeats") {
            repeats = std::max(1, std::atoi(value().c_str()));
        } else if (arg == "--no-limit") {
            limit = false;
        } else if (!arg.empty() && arg[0] == '-') {
            usage();
        } else {
            input = arg;
        }
    }
    if (input.empty()) usage();
    std::string meshName = input.substr(input.find_last_of('/') + 1);
    Mesh mesh = readObj(input);
    int numControl = (int)mesh.positions.size() / 3;

    // Refined stencils.
    std::unique_ptr<Far::TopologyRefiner> uniform(makeRefiner(mesh, scheme));
    Clock::time_point t0 = Clock::now();
    Far::TopologyRefiner::UniformOptions uniformOptions(level);
    uniformOptions.fullTopologyInLastLevel = limit;  // PrimvarRefiner::Limit, for the check
    uniform->RefineUniform(uniformOptions);
    double refineMs = msSince(t0);
    Far::StencilTableFactory::Options options;
    options.interpolationMode = Far::StencilTableFactory::INTERPOLATE_VERTEX;
    options.generateIntermediateLevels = false;
    options.factorizeIntermediateLevels = true;
    t0 = Clock::now();
    std::unique_ptr<Far::StencilTable const> table(Far::StencilTableFactory::Create(*uniform, options));
    double buildMs = msSince(t0);
    int numStencils = table->GetNumStencils();
    if (numStencils != uniform->GetLevel(level).GetNumVertices()) fail("the table does not cover the last level");
    long entries = (long)table->GetControlIndices().size();
    std::vector<float> dst(3 * (size_t)numStencils);
    Osd::BufferDescriptor desc(0, 3, 3);
    Timing eval = timeRuns(repeats, [&] {
        Osd::CpuEvaluator::EvalStencils(mesh.positions.data(), desc, dst.data(), desc, table->GetSizes().data(),
                                        table->GetOffsets().data(), table->GetControlIndices().data(),
                                        table->GetWeights().data(), 0, numStencils);
    });
    long bytes = 4L * (2L * numStencils + 2L * entries);
    std::printf("table=refined mesh=%s scheme=%s level=%d control_vertices=%d stencils=%d entries=%ld "
                "table_bytes=%ld bytes_per_stencil=%.1f refine_ms=%.2f build_ms=%.2f eval_best_ms=%.3f "
                "eval_median_ms=%.3f ns_per_stencil=%.2f\n",
                meshName.c_str(), schemeName.c_str(), level, numControl, numStencils, entries, bytes,
                (double)bytes / numStencils, refineMs, buildMs, eval.best, eval.median,
                eval.median * 1e6 / numStencils);
    std::fflush(stdout);
    table.reset();
    if (!limit) return 0;

    // Limit stencils at the same vertices, grouped by ptex face as the factory takes them.
    std::vector<Location> at = lastLevelLocations(*uniform, scheme == Sdc::SCHEME_CATMARK);
    std::vector<int> order(at.size());
    for (size_t v = 0; v < order.size(); ++v) order[v] = (int)v;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return at[a].ptex < at[b].ptex; });
    std::vector<float> s(order.size()), t(order.size());
    Far::LimitStencilTableFactory::LocationArrayVec arrays;
    for (size_t i = 0; i < order.size(); ++i) {
        s[i] = (float)at[order[i]].s;
        t[i] = (float)at[order[i]].t;
        if (arrays.empty() || arrays.back().ptexIdx != at[order[i]].ptex) {
            Far::LimitStencilTableFactory::LocationArray array;
            array.ptexIdx = at[order[i]].ptex;
            array.s = &s[i];
            array.t = &t[i];
            arrays.push_back(array);
        }
        ++arrays.back().numLocations;
    }
    std::unique_ptr<Far::TopologyRefiner> adaptive(makeRefiner(mesh, scheme));
    t0 = Clock::now();
    adaptive->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(level));
    double adaptiveMs = msSince(t0);
    t0 = Clock::now();
    std::unique_ptr<Far::LimitStencilTable const> limitTable(Far::LimitStencilTableFactory::Create(*adaptive, arrays));
    double limitBuildMs = msSince(t0);
    if (!limitTable) fail("LimitStencilTableFactory::Create failed");
    int numLimit = limitTable->GetNumStencils();
    if (numLimit != (int)order.size()) fail("the limit table has the wrong number of stencils");
    long limitEntries = (long)limitTable->GetControlIndices().size();
    std::vector<float> pos(3 * (size_t)numLimit), du(3 * (size_t)numLimit), dv(3 * (size_t)numLimit);
    Timing limitEval = timeRuns(repeats, [&] {
        Osd::CpuEvaluator::EvalStencils(mesh.positions.data(), desc, pos.data(), desc, du.data(), desc, dv.data(),
                                        desc, limitTable->GetSizes().data(), limitTable->GetOffsets().data(),
                                        limitTable->GetControlIndices().data(), limitTable->GetWeights().data(),
                                        limitTable->GetDuWeights().data(), limitTable->GetDvWeights().data(), 0,
                                        numLimit);
    });

    // The check: PrimvarRefiner::Limit on the uniform refinement.
    std::vector<std::vector<Point3>> levels(level + 1);
    levels[0].resize(numControl);
    for (int v = 0; v < numControl; ++v)
        for (int k = 0; k < 3; ++k) levels[0][v].p[k] = mesh.positions[3 * v + k];
    Far::PrimvarRefiner primvar(*uniform);
    for (int l = 1; l <= level; ++l) {
        levels[l].resize(uniform->GetLevel(l).GetNumVertices());
        Point3 const * src = levels[l - 1].data();
        Point3 * dst = levels[l].data();
        primvar.Interpolate(l, src, dst);
    }
    std::vector<Point3> exact(levels[level].size());
    primvar.Limit(levels[level].data(), exact);
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (Point3 const & p : exact)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p.p[k]), hi[k] = std::max(hi[k], p.p[k]);
    double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double worst = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        float const * p = exact[order[i]].p;
        float const * q = &pos[3 * i];
        double d = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        worst = std::max(worst, d);
    }
    long limitBytes = 4L * (2L * numLimit + 4L * limitEntries);
    std::printf("table=limit mesh=%s scheme=%s level=%d control_vertices=%d stencils=%d entries=%ld "
                "table_bytes=%ld bytes_per_stencil=%.1f refine_ms=%.2f build_ms=%.2f eval_best_ms=%.3f "
                "eval_median_ms=%.3f ns_per_stencil=%.2f limit_check=%.2e\n",
                meshName.c_str(), schemeName.c_str(), level, numControl, numLimit, limitEntries, limitBytes,
                (double)limitBytes / numLimit, adaptiveMs, limitBuildMs, limitEval.best, limitEval.median,
                limitEval.median * 1e6 / numLimit, worst / diagonal);
    return 0;
}
