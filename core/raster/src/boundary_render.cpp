#include "boundary_render.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>

namespace unidist::raster::detail {
namespace {

// Coincident faces of touching pieces: a front face pulled this far toward the eye (in depth-buffer units
// and slopes) still counts as reaching the current boundary, so a face shared by two pieces does not look
// like boundary. The same slack bridges cracks thinner than the depth buffer resolves (docs/raster.md).
constexpr float kCoincidentSlope = -1.0f, kCoincidentUnits = -4.0f;

void draw(const RenderablePiece& piece) {
  glVertexPointer(3, GL_FLOAT, 0, piece.xyz.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, piece.rgba.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(piece.xyz.size() / 3));
}

void loadView(const CubeView& view, double nearPlane, double farPlane) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glFrustum(-nearPlane, nearPlane, -nearPlane, nearPlane, nearPlane, farPlane);  // 90° square
  // Eye frame: rows right, up, −axis (column-major for OpenGL); the geometry is already relative to the eye.
  const Eigen::Vector3d back = -view.axis;
  const GLdouble m[16] = {view.right.x(), view.up.x(), back.x(), 0, view.right.y(), view.up.y(), back.y(), 0,
                          view.right.z(),  view.up.z(), back.z(), 0, 0, 0, 0, 1};
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(m);
}

}  // namespace

BoundaryRenderer::BoundaryRenderer(OffscreenContext& context, int resolution) : resolution_(resolution) {
  context.makeCurrent(resolution, resolution);
  glPushAttrib(GL_ALL_ATTRIB_BITS);
  glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS);
  glMatrixMode(GL_PROJECTION);
  glPushMatrix();
  glMatrixMode(GL_MODELVIEW);
  glPushMatrix();
  glViewport(0, 0, resolution, resolution);
  for (GLenum off : {GL_DITHER, GL_LIGHTING, GL_BLEND, GL_TEXTURE_2D, GL_SCISSOR_TEST, GL_ALPHA_TEST, GL_FOG})
    glDisable(off);
  glShadeModel(GL_FLAT);  // ids must arrive unchanged
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_STENCIL_TEST);
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glDepthRange(0.0, 1.0);
  glEnable(GL_DEPTH_CLAMP);  // fragments nearer than the near plane are kept (at depth 0), never clipped
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPolygonOffset(kCoincidentSlope, kCoincidentUnits);
}

BoundaryRenderer::~BoundaryRenderer() {
  if (!queries_.empty()) glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
  glMatrixMode(GL_PROJECTION);
  glPopMatrix();
  glMatrixMode(GL_MODELVIEW);
  glPopMatrix();
  glPopClientAttrib();
  glPopAttrib();
}

ViewImage BoundaryRenderer::render(const CubeView& view, const std::vector<RenderablePiece>& pieces,
                                   const std::vector<int>& order, double nearPlane, int maxPasses) {
  ViewImage image;
  std::vector<int> visible;  // pieces not containing the eye that meet this view, nearest first
  double farPlane = nearPlane;
  for (const RenderablePiece& piece : pieces)
    if (piece.containsEye) farPlane = std::max(farPlane, piece.maxDistance);
  for (int index : order) {
    const RenderablePiece& piece = pieces[static_cast<std::size_t>(index)];
    if (view.culls(piece.box)) {
      ++image.culled;
      continue;
    }
    visible.push_back(index);
    farPlane = std::max(farPlane, piece.maxDistance);
  }
  farPlane *= 1.0 + 1e-6;  // eye depth <= distance, so every vertex lies before it
  image.nearPlane = nearPlane;
  image.farPlane = farPlane;
  loadView(view, nearPlane, farPlane);

  // Pass 0: the pieces holding the eye, back faces, farthest wins (each covers the ray from the eye to its exit).
  glClearDepth(0.0);
  glClearStencil(0);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glDepthFunc(GL_GREATER);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glCullFace(GL_FRONT);
  for (const RenderablePiece& piece : pieces)
    if (piece.containsEye) draw(piece), ++image.rendered;
  image.passes = 1;

  if (queries_.size() < visible.size()) {
    if (!queries_.empty()) glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    queries_.assign(visible.size(), 0);
    glGenQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
  }
  // Passes: a piece whose front face is not behind the boundary reaches it (its ray interval starts inside the
  // covered stretch), so its back face, where farther, pushes the boundary out. Front faces mark the pixels
  // where they lie behind the boundary ("blocked") with this piece's stencil value; back faces draw elsewhere.
  int stencilValue = 0;
  for (int pass = 0; pass < maxPasses && !visible.empty(); ++pass) {
    for (std::size_t k = 0; k < visible.size(); ++k) {
      const RenderablePiece& piece = pieces[static_cast<std::size_t>(visible[k])];
      if (++stencilValue > 255) {
        glClear(GL_STENCIL_BUFFER_BIT);
        stencilValue = 1;
      }
      glCullFace(GL_BACK);
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glDepthMask(GL_FALSE);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glStencilFunc(GL_ALWAYS, stencilValue, 0xff);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      draw(piece);

      glCullFace(GL_FRONT);
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDepthMask(GL_TRUE);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glStencilFunc(GL_NOTEQUAL, stencilValue, 0xff);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      glBeginQuery(GL_SAMPLES_PASSED, queries_[k]);
      draw(piece);
      glEndQuery(GL_SAMPLES_PASSED);
    }
    image.rendered += static_cast<int>(visible.size());
    ++image.passes;
    // Stop as soon as a pass moved no pixel (the greater-depth test passes only where the boundary moves).
    GLuint moved = 0;
    for (std::size_t k = 0; k < visible.size() && moved == 0; ++k) glGetQueryObjectuiv(queries_[k], GL_QUERY_RESULT, &moved);
    if (moved == 0) break;
  }

  const std::size_t pixels = static_cast<std::size_t>(resolution_) * static_cast<std::size_t>(resolution_);
  image.depth.resize(pixels);
  std::vector<unsigned char> rgba(pixels * 4);
  glReadPixels(0, 0, resolution_, resolution_, GL_DEPTH_COMPONENT, GL_FLOAT, image.depth.data());
  glReadPixels(0, 0, resolution_, resolution_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  image.ids.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p)
    image.ids[p] = std::uint32_t(rgba[4 * p]) | std::uint32_t(rgba[4 * p + 1]) << 8 |
                   std::uint32_t(rgba[4 * p + 2]) << 16 | std::uint32_t(rgba[4 * p + 3]) << 24;
  return image;
}

}  // namespace unidist::raster::detail
