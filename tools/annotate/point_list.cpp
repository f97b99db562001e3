#include "point_list.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace annotate {

std::vector<Eigen::Vector2d> readPointList(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": cannot be read");
    std::vector<Eigen::Vector2d> points;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream fields(line);
        double x = 0, y = 0;
        std::string rest;
        if (!(fields >> x >> y) || (fields >> rest) || !std::isfinite(x) || !std::isfinite(y))
            throw std::runtime_error(path + ":" + std::to_string(number) +
                                     ": expected two numbers, x and y in pixels");
        points.emplace_back(x, y);
    }
    return points;
}

}  // namespace annotate
