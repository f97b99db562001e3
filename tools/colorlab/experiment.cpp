#include "experiment.hpp"

#include "platform/file_source.hpp"
#include "plots.hpp"

#include <filesystem>
#include <stdexcept>

namespace colorlab {

Recording readRecording(const AnalysisOptions& o)
{
    int columns = 0, rows = 0;
    if (o.samplesFile.empty()) {
        if (o.grid.empty()) {
            throw SampleError("no samples: give a sample list (--samples FILE) or --grid NxM");
        }
        parseGrid(o.grid, columns, rows);
    }
    platform::FileSource source(o.input, false, platform::ReplayRate::max(), 25.0);
    Recording rec;
    rec.width = source.size().width;
    rec.height = source.size().height;
    rec.samples = o.samplesFile.empty()
                      ? gridSamples(rec.width, rec.height, columns, rows, o.radius)
                      : readSampleFile(o.samplesFile);
    checkSamples(rec.samples, rec.width, rec.height);

    vision::Frame frame;
    for (long index = 0; o.maxFrames <= 0 || index < o.maxFrames; ++index) {
        const platform::SourceStatus status = source.next(frame);
        if (status == platform::SourceStatus::EndOfStream) {
            break;
        }
        if (status == platform::SourceStatus::Lost) {
            throw std::runtime_error(std::string(source.lastError()));
        }
        std::vector<Measurement> row;
        row.reserve(rec.samples.size());
        for (const Sample& s : rec.samples) {
            row.push_back(measureDisc(frame.image, s));
        }
        rec.frameNumbers.push_back(static_cast<long>(frame.sequence));
        rec.measurements.push_back(std::move(row));
    }
    if (rec.measurements.empty()) {
        throw std::runtime_error(o.input + ": no frames decoded");
    }
    return rec;
}

AnalysisResult analyseRecording(Recording recording, bool excludeSaturated)
{
    AnalysisResult out;
    out.recording = std::move(recording);
    const Recording& rec = out.recording;
    out.frames.total = static_cast<int>(rec.measurements.size());
    out.frames.excluded = excludeSaturated;
    for (std::size_t row = 0; row < rec.measurements.size(); ++row) {
        out.frames.saturated += rec.rowSaturated(row) ? 1 : 0;
    }
    if (out.frames.used() == 0) {
        throw std::runtime_error(std::string("all ") + std::to_string(out.frames.total) +
                                 " frames are saturated (a channel at 255 in some sample); "
                                 "nothing left with --exclude-saturated");
    }
    const std::vector<bool> use = usedRows(rec, excludeSaturated);
    for (const auto& info : vision::colorSpaces()) {
        out.stats.push_back(computeSpaceStats(rec, use, info.space));
    }
    out.ranking = rankSpaces(out.stats);
    out.rankingText = rankingText(out.stats, out.ranking);
    return out;
}

std::vector<bool> usedRows(const Recording& rec, bool excludeSaturated)
{
    std::vector<bool> use(rec.measurements.size(), true);
    for (std::size_t row = 0; row < use.size(); ++row) {
        use[row] = !(excludeSaturated && rec.rowSaturated(row));
    }
    return use;
}

AnalysisResult runAnalysis(const AnalysisOptions& o)
{
    AnalysisResult result = analyseRecording(readRecording(o), o.excludeSaturated);
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    if (ec) {
        throw std::runtime_error(o.outDir + ": cannot create folder: " + ec.message());
    }
    const Recording& rec = result.recording;
    const std::vector<bool> use = usedRows(rec, o.excludeSaturated);
    writeSeries(o.outDir, rec, use);
    writeSaturatedFrames(o.outDir, rec);
    writeStdevTables(o.outDir, rec, result.stats, result.frames);
    writeDpTables(o.outDir, rec, result.stats, result.frames);
    writeText(o.outDir, "ranking.txt", result.rankingText);
    if (o.plots) {
        for (const SpaceStats& st : result.stats) {
            plotSeries(o.outDir, rec, use, st.space);
            plotDp(o.outDir, rec, st);
        }
        plotSummary(o.outDir, result.stats);
    }
    return result;
}

}  // namespace colorlab
