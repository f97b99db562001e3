#include "preview.hpp"

#include "models.hpp"
#include "platform/egl_context.hpp"

#include <GLES2/gl2.h>
#include <GLES2/gl2ext.h>
#include <tiny_obj_loader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace overlaygen {

namespace {

const char* const kVertexShader = R"(
attribute vec3 aPosition;
attribute vec3 aNormal;
uniform mat4 uModelViewProjection;
uniform mat3 uNormalMatrix;
varying vec3 vNormal;
void main() {
    vNormal = uNormalMatrix * aNormal;
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
}
)";

const char* const kFragmentShader = R"(
precision mediump float;
uniform vec4 uColor;
uniform float uShininess;
uniform vec3 uLight;
uniform vec3 uHalfway;
varying vec3 vNormal;
void main() {
    vec3 n = normalize(vNormal);
    float diffuse = max(dot(n, uLight), 0.0);
    float specular = uShininess > 0.0 ? pow(max(dot(n, uHalfway), 0.0), uShininess) * 0.5 : 0.0;
    gl_FragColor = vec4(uColor.rgb * (0.35 + 0.75 * diffuse) + vec3(specular), uColor.a);
}
)";

GLuint compile(GLenum type, const char* source)
{
    const GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("preview: shader does not compile: ") + log);
    }
    return shader;
}

/// Interleaved position + normal triangles of one colour.
struct Batch {
    std::vector<float> vertices;
    std::array<double, 4> rgba{};
    double shininess = 0.0;
};

Eigen::Matrix4f perspective(float fovYDegrees, float aspect, float zNear, float zFar)
{
    const float f = 1.0f / std::tan(fovYDegrees * std::numbers::pi_v<float> / 360.0f);
    Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
    m(0, 0) = f / aspect;
    m(1, 1) = f;
    m(2, 2) = (zFar + zNear) / (zNear - zFar);
    m(2, 3) = 2.0f * zFar * zNear / (zNear - zFar);
    m(3, 2) = -1.0f;
    return m;
}

Eigen::Matrix4f lookAt(const Eigen::Vector3f& eye, const Eigen::Vector3f& target,
                       const Eigen::Vector3f& up)
{
    const Eigen::Vector3f f = (target - eye).normalized();
    const Eigen::Vector3f s = f.cross(up).normalized();
    const Eigen::Vector3f u = s.cross(f);
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    m.block<1, 3>(0, 0) = s.transpose();
    m.block<1, 3>(1, 0) = u.transpose();
    m.block<1, 3>(2, 0) = -f.transpose();
    m(0, 3) = -s.dot(eye);
    m(1, 3) = -u.dot(eye);
    m(2, 3) = f.dot(eye);
    return m;
}

/// An ellipsoid whose horizontal sections are superellipses of exponent `squareness` (the
/// renderer's head proxy); normals from the parametric derivatives.
void addEllipsoid(Batch& batch, const Vec3& centre, const Vec3& semi, double squareness = 2.0)
{
    const int around = 64, rows = 32;
    const auto surface = [&](double theta, double phi) {
        const double s = std::sin(theta), c = std::cos(theta);
        const double k =
            1.0 / std::pow(std::pow(std::abs(s), squareness) + std::pow(std::abs(c), squareness),
                           1.0 / squareness);
        const Vec3 unit(std::cos(phi) * k * s, std::sin(phi), std::cos(phi) * k * c);
        return Vec3(centre + unit.cwiseProduct(semi));
    };
    const auto push = [&](int i, int j) {
        const double theta = 2.0 * std::numbers::pi * i / around;
        const double phi = std::numbers::pi * j / rows - std::numbers::pi / 2.0;
        const double h = 1e-4;
        const Vec3 p = surface(theta, phi);
        const double phiClamped =
            std::clamp(phi, -std::numbers::pi / 2 + h, std::numbers::pi / 2 - h);
        const Vec3 dTheta = surface(theta + h, phiClamped) - surface(theta - h, phiClamped);
        const Vec3 dPhi = surface(theta, phiClamped + h) - surface(theta, phiClamped - h);
        const Vec3 n = dTheta.cross(dPhi).normalized();
        for (double v : {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()})
            batch.vertices.push_back(static_cast<float>(v));
    };
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < around; ++i) {
            push(i, j);
            push(i + 1, j);
            push(i + 1, j + 1);
            push(i, j);
            push(i + 1, j + 1);
            push(i, j + 1);
        }
}

}  // namespace

struct PreviewRenderer::Impl {
    platform::EglContext egl;
    int width = 0;
    int height = 0;
    GLuint framebuffer = 0;
    GLuint colour = 0;
    GLuint depth = 0;
    GLuint program = 0;

    void draw(const Batch& batch, const Eigen::Matrix4f& mvp, const Eigen::Matrix3f& normalMatrix)
    {
        if (batch.vertices.empty())
            return;
        glUseProgram(program);
        glUniformMatrix4fv(glGetUniformLocation(program, "uModelViewProjection"), 1, GL_FALSE,
                           mvp.data());
        glUniformMatrix3fv(glGetUniformLocation(program, "uNormalMatrix"), 1, GL_FALSE,
                           normalMatrix.data());
        glUniform4f(glGetUniformLocation(program, "uColor"), static_cast<float>(batch.rgba[0]),
                    static_cast<float>(batch.rgba[1]), static_cast<float>(batch.rgba[2]),
                    static_cast<float>(batch.rgba[3]));
        glUniform1f(glGetUniformLocation(program, "uShininess"),
                    static_cast<float>(batch.shininess));
        const Eigen::Vector3f light = Eigen::Vector3f(-0.4f, 0.6f, 0.7f).normalized();
        const Eigen::Vector3f halfway = (light + Eigen::Vector3f(0, 0, 1)).normalized();
        glUniform3f(glGetUniformLocation(program, "uLight"), light.x(), light.y(), light.z());
        glUniform3f(glGetUniformLocation(program, "uHalfway"), halfway.x(), halfway.y(),
                    halfway.z());
        const GLint position = glGetAttribLocation(program, "aPosition");
        const GLint normal = glGetAttribLocation(program, "aNormal");
        glEnableVertexAttribArray(static_cast<GLuint>(position));
        glEnableVertexAttribArray(static_cast<GLuint>(normal));
        glVertexAttribPointer(static_cast<GLuint>(position), 3, GL_FLOAT, GL_FALSE,
                              6 * sizeof(float), batch.vertices.data());
        glVertexAttribPointer(static_cast<GLuint>(normal), 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                              batch.vertices.data() + 3);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(batch.vertices.size() / 6));
    }
};

PreviewRenderer::PreviewRenderer(int width, int height) : impl_(std::make_unique<Impl>())
{
    if (!impl_->egl.makeCurrent())
        throw std::runtime_error("preview: eglMakeCurrent without a surface failed");
    impl_->width = width;
    impl_->height = height;
    glGenFramebuffers(1, &impl_->framebuffer);
    glGenRenderbuffers(1, &impl_->colour);
    glGenRenderbuffers(1, &impl_->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, impl_->colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8_OES, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, impl_->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT16, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, impl_->framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, impl_->colour);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, impl_->depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("preview: framebuffer incomplete");
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    impl_->program = glCreateProgram();
    glAttachShader(impl_->program, vs);
    glAttachShader(impl_->program, fs);
    glLinkProgram(impl_->program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = 0;
    glGetProgramiv(impl_->program, GL_LINK_STATUS, &linked);
    if (!linked)
        throw std::runtime_error("preview: shader program does not link");
}

PreviewRenderer::~PreviewRenderer()
{
    glDeleteProgram(impl_->program);
    glDeleteRenderbuffers(1, &impl_->colour);
    glDeleteRenderbuffers(1, &impl_->depth);
    glDeleteFramebuffers(1, &impl_->framebuffer);
    impl_->egl.releaseCurrent();
}

cv::Mat PreviewRenderer::render(const Model& model, const std::string& objFile, double yawDegrees)
{
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    // No .mtl lookup: materials come from the model (as they come from the catalogue).
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, objFile.c_str(), nullptr,
                          true))
        throw std::runtime_error("preview: " + objFile + ": " + error);

    std::map<std::string, int> partMaterial;
    for (const Part& part : model.parts)
        partMaterial[part.name] = part.material;
    std::vector<Batch> batches(model.materials.size());
    for (std::size_t m = 0; m < batches.size(); ++m) {
        batches[m].rgba = model.materials[m].rgba;
        batches[m].shininess = model.materials[m].shininess;
    }
    for (const tinyobj::shape_t& shape : shapes) {
        const auto found = partMaterial.find(shape.name);
        if (found == partMaterial.end())
            throw std::runtime_error("preview: " + objFile + ": unknown object " + shape.name);
        Batch& batch = batches[static_cast<std::size_t>(found->second)];
        for (const tinyobj::index_t& index : shape.mesh.indices) {
            const std::size_t v = static_cast<std::size_t>(index.vertex_index) * 3;
            const std::size_t n = static_cast<std::size_t>(index.normal_index) * 3;
            for (int k = 0; k < 3; ++k)
                batch.vertices.push_back(attrib.vertices[v + static_cast<std::size_t>(k)]);
            for (int k = 0; k < 3; ++k)
                batch.vertices.push_back(attrib.normals[n + static_cast<std::size_t>(k)]);
        }
    }

    // Model (anchor origin) -> head (eye midpoint origin) -> turned about the head's axis.
    Vec3 anchor = Vec3::Zero();
    const double w = HeadMetrics::faceWidth;
    if (model.anchor == "head_top")
        anchor = Vec3(HeadMetrics::headTop[0], HeadMetrics::headTop[1], HeadMetrics::headTop[2]);
    else if (model.anchor == "forehead_top")
        anchor = Vec3(0.0, 0.45 * w, -0.05 * w);
    else if (model.anchor == "nose_bridge")
        anchor = Vec3(0.0, -0.04 * w, 0.06 * w);
    const Vec3 pivot(0.0, 0.0, HeadMetrics::proxyCentre[2]);
    const Eigen::Matrix3d turn = rotationY(yawDegrees * std::numbers::pi / 180.0);
    Eigen::Matrix4f toHead = Eigen::Matrix4f::Identity();
    toHead.block<3, 3>(0, 0) = turn.cast<float>();
    toHead.block<3, 1>(0, 3) = (turn * (anchor - pivot) + pivot).cast<float>();
    Eigen::Matrix4f headOnly = Eigen::Matrix4f::Identity();
    headOnly.block<3, 3>(0, 0) = turn.cast<float>();
    headOnly.block<3, 1>(0, 3) = (pivot - turn * pivot).cast<float>();

    // The mirror's camera is above the display, looking a little down at the face.
    const float distance = 0.82f;
    const float elevation = 8.0f * std::numbers::pi_v<float> / 180.0f;
    const Eigen::Vector3f target(0.0f, 0.09f, -0.06f);
    const Eigen::Vector3f eye =
        target + distance * Eigen::Vector3f(0.0f, std::sin(elevation), std::cos(elevation));
    const Eigen::Matrix4f viewProjection =
        perspective(32.0f, static_cast<float>(impl_->width) / static_cast<float>(impl_->height),
                    0.1f, 5.0f) *
        lookAt(eye, target, Eigen::Vector3f::UnitY());

    Batch head;
    head.rgba = {0.80, 0.62, 0.50, 1.0};
    addEllipsoid(
        head,
        Vec3(HeadMetrics::proxyCentre[0], HeadMetrics::proxyCentre[1], HeadMetrics::proxyCentre[2]),
        Vec3(HeadMetrics::proxySemiAxes[0], HeadMetrics::proxySemiAxes[1],
             HeadMetrics::proxySemiAxes[2]),
        HeadMetrics::proxySquareness);
    Batch eyes;
    eyes.rgba = {0.15, 0.10, 0.08, 1.0};
    eyes.shininess = 60.0;
    for (double x : {-0.0315, 0.0315})
        addEllipsoid(eyes, Vec3(x, 0.0, -0.0015), Vec3(0.0065, 0.0045, 0.004));

    glBindFramebuffer(GL_FRAMEBUFFER, impl_->framebuffer);
    glViewport(0, 0, impl_->width, impl_->height);
    glClearColor(0.62f, 0.66f, 0.70f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    const Eigen::Matrix3f turnF = turn.cast<float>();
    impl_->draw(head, viewProjection * headOnly, turnF);
    impl_->draw(eyes, viewProjection * headOnly, turnF);
    for (const Batch& batch : batches)
        if (batch.rgba[3] >= 1.0)
            impl_->draw(batch, viewProjection * toHead, turnF);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    for (const Batch& batch : batches)
        if (batch.rgba[3] < 1.0)
            impl_->draw(batch, viewProjection * toHead, turnF);
    glDepthMask(GL_TRUE);
    glFinish();

    cv::Mat rgba(impl_->height, impl_->width, CV_8UC4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, impl_->width, impl_->height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data);
    cv::Mat bgr;
    cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
    cv::flip(bgr, bgr, 0);  // GL rows start at the bottom
    return bgr;
}

}  // namespace overlaygen
