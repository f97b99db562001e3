// aam-build: the offline Active Appearance Model builder (§5). So far: `mesh` reads CANDIDE-3 and
// reports the dissertation's cut of it.
#include "wfm_reader.hpp"

#include "vision/candide_reduction.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

namespace {

int describeMesh(const std::string& wfm) {
    const vision::CandideMesh full = aam::loadWfm(wfm);
    const vision::CandideMesh face = vision::reduceCandideForTracking(full);
    std::printf("candide: vertices=%zu triangles=%zu animation_units=%zu shape_units=%zu\n", full.vertices.size(),
                full.triangles.size(), full.animationUnits.size(), full.shapeUnits.size());
    std::printf("tracked: vertices=%zu triangles=%zu animation_units=%zu shape_units=%zu\n", face.vertices.size(),
                face.triangles.size(), face.animationUnits.size(), face.shapeUnits.size());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"aam-build: the offline Active Appearance Model builder"};
    app.require_subcommand(1);
    std::string wfm = "../shared/data/candide3/candide3.wfm";
    auto* mesh = app.add_subcommand("mesh", "read CANDIDE-3 and report the tracked cut of it");
    mesh->add_option("--wfm", wfm, "the CANDIDE-3 .wfm file")->capture_default_str();
    CLI11_PARSE(app, argc, argv);
    try {
        return describeMesh(wfm);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "aam-build: %s\n", e.what());
        return 1;
    }
}
