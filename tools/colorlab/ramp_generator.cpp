#include "ramp_generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <stdexcept>

namespace colorlab {
namespace {

struct Patch {
    const char* name;
    double rho[3];  ///< linear reflectance R, G, B
};

// Linear-RGB reflectances of construction paper, in the layout of the dissertation's Figure 11.
constexpr Patch kPatches[8] = {
    {"orange", {0.78, 0.32, 0.06}}, {"red", {0.62, 0.07, 0.08}},      {"green", {0.08, 0.42, 0.16}},
    {"blue", {0.06, 0.13, 0.52}},   {"yellow", {0.82, 0.70, 0.10}},   {"brown", {0.30, 0.17, 0.09}},
    {"beige", {0.72, 0.62, 0.46}},  {"black", {0.050, 0.046, 0.042}},
};
constexpr double kBackground = 0.25;

}  // namespace

double rampGain(const RampOptions& o, int frame) noexcept
{
    if (o.frames < 2) {
        return o.maxGain;
    }
    const double u = static_cast<double>(frame) / (o.frames - 1);
    return o.maxGain - (o.maxGain - o.minGain) * (1.0 - std::abs(2.0 * u - 1.0));
}

void generateRamp(const RampOptions& o)
{
    if (o.frames < 2 || o.width < 64 || o.height < 48) {
        throw std::runtime_error("generate: need at least 2 frames of 64x48");
    }
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    if (ec) {
        throw std::runtime_error(o.outDir + ": cannot create folder: " + ec.message());
    }
    // Patch rectangles: 4 columns x 2 rows of cells, each patch inset in its cell.
    const int cw = o.width / 4;
    const int ch = o.height / 2;
    cv::Mat_<std::uint8_t> patchOf(o.height, o.width, std::uint8_t{255});
    for (int p = 0; p < 8; ++p) {
        const int x0 = (p % 4) * cw + cw / 8, x1 = (p % 4 + 1) * cw - cw / 8;
        const int y0 = (p / 4) * ch + ch / 6, y1 = (p / 4 + 1) * ch - ch / 6;
        patchOf(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(p);
    }
    {
        const std::string path = o.outDir + "/samples.txt";
        std::ofstream s(path);
        s << "# colorlab generate: patch centres (name x y radius)\n";
        for (int p = 0; p < 8; ++p) {
            s << kPatches[p].name << ' ' << (p % 4) * cw + cw / 2 << ' ' << (p / 4) * ch + ch / 2
              << " 3\n";
        }
        if (!s) {
            throw std::runtime_error(path + ": cannot write");
        }
    }
    std::ofstream illum(o.outDir + "/illumination.csv");
    illum << "frame,gain\n";

    std::mt19937 rng(o.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    cv::Mat3b frame(o.height, o.width);
    char name[64];
    for (int f = 0; f < o.frames; ++f) {
        const double gain = rampGain(o, f);
        illum << f << ',' << gain << '\n';
        for (int y = 0; y < o.height; ++y) {
            for (int x = 0; x < o.width; ++x) {
                const int p = patchOf(y, x);
                cv::Vec3b& px = frame(y, x);
                for (int c = 0; c < 3; ++c) {
                    const double rho = p < 8 ? kPatches[p].rho[c] : kBackground;
                    const double signal = o.exposure * gain * rho;
                    const double sigma =
                        std::sqrt(o.shotNoise * signal + o.readNoise * o.readNoise);
                    const double s = std::clamp(signal + sigma * normal(rng), 0.0, 1.0);
                    const double v = std::round(255.0 * std::pow(s, 1.0 / o.gamma));
                    px[2 - c] = static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));  // BGR
                }
            }
        }
        std::snprintf(name, sizeof name, "/frame_%04d.png", f);
        const std::string path = o.outDir + name;
        if (!cv::imwrite(path, frame)) {
            throw std::runtime_error(path + ": cannot write PNG");
        }
    }
    if (!illum) {
        throw std::runtime_error(o.outDir + "/illumination.csv: cannot write");
    }
}

}  // namespace colorlab
