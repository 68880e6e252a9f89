#include "display/image_view.h"

#include <stdexcept>
#include <string>

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

namespace igi {
namespace {

const char* kVertex = R"(#version 120
varying vec2 uv;
void main() {
  uv = gl_MultiTexCoord0.xy;
  gl_Position = gl_Vertex;
}
)";

// Nearest texel, so each window pixel shows its own image pixel unfiltered.
const char* kFragment = R"(#version 120
uniform sampler2D image;
uniform float exposure;
varying vec2 uv;
float srgb(float v) {
  v = clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}
void main() {
  vec3 c = exposure * texture2D(image, uv).rgb;
  gl_FragColor = vec4(srgb(c.r), srgb(c.g), srgb(c.b), 1.0);
}
)";

GLuint compile(GLenum kind, const char* source) {
  GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("display shader: ") + log);
  }
  return shader;
}

}  // namespace

ImageView::ImageView() {
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertex), fragment = compile(GL_FRAGMENT_SHADER, kFragment);
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("display shader: does not link");
  exposure_location_ = glGetUniformLocation(program_, "exposure");
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

ImageView::~ImageView() {
  glDeleteTextures(1, &texture_);
  glDeleteProgram(program_);
}

void ImageView::upload(const Image& image) {
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (image.width != width_ || image.height != height_) {
    width_ = image.width;
    height_ = image.height;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width_, height_, 0, GL_RGB, GL_FLOAT, image.pixels.data());
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGB, GL_FLOAT, image.pixels.data());
  }
}

void ImageView::draw(int width, int height, float exposure) const {
  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glUseProgram(program_);
  glUniform1f(exposure_location_, exposure);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glBegin(GL_QUADS);  // texture row 0 (image row 0) at the top of the window
  glTexCoord2f(0, 1); glVertex2f(-1, -1);
  glTexCoord2f(1, 1); glVertex2f(1, -1);
  glTexCoord2f(1, 0); glVertex2f(1, 1);
  glTexCoord2f(0, 0); glVertex2f(-1, 1);
  glEnd();
  glUseProgram(0);
}

}  // namespace igi
