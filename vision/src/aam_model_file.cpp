// The AAM model file (docs/aam-model-format.md): a 20-byte header (magic, version, payload size,
// the payload's CRC-32), then the payload, little-endian, its parts in the model's order. The
// header is checked before the payload is parsed, so a short, foreign, newer or damaged file is
// named as such; the payload's counts and indices are checked again, so a model that passed the
// checksum but came from a faulty writer cannot index out of bounds later.
#include "crc32.hpp"
#include "vision/aam_model.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace vision {

namespace {

static_assert(std::endian::native == std::endian::little, "the model file is little-endian");

constexpr std::size_t kHeaderBytes = 20;
// The format's bounds: far above the cut CANDIDE (84 vertices, 144 triangles, 6 + 10 units) and a
// 256-px frame, far below what a 32-bit product could not allocate.
constexpr std::uint32_t kMaxVertices = 1000, kMaxTriangles = 4000, kMaxUnits = 64,
                        kMaxFrameSide = 1024, kMaxAppearanceModes = 1000;

class FormatError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class PayloadWriter {
public:
    template <typename T>
    void put(T value)
    {
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        bytes.append(raw, sizeof(T));
    }
    void putText(const std::string& text)
    {
        if (text.size() > 255)
            throw std::invalid_argument("aam model: unit name \"" + text + "\" is over 255 bytes");
        put<std::uint8_t>(static_cast<std::uint8_t>(text.size()));
        bytes += text;
    }
    void putFloats(const std::vector<float>& values)
    {
        for (const float v : values)
            put(v);
    }
    std::string bytes;
};

class PayloadReader {
public:
    explicit PayloadReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

    template <typename T>
    T get(const char* what)
    {
        if (bytes_.size() - at_ < sizeof(T))
            throw FormatError(std::string("malformed: the payload ends in ") + what);
        T value;
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }
    std::uint32_t count(const char* what, std::uint32_t max)
    {
        const auto n = get<std::uint32_t>(what);
        if (n > max)
            throw FormatError("malformed: " + std::to_string(n) + " " + what + " (at most " +
                              std::to_string(max) + ")");
        return n;
    }
    std::string text(const char* what)
    {
        const auto n = get<std::uint8_t>(what);
        std::string s;
        for (std::uint8_t i = 0; i < n; ++i)
            s += static_cast<char>(get<std::uint8_t>(what));
        return s;
    }
    float finite(const char* what)
    {
        const auto v = get<float>(what);
        if (!std::isfinite(v))
            throw FormatError(std::string("malformed: a value of ") + what + " is not finite");
        return v;
    }
    std::vector<float> floats(std::size_t n, const char* what)
    {
        if ((bytes_.size() - at_) / sizeof(float) < n)
            throw FormatError(std::string("malformed: the payload ends in ") + what);
        std::vector<float> out(n);
        for (float& v : out)
            v = finite(what);
        return out;
    }
    bool atEnd() const noexcept { return at_ == bytes_.size(); }

private:
    std::span<const std::byte> bytes_;
    std::size_t at_ = 0;
};

struct Counts {
    std::uint32_t vertices, triangles, animationUnits, shapeUnits, shapeModes, width, height,
        pixels, appearanceModes;
};

void checkSizes(const AamModel& m)
{
    const std::size_t v = m.mesh.vertices.size(), p = m.pixels.size();
    const bool agree = m.mesh.candideNumber.size() == v && m.meanShape.size() == 2 * v &&
                       m.shapeModes.size() == 2 * v * m.shapeVariances.size() &&
                       m.meanAppearance.size() == p &&
                       m.appearanceModes.size() == p * m.appearanceVariances.size();
    if (!agree)
        throw std::invalid_argument("aam model: its parts disagree in size");
    if (v > kMaxVertices || m.mesh.triangles.size() > kMaxTriangles ||
        m.mesh.animationUnits.size() > kMaxUnits || m.mesh.shapeUnits.size() > kMaxUnits ||
        m.frameWidth <= 0 || m.frameHeight <= 0 || m.frameWidth > static_cast<int>(kMaxFrameSide) ||
        m.frameHeight > static_cast<int>(kMaxFrameSide) ||
        m.appearanceVariances.size() > kMaxAppearanceModes || m.shapeVariances.size() > 2 * v) {
        throw std::invalid_argument(
            "aam model: beyond the format's bounds (docs/aam-model-format.md)");
    }
}

void putUnits(PayloadWriter& w, const std::vector<CandideUnit>& units)
{
    for (const CandideUnit& unit : units) {
        w.putText(unit.name);
        w.putText(unit.label);
        w.put<std::uint32_t>(static_cast<std::uint32_t>(unit.vertices.size()));
        for (std::size_t k = 0; k < unit.vertices.size(); ++k) {
            w.put<std::uint16_t>(static_cast<std::uint16_t>(unit.vertices[k]));
            for (int c = 0; c < 3; ++c)
                w.put(unit.displacements[k][c]);
        }
    }
}

std::vector<CandideUnit> getUnits(PayloadReader& r, std::uint32_t count, std::uint32_t vertices)
{
    std::vector<CandideUnit> units(count);
    for (CandideUnit& unit : units) {
        unit.name = r.text("a unit's name");
        unit.label = r.text("a unit's label");
        const std::uint32_t entries = r.count("unit entries", vertices);
        for (std::uint32_t k = 0; k < entries; ++k) {
            const auto vertex = r.get<std::uint16_t>("a unit's entries");
            if (vertex >= vertices)
                throw FormatError("malformed: unit \"" + unit.name + "\" moves vertex " +
                                  std::to_string(vertex) + " of " + std::to_string(vertices));
            unit.vertices.push_back(vertex);
            const float x = r.finite("a unit's displacements"),
                        y = r.finite("a unit's displacements"),
                        z = r.finite("a unit's displacements");
            unit.displacements.emplace_back(x, y, z);
        }
    }
    return units;
}

Counts getCounts(PayloadReader& r)
{
    Counts c{};
    c.vertices = r.count("vertices", kMaxVertices);
    c.triangles = r.count("triangles", kMaxTriangles);
    c.animationUnits = r.count("animation units", kMaxUnits);
    c.shapeUnits = r.count("shape units", kMaxUnits);
    c.shapeModes = r.count("shape modes", 2 * c.vertices);
    c.width = r.count("pixels of frame width", kMaxFrameSide);
    c.height = r.count("pixels of frame height", kMaxFrameSide);
    c.pixels = r.count("appearance pixels", c.width * c.height);
    c.appearanceModes = r.count("appearance modes", kMaxAppearanceModes);
    if (c.width == 0 || c.height == 0)
        throw FormatError("malformed: an empty appearance frame");
    return c;
}

void getMesh(PayloadReader& r, const Counts& c, CandideMesh& mesh)
{
    for (std::uint32_t i = 0; i < c.vertices; ++i) {
        mesh.candideNumber.push_back(r.get<std::int32_t>("the vertices"));
        const float x = r.finite("the vertices"), y = r.finite("the vertices"),
                    z = r.finite("the vertices");
        mesh.vertices.emplace_back(x, y, z);
    }
    for (std::uint32_t t = 0; t < c.triangles; ++t) {
        std::array<int, 3> tri{};
        for (int& v : tri) {
            v = r.get<std::uint16_t>("the triangles");
            if (v >= static_cast<int>(c.vertices))
                throw FormatError("malformed: triangle " + std::to_string(t) + " uses vertex " +
                                  std::to_string(v) + " of " + std::to_string(c.vertices));
        }
        mesh.triangles.push_back(tri);
    }
    mesh.animationUnits = getUnits(r, c.animationUnits, c.vertices);
    mesh.shapeUnits = getUnits(r, c.shapeUnits, c.vertices);
}

void getPixels(PayloadReader& r, const Counts& c, std::vector<AppearancePixel>& pixels)
{
    for (std::uint32_t i = 0; i < c.pixels; ++i) {
        AppearancePixel p;
        p.x = r.get<std::uint16_t>("the pixel table");
        p.y = r.get<std::uint16_t>("the pixel table");
        p.triangle = r.get<std::uint16_t>("the pixel table");
        if (p.x >= c.width || p.y >= c.height || p.triangle >= c.triangles) {
            throw FormatError("malformed: appearance pixel " + std::to_string(i) +
                              " is outside the frame or the mesh");
        }
        pixels.push_back(p);
    }
}

AamModel getPayload(std::span<const std::byte> payload)
{
    PayloadReader r(payload);
    const Counts c = getCounts(r);
    AamModel m;
    getMesh(r, c, m.mesh);
    m.meanShape = r.floats(2 * c.vertices, "the mean shape");
    m.shapeModes = r.floats(std::size_t{2} * c.vertices * c.shapeModes, "the shape modes");
    m.shapeVariances = r.floats(c.shapeModes, "the shape variances");
    m.frameWidth = static_cast<int>(c.width);
    m.frameHeight = static_cast<int>(c.height);
    getPixels(r, c, m.pixels);
    m.meanAppearance = r.floats(c.pixels, "the mean appearance");
    m.appearanceModes = r.floats(std::size_t{c.pixels} * c.appearanceModes, "the appearance modes");
    m.appearanceVariances = r.floats(c.appearanceModes, "the appearance variances");
    if (!r.atEnd())
        throw FormatError("malformed: bytes left after the appearance variances");
    return m;
}

std::uint32_t headerWord(std::span<const std::byte> bytes, std::size_t at)
{
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

std::string hex(std::uint32_t v)
{
    char text[11];
    std::snprintf(text, sizeof text, "0x%08x", v);
    return text;
}

}  // namespace

std::string encodeAamModel(const AamModel& m)
{
    checkSizes(m);
    PayloadWriter w;
    for (const std::size_t n :
         {m.mesh.vertices.size(), m.mesh.triangles.size(), m.mesh.animationUnits.size(),
          m.mesh.shapeUnits.size(), m.shapeVariances.size(), static_cast<std::size_t>(m.frameWidth),
          static_cast<std::size_t>(m.frameHeight), m.pixels.size(), m.appearanceVariances.size()}) {
        w.put<std::uint32_t>(static_cast<std::uint32_t>(n));
    }
    for (std::size_t i = 0; i < m.mesh.vertices.size(); ++i) {
        w.put<std::int32_t>(m.mesh.candideNumber[i]);
        for (int c = 0; c < 3; ++c)
            w.put(m.mesh.vertices[i][c]);
    }
    for (const auto& tri : m.mesh.triangles) {
        for (const int v : tri)
            w.put<std::uint16_t>(static_cast<std::uint16_t>(v));
    }
    putUnits(w, m.mesh.animationUnits);
    putUnits(w, m.mesh.shapeUnits);
    for (const auto* part : {&m.meanShape, &m.shapeModes, &m.shapeVariances})
        w.putFloats(*part);
    for (const AppearancePixel& p : m.pixels) {
        w.put(p.x);
        w.put(p.y);
        w.put(p.triangle);
    }
    for (const auto* part : {&m.meanAppearance, &m.appearanceModes, &m.appearanceVariances})
        w.putFloats(*part);
    PayloadWriter header;
    header.bytes.assign(kAamModelMagic, sizeof kAamModelMagic);
    header.put<std::uint32_t>(kAamModelVersion);
    header.put<std::uint32_t>(static_cast<std::uint32_t>(w.bytes.size()));
    header.put<std::uint32_t>(crc32(std::as_bytes(std::span(w.bytes.data(), w.bytes.size()))));
    return header.bytes + w.bytes;
}

AamModelFile decodeAamModel(std::span<const std::byte> bytes)
{
    AamModelFile out;
    if (bytes.size() < kHeaderBytes) {
        out.problem = "truncated: " + std::to_string(bytes.size()) +
                      " bytes, shorter than the 20-byte header";
        return out;
    }
    if (std::memcmp(bytes.data(), kAamModelMagic, sizeof kAamModelMagic) != 0) {
        out.problem = "not an AAM model file (it does not start with MIRRAAM)";
        return out;
    }
    const std::uint32_t version = headerWord(bytes, 8), size = headerWord(bytes, 12),
                        sum = headerWord(bytes, 16);
    if (version != kAamModelVersion) {
        out.problem = "model format version " + std::to_string(version) +
                      "; this build reads version " + std::to_string(kAamModelVersion);
        return out;
    }
    const std::span<const std::byte> payload = bytes.subspan(kHeaderBytes);
    if (payload.size() != size) {
        out.problem = (payload.size() < size ? "truncated: " : "trailing bytes: ") +
                      std::string("the header announces ") + std::to_string(size) +
                      " payload bytes, the file has " + std::to_string(payload.size());
        return out;
    }
    if (const std::uint32_t actual = crc32(payload); actual != sum) {
        out.problem =
            "corrupt: the payload's CRC-32 is " + hex(actual) + ", the header says " + hex(sum);
        return out;
    }
    try {
        out.model = getPayload(payload);
        out.ok = true;
    } catch (const FormatError& e) {
        out.problem = e.what();
    }
    return out;
}

AamModelFile loadAamModel(const std::string& path)
{
    const BoundedFile file = readBoundedFile(path, limits::kAamModelBytes);
    AamModelFile out;
    if (file.status != BoundedFile::Status::Ok) {
        out.problem = path + ": " + file.problem;
        return out;
    }
    out = decodeAamModel(std::as_bytes(std::span(file.text.data(), file.text.size())));
    if (!out.ok)
        out.problem = path + ": " + out.problem;
    return out;
}

}  // namespace vision
