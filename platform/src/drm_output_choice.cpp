// GCC 12 at -O3 reports a false -Wrestrict inside libstdc++'s char_traits for `"literal" +
// std::string` (GCC bug 105329); the message building below is start-up code, not a hot path.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif
#include "drm_output_choice.hpp"

#include "platform/drm_display.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace platform {

namespace {

using ConnectorPtr = std::unique_ptr<drmModeConnector, decltype(&drmModeFreeConnector)>;

double refreshOf(const drmModeModeInfo& m) noexcept
{
    if (m.htotal == 0 || m.vtotal == 0)
        return m.vrefresh;
    double hz = m.clock * 1000.0 / (static_cast<double>(m.htotal) * m.vtotal);
    if ((m.flags & DRM_MODE_FLAG_INTERLACE) != 0)
        hz *= 2.0;
    if ((m.flags & DRM_MODE_FLAG_DBLSCAN) != 0)
        hz /= 2.0;
    return hz;
}

/// The cards to look at: the one asked for, else every /dev/dri/cardN in order.
std::vector<std::string> candidateCards(const std::string& card)
{
    if (!card.empty())
        return {card};
    std::vector<std::string> cards;
    for (int n = 0; n < 16; ++n) {
        const std::string path = "/dev/dri/card" + std::to_string(n);
        if (access(path.c_str(), F_OK) == 0)
            cards.push_back(path);
    }
    return cards;
}

/// A connected connector with modes on `fd`, or nullptr (caller frees). `why` says what was found.
drmModeConnector* connectedConnector(int fd, std::string& why)
{
    drmModeRes* resources = drmModeGetResources(fd);
    if (resources == nullptr) {
        why = "not a KMS device (" + std::string(std::strerror(errno)) + ")";
        return nullptr;
    }
    drmModeConnector* found = nullptr;
    for (int i = 0; i < resources->count_connectors && found == nullptr; ++i) {
        drmModeConnector* c = drmModeGetConnector(fd, resources->connectors[i]);
        if (c != nullptr && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0)
            found = c;
        else if (c != nullptr)
            drmModeFreeConnector(c);
    }
    if (found == nullptr)
        why = resources->count_connectors == 0 ? "no connectors" : "no connected display";
    drmModeFreeResources(resources);
    return found;
}

std::string connectorName(const drmModeConnector* c)
{
    const char* type = drmModeGetConnectorTypeName(c->connector_type);
    return std::string(type != nullptr ? type : "Unknown") + "-" +
           std::to_string(c->connector_type_id);
}

/// A CRTC that can drive `connector`: its current encoder's, else any its encoders allow.
std::uint32_t findCrtc(int fd, const drmModeRes* resources, const drmModeConnector* connector)
{
    if (connector->encoder_id != 0) {
        if (drmModeEncoder* e = drmModeGetEncoder(fd, connector->encoder_id)) {
            const std::uint32_t crtc = e->crtc_id;
            drmModeFreeEncoder(e);
            if (crtc != 0)
                return crtc;
        }
    }
    for (int i = 0; i < connector->count_encoders; ++i) {
        drmModeEncoder* e = drmModeGetEncoder(fd, connector->encoders[i]);
        if (e == nullptr)
            continue;
        for (int j = 0; j < resources->count_crtcs; ++j) {
            if ((e->possible_crtcs & (1u << j)) != 0) {
                drmModeFreeEncoder(e);
                return resources->crtcs[j];
            }
        }
        drmModeFreeEncoder(e);
    }
    return 0;
}

DisplayModeRequest modeRequest(const std::string& text)
{
    DisplayModeRequest request;
    std::string problem;
    if (!parseDisplayMode(text, request, problem))
        throwDrmError("", problem);
    return request;
}

/// The first candidate card with a connected connector: the card opened into `out`, the connector.
ConnectorPtr openConnectedCard(const std::string& card, DrmOutput& out)
{
    const std::vector<std::string> cards = candidateCards(card);
    if (cards.empty())
        throwDrmError("", "no /dev/dri/card* (no KMS driver loaded, or no permission to see it)");
    std::string tried;
    for (const std::string& path : cards) {
        const int cardFd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
        std::string why;
        if (cardFd < 0) {
            why = std::strerror(errno);
        } else {
            if (drmModeConnector* connector = connectedConnector(cardFd, why)) {
                out.fd = cardFd;
                out.cardPath = path;
                return {connector, drmModeFreeConnector};
            }
            ::close(cardFd);
        }
        tried += (tried.empty() ? "" : "; ") + path + ": " + why;
    }
    throwDrmError("", card.empty() ? "no card with a connected display (" + tried + ")" : tried);
}

/// The connector's mode that `request` asks for; `text` is the request as the config wrote it.
drmModeModeInfo chosenMode(const DrmOutput& out, const drmModeConnector& connector,
                           const DisplayModeRequest& request, const std::string& text)
{
    std::vector<DisplayModeCandidate> candidates;
    for (int i = 0; i < connector.count_modes; ++i)
        candidates.push_back(displayModeCandidateOf(connector.modes[i]));
    const int chosen = chooseDisplayMode(candidates, request);
    if (chosen < 0) {
        std::string list;
        for (std::size_t i = 0; i < candidates.size() && i < 12; ++i)
            list += (list.empty() ? "" : " ") + displayModeName(candidates[i]);
        throwDrmError(out.cardPath,
                      out.connectorName + " has no mode " + text + " (modes: " + list + ")");
    }
    return connector.modes[chosen];
}

std::uint32_t crtcFor(int fd, const drmModeConnector& connector)
{
    drmModeRes* resources = drmModeGetResources(fd);
    const std::uint32_t crtc = resources != nullptr ? findCrtc(fd, resources, &connector) : 0;
    if (resources != nullptr)
        drmModeFreeResources(resources);
    return crtc;
}

}  // namespace

DrmOutput chooseDrmOutput(const std::string& card, const std::string& mode)
{
    const DisplayModeRequest request = modeRequest(mode);
    DrmOutput out;
    const ConnectorPtr connector = openConnectedCard(card, out);
    try {
        out.connectorId = connector->connector_id;
        out.connectorName = connectorName(connector.get());
        out.mode = chosenMode(out, *connector, request, mode);
        out.crtcId = crtcFor(out.fd, *connector);
        if (out.crtcId == 0)
            throwDrmError(out.cardPath, "no CRTC can drive " + out.connectorName);
    } catch (...) {
        ::close(out.fd);
        throw;
    }
    return out;
}

DisplayModeCandidate displayModeCandidateOf(const drmModeModeInfo& m) noexcept
{
    return {m.hdisplay, m.vdisplay, refreshOf(m), (m.type & DRM_MODE_TYPE_PREFERRED) != 0,
            (m.flags & DRM_MODE_FLAG_INTERLACE) != 0};
}

void throwDrmError(const std::string& cardPath, const std::string& what)
{
    throw std::runtime_error("drm: " + (cardPath.empty() ? "" : cardPath + ": ") + what);
}

bool drmDisplayAvailable() noexcept
{
    try {
        for (const std::string& path : candidateCards("")) {
            const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
            if (fd < 0)
                continue;
            std::string why;
            drmModeConnector* c = connectedConnector(fd, why);
            ::close(fd);
            if (c != nullptr) {
                drmModeFreeConnector(c);
                return true;
            }
        }
    } catch (...) {
    }
    return false;
}

}  // namespace platform
