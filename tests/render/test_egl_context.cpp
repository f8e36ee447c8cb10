// An OpenGL 3.3 core context comes up with no display server: no DISPLAY, no WAYLAND_DISPLAY.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "render/egl_context.h"

namespace cascade::render {

TEST(EglContext, CreatedWithoutDisplay) {
  unsetenv("DISPLAY");
  unsetenv("WAYLAND_DISPLAY");
  EglContext context;
  EXPECT_TRUE(context.platform() == "device" || context.platform() == "surfaceless") << context.platform();
  int major = 0, minor = 0;
  // Desktop GL reports "M.m ..." (GLES would say "OpenGL ES M.m").
  ASSERT_EQ(std::sscanf(context.version().c_str(), "%d.%d", &major, &minor), 2) << context.version();
  EXPECT_GE(major * 10 + minor, 33) << context.version();
  EXPECT_FALSE(context.renderer().empty());
  std::printf("EGL platform %s, GL_RENDERER %s, GL_VERSION %s\n", context.platform().c_str(),
              context.renderer().c_str(), context.version().c_str());
}

TEST(EglContext, TwoContextsInTurn) {
  // A service may drop its renderer and make another: the second must not find the display gone.
  { EglContext first; }
  EglContext second;
  EXPECT_FALSE(second.renderer().empty());
}

}  // namespace cascade::render
