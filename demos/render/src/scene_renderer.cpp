#include "unidist/render/scene_renderer.h"

#include "unidist/primitives.h"
#include "unidist/raster/offscreen_context.h"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

namespace unidist::render {
namespace {

/// Distinct, mid-saturated colours for the moving bodies; static bodies are grey.
Eigen::Vector3f bodyColour(std::size_t index, bool isStatic) {
  static constexpr float palette[][3] = {{0.22f, 0.49f, 0.80f}, {0.86f, 0.42f, 0.16f}, {0.27f, 0.66f, 0.35f},
                                         {0.70f, 0.30f, 0.70f}, {0.85f, 0.72f, 0.20f}, {0.20f, 0.68f, 0.70f},
                                         {0.80f, 0.30f, 0.35f}, {0.50f, 0.45f, 0.80f}};
  if (isStatic) return {0.62f, 0.62f, 0.64f};
  const float* c = palette[index % (sizeof palette / sizeof palette[0])];
  return {c[0], c[1], c[2]};
}

bool isHalfSpace(const SceneBody& body) { return body.model && body.model->type() == ModelType::Plane; }

/// World box of the bounded bodies at their start poses, grown by their shadow straight down on each
/// half-space so that the floor under them is in the picture.
Aabb sceneBounds(const Scene& scene) {
  Aabb box;
  for (const SceneBody& b : scene.bodies)
    if (!isHalfSpace(b) && b.model->localBounds().bounded()) {
      const Aabb world = b.model->localBounds().transformed(b.pose);
      box.extend(world.min);
      box.extend(world.max);
    }
  if (box.empty()) box.extend(Eigen::Vector3d::Zero());
  const Aabb bodies = box;
  for (const SceneBody& b : scene.bodies) {
    if (!isHalfSpace(b)) continue;
    const auto& plane = static_cast<const Plane&>(*b.model);
    const Eigen::Vector3d n = b.pose.linear() * plane.normal();
    const double d = plane.offset() + n.dot(b.pose.translation());
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1 ? bodies.max : bodies.min).x(), (corner & 2 ? bodies.max : bodies.min).y(),
                              (corner & 4 ? bodies.max : bodies.min).z());
      box.extend(p - (n.dot(p) - d) * n);
    }
  }
  if (!(box.diagonal() > 0)) {  // a single point: give it a unit size
    box.extend(box.min - Eigen::Vector3d::Constant(0.5));
    box.extend(box.max + Eigen::Vector3d::Constant(0.5));
  }
  return box;
}

void setColour(const std::uint8_t (&c)[3]) { glColor3ub(c[0], c[1], c[2]); }

}  // namespace

SceneRenderer::SceneRenderer(const Scene& scene, const RenderOptions& options)
    : context_(std::make_unique<raster::OffscreenContext>(options.width, options.height)), options_(options) {
  const Aabb bounds = sceneBounds(scene);
  const Eigen::Vector3d up = scene.gravity.norm() > 0 ? Eigen::Vector3d(-scene.gravity) : Eigen::Vector3d::UnitZ();
  camera_ = options.camera ? *options.camera : frameBounds(bounds, up, double(options.width) / options.height);
  contactLength_ = 0.06 * 2 * (camera_.eye - camera_.target).norm() * std::tan(camera_.fovY / 2);

  TessellationOptions tessellation;
  tessellation.relativeChordError = options.relativeChordError;
  tessellation.planeHalfExtent = 1.5 * bounds.diagonal();
  planes_.reserve(scene.bodies.size());  // meshes_ points into it
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const SceneBody& b = scene.bodies[i];
    if (!b.model) throw InputError("render: body '" + b.name + "' has no model");
    isPlane_.push_back(isHalfSpace(b));
    colours_.push_back(bodyColour(i, b.isStatic));
    if (isPlane_.back()) {
      tessellation.planeCentre = b.pose.inverse() * bounds.center();
      planes_.push_back(tessellate(*b.model, tessellation));
      meshes_.push_back(&planes_.back());
    } else {
      auto found = shared_.find(b.model.get());
      if (found == shared_.end()) found = shared_.emplace(b.model.get(), tessellate(*b.model, tessellation)).first;
      meshes_.push_back(&found->second);
    }
  }
}

SceneRenderer::~SceneRenderer() = default;

Image SceneRenderer::render(const std::vector<BodyState>& bodies, const std::vector<SimContact>& contacts) {
  if (bodies.size() != meshes_.size())
    throw InputError("render: " + std::to_string(bodies.size()) + " body poses for a scene of " +
                     std::to_string(meshes_.size()) + " bodies");
  const int w = options_.width, h = options_.height;
  context_->makeCurrent(w, h);
  glViewport(0, 0, w, h);
  glClearColor(Palette::background[0] / 255.0f, Palette::background[1] / 255.0f, Palette::background[2] / 255.0f, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glMatrixMode(GL_PROJECTION);
  const Eigen::Matrix4d projection = camera_.projection(double(w) / h);
  glLoadMatrixd(projection.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();

  // One light fixed to the camera (upper left, in front), so every frame is lit alike whatever the scene.
  const GLfloat lightDirection[] = {-0.35f, 0.6f, 0.72f, 0.0f}, ambient[] = {0.32f, 0.32f, 0.32f, 1},
                diffuse[] = {0.75f, 0.75f, 0.75f, 1}, specular[] = {0.25f, 0.25f, 0.25f, 1};
  glLightfv(GL_LIGHT0, GL_POSITION, lightDirection);
  glLightfv(GL_LIGHT0, GL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, specular);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);  // open surfaces and planes seen from behind
  glEnable(GL_LIGHT0);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 24);
  glEnable(GL_NORMALIZE);
  glEnable(GL_DEPTH_TEST);
  glShadeModel(GL_SMOOTH);

  const Eigen::Matrix4d view = camera_.view();
  glLoadMatrixd(view.data());
  for (std::size_t i = 0; i < bodies.size(); ++i) drawBody(*meshes_[i], bodies[i].pose, colours_[i]);
  drawContacts(contacts);

  // OpenGL's rows run bottom-up; pictures top-down.
  const std::vector<unsigned char>& rgba = context_->colour();
  Image image;
  image.width = w;
  image.height = h;
  image.rgb.resize(3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    const unsigned char* from = &rgba[4 * static_cast<std::size_t>(h - 1 - y) * static_cast<std::size_t>(w)];
    std::uint8_t* to = &image.rgb[3 * static_cast<std::size_t>(y) * static_cast<std::size_t>(w)];
    for (int x = 0; x < w; ++x, from += 4, to += 3) std::copy(from, from + 3, to);
  }
  return image;
}

void SceneRenderer::drawBody(const DisplayMesh& mesh, const Eigen::Isometry3d& pose,
                             const Eigen::Vector3f& colour) const {
  glPushMatrix();
  const Eigen::Matrix4d X = pose.matrix();
  glMultMatrixd(X.data());
  glEnable(GL_LIGHTING);
  glColor3f(colour.x(), colour.y(), colour.z());
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  if (!mesh.triangles.empty()) {
    glEnable(GL_POLYGON_OFFSET_FILL);  // grid lines lying on a face win the depth test
    glPolygonOffset(1, 1);
    glVertexPointer(3, GL_DOUBLE, 0, mesh.positions.data());
    glNormalPointer(GL_DOUBLE, 0, mesh.normals.data());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.triangles.size()), GL_UNSIGNED_INT, mesh.triangles.data());
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  if (!mesh.points.empty()) {
    glPointSize(std::max(2.0f, options_.height / 160.0f));
    glVertexPointer(3, GL_DOUBLE, 0, mesh.points.data());
    glNormalPointer(GL_DOUBLE, 0, mesh.pointNormals.data());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(mesh.points.size()));
  }
  glDisableClientState(GL_NORMAL_ARRAY);
  if (!mesh.linePoints.empty()) {
    glDisable(GL_LIGHTING);
    glColor3f(0.75f * colour.x(), 0.75f * colour.y(), 0.75f * colour.z());
    glVertexPointer(3, GL_DOUBLE, 0, mesh.linePoints.data());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(mesh.linePoints.size()));
  }
  glDisableClientState(GL_VERTEX_ARRAY);
  glPopMatrix();
}

/// Over everything (no depth test): a contact hidden inside a pile is still where the engine put it.
void SceneRenderer::drawContacts(const std::vector<SimContact>& contacts) const {
  if (contacts.empty()) return;
  glDisable(GL_LIGHTING);
  glDisable(GL_DEPTH_TEST);
  glLineWidth(std::max(1.0f, options_.height / 360.0f));
  setColour(Palette::contactNormal);
  glBegin(GL_LINES);
  for (const SimContact& c : contacts) {
    if (!c.point.allFinite() || !c.normal.allFinite()) continue;
    const Eigen::Vector3d tip = c.point + contactLength_ * c.normal.normalized();
    glVertex3d(c.point.x(), c.point.y(), c.point.z());
    glVertex3d(tip.x(), tip.y(), tip.z());
  }
  glEnd();
  glPointSize(std::max(3.0f, options_.height / 100.0f));
  setColour(Palette::contactDot);
  glBegin(GL_POINTS);
  for (const SimContact& c : contacts)
    if (c.point.allFinite()) glVertex3d(c.point.x(), c.point.y(), c.point.z());
  glEnd();
  glEnable(GL_DEPTH_TEST);
}

}  // namespace unidist::render
