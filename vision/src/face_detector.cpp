// FaceDetector: the Viola-Jones scan (METHOD.md §3) of an OpenCV Haar cascade over every scale
// and position of a frame, as cv::CascadeClassifier::detectMultiScale (OpenCV 4.6) scans it, so
// that it gives the same boxes with the same cascade and parameters. The cascade in fixed point:
// fixed_cascade.cpp; the first stages a row at a time: row_prefilter.cpp; the bit-exact resize:
// scaled_integrals.cpp; the grouping of the raw hits: detection_grouping.cpp.

#include "vision/face_detector.hpp"

#include "detection_grouping.hpp"
#include "fixed_cascade.hpp"
#include "row_prefilter.hpp"
#include "scaled_integrals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vision {
namespace {

// Coarse to fine (detectCoarseToFine): the coarse grid's windows go through this many stages
// before their neighbours are looked at. Fewer cost more (more survivors, whose neighbours are
// decided one at a time), more lose faces: with 7 or 8 a cold start lost a face of facegen seed
// 13 `three` for 25 frames and showed the photograph of seed 13 `four` for 50 (docs/ARM.md).
constexpr int kCoarseStages = 6;

const FaceDetectorOptions& checked(const FaceDetectorOptions& options)
{
    if (!(options.scaleFactor > 1.0))
        throw std::runtime_error("face detector: scaleFactor <= 1");
    if (options.maxFrameSize.width <= 0 || options.maxFrameSize.height <= 0 ||
        options.maxRawHits <= 0 || options.maxFaces <= 0) {
        throw std::runtime_error("face detector: bad frame size or capacities");
    }
    return options;
}

// Which windows a scan evaluates (§3): those with enough of the mask under them (no mask: all)
// whose centre lies in no excluded box.
struct WindowFilter {
    const IntegralImage* mask = nullptr;
    float minFraction = 0.0f;
    std::span<const Rect> exclude;
};

}  // namespace

struct FaceDetector::Impl {
    Impl(const HaarCascade& haar, const FaceDetectorOptions& o)
        : options(checked(o)),
          cascade(haar, o.maxFrameSize.width + 1, true),
          tables(o.maxFrameSize, cascade.rowForm()),
          prefilter(o.maxFrameSize.width + 1),
          grouping(o.maxRawHits),
          rowWanted(static_cast<std::size_t>(o.maxFrameSize.width + 1), 0),
          coarseAlive{std::vector<std::uint8_t>(static_cast<std::size_t>(o.maxFrameSize.width + 2)),
                      std::vector<std::uint8_t>(static_cast<std::size_t>(o.maxFrameSize.width + 2))},
          columnX(static_cast<std::size_t>(o.maxFrameSize.width + 1)),
          columnMask0(columnX.size()),
          columnMask1(columnX.size()),
          raw(static_cast<std::size_t>(o.maxRawHits)),
          faces(static_cast<std::size_t>(o.maxFaces))
    {
    }

    FaceDetectorOptions options;
    FixedCascade cascade;
    ScaledIntegrals tables;
    RowPrefilter prefilter;
    DetectionGrouping grouping;
    std::vector<std::uint8_t> rowWanted;  // per window of a row: not masked out nor excluded
    // Coarse to fine: per window of the last two coarse rows, passed the first stages (and a
    // zero entry past the last window).
    std::vector<std::uint8_t> coarseAlive[2];
    std::vector<int> columnX, columnMask0, columnMask1;  // prepareColumns

    std::vector<Rect> raw;
    int rawCount = 0;
    bool rawOverflow = false;
    std::vector<Rect> faces;
    int faceCount = 0;
    long windows = 0;

    char error[160] = "";

    void setError(const char* msg) noexcept { std::snprintf(error, sizeof error, "%s", msg); }

    // Where a scan stands: the next scale of OpenCV's list and the next window in it. detect()
    // runs a scan from start to end in one call; detectMaskedIncremental() keeps it between calls.
    struct Cursor {
        bool active = false;   // a scan is in progress
        bool inScale = false;  // the scale fields below describe the scale being scanned
        Size image{};          // size of the images of this scan
        double nextFactor = 1.0;
        int nstripes = 0;
        float sc = 1.0f;
        int dw = 0, dh = 0, step = 2, xEnd = 0, yEnd = 0, boxW = 0, boxH = 0;
        int stepShift = 1;  // x / step without a division
        int y = 0, x = 0;   // next window of the scale

        // A window's position in the image: round(x * scale), as OpenCV places its raw hits.
        int imageX(int wx) const noexcept
        {
            return static_cast<int>(std::lrint(static_cast<float>(wx) * sc));
        }
        int imageY() const noexcept
        {
            return static_cast<int>(std::lrint(static_cast<float>(y) * sc));
        }
    };
    Cursor cursor;

    enum class Stop { Done, Budget, FirstHit };

    void startScan(Size image) noexcept
    {
        rawCount = 0;
        rawOverflow = false;
        cursor = {};
        cursor.active = true;
        cursor.image = image;
    }

    // Moves the cursor to the next scale with windows to scan, as OpenCV's
    // detectMultiScaleNoGrouping lists them: factor = scaleFactor^k (double, stored as float)
    // while the window fits the image; those with a window below minSize skipped, the first above
    // maxSize ends the list. The image is shrunk to round(size / scale) and a fixed window slides
    // over it with a step of 2 px when scale < 2 and 1 px otherwise. False past the last scale.
    bool enterNextScale() noexcept
    {
        Cursor& c = cursor;
        const int winW = cascade.windowWidth();
        const int winH = cascade.windowHeight();
        const int imgW = c.image.width;
        const int imgH = c.image.height;
        const int maxW = options.maxSize.width > 0 ? options.maxSize.width : imgW;
        const int maxH = options.maxSize.height > 0 ? options.maxSize.height : imgH;
        if (imgW < winW || imgH < winH)
            return false;
        for (;;) {
            const double factor = c.nextFactor;
            c.nextFactor *= options.scaleFactor;
            if (std::lrint(winW * factor) > imgW || std::lrint(winH * factor) > imgH)
                return false;
            const auto sc = static_cast<float>(factor);
            const long ww = std::lrint(static_cast<float>(winW) * sc);
            const long wh = std::lrint(static_cast<float>(winH) * sc);
            if (ww > maxW || wh > maxH)
                return false;
            if (ww < options.minSize.width || wh < options.minSize.height)
                continue;

            const int dw = static_cast<int>(std::lrint(static_cast<float>(imgW) / sc));
            const int dh = static_cast<int>(std::lrint(static_cast<float>(imgH) / sc));
            const int step = sc >= 2.0f ? 1 : 2;
            const int xEnd = std::max(dw + 1 - winW, 0);
            const int rows = std::max(dh + 1 - winH, 0);
            // OpenCV cuts the rows into ceil(w0 / 32) stripes (w0: the first scale's working
            // width) of a whole number of steps, rounding the step count down: the last row of
            // a scale can fall outside every stripe and is then never scanned.
            if (c.nstripes == 0)
                c.nstripes = std::max((xEnd + 31) / 32, 1);
            const int stripe = std::max((rows / step + c.nstripes - 1) / c.nstripes, 1) * step;
            const int yEnd = std::min(c.nstripes * stripe, rows);
            if (xEnd == 0 || yEnd == 0)
                continue;
            c.sc = sc;
            c.dw = dw;
            c.dh = dh;
            c.step = step;
            c.stepShift = step == 2 ? 1 : 0;
            c.xEnd = xEnd;
            c.yEnd = yEnd;
            c.boxW = static_cast<int>(ww);
            c.boxH = static_cast<int>(wh);
            c.y = 0;
            c.x = 0;
            c.inScale = true;
            return true;
        }
    }

    // The Viola-Jones scan (§3) as cv::CascadeClassifier::detectMultiScaleNoGrouping runs it, from
    // the cursor on, over `gray` (the frame of this call), evaluating at most `budget` windows
    // (skipped windows do not count). A scale is shrunk from `gray` only when one of its windows
    // is evaluated in this call, and only in the rows of such windows. With firstHit, stops
    // after the first window that passes.
    Stop run(const ConstImageView& gray, const WindowFilter& filter, bool firstHit,
             long budget) noexcept
    {
        Cursor& c = cursor;
        windows = 0;
        bool prepared = false;  // the cursor's scale is shrunk from this call's frame
        for (;;) {
            // Step 1: the next scale of OpenCV's list (window size, shrunk image size, step).
            if (!c.inScale) {
                if (!enterNextScale()) {
                    c.active = false;
                    return Stop::Done;
                }
                prepared = false;
            }
            for (; c.y < c.yEnd; c.y += c.step, c.x = 0) {
                // Step 2 (§3): only the windows with enough of the mask set, and none centred on
                // a face already tracked.
                const int j0 = c.x >> c.stepShift;
                const int j1 = (c.xEnd + c.step - 1) / c.step;
                const int wanted = selectWindows(gray.size(), filter, j0, j1);
                if (wanted == 0)
                    continue;
                if (windows >= budget)
                    return Stop::Budget;  // resumes at this row's first window to evaluate
                // Step 3: the frame shrunk to this scale, and its integral tables, only in the
                // rows of the windows evaluated.
                if (!prepared) {
                    tables.begin(gray, c.dw, c.dh, cascade.rowForm() && c.step == 2);
                    prepared = true;
                }
                tables.prepareRows(c.y, c.y + cascade.windowHeight());
                // Step 4: the cascade's first stages for the whole row at once.
                const int done = cascade.rowForm() && wanted >= RowPrefilter::kMinWindows
                                     ? prefilter.run(cascade, tables, c.y, c.step, j0, j1,
                                                     rowWanted.data())
                                     : 0;
                // Step 5: each window through the rest of the cascade; those passing are hits (in
                // first-hit mode, §3's verification, the first one ends the scan).
                const Stop stop = evaluateRow(done, firstHit, budget);
                if (stop != Stop::Done)
                    return stop;
            }
            c.inScale = false;
        }
    }

    // Marks the windows j0 <= j < j1 of the cursor's row that `filter` lets through in
    // rowWanted; returns how many (j1 - j0 without a filter).
    int selectWindows(Size image, const WindowFilter& filter, int j0, int j1) noexcept
    {
        const Cursor& c = cursor;
        if (filter.exclude.empty() && filter.mask == nullptr) {
            for (int j = j0; j < j1; ++j)
                rowWanted[static_cast<std::size_t>(j)] = 1;
            return j1 - j0;
        }
        const int by = c.imageY();
        int wanted = 0;
        for (int j = j0; j < j1; ++j) {
            const bool ok = windowWanted(image, filter, c.imageX(j * c.step), by);
            rowWanted[static_cast<std::size_t>(j)] = ok;
            wanted += ok;
        }
        return wanted;
    }

    // Coarse to fine: per window column x of the cursor's scale (shrunk-image pixels), its
    // image x and the mask columns it covers (as windowWanted maps them), once per scale.
    void prepareColumns(Size image, const WindowFilter& filter) noexcept
    {
        const Cursor& c = cursor;
        const int mw = filter.mask != nullptr ? filter.mask->size().width : 0;
        for (int x = 0; x < c.xEnd; ++x) {
            const int bx = c.imageX(x);
            const auto k = static_cast<std::size_t>(x);
            columnX[k] = bx;
            columnMask0[k] = bx * mw / image.width;
            columnMask1[k] = ((bx + c.boxW) * mw + image.width - 1) / image.width;
        }
    }

    // windowWanted for the window at column x (prepareColumns) of the row at image y `by`,
    // whose mask rows are my0..my1.
    bool columnWanted(const WindowFilter& filter, int x, int by, int my0, int my1) const noexcept
    {
        const Cursor& c = cursor;
        const auto k = static_cast<std::size_t>(x);
        const int cx = columnX[k] + c.boxW / 2;
        const int cy = by + c.boxH / 2;
        for (const Rect& e : filter.exclude)
            if (cx >= e.x && cx < e.x + e.width && cy >= e.y && cy < e.y + e.height)
                return false;
        return filter.mask == nullptr ||
               filter.mask->maskFraction({columnMask0[k], my0, columnMask1[k] - columnMask0[k],
                                          my1 - my0}) >= filter.minFraction;
    }

    // The mask rows of the cursor's row (windowWanted's mapping).
    void maskRows(Size image, const WindowFilter& filter, int& my0, int& my1) const noexcept
    {
        const Cursor& c = cursor;
        const int by = c.imageY();
        const int mh = filter.mask != nullptr ? filter.mask->size().height : 0;
        my0 = by * mh / image.height;
        my1 = ((by + c.boxH) * mh + image.height - 1) / image.height;
    }

    // Whether `filter` lets the cursor's scale's window at image position (bx, by) through:
    // enough of the mask under it, its centre in no excluded box.
    bool windowWanted(Size image, const WindowFilter& filter, int bx, int by) const noexcept
    {
        const Cursor& c = cursor;
        const int cx = bx + c.boxW / 2;
        const int cy = by + c.boxH / 2;
        for (const Rect& e : filter.exclude)
            if (cx >= e.x && cx < e.x + e.width && cy >= e.y && cy < e.y + e.height)
                return false;
        if (filter.mask == nullptr)
            return true;
        // The window mapped proportionally onto the mask, rounded outwards.
        const Size maskSize = filter.mask->size();
        const int mx0 = bx * maskSize.width / image.width;
        const int my0 = by * maskSize.height / image.height;
        const int mx1 = ((bx + c.boxW) * maskSize.width + image.width - 1) / image.width;
        const int my1 = ((by + c.boxH) * maskSize.height + image.height - 1) / image.height;
        return filter.mask->maskFraction({mx0, my0, mx1 - mx0, my1 - my0}) >= filter.minFraction;
    }

    // The wanted windows of the cursor's row from its x on, each decided by the prefilter's
    // result or through the rest of the cascade (`done`: the stages the prefilter did); the
    // passing ones become raw hits at (round(x * scale), round(y * scale)). Done at the row's end.
    Stop evaluateRow(int done, bool firstHit, long budget) noexcept
    {
        Cursor& c = cursor;
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(c.y) * tables.stride();
        for (; c.x < c.xEnd; c.x += c.step) {
            const int x = c.x;
            const int j = x >> c.stepShift;
            if (!rowWanted[static_cast<std::size_t>(j)])
                continue;
            if (windows >= budget)
                return Stop::Budget;  // resumes at this window
            ++windows;
            // After the prefilter: decided (<= 0), alive after `done` stages (1), or parked at
            // an undecidable stage sum (2).
            const int pre = done > 0 ? prefilter.result(j) : 1;
            const std::ptrdiff_t at = row + x;
            const int result = pre <= 0
                                   ? pre
                                   : cascade.evaluate(tables.sum() + at, tables.squaredSum() + at,
                                                      pre == 1 ? done : prefilter.from(j));
            if (result > 0) {
                addRawHit({c.imageX(x), c.imageY(), c.boxW, c.boxH});
                if (firstHit) {
                    c.x += c.step;
                    return Stop::FirstHit;
                }
            }
            if (result == 0)
                c.x += c.step;  // OpenCV skips past a first-stage rejection
        }
        return Stop::Done;
    }

    // Coarse to fine (detectCoarseToFine): per scale, the coarse grid through the first
    // kCoarseStages stages, then the windows of the full grid next to a coarse window that
    // passed. The coarse grid is every other row of the scan's grid and, in them, every other
    // window: 2 px apart in the shrunk image at a step-1 scale, 4 px at a step-2 one, which
    // the row prefilter takes from the table deinterleaved 2 or 4 ways. Rows in order, so the
    // raw hits come in OpenCV's order: coarse row r, then the rows r - 1 (between two coarse
    // rows) and r.
    void scanCoarseToFine(const ConstImageView& gray, const WindowFilter& filter) noexcept
    {
        startScan(gray.size());
        windows = 0;
        Cursor& c = cursor;
        while (enterNextScale()) {
            const int rows = (c.yEnd + c.step - 1) / c.step;
            const int cols = (c.xEnd + c.step - 1) / c.step;
            prepareColumns(gray.size(), filter);
            std::uint8_t* above = coarseAlive[0].data();  // coarse row r - 2
            std::uint8_t* here = coarseAlive[1].data();   // coarse row r
            std::fill_n(above, cols + 1, 0);
            bool prepared = false;
            int aliveAbove = 0;  // coarse windows that passed in row r - 2, and in row r
            for (int r = 0; r <= rows; r += 2) {
                std::fill_n(here, cols + 1, 0);
                const int aliveHere = r < rows ? coarseRow(gray, filter, r, here, prepared) : 0;
                if (r > 0 && aliveAbove + aliveHere > 0)
                    fineRow(gray, filter, r - 1, cols, above, here, prepared);
                if (aliveHere > 0)
                    fineRow(gray, filter, r, cols, nullptr, here, prepared);
                std::swap(above, here);
                aliveAbove = aliveHere;
            }
            c.inScale = false;
        }
        c.active = false;
    }

    // The scale's table rows of grid row r, shrunk from `gray` on first use (with the table
    // deinterleaved as the coarse rows' windows are apart: 2 ways, or 4 at a step-2 scale).
    void prepareGridRow(const ConstImageView& gray, int r, bool& prepared) noexcept
    {
        Cursor& c = cursor;
        if (!prepared) {
            tables.begin(gray, c.dw, c.dh, cascade.rowForm() && c.step == 1,
                         cascade.rowForm() && c.step == 2);
            prepared = true;
        }
        c.y = r * c.step;
        tables.prepareRows(c.y, c.y + cascade.windowHeight());
    }

    // Coarse row r: its even windows through the first stages (the row prefilter, then the
    // exact path to the last of them); alive[j] = 1 (j: the scan grid's window) where one
    // passed. Returns how many passed.
    int coarseRow(const ConstImageView& gray, const WindowFilter& filter, int r,
                   std::uint8_t* alive, bool& prepared) noexcept
    {
        Cursor& c = cursor;
        const int apart = 2 * c.step;                   // coarse windows, in shrunk pixels
        const int n = (c.xEnd + apart - 1) / apart;  // at x = 0, apart, ... < xEnd
        c.y = r * c.step;
        const int by = c.imageY();
        int my0 = 0, my1 = 0;
        maskRows(gray.size(), filter, my0, my1);
        int wanted = 0;
        for (int k = 0; k < n; ++k) {
            const bool ok = columnWanted(filter, apart * k, by, my0, my1);
            rowWanted[static_cast<std::size_t>(k)] = ok;
            wanted += ok;
        }
        if (wanted == 0)
            return 0;
        prepareGridRow(gray, r, prepared);
        windows += wanted;
        const int done = cascade.rowForm() && wanted >= RowPrefilter::kMinWindows
                             ? prefilter.run(cascade, tables, c.y, apart, 0, n,
                                             rowWanted.data(), kCoarseStages)
                             : 0;
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(c.y) * tables.stride();
        int passed = 0;
        for (int k = 0; k < n; ++k) {
            if (!rowWanted[static_cast<std::size_t>(k)])
                continue;
            const int pre = done > 0 ? prefilter.result(k) : 1;
            int result = pre;
            if (pre == 2 || (pre == 1 && done < kCoarseStages)) {
                const std::ptrdiff_t at = row + apart * k;
                result = cascade.evaluate(tables.sum() + at, tables.squaredSum() + at,
                                          pre == 2 ? prefilter.from(k) : done, kCoarseStages);
            }
            alive[2 * k] = result > 0;
            passed += result > 0;
        }
        return passed;
    }

    // Row r of the full grid: each window next to a coarse window that passed (in the coarse
    // rows `above` and `here`; `above` null for a coarse row itself, whose coarse windows are
    // decided already) decided, if OpenCV's scan evaluates it (below); hits added.
    void fineRow(const ConstImageView& gray, const WindowFilter& filter, int r, int cols,
                 const std::uint8_t* above, const std::uint8_t* here, bool& prepared) noexcept
    {
        Cursor& c = cursor;
        bool ready = false;
        c.y = r * c.step;
        const int by = c.imageY();
        int my0 = 0, my1 = 0;
        maskRows(gray.size(), filter, my0, my1);
        const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(c.y) * tables.stride();
        // OpenCV's scan skips the window after one its first stage rejects (evaluateRow): a
        // window is evaluated when wanted and the one before it was not evaluated and rejected
        // at the first stage. So that the hits are the full scan's, a window is decided only
        // if that scan evaluates it: the run of wanted windows rejected at the first stage
        // before it is found (those windows' first stage decided here), and the evaluated ones
        // alternate from its start. `known`: the last window whose place in that is known.
        int known = -1;
        bool knownEvaluated = false, knownFirstReject = false;
        const auto firstStageRejects = [&](int k) {
            const std::ptrdiff_t at = row + static_cast<std::ptrdiff_t>(k) * c.step;
            return cascade.evaluate(tables.sum() + at, tables.squaredSum() + at, 0, 1) == 0;
        };
        const auto evaluatedByTheFullScan = [&](int j) {
            int run = 0;
            bool startEvaluated = true;  // the window after the run's start
            for (int k = j - 1; k >= 0; --k, ++run) {
                if (k == known) {
                    startEvaluated = !(knownEvaluated && knownFirstReject);
                    break;
                }
                if (!columnWanted(filter, k * c.step, by, my0, my1) || !firstStageRejects(k))
                    break;
            }
            return run % 2 == 0 ? startEvaluated : !startEvaluated;
        };
        for (int j = 0; j < cols; ++j) {
            // A coarse window that passed goes on from the stages it passed; one that did
            // not is rejected.
            const bool coarse = above == nullptr && j % 2 == 0;
            const bool passed = coarse && here[j] != 0;
            if (coarse && !passed)
                continue;
            // The coarse windows within one step of it, along a row, a column or both.
            bool near = passed;
            for (int k = std::max(j - 1, 0); k <= j + 1 && !near; ++k)
                near = here[k] != 0 || (above != nullptr && above[k] != 0);
            if (!near)
                continue;
            const int x = j * c.step;
            if (!passed && !columnWanted(filter, x, by, my0, my1))
                continue;
            if (!ready) {
                prepareGridRow(gray, r, prepared);
                ready = true;
            }
            const bool evaluated = evaluatedByTheFullScan(j);
            known = j;
            knownEvaluated = evaluated;
            knownFirstReject = false;
            if (!evaluated)
                continue;
            if (!passed)
                ++windows;
            const std::ptrdiff_t at = row + x;
            const int result = cascade.evaluate(tables.sum() + at, tables.squaredSum() + at,
                                                passed ? kCoarseStages : 0);
            knownFirstReject = result == 0;
            if (result > 0)
                addRawHit({columnX[static_cast<std::size_t>(x)], by, c.boxW, c.boxH});
        }
    }

    void addRawHit(const Rect& r) noexcept
    {
        if (rawCount < static_cast<int>(raw.size()))
            raw[static_cast<std::size_t>(rawCount++)] = r;
        else
            rawOverflow = true;
    }

    // A whole scan in one call (detect, detectMasked, detectFirst).
    Stop scanWhole(const ConstImageView& gray, const WindowFilter& filter, bool firstHit) noexcept
    {
        startScan(gray.size());
        const Stop stop = run(gray, filter, firstHit, std::numeric_limits<long>::max());
        cursor.active = false;
        return stop;
    }

    bool checkImage(const ConstImageView& gray) noexcept
    {
        if (gray.empty() || gray.format != PixelFormat::Gray8) {
            setError("face detector: expected a Gray8 image");
            return false;
        }
        if (gray.width > options.maxFrameSize.width || gray.height > options.maxFrameSize.height) {
            setError("face detector: image larger than the configured maxFrameSize");
            return false;
        }
        return true;
    }

    // The faces of the scan as cv::CascadeClassifier::detectMultiScale returns them.
    int finish(Size image) noexcept
    {
        faceCount = grouping.faces({raw.data(), static_cast<std::size_t>(rawCount)},
                                   options.minNeighbors, image, faces);
        return faceCount;
    }
};

FaceDetector::FaceDetector(const HaarCascade& cascade, const FaceDetectorOptions& options)
    : impl_(std::make_unique<Impl>(cascade, options))
{
}

FaceDetector::~FaceDetector() = default;
FaceDetector::FaceDetector(FaceDetector&&) noexcept = default;
FaceDetector& FaceDetector::operator=(FaceDetector&&) noexcept = default;

int FaceDetector::detect(const ConstImageView& gray) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    d.scanWhole(gray, {}, false);
    return d.finish(gray.size());
}

int FaceDetector::detectMasked(const ConstImageView& gray, const IntegralImage& mask,
                               float minFraction, std::span<const Rect> exclude) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    if (mask.size().width <= 0 || mask.size().height <= 0) {
        d.setError("face detector: empty mask integral image");
        return -1;
    }
    d.scanWhole(gray, {&mask, minFraction, exclude}, false);
    return d.finish(gray.size());
}

bool FaceDetector::detectMaskedIncremental(const ConstImageView& gray, const IntegralImage* mask,
                                           float minFraction, std::span<const Rect> exclude,
                                           long windowBudget) noexcept
{
    Impl& d = *impl_;
    d.windows = 0;
    if (!d.checkImage(gray)) {
        d.cursor.active = false;
        return false;
    }
    if (mask != nullptr && (mask->size().width <= 0 || mask->size().height <= 0)) {
        d.setError("face detector: empty mask integral image");
        d.cursor.active = false;
        return false;
    }
    if (!d.cursor.active || d.cursor.image != gray.size())
        d.startScan(gray.size());
    const long budget = windowBudget > 0 ? windowBudget : std::numeric_limits<long>::max();
    if (d.run(gray, {mask, minFraction, exclude}, false, budget) != Impl::Stop::Done)
        return false;
    d.finish(gray.size());
    return true;
}

void FaceDetector::resetIncremental() noexcept
{
    impl_->cursor.active = false;
}

bool FaceDetector::incrementalScanActive() const noexcept
{
    return impl_->cursor.active;
}

int FaceDetector::detectCoarseToFine(const ConstImageView& gray, const IntegralImage* mask,
                                     float minFraction, std::span<const Rect> exclude) noexcept
{
    Impl& d = *impl_;
    if (!d.checkImage(gray))
        return -1;
    if (mask != nullptr && (mask->size().width <= 0 || mask->size().height <= 0)) {
        d.setError("face detector: empty mask integral image");
        return -1;
    }
    d.scanCoarseToFine(gray, {mask, minFraction, exclude});
    return d.finish(gray.size());
}

bool FaceDetector::detectFirst(const ConstImageView& gray, Rect& hit) noexcept
{
    Impl& d = *impl_;
    d.faceCount = 0;
    if (!d.checkImage(gray))
        return false;
    if (d.scanWhole(gray, {}, true) != Impl::Stop::FirstHit || d.rawCount == 0)
        return false;
    hit = d.raw[0];
    return true;
}

std::span<const Rect> FaceDetector::faces() const noexcept
{
    const Impl& d = *impl_;
    return {d.faces.data(), static_cast<std::size_t>(d.faceCount)};
}

std::span<const Rect> FaceDetector::rawHits() const noexcept
{
    return {impl_->raw.data(), static_cast<std::size_t>(impl_->rawCount)};
}

bool FaceDetector::rawHitsOverflowed() const noexcept
{
    return impl_->rawOverflow;
}

long FaceDetector::windowsEvaluated() const noexcept
{
    return impl_->windows;
}

Size FaceDetector::windowSize() const noexcept
{
    return {impl_->cascade.windowWidth(), impl_->cascade.windowHeight()};
}

const char* FaceDetector::lastError() const noexcept
{
    return impl_->error;
}

}  // namespace vision
