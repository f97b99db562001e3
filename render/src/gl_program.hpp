#pragma once
// Private GL helpers of the renderer: a shader program whose compile and link failures become one
// readable line, and owning handles for textures and buffers, so that a constructor throwing
// half-way through creating GL objects leaks none of them.

#include <GLES2/gl2.h>

#include <initializer_list>

namespace render::detail {

/// A linked GLES2 program. Needs a current context; the destructor needs it still current.
class GlProgram {
public:
    /// Compiles both shaders and links them; attribute i of `attributes` gets location i.
    /// Throws std::runtime_error with one line, e.g.
    /// "video fragment shader does not compile: 0:4(12): error: ...".
    GlProgram(const char* name, const char* vertexSource, const char* fragmentSource,
              std::initializer_list<const char*> attributes);
    ~GlProgram();
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    GLuint id() const noexcept { return id_; }
    /// Location of a uniform the shaders use; throws when it is not there (typo, optimised out).
    GLint uniform(const char* uniformName) const;

private:
    const char* name_;
    GLuint id_ = 0;
};

/// An owned texture name.
class GlTexture {
public:
    GlTexture() noexcept { glGenTextures(1, &id_); }
    ~GlTexture()
    {
        if (id_ != 0)
            glDeleteTextures(1, &id_);
    }
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;
    GLuint id() const noexcept { return id_; }

private:
    GLuint id_ = 0;
};

/// An owned buffer object name.
class GlBuffer {
public:
    GlBuffer() noexcept { glGenBuffers(1, &id_); }
    ~GlBuffer()
    {
        if (id_ != 0)
            glDeleteBuffers(1, &id_);
    }
    GlBuffer(const GlBuffer&) = delete;
    GlBuffer& operator=(const GlBuffer&) = delete;
    GLuint id() const noexcept { return id_; }

private:
    GLuint id_ = 0;
};

/// Draws a quad as a 4-vertex triangle strip of interleaved (x, y, s, t) floats: uploads them into
/// `buffer`, feeds attributes 0 (position) and 1 (texture coordinate) and unbinds the buffer.
/// The caller has bound its program, texture and uniforms.
void drawTexturedStrip(const GlBuffer& buffer, const float (&vertices)[16]) noexcept;

}  // namespace render::detail
