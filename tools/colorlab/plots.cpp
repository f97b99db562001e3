#include "plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace colorlab {
namespace {

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(220, 220, 220);
// Component colours (BGR): first red, second green, third blue, as the dissertation's plots.
const cv::Scalar kComponent[3] = {cv::Scalar(40, 40, 220), cv::Scalar(40, 160, 40),
                                  cv::Scalar(220, 80, 40)};

std::string plotDir(const std::string& dir)
{
    const std::string sub = dir + "/plots";
    std::error_code ec;
    std::filesystem::create_directories(sub, ec);
    if (ec) {
        throw std::runtime_error(sub + ": cannot create folder: " + ec.message());
    }
    return sub;
}

void save(const std::string& path, const cv::Mat& image)
{
    bool ok = false;
    try {
        ok = cv::imwrite(path, image);
    } catch (const cv::Exception& e) {
        throw std::runtime_error(path + ": cannot write PNG: " + e.what());
    }
    if (!ok) {
        throw std::runtime_error(path + ": cannot write PNG");
    }
}

void text(cv::Mat& img, const std::string& s, int x, int y, double scale = 0.4,
          const cv::Scalar& colour = kBlack)
{
    cv::putText(img, s, cv::Point(x, y), cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

std::string fmt(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

}  // namespace

void plotSeries(const std::string& dir, const Recording& rec, const std::vector<bool>& useRow,
                vision::ColorSpace space)
{
    const auto& info = vision::colorSpaceInfo(space);
    const int n = std::min<int>(static_cast<int>(rec.samples.size()), kMaxPanels);
    const int cols = std::min(n, 4);
    const int rows = (n + cols - 1) / cols;
    constexpr int kPanelW = 300, kPanelH = 180, kTop = 40, kMarginL = 44, kMarginB = 18;
    cv::Mat img(kTop + rows * kPanelH, cols * kPanelW, CV_8UC3, kWhite);

    // Converted values and the shared y range (1st..99th percentile, so the spikes of an unstable
    // component do not flatten the rest).
    std::vector<std::vector<std::array<double, 3>>> values(n);
    std::vector<long> frames;
    std::vector<double> all;
    for (std::size_t row = 0; row < rec.measurements.size(); ++row) {
        if (!useRow[row]) {
            continue;
        }
        frames.push_back(rec.frameNumbers[row]);
        for (int s = 0; s < n; ++s) {
            const Measurement& m = rec.measurements[row][s];
            values[s].push_back(vision::convertReference(space, m.r, m.g, m.b));
            for (int c = 0; c < info.components; ++c) {
                all.push_back(values[s].back()[c]);
            }
        }
    }
    double lo = 0.0, hi = 1.0;
    if (!all.empty()) {
        std::sort(all.begin(), all.end());
        lo = all[all.size() / 100];
        hi = all[all.size() - 1 - all.size() / 100];
    }
    if (hi - lo < 1e-9) {
        lo -= 1.0;
        hi += 1.0;
    }
    const double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
    const double f0 = frames.empty() ? 0.0 : static_cast<double>(frames.front());
    const double f1 = frames.size() < 2 ? f0 + 1.0 : static_cast<double>(frames.back());

    std::string title = std::string(info.name) + " over time (frame number); components:";
    text(img, title, 8, 16, 0.5);
    int lx = 8 + static_cast<int>(title.size()) * 9;
    for (int c = 0; c < info.components; ++c) {
        const std::string label =
            std::string(info.componentNames[c]) + (info.chromatic[c] ? "" : " (not in DP)");
        text(img, label, lx, 16, 0.5, kComponent[c]);
        lx += static_cast<int>(label.size()) * 9 + 12;
    }
    if (static_cast<int>(rec.samples.size()) > n) {
        text(img,
             std::string("first ") + std::to_string(n) + " of " +
                 std::to_string(rec.samples.size()) + " samples shown",
             8, 32, 0.4);
    }

    for (int s = 0; s < n; ++s) {
        const int ox = (s % cols) * kPanelW;
        const int oy = kTop + (s / cols) * kPanelH;
        const cv::Rect area(ox + kMarginL, oy + 16, kPanelW - kMarginL - 8,
                            kPanelH - 16 - kMarginB);
        cv::rectangle(img, area, kGrid, 1);
        text(img, rec.samples[s].name, ox + kMarginL, oy + 12, 0.4);
        text(img, fmt(hi), ox + 2, area.y + 10, 0.33);
        text(img, fmt(lo), ox + 2, area.y + area.height, 0.33);
        text(img, std::to_string(static_cast<long>(f0)), area.x, area.y + area.height + 13, 0.33);
        text(img, std::to_string(static_cast<long>(f1)), area.x + area.width - 24,
             area.y + area.height + 13, 0.33);
        auto toPoint = [&](std::size_t i, double v) {
            const double fx = (static_cast<double>(frames[i]) - f0) / (f1 - f0);
            const double fy = (std::clamp(v, lo, hi) - lo) / (hi - lo);
            return cv::Point(
                area.x + static_cast<int>(std::lround(fx * (area.width - 1))),
                area.y + area.height - 1 - static_cast<int>(std::lround(fy * (area.height - 1))));
        };
        if (lo < 0.0 && hi > 0.0) {
            cv::line(img, toPoint(0, 0.0), cv::Point(area.x + area.width - 1, toPoint(0, 0.0).y),
                     kGrid, 1);
        }
        for (int c = 0; c < info.components; ++c) {
            for (std::size_t i = 1; i < values[s].size(); ++i) {
                cv::line(img, toPoint(i - 1, values[s][i - 1][c]), toPoint(i, values[s][i][c]),
                         kComponent[c], info.chromatic[c] ? 2 : 1, cv::LINE_AA);
            }
        }
    }
    save(plotDir(dir) + "/series_" + info.name + ".png", img);
}

void plotDp(const std::string& dir, const Recording& rec, const SpaceStats& stats)
{
    const auto& info = vision::colorSpaceInfo(stats.space);
    constexpr int kW = 720, kH = 300, kL = 50, kR = 10, kT = 40, kB = 30;
    cv::Mat img(kH, kW, CV_8UC3, kWhite);
    double top = 2.0;
    for (double d : stats.dp) {
        if (d < kDpCap) {
            top = std::max(top, d * 1.05);
        }
    }
    const cv::Rect area(kL, kT, kW - kL - kR, kH - kT - kB);
    cv::rectangle(img, area, kGrid, 1);
    char title[200];
    std::snprintf(title, sizeof title,
                  "%s: discriminative power per pair (mean %.3g, min %.3g, %d of %zu < 1)",
                  info.name, stats.dpMean, stats.dpMin, stats.pairsBelowOne, stats.dp.size());
    text(img, title, 8, 18, 0.45);
    text(img, fmt(top), 4, area.y + 10, 0.35);
    text(img, "0", 30, area.y + area.height, 0.35);
    text(img, std::string("color pair (1..") + std::to_string(stats.dp.size()) + ")", area.x,
         area.y + area.height + 20, 0.4);
    auto yOf = [&](double v) {
        return area.y + area.height - 1 -
               static_cast<int>(std::lround(std::min(v, top) / top * (area.height - 1)));
    };
    const int pairs = static_cast<int>(stats.dp.size());
    const int n = static_cast<int>(rec.samples.size());
    for (int k = 0; k < pairs; ++k) {
        const int x0 = area.x + k * area.width / std::max(pairs, 1);
        const int x1 = area.x + (k + 1) * area.width / std::max(pairs, 1) - (pairs < 100 ? 2 : 0);
        const double d = stats.dp[k];
        const cv::Scalar colour = d < 1.0 ? cv::Scalar(60, 60, 230) : cv::Scalar(200, 120, 40);
        cv::rectangle(img, cv::Point(x0, yOf(d)), cv::Point(std::max(x0, x1), yOf(0.0)), colour,
                      cv::FILLED);
        if (pairs <= 40) {
            const auto [i, j] = pairOf(n, k);
            text(img, std::to_string(i + 1) + "-" + std::to_string(j + 1), x0,
                 area.y + area.height + 10, 0.28);
        }
    }
    cv::line(img, cv::Point(area.x, yOf(1.0)), cv::Point(area.x + area.width - 1, yOf(1.0)), kBlack,
             1);
    text(img, "DP = 1", area.x + area.width - 50, yOf(1.0) - 3, 0.35);
    save(plotDir(dir) + "/dp_" + info.name + ".png", img);
}

void plotSummary(const std::string& dir, const std::vector<SpaceStats>& stats)
{
    constexpr int kW = 720, kH = 340, kPanelH = 150;
    cv::Mat img(kH, kW, CV_8UC3, kWhite);
    const int n = static_cast<int>(stats.size());
    auto panel = [&](int oy, const std::string& title, auto value, const cv::Scalar& colour) {
        double top = 1e-9;
        for (const SpaceStats& s : stats) {
            const double v = value(s);
            if (std::isfinite(v) && v < kDpCap) {
                top = std::max(top, v * 1.1);
            }
        }
        const cv::Rect area(40, oy + 22, kW - 50, kPanelH - 44);
        cv::rectangle(img, area, kGrid, 1);
        text(img, title + " (max " + fmt(top) + ")", 8, oy + 14, 0.45);
        for (int i = 0; i < n; ++i) {
            const double v = std::min(value(stats[i]), top);
            const int x0 = area.x + i * area.width / n + 6;
            const int x1 = area.x + (i + 1) * area.width / n - 6;
            const int y = area.y + area.height - 1 -
                          static_cast<int>(std::lround(v / top * (area.height - 1)));
            cv::rectangle(img, cv::Point(x0, y), cv::Point(x1, area.y + area.height - 1), colour,
                          cv::FILLED);
            text(img, vision::colorSpaceInfo(stats[i].space).name, x0, area.y + area.height + 14,
                 0.33);
        }
    };
    panel(
        0, "invariance: mean std-dev of chromatic components, % of range (lower is better)",
        [](const SpaceStats& s) { return s.invariancePercent; }, cv::Scalar(60, 60, 230));
    panel(
        kPanelH + 20, "minimum discriminative power over pairs (higher is better)",
        [](const SpaceStats& s) { return s.dpMin; }, cv::Scalar(200, 120, 40));
    save(plotDir(dir) + "/summary.png", img);
}

}  // namespace colorlab
