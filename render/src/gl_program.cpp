#include "gl_program.hpp"

#include <stdexcept>
#include <string>

namespace render::detail {
namespace {

// The first non-empty line of a GL info log: enough to find the fault, and keeps errors one line.
std::string firstLine(std::string log)
{
    const auto start = log.find_first_not_of(" \t\r\n");
    if (start == std::string::npos)
        return "(empty info log)";
    log.erase(0, start);
    const auto end = log.find_first_of("\r\n\0", 0, 3);  // the log ends in a NUL
    if (end != std::string::npos)
        log.erase(end);
    while (!log.empty() && (log.back() == ' ' || log.back() == '\t'))
        log.pop_back();
    return log;
}

std::string shaderLog(GLuint shader)
{
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    if (length > 0)
        glGetShaderInfoLog(shader, length, nullptr, log.data());
    return firstLine(std::move(log));
}

std::string programLog(GLuint program)
{
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    if (length > 0)
        glGetProgramInfoLog(program, length, nullptr, log.data());
    return firstLine(std::move(log));
}

GLuint compile(const char* programName, GLenum type, const char* source)
{
    const char* kind = type == GL_VERTEX_SHADER ? "vertex" : "fragment";
    const GLuint shader = glCreateShader(type);
    if (shader == 0)
        throw std::runtime_error(std::string(programName) + " " + kind +
                                 " shader: glCreateShader failed (no current GLES2 context?)");
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string message = std::string(programName) + " " + kind +
                                    " shader does not compile: " + shaderLog(shader);
        glDeleteShader(shader);
        throw std::runtime_error(message);
    }
    return shader;
}

}  // namespace

GlProgram::GlProgram(const char* name, const char* vertexSource, const char* fragmentSource,
                     std::initializer_list<const char*> attributes)
    : name_(name)
{
    const GLuint vertex = compile(name, GL_VERTEX_SHADER, vertexSource);
    GLuint fragment = 0;
    try {
        fragment = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vertex);
        throw;
    }
    id_ = glCreateProgram();
    glAttachShader(id_, vertex);
    glAttachShader(id_, fragment);
    GLuint location = 0;
    for (const char* attribute : attributes)
        glBindAttribLocation(id_, location++, attribute);
    glLinkProgram(id_);
    // The program keeps what it needs; flagging the shaders now frees them with the program.
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string message =
            std::string(name) + " program does not link: " + programLog(id_);
        glDeleteProgram(id_);
        id_ = 0;
        throw std::runtime_error(message);
    }
}

GlProgram::~GlProgram()
{
    if (id_ != 0)
        glDeleteProgram(id_);
}

GLint GlProgram::uniform(const char* uniformName) const
{
    const GLint location = glGetUniformLocation(id_, uniformName);
    if (location < 0)
        throw std::runtime_error(std::string(name_) + " program has no uniform " + uniformName);
    return location;
}

void drawTexturedStrip(const GlBuffer& buffer, const float (&vertices)[16]) noexcept
{
    glBindBuffer(GL_ARRAY_BUFFER, buffer.id());
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof vertices, vertices);
    const auto stride = static_cast<GLsizei>(4 * sizeof(float));
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(0));
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(2 * sizeof(float)));
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
    glDisableVertexAttribArray(1);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace render::detail
