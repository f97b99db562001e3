#include "firmware/person_store.hpp"

#include "atomic_file.hpp"
#include "firmware/day_calendar.hpp"
#include "state_file.hpp"
#include "vision/aam_model.hpp"
#include "vision/bounded_file.hpp"
#include "vision/input_limits.hpp"

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace firmware {

namespace {

constexpr std::string_view kSuffix = ".toml";

bool isNameChar(char c) noexcept
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '-';
}

/// Appends `values` as a TOML array of floats ("[1.0e+00, ...]"); the new length, or -1.
int appendFloats(char* text, std::size_t size, int n, const float* values, int count) noexcept
{
    n += std::snprintf(text + n, size - static_cast<std::size_t>(n), "[");
    for (int i = 0; i < count && n < static_cast<int>(size); ++i)
        n += std::snprintf(text + n, size - static_cast<std::size_t>(n), "%s%.9e", i ? ", " : "",
                           static_cast<double>(values[i]));
    if (n < static_cast<int>(size))
        n += std::snprintf(text + n, size - static_cast<std::size_t>(n), "]\n");
    return n < static_cast<int>(size) ? n : -1;
}

/// Appends `bytes` as a TOML string of hex digits ("\"0a1f...\""); the new length, or -1.
int appendHex(char* text, std::size_t size, int n, const std::uint8_t* bytes, int count) noexcept
{
    static constexpr char kDigits[] = "0123456789abcdef";
    if (n < 0 || static_cast<std::size_t>(n) + 2 * static_cast<std::size_t>(count) + 4 > size)
        return -1;
    text[n++] = '"';
    for (int i = 0; i < count; ++i) {
        text[n++] = kDigits[bytes[i] >> 4];
        text[n++] = kDigits[bytes[i] & 15];
    }
    text[n++] = '"';
    text[n++] = '\n';
    text[n] = '\0';
    return n;
}

/// A hex string of at most `capacity` bytes into `out`; how many, or -1.
int readHex(const toml::node_view<const toml::node> node, std::uint8_t* out, int capacity)
{
    const std::optional<std::string_view> hex = node.value<std::string_view>();
    if (!hex || hex->size() % 2 != 0 || hex->size() / 2 > static_cast<std::size_t>(capacity))
        return -1;
    const auto digit = [](char c) {
        return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    };
    for (std::size_t i = 0; i < hex->size(); i += 2) {
        const int hi = digit((*hex)[i]), lo = digit((*hex)[i + 1]);
        if (hi < 0 || lo < 0)
            return -1;
        out[i / 2] = static_cast<std::uint8_t>(hi * 16 + lo);
    }
    return static_cast<int>(hex->size() / 2);
}

/// A float array of at most `capacity` finite numbers; its length, or -1.
int readFloats(const toml::node_view<const toml::node> node, float* out, int capacity)
{
    const toml::array* array = node.as_array();
    if (!array || static_cast<int>(array->size()) > capacity)
        return -1;
    int n = 0;
    for (const toml::node& v : *array) {
        const std::optional<double> d = v.value<double>();
        if (!d || !std::isfinite(*d))
            return -1;
        out[n++] = static_cast<float>(*d);
    }
    return n;
}

/// One person's file into `person`; false with why (no path) in `problem`.
bool decodePerson(const toml::table& t, std::string_view stem, std::uint32_t modelId,
                  Person& person, std::string& problem)
{
    const std::optional<std::string> name = t["name"].value<std::string>();
    const char* why = "";
    if (!name || !checkPersonName(*name, why) || *name != stem) {
        problem = "name must be the file's own name";
        return false;
    }
    char model[32];
    std::snprintf(model, sizeof model, "crc32:%08x", modelId);
    const std::optional<std::string> fileModel = t["model"].value<std::string>();
    if (!fileModel) {
        problem = "no model = \"crc32:...\"";
        return false;
    }
    if (*fileModel != model) {
        problem = "taken with another AAM model (" + fileModel->substr(0, 40) + ", this one is " +
                  model + ")";
        return false;
    }
    Person p;
    copyName(*name, p.name, sizeof p.name);
    const std::optional<std::int64_t> samples = t["samples"].value<std::int64_t>();
    if (!samples || *samples < 1 || *samples > 1'000'000) {
        problem = "samples must be a positive count";
        return false;
    }
    p.signature.samples = static_cast<int>(*samples);
    if (readFloats(t["shape"], p.signature.shapeUnits.data(), vision::kAamShapeUnits) !=
        vision::kAamShapeUnits) {
        problem = "shape must be " + std::to_string(vision::kAamShapeUnits) + " finite numbers";
        return false;
    }
    const int appearance = t.contains("appearance")
                               ? readFloats(t["appearance"], p.signature.appearance.data(),
                                            vision::kFaceSignatureMaxAppearance)
                               : 0;
    if (appearance < 0) {
        problem = "appearance must be at most " +
                  std::to_string(vision::kFaceSignatureMaxAppearance) + " finite numbers";
        return false;
    }
    p.signature.appearanceCount = appearance;
    // The texture descriptor (beyond §6); a file written before it has none and is matched on
    // the shape units and the appearance alone.
    const int texture = t.contains("texture") ? readHex(t["texture"], p.signature.texture.data(),
                                                        vision::kFaceSignatureMaxTexture)
                                              : 0;
    if (texture < 0) {
        problem = "texture must be a string of at most " +
                  std::to_string(2 * vision::kFaceSignatureMaxTexture) + " hex digits";
        return false;
    }
    p.signature.textureCount = texture;
    if (t.contains("overlay")) {
        const std::optional<std::string> overlay = t["overlay"].value<std::string>();
        if (!overlay || overlay->empty() || !copyName(*overlay, p.overlay, sizeof p.overlay) ||
            std::any_of(overlay->begin(), overlay->end(), [](char c) {
                return static_cast<unsigned char>(c) < 0x20 || c == '"' || c == '\\';
            })) {
            problem = "overlay must be an overlay's name";
            return false;
        }
    }
    if (t.contains("birthday")) {
        const std::optional<std::string> birthday = t["birthday"].value<std::string>();
        if (!birthday || !parseBirthday(*birthday, p.birthdayMonth, p.birthdayDay)) {
            problem = "birthday must be \"MM-DD\"";
            return false;
        }
    }
    person = p;
    return true;
}

}  // namespace

bool checkPersonName(std::string_view name, const char*& why) noexcept
{
    if (name.empty() || name.size() > kMaxPersonNameLength) {
        why = "a name is 1-32 characters";
        return false;
    }
    if (!std::all_of(name.begin(), name.end(), isNameChar)) {
        why = "a name is made of letters a-z, A-Z, digits, '_' and '-'";
        return false;
    }
    if (name.front() == '-' || name.front() == '_') {
        why = "a name starts with a letter or a digit";
        return false;
    }
    if (name == "guest") {
        why = "'guest' is what an unknown face is called";
        return false;
    }
    return true;
}

bool parseBirthday(std::string_view text, int& month, int& day) noexcept
{
    if (text.size() != 5 || text[2] != '-')
        return false;
    for (const std::size_t i : {0u, 1u, 3u, 4u})
        if (text[i] < '0' || text[i] > '9')
            return false;
    const int m = (text[0] - '0') * 10 + (text[1] - '0');
    const int d = (text[3] - '0') * 10 + (text[4] - '0');
    if (m < 1 || m > 12 || d < 1 || d > daysInMonth(2000, m))  // 2000: 02-29 exists
        return false;
    month = m;
    day = d;
    return true;
}

bool copyName(std::string_view text, char* out, std::size_t size) noexcept
{
    if (text.size() >= size)
        return false;
    std::memcpy(out, text.data(), text.size());
    out[text.size()] = '\0';
    return true;
}

PersonStore::PersonStore(const std::string& stateDir, std::uint32_t modelId, bool create)
    : dir_(stateDir + "/people"), modelId_(modelId)
{
    if (!create) {
        std::snprintf(error_, sizeof error_, "%s: not made", dir_.c_str());
        return;
    }
    usable_ = createStateFolder(dir_, error_, sizeof error_);
    if (usable_)
        ::chmod(dir_.c_str(), 0700);  // who the mirror knows is nobody else's business
}

std::uint32_t PersonStore::modelIdOf(const std::string& modelPath)
{
    const vision::BoundedFile file =
        vision::readBoundedFile(modelPath, vision::limits::kAamModelBytes);
    // The header: magic (8 bytes), version, payload size, the payload's CRC-32 (little-endian).
    if (file.status != vision::BoundedFile::Status::Ok || file.text.size() < 20 ||
        std::memcmp(file.text.data(), vision::kAamModelMagic, sizeof vision::kAamModelMagic) != 0)
        return 0;
    std::uint32_t crc = 0;
    for (int i = 3; i >= 0; --i)
        crc = (crc << 8) | static_cast<unsigned char>(file.text[16 + static_cast<std::size_t>(i)]);
    return crc;
}

std::vector<Person> PersonStore::loadAll(std::vector<std::string>& warnings) const
{
    std::vector<Person> people;
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
        const std::string file = entry.path().filename().string();
        if (file.size() > kSuffix.size() && file.ends_with(kSuffix))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const std::filesystem::path& path : files) {
        const std::string stem = path.stem().string();
        std::string warning;
        const std::optional<toml::table> table = readStateToml(path.string(), warning);
        if (!table) {
            warnings.push_back("people: " + (warning.empty() ? path.string() + ": gone" : warning) +
                               " (person skipped)");
            continue;
        }
        Person person;
        std::string problem;
        if (!decodePerson(*table, stem, modelId_, person, problem)) {
            warnings.push_back("people: " + path.string() + ": " + problem + "; skipped");
            continue;
        }
        if (static_cast<int>(people.size()) == kMaxPeople) {
            warnings.push_back("people: " + path.string() + ": more than " +
                               std::to_string(kMaxPeople) + " people; skipped");
            continue;
        }
        people.push_back(person);
    }
    return people;
}

const char* PersonStore::pathOf(const char* name) noexcept
{
    std::snprintf(path_, sizeof path_, "%s/%s.toml", dir_.c_str(), name);
    return path_;
}

bool PersonStore::save(const Person& p) noexcept
{
    if (!usable_)
        return false;
    char text[8192];  // the texture's hex digits (at most 2950) and 74 floats fit
    int n = std::snprintf(text, sizeof text,
                          "# a person the mirror knows (person add): their face signature's "
                          "numbers, never an image\nname = \"%s\"\nmodel = \"crc32:%08x\"\n"
                          "samples = %d\nshape = ",
                          p.name, modelId_, p.signature.samples);
    n = appendFloats(text, sizeof text, n, p.signature.shapeUnits.data(), vision::kAamShapeUnits);
    if (n >= 0) {
        n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), "appearance = ");
        n = appendFloats(text, sizeof text, n, p.signature.appearance.data(),
                         std::clamp(p.signature.appearanceCount, 0,
                                    vision::kFaceSignatureMaxAppearance));
    }
    if (n >= 0 && p.signature.textureCount > 0) {
        n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n), "texture = ");
        n = appendHex(text, sizeof text, n, p.signature.texture.data(),
                      std::clamp(p.signature.textureCount, 0, vision::kFaceSignatureMaxTexture));
    }
    if (n >= 0 && p.overlay[0])
        n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n),
                           "overlay = \"%s\"\n", p.overlay);
    if (n >= 0 && n < static_cast<int>(sizeof text) && p.birthdayMonth > 0)
        n += std::snprintf(text + n, sizeof text - static_cast<std::size_t>(n),
                           "birthday = \"%02d-%02d\"\n", p.birthdayMonth, p.birthdayDay);
    if (n < 0 || n >= static_cast<int>(sizeof text)) {
        std::snprintf(error_, sizeof error_, "%s: too long", pathOf(p.name));
        return false;
    }
    std::snprintf(tempPath_, sizeof tempPath_, "%s/.%s.toml.tmp", dir_.c_str(), p.name);
    return writeFileAtomically(dir_.c_str(), pathOf(p.name), tempPath_, text,
                               static_cast<std::size_t>(n), error_, sizeof error_, 0600);
}

bool PersonStore::remove(const char* name) noexcept
{
    if (::unlink(pathOf(name)) != 0 && errno != ENOENT) {
        std::snprintf(error_, sizeof error_, "%s: %s", path_, std::strerror(errno));
        return false;
    }
    return true;
}

int PersonStore::removeAll() noexcept
{
    DIR* d = ::opendir(dir_.c_str());
    if (!d)
        return 0;
    int removed = 0;
    while (const dirent* e = ::readdir(d)) {
        const std::string_view file = e->d_name;
        if (file.size() <= kSuffix.size() || !file.ends_with(kSuffix))
            continue;
        std::snprintf(path_, sizeof path_, "%s/%s", dir_.c_str(), e->d_name);
        removed += ::unlink(path_) == 0;
    }
    ::closedir(d);
    return removed;
}

}  // namespace firmware
