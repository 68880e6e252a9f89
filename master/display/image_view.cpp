#include "display/image_view.h"

#include <cstdio>
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

// The table's node n of a channel stands for 2^(lo + n (hi - lo) / (size - 1));
// texel centres sit at (n + 0.5) / size; under 2^lo reads the lowest node.
// Between nodes, the four corners of the cell's tetrahedron that holds the
// point (view_table_lookup() is the same lookup on the CPU): the largest
// fraction's axis first, then the next.
std::string fragment_source() {
  char constants[160];
  std::snprintf(constants, sizeof constants, "const float lo = %.9g, hi = %.9g, size = %d.0;\n", kViewTableLog2Min,
                kViewTableLog2Max, kViewTableSize);
  return std::string("#version 120\n") + constants + R"(uniform sampler2D image;
uniform sampler3D view_table;
uniform float exposure;
varying vec2 uv;
vec3 node(vec3 n) { return texture3D(view_table, (n + 0.5) / size).rgb; }
void main() {
  vec3 c = max(exposure * texture2D(image, uv).rgb, vec3(exp2(lo)));
  vec3 u = clamp((log2(c) - lo) / (hi - lo), 0.0, 1.0) * (size - 1.0);
  vec3 base = min(floor(u), vec3(size - 2.0));
  vec3 f = u - base;
  vec3 first, second, w;  // the first and second steps, and the fractions from largest to smallest
  if (f.r >= f.g && f.g >= f.b) { first = vec3(1, 0, 0); second = vec3(1, 1, 0); w = f.rgb; }
  else if (f.r >= f.b && f.b >= f.g) { first = vec3(1, 0, 0); second = vec3(1, 0, 1); w = f.rbg; }
  else if (f.b >= f.r && f.r >= f.g) { first = vec3(0, 0, 1); second = vec3(1, 0, 1); w = f.brg; }
  else if (f.g >= f.r && f.r >= f.b) { first = vec3(0, 1, 0); second = vec3(1, 1, 0); w = f.grb; }
  else if (f.g >= f.b && f.b >= f.r) { first = vec3(0, 1, 0); second = vec3(0, 1, 1); w = f.gbr; }
  else { first = vec3(0, 0, 1); second = vec3(0, 1, 1); w = f.bgr; }
  vec3 shown = (1.0 - w.x) * node(base) + (w.x - w.y) * node(base + first) + (w.y - w.z) * node(base + second) +
               w.z * node(base + 1.0);
  gl_FragColor = vec4(shown, 1.0);
}
)";
}

// Display pixels (upload_srgb8) go to the screen as they are.
const char* kPlainFragment = R"(#version 120
uniform sampler2D image;
varying vec2 uv;
void main() { gl_FragColor = vec4(texture2D(image, uv).rgb, 1.0); }
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

GLuint make_texture(GLenum target) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(target, texture);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // the image's is set at each draw
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return texture;
}

GLuint link(const char* fragment_text) {
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertex);
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, fragment_text);
  const GLuint program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("display shader: does not link");
  glUseProgram(program);
  glUniform1i(glGetUniformLocation(program, "image"), 0);
  glUseProgram(0);
  return program;
}

}  // namespace

ImageView::ImageView() {
  program_ = link(fragment_source().c_str());
  plain_program_ = link(kPlainFragment);
  exposure_location_ = glGetUniformLocation(program_, "exposure");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "view_table"), 1);
  glUseProgram(0);
  texture_ = make_texture(GL_TEXTURE_2D);
  table_ = make_texture(GL_TEXTURE_3D);
}

ImageView::~ImageView() {
  glDeleteTextures(1, &texture_);
  glDeleteTextures(1, &table_);
  glDeleteProgram(program_);
  glDeleteProgram(plain_program_);
}

void ImageView::upload(const Image& image) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (image.width != width_ || image.height != height_ || srgb8_) {
    width_ = image.width;
    height_ = image.height;
    srgb8_ = false;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, width_, height_, 0, GL_RGB, GL_FLOAT, image.pixels.data());
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGB, GL_FLOAT, image.pixels.data());
  }
}

void ImageView::upload_srgb8(const std::vector<unsigned char>& rgb, int width, int height) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (width != width_ || height != height_ || !srgb8_) {
    width_ = width;
    height_ = height;
    srgb8_ = true;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width, height, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  }
}

void ImageView::draw(int window_width, int window_height, const Viewport& where, const ToneMapping& tone) {
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_3D, table_);
  if (!table_built_ || tone.view != view_) {
    const std::vector<glm::vec3> table = view_table(tone.view);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // Half floats: steps of 1/2048 at the top, a tenth of an 8-bit step.
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB16F, kViewTableSize, kViewTableSize, kViewTableSize, 0, GL_RGB, GL_FLOAT,
                 table.data());
    table_built_ = true;
    view_ = tone.view;
  }
  glViewport(0, 0, window_width, window_height);
  glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  // GL's viewport counts rows from the bottom.
  glViewport(GLint(where.x), GLint(float(window_height) - where.y - where.height), GLsizei(where.width),
             GLsizei(where.height));
  glDisable(GL_BLEND);
  glUseProgram(srgb8_ ? plain_program_ : program_);
  if (!srgb8_) glUniform1f(exposure_location_, tone.exposure);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  // At its own size each window pixel shows its own image pixel, unfiltered; smaller, neighbours are averaged.
  const GLint filter = where.scale == 1.0f ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glBegin(GL_QUADS);  // texture row 0 (image row 0) at the top of the viewport
  glTexCoord2f(0, 1); glVertex2f(-1, -1);
  glTexCoord2f(1, 1); glVertex2f(1, -1);
  glTexCoord2f(1, 0); glVertex2f(1, 1);
  glTexCoord2f(0, 0); glVertex2f(-1, 1);
  glEnd();
  glUseProgram(0);
  glViewport(0, 0, window_width, window_height);  // ImGui draws over the whole window
}

}  // namespace igi
