#pragma once
// Scenes for the 3D overlay tests, the snapshots and the benchmark: a GL test context with a depth
// buffer, real faces of the IMM database placed from their landmarks, the catalogue to draw.

#include "gl_test_context.hpp"
#include "render/face_overlay_layer.hpp"
#include "render/overlay_catalogue.hpp"
#include "vision/face_tracker.hpp"
#include "vision/head_pose.hpp"
#include "vision/image.hpp"

#include <GLES2/gl2.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace testing_support {

/// A depth renderbuffer attached to the framebuffer bound now (GlTestContext has colour only).
class DepthAttachment {
public:
    DepthAttachment(int width, int height)
    {
        glGenRenderbuffers(1, &renderbuffer_);
        glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                  renderbuffer_);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("depth attachment: framebuffer incomplete");
    }
    ~DepthAttachment()
    {
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, 0);
        glDeleteRenderbuffers(1, &renderbuffer_);
    }
    DepthAttachment(const DepthAttachment&) = delete;
    DepthAttachment& operator=(const DepthAttachment&) = delete;

private:
    GLuint renderbuffer_ = 0;
};

/// The eye centres of an IMM face (.asf: 58 points, relative coordinates; paths 1 and 2 are the
/// eyes), in pixels of its 640x480 picture.
struct EyeCentres {
    vision::Point2f first;   ///< path 1 (image right)
    vision::Point2f second;  ///< path 2 (image left)
};

inline EyeCentres immEyes(const std::string& asfPath, int width = 640, int height = 480)
{
    std::ifstream in(asfPath);
    if (!in)
        throw std::runtime_error("cannot read " + asfPath);
    double sum[3][2] = {};
    int count[3] = {};
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream fields(line);
        int path = 0;
        int type = 0;
        double x = 0;
        double y = 0;
        if (!(fields >> path >> type >> x >> y))
            continue;
        if (path == 1 || path == 2) {
            sum[path][0] += x * width;
            sum[path][1] += y * height;
            ++count[path];
        }
    }
    if (count[1] == 0 || count[2] == 0)
        throw std::runtime_error("no eye points in " + asfPath);
    return {{static_cast<float>(sum[1][0] / count[1]), static_cast<float>(sum[1][1] / count[1])},
            {static_cast<float>(sum[2][0] / count[2]), static_cast<float>(sum[2][1] / count[2])}};
}

/// The tracker face whose box puts the head model's eyes on `eyes` (the inverse of
/// vision::headPoseFromFace with HeadModel's interocular ratio), confirmed, shifted by (dx, dy).
inline vision::TrackedFace faceFromEyes(
    const EyeCentres& eyes, int id, float dx = 0.f, float dy = 0.f,
    float interocularPerFaceWidth = render::HeadModel{}.interocularPerFaceWidth)
{
    const float ex = eyes.first.x - eyes.second.x;
    const float ey = eyes.first.y - eyes.second.y;
    const float distance = std::sqrt(ex * ex + ey * ey);
    const float roll = std::atan2(ey, ex);
    vision::TrackedFace face;
    face.id = id;
    face.size = distance / interocularPerFaceWidth;
    face.rollDegrees = roll * 180.f / 3.14159265f;
    const float above = vision::kEyeMidpointAboveBoxCentre * face.size;
    const float mx = 0.5f * (eyes.first.x + eyes.second.x) + dx;
    const float my = 0.5f * (eyes.first.y + eyes.second.y) + dy;
    face.centre = {mx - above * std::sin(roll), my + above * std::cos(roll)};
    face.state = vision::FaceState::Confirmed;
    face.hits = 5;
    face.confidence = 1.f;
    return face;
}

/// The project's catalogue when it is there, else the tests' minimal one.
inline std::string overlayCataloguePath(const std::string& sourceDir)
{
    const std::string project = sourceDir + "/assets/overlays/catalogue.toml";
    if (std::filesystem::exists(project))
        return project;
    return sourceDir + "/tests/data/overlays/catalogue.toml";
}

}  // namespace testing_support
