#include "render/particle_drawer.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstddef>
#include <string>

#include "render/egl_context.h"

namespace cascade::render {

namespace {

const char* const kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 centre;
layout(location = 1) in vec4 colour;
uniform mat4 view;
uniform mat4 projection;
uniform float radius;
uniform float pixel_scale;
uniform bool perspective;
out vec4 sprite_colour;
out vec3 centre_in_view;
void main() {
  vec4 c = view * vec4(centre, 1.0);
  centre_in_view = c.xyz;
  sprite_colour = colour;
  gl_Position = projection * c;
  gl_PointSize = 2.0 * radius * (perspective ? pixel_scale / -c.z : pixel_scale);
}
)";

// A headlight along the view direction: the centre of each sphere shows its colour exactly, the
// rim darkens to the ambient quarter.
const char* const kFragmentShader = R"(#version 330 core
in vec4 sprite_colour;
in vec3 centre_in_view;
uniform mat4 projection;
uniform float radius;
out vec4 fragment;
void main() {
  vec2 p = gl_PointCoord * 2.0 - 1.0;
  p.y = -p.y;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  vec3 normal = vec3(p, sqrt(1.0 - r2));
  vec4 surface = projection * vec4(centre_in_view + radius * normal, 1.0);
  gl_FragDepth = 0.5 * surface.z / surface.w + 0.5;
  fragment = vec4(sprite_colour.rgb * (0.25 + 0.75 * normal.z), sprite_colour.a);
}
)";

unsigned compile(GLenum kind, const char* source) {
  const unsigned shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw RenderError(std::string("sphere impostor shader does not compile: ") + log);
  }
  return shader;
}

std::vector<float> to_float(const Eigen::Matrix4d& m) {
  std::vector<float> f(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) f[std::size_t(4 * c + r)] = float(m(r, c));  // column-major, as GL reads it
  return f;
}

}  // namespace

ParticleDrawer::ParticleDrawer() {
  const unsigned vs = compile(GL_VERTEX_SHADER, kVertexShader), fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) throw RenderError("sphere impostor program does not link");
  view_location_ = glGetUniformLocation(program_, "view");
  projection_location_ = glGetUniformLocation(program_, "projection");
  radius_location_ = glGetUniformLocation(program_, "radius");
  pixel_scale_location_ = glGetUniformLocation(program_, "pixel_scale");
  perspective_location_ = glGetUniformLocation(program_, "perspective");

  glGenVertexArrays(1, &vertex_array_);
  glGenBuffers(1, &buffer_);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(SpriteVertex),
                        reinterpret_cast<void*>(offsetof(SpriteVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(SpriteVertex),
                        reinterpret_cast<void*>(offsetof(SpriteVertex, colour)));
  glGenFramebuffers(1, &framebuffer_);
  glGenRenderbuffers(1, &colour_buffer_);
  glGenRenderbuffers(1, &depth_buffer_);
}

ParticleDrawer::~ParticleDrawer() {
  glDeleteRenderbuffers(1, &depth_buffer_);
  glDeleteRenderbuffers(1, &colour_buffer_);
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteBuffers(1, &buffer_);
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteProgram(program_);
}

void ParticleDrawer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  glBindRenderbuffer(GL_RENDERBUFFER, colour_buffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_buffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("framebuffer of " + std::to_string(width) + "x" + std::to_string(height) + " is incomplete");
  width_ = width;
  height_ = height;
}

void ParticleDrawer::upload_and_draw(const std::vector<SpriteVertex>& sprites) {
  if (sprites.empty()) return;
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(sprites.size() * sizeof(SpriteVertex)), sprites.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_POINTS, 0, GLsizei(sprites.size()));
}

void ParticleDrawer::draw(const std::vector<SpriteVertex>& opaque, const std::vector<SpriteVertex>& translucent,
                          const FramedCamera& camera, double radius, Rgb8 background, RgbImage& image) {
  resize(image.width, image.height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, image.width, image.height);
  glClearColor(background.r / 255.f, background.g / 255.f, background.b / 255.f, 1.f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // The scene's viewport: the image's left part when a colour bar takes the right.
  glViewport(0, image.height - camera.viewport_height, camera.viewport_width, camera.viewport_height);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(program_);
  glUniformMatrix4fv(view_location_, 1, GL_FALSE, to_float(camera.view).data());
  glUniformMatrix4fv(projection_location_, 1, GL_FALSE, to_float(camera.projection).data());
  glUniform1f(radius_location_, float(radius));
  glUniform1f(pixel_scale_location_, float(camera.pixel_scale));
  glUniform1i(perspective_location_, camera.perspective ? 1 : 0);
  glBindVertexArray(vertex_array_);
  glBindBuffer(GL_ARRAY_BUFFER, buffer_);

  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  upload_and_draw(opaque);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);  // keeps alpha at 1
  glDepthMask(GL_FALSE);
  upload_and_draw(translucent);
  glDepthMask(GL_TRUE);

  // GL's rows run bottom up; the image's top down.
  std::vector<std::uint8_t> rgba(std::size_t(image.width) * std::size_t(image.height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw RenderError("OpenGL error 0x" + std::to_string(unsigned(error)) + " while drawing particles");
  for (int row = 0; row < image.height; ++row) {
    const std::uint8_t* src = &rgba[std::size_t(image.height - 1 - row) * std::size_t(image.width) * 4];
    std::uint8_t* dst = &image.pixels[std::size_t(row) * std::size_t(image.width) * 3];
    for (int x = 0; x < image.width; ++x) {
      dst[3 * x] = src[4 * x];
      dst[3 * x + 1] = src[4 * x + 1];
      dst[3 * x + 2] = src[4 * x + 2];
    }
  }
}

}  // namespace cascade::render
