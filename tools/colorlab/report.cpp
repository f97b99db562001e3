#include "report.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace colorlab {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File openForWriting(const std::string& path)
{
    File f(std::fopen(path.c_str(), "w"));
    if (!f) {
        throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
    }
    return f;
}

void finish(File f, const std::string& path)
{
    const bool failed = std::ferror(f.get()) != 0;
    if (std::fclose(f.release()) != 0 || failed) {
        throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
    }
}

std::string pairName(const Recording& rec, int k)
{
    const auto [i, j] = pairOf(static_cast<int>(rec.samples.size()), k);
    return rec.samples[i].name + "-" + rec.samples[j].name;
}

std::string frameUseLine(const FrameUse& use)
{
    return std::to_string(use.used()) + " of " + std::to_string(use.total) + " frames used; " +
           std::to_string(use.saturated) + " saturated (a channel at 255 in a sample) " +
           (use.excluded ? "excluded" : "included");
}

}  // namespace

void writeText(const std::string& dir, const std::string& name, const std::string& text)
{
    const std::string path = dir + "/" + name;
    File f = openForWriting(path);
    std::fputs(text.c_str(), f.get());
    finish(std::move(f), path);
}

void writeSeries(const std::string& dir, const Recording& rec, const std::vector<bool>& useRow)
{
    const std::string sub = dir + "/series";
    std::error_code ec;
    std::filesystem::create_directories(sub, ec);
    if (ec) {
        throw std::runtime_error(sub + ": cannot create folder: " + ec.message());
    }
    for (std::size_t s = 0; s < rec.samples.size(); ++s) {
        for (const auto& info : vision::colorSpaces()) {
            const std::string path = sub + "/" + rec.samples[s].name + "_" + info.name + ".csv";
            File f = openForWriting(path);
            std::fputs("frame", f.get());
            for (int c = 0; c < info.components; ++c) {
                std::fprintf(f.get(), ",%s", info.componentNames[c]);
            }
            std::fputs(",saturated\n", f.get());
            for (std::size_t row = 0; row < rec.measurements.size(); ++row) {
                if (!useRow[row]) {
                    continue;
                }
                const Measurement& m = rec.measurements[row][s];
                const auto v = vision::convertReference(info.space, m.r, m.g, m.b);
                std::fprintf(f.get(), "%ld", rec.frameNumbers[row]);
                for (int c = 0; c < info.components; ++c) {
                    std::fprintf(f.get(), ",%.6g", v[c]);
                }
                std::fprintf(f.get(), ",%d\n", m.saturated ? 1 : 0);
            }
            finish(std::move(f), path);
        }
    }
}

void writeSaturatedFrames(const std::string& dir, const Recording& rec)
{
    std::string text = "# frames with a channel at 255 in some sample's disc\n";
    for (std::size_t row = 0; row < rec.measurements.size(); ++row) {
        if (rec.rowSaturated(row)) {
            text += std::to_string(rec.frameNumbers[row]) + "\n";
        }
    }
    writeText(dir, "saturated.txt", text);
}

void writeStdevTables(const std::string& dir, const Recording& rec,
                      const std::vector<SpaceStats>& stats, const FrameUse& use)
{
    const std::string csvPath = dir + "/stdev.csv";
    File csv = openForWriting(csvPath);
    std::fputs("space,component,chromatic,range", csv.get());
    for (const Sample& s : rec.samples) {
        std::fprintf(csv.get(), ",%s", s.name.c_str());
    }
    std::fputs(",mean,mean_percent_of_range\n", csv.get());

    const std::string txtPath = dir + "/stdev.txt";
    File txt = openForWriting(txtPath);
    std::fprintf(txt.get(),
                 "Standard deviation over time of each component (3.4), per sample, and the "
                 "mean over samples\n(absolute and as %% of the component's range). * = chromatic "
                 "component (used for DP and the ranking).\n%s\n\n",
                 frameUseLine(use).c_str());
    std::fprintf(txt.get(), "%-14s %-4s", "space", "comp");
    for (const Sample& s : rec.samples) {
        std::fprintf(txt.get(), " %9.9s", s.name.c_str());
    }
    std::fprintf(txt.get(), " %9s %8s\n", "mean", "% range");

    for (const SpaceStats& st : stats) {
        const auto& info = vision::colorSpaceInfo(st.space);
        for (int c = 0; c < info.components; ++c) {
            const double range = componentRange(st.space, c);
            std::fprintf(csv.get(), "%s,%s,%d,%.6g", info.name, info.componentNames[c],
                         info.chromatic[c] ? 1 : 0, range);
            std::fprintf(txt.get(), "%-14s %-3s%c", c == 0 ? info.name : "", info.componentNames[c],
                         info.chromatic[c] ? '*' : ' ');
            for (const ComponentStats& cs : st.samples) {
                std::fprintf(csv.get(), ",%.6g", cs.stdev[c]);
                std::fprintf(txt.get(), " %9.4g", cs.stdev[c]);
            }
            const double pct = st.meanStdevPercent[c];
            if (std::isnan(pct)) {
                std::fprintf(csv.get(), ",%.6g,\n", st.meanStdev[c]);
                std::fprintf(txt.get(), " %9.4g %8s\n", st.meanStdev[c], "-");
            } else {
                std::fprintf(csv.get(), ",%.6g,%.6g\n", st.meanStdev[c], pct);
                std::fprintf(txt.get(), " %9.4g %7.3f%%\n", st.meanStdev[c], pct);
            }
        }
    }
    finish(std::move(csv), csvPath);
    finish(std::move(txt), txtPath);
}

void writeDpTables(const std::string& dir, const Recording& rec,
                   const std::vector<SpaceStats>& stats, const FrameUse& use)
{
    const int pairs = stats.empty() ? 0 : static_cast<int>(stats.front().dp.size());
    const std::string csvPath = dir + "/dp.csv";
    File csv = openForWriting(csvPath);
    std::fputs("pair", csv.get());
    for (const SpaceStats& st : stats) {
        std::fprintf(csv.get(), ",%s", vision::colorSpaceInfo(st.space).name);
    }
    std::fputs("\n", csv.get());
    for (int k = 0; k < pairs; ++k) {
        std::fputs(pairName(rec, k).c_str(), csv.get());
        for (const SpaceStats& st : stats) {
            std::fprintf(csv.get(), ",%.6g", st.dp[k]);
        }
        std::fputs("\n", csv.get());
    }
    finish(std::move(csv), csvPath);

    const std::string txtPath = dir + "/dp.txt";
    File txt = openForWriting(txtPath);
    std::fprintf(txt.get(),
                 "Discriminative power (eq. 19) for all %d pairs of %zu samples:\n"
                 "DP_ij = |mean(c_i) - mean(c_j)| / (|stdev(c_i)| + |stdev(c_j)|), c the vector "
                 "of the space's chromatic\ncomponents, |.| the Euclidean norm (luminance dropped "
                 "from YIQ, HSV, HLS, CIELAB; H from the derivative\nspace). DP < 1: the noise is "
                 "larger than the difference. Capped at %g.\n%s\n\n",
                 pairs, rec.samples.size(), kDpCap, frameUseLine(use).c_str());
    std::fprintf(txt.get(), "%-24s", "pair");
    for (const SpaceStats& st : stats) {
        std::fprintf(txt.get(), " %12s", vision::colorSpaceInfo(st.space).name);
    }
    std::fputs("\n", txt.get());
    for (int k = 0; k < pairs; ++k) {
        std::fprintf(txt.get(), "%-24.24s", pairName(rec, k).c_str());
        for (const SpaceStats& st : stats) {
            std::fprintf(txt.get(), " %12.4g", st.dp[k]);
        }
        std::fputs("\n", txt.get());
    }
    std::fprintf(txt.get(), "%-24s", "mean");
    for (const SpaceStats& st : stats) {
        std::fprintf(txt.get(), " %12.4g", st.dpMean);
    }
    std::fprintf(txt.get(), "\n%-24s", "min");
    for (const SpaceStats& st : stats) {
        std::fprintf(txt.get(), " %12.4g", st.dpMin);
    }
    std::fprintf(txt.get(), "\n%-24s", "pairs with DP < 1");
    for (const SpaceStats& st : stats) {
        std::fprintf(txt.get(), " %12d", st.pairsBelowOne);
    }
    std::fputs("\n", txt.get());
    finish(std::move(txt), txtPath);
}

std::string rankingText(const std::vector<SpaceStats>& stats,
                        const std::vector<RankedSpace>& ranking)
{
    std::string text =
        "Ranking of the colour spaces for this recording. Each space is ranked (1 = best) on\n"
        "invariance (mean std-dev of its chromatic components, % of range, lower is better),\n"
        "mean DP and minimum DP over all pairs (higher is better); ordered by the sum of the\n"
        "three ranks, ties to the higher mean DP.\n\n";
    char line[256];
    std::snprintf(line, sizeof line, "%-4s %-14s %10s %10s %10s %5s %5s %5s %5s\n", "#", "space",
                  "stdev %", "mean DP", "min DP", "r.inv", "r.avg", "r.min", "score");
    text += line;
    int place = 1;
    for (const RankedSpace& r : ranking) {
        const SpaceStats* st = nullptr;
        for (const SpaceStats& s : stats) {
            if (s.space == r.space) {
                st = &s;
            }
        }
        if (st == nullptr) {
            continue;
        }
        std::snprintf(line, sizeof line, "%-4d %-14s %10.4g %10.4g %10.4g %5d %5d %5d %5d\n",
                      place++, vision::colorSpaceInfo(r.space).name, st->invariancePercent,
                      st->dpMean, st->dpMin, r.invarianceRank, r.dpMeanRank, r.dpMinRank, r.score);
        text += line;
    }
    text += '\n';
    text += rankingLine(ranking);
    text += '\n';
    return text;
}

}  // namespace colorlab
