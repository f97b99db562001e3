#include "asset_files.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace overlaygen {

namespace {

void writeText(const std::filesystem::path& path, const std::string& text)
{
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out)
        throw std::runtime_error("overlaygen: cannot write " + path.string() + ": " +
                                 std::strerror(errno));
}

}  // namespace

std::string readText(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<GeneratedFile> meshFiles(const std::vector<Model>& models)
{
    std::vector<GeneratedFile> files;
    for (const Model& model : models) {
        files.push_back({objPath(model), objText(model, finish(model))});
        files.push_back({mtlPath(model), mtlText(model)});
    }
    return files;
}

void writeAssets(const std::string& dir, const std::vector<Model>& models)
{
    for (const GeneratedFile& file : meshFiles(models))
        writeText(std::filesystem::path(dir) / file.path, file.text);
    const std::filesystem::path catalogue = std::filesystem::path(dir) / "catalogue.toml";
    writeText(catalogue, mergeCatalogue(readText(catalogue.string()), catalogueBlock(models)));
}

std::vector<std::string> staleAssets(const std::string& dir, const std::vector<Model>& models)
{
    std::vector<std::string> stale;
    for (const GeneratedFile& file : meshFiles(models)) {
        const std::string path = (std::filesystem::path(dir) / file.path).string();
        if (!std::filesystem::exists(path))
            stale.push_back(file.path + ": missing");
        else if (readText(path) != file.text)
            stale.push_back(file.path + ": differs from the generator's output");
    }
    const std::string catalogue =
        readText((std::filesystem::path(dir) / "catalogue.toml").string());
    if (catalogue.find(catalogueBlock(models)) == std::string::npos)
        stale.push_back("catalogue.toml: generated block missing or different");
    return stale;
}

}  // namespace overlaygen
