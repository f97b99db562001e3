// BoxCache (box_cache.hpp).
#include "box_cache.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mirror_eval {

BoxCache::BoxCache(std::string path) : path_(std::move(path))
{
    if (path_.empty() || !std::filesystem::exists(path_))
        return;
    std::ifstream in(path_);
    if (!in)
        throw std::runtime_error("--boxes " + path_ + ": cannot be read");
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream fields(line);
        std::string stem, first;
        if (!(fields >> stem >> first))
            throw std::runtime_error("--boxes " + path_ + " line " + std::to_string(number) +
                                     ": expected `<stem> -` or `<stem> left top right bottom`");
        if (first == "-") {
            boxes_[stem] = std::nullopt;
            continue;
        }
        FaceBoxPx b;
        std::istringstream rest(first);
        if (!(rest >> b.left) || !(fields >> b.top >> b.right >> b.bottom) ||
            !(b.right > b.left && b.bottom > b.top))
            throw std::runtime_error("--boxes " + path_ + " line " + std::to_string(number) +
                                     ": not a box");
        boxes_[stem] = b;
    }
}

std::optional<std::optional<FaceBoxPx>> BoxCache::find(const std::string& stem) const
{
    const auto it = boxes_.find(stem);
    if (it == boxes_.end())
        return std::nullopt;
    return it->second;
}

void BoxCache::put(const std::string& stem, const std::optional<FaceBoxPx>& box)
{
    if (path_.empty())
        return;
    boxes_[stem] = box;
    changed_ = true;
}

void BoxCache::save() const
{
    if (path_.empty() || !changed_)
        return;
    const std::string tmp = path_ + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        for (const auto& [stem, box] : boxes_) {
            if (box) {
                char line[160];
                std::snprintf(line, sizeof line, "%s %.3f %.3f %.3f %.3f\n", stem.c_str(),
                              box->left, box->top, box->right, box->bottom);
                out << line;
            } else {
                out << stem << " -\n";
            }
        }
        if (!out.flush())
            throw std::runtime_error("--boxes " + path_ + ": cannot be written");
    }
    std::filesystem::rename(tmp, path_);
}

}  // namespace mirror_eval
