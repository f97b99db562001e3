// overlaygen: writes the project's overlay models (OBJ + MTL) and their catalogue entries into
// assets/overlays/, checks that the committed files are what it generates, and renders previews.

#include "asset_files.hpp"
#include "models.hpp"
#include "preview.hpp"
#include "tool_cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace {

int preview(const std::string& assets, const std::string& out, int size)
{
    using namespace overlaygen;
    std::filesystem::create_directories(out);
    PreviewRenderer renderer(size, size);
    std::vector<cv::Mat> rows;
    for (const Model& model : buildAllModels()) {
        const std::string obj = (std::filesystem::path(assets) / objPath(model)).string();
        std::vector<cv::Mat> views;
        for (double yaw : {0.0, 45.0, -90.0})
            views.push_back(renderer.render(model, obj, yaw));
        cv::Mat row;
        cv::hconcat(views, row);
        cv::putText(row, model.name, {8, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.7, {20, 20, 20}, 2);
        const std::string png = (std::filesystem::path(out) / (model.name + ".png")).string();
        cv::imwrite(png, row);
        std::printf("%s\n", png.c_str());
        rows.push_back(row);
    }
    cv::Mat sheet;
    cv::vconcat(rows, sheet);
    const std::string png = (std::filesystem::path(out) / "all.png").string();
    cv::imwrite(png, sheet);
    std::printf("%s\n", png.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "overlaygen: the mirror's own hat and glasses models. Writes Wavefront OBJ (+ MTL) "
        "files and the generated block of catalogue.toml into the overlay directory."};
    app.require_subcommand(1);
    tool_cli::addVersion(app, "overlaygen");
    std::string dir = "assets/overlays";
    std::string out = "overlay-previews";
    int size = 480;
    CLI::App* write = app.add_subcommand("write", "Generate the models into the directory");
    write->add_option("--dir", dir, "Overlay directory (catalogue.toml)")->capture_default_str();
    CLI::App* check =
        app.add_subcommand("check", "Exit 1 when the directory's files differ from the generator");
    check->add_option("--dir", dir, "Overlay directory")->capture_default_str();
    CLI::App* view = app.add_subcommand(
        "preview", "Render every model on a stand-in head (front, 45 degrees, side) to PNG");
    view->add_option("--dir", dir, "Overlay directory to read the OBJ files from")
        ->capture_default_str();
    view->add_option("--out", out, "Directory for the PNG files")->capture_default_str();
    view->add_option("--size", size, "Pixels per view (square)")->capture_default_str();
    if (const int code = tool_cli::parse(app, argc, argv); code >= 0)
        return code;

    try {
        if (write->parsed()) {
            overlaygen::writeAssets(dir, overlaygen::buildAllModels());
            std::printf("overlaygen: wrote %s\n", dir.c_str());
            return 0;
        }
        if (check->parsed()) {
            const auto stale = overlaygen::staleAssets(dir, overlaygen::buildAllModels());
            for (const std::string& line : stale)
                std::fprintf(stderr, "overlaygen: %s/%s\n", dir.c_str(), line.c_str());
            return stale.empty() ? 0 : 1;
        }
        return preview(dir, out, size);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
