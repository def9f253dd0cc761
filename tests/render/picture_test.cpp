// Pictures of known scenes: a sphere covers exactly the pixels whose rays hit it, contacts show in their
// colours where they project, every model type draws something, and the camera's project() and ray() agree.
#include "unidist/adapters/load.h"
#include "unidist/primitives.h"
#include "unidist/render/scene_renderer.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using unidist::render::Image;
using unidist::render::Palette;
using unidist::render::SceneRenderer;

unidist::Scene oneBody(std::shared_ptr<const unidist::Model> model, const std::string& source) {
  unidist::Scene scene;
  unidist::SceneBody body;
  body.name = "body";
  body.modelSource = source;
  body.model = std::move(model);
  body.mass = 1;
  scene.bodies.push_back(body);
  return scene;
}

std::vector<unidist::BodyState> startPoses(const unidist::Scene& scene) {
  std::vector<unidist::BodyState> out;
  for (const unidist::SceneBody& b : scene.bodies) out.push_back({b.name, b.pose, {}, {}});
  return out;
}

bool is(const Image& image, int x, int y, const std::uint8_t (&rgb)[3]) {
  const std::uint8_t* p = image.pixel(x, y);
  return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
}

int nonBackground(const Image& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += !is(image, x, y, Palette::background);
  return n;
}

TEST(Picture, SphereCoversThePixelsItShould) {
  const double r = 1;
  const unidist::Scene scene = oneBody(std::make_shared<unidist::Sphere>(r), "sphere:r=1");
  unidist::render::RenderOptions options;
  options.width = 160;
  options.height = 120;
  SceneRenderer renderer(scene, options);
  const Image image = renderer.render(startPoses(scene), {});
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 120);
  const unidist::render::Camera& camera = renderer.camera();
  const double distance = camera.eye.norm();
  // A pixel's footprint at the sphere, with room for the chords and the rasteriser's rounding.
  const double margin = 1.5 * 2 * distance * std::tan(camera.fovY / 2) / image.height + 2 * 2e-3 * r;
  int inside = 0, wrong = 0, darkest = 255, brightest = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Eigen::Vector3d ray = camera.ray(x + 0.5, y + 0.5, image.width, image.height);
      const double miss = (camera.eye - camera.eye.dot(ray) * ray).norm();  // ray's distance from the centre
      const bool background = is(image, x, y, Palette::background);
      if (miss < r - margin) {
        ++inside;
        wrong += background;
        darkest = std::min<int>(darkest, image.pixel(x, y)[2]);
        brightest = std::max<int>(brightest, image.pixel(x, y)[2]);
      } else if (miss > r + margin) {
        wrong += !background;
      }
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(inside, image.width * image.height / 20);  // the sphere fills a good part of the view
  EXPECT_GT(brightest - darkest, 60) << "shaded, not flat";
}

TEST(Picture, ContactsShowInTheirColours) {
  const unidist::Scene scene = oneBody(std::make_shared<unidist::Sphere>(1), "sphere:r=1");
  unidist::render::RenderOptions options;
  options.width = 200;
  options.height = 150;
  SceneRenderer renderer(scene, options);
  // One contact on the sphere's top, one beside it in the background; normals pointing up.
  const std::vector<unidist::SimContact> contacts = {{{0, 0, 1}, {0, 0, 1}, 0}, {{0, 1.4, 0}, {0, 0, 1}, -0.01}};
  const Image image = renderer.render(startPoses(scene), contacts);
  const unidist::render::Camera& camera = renderer.camera();
  for (const unidist::SimContact& c : contacts) {
    const auto at = camera.project(c.point, image.width, image.height);
    ASSERT_TRUE(at);
    EXPECT_TRUE(is(image, int(at->x()), int(at->y()), Palette::contactDot)) << c.point.transpose();
    // The normal's far end is off the dot and drawn in the normal's colour (also over the sphere).
    const auto tip = camera.project(c.point + renderer.contactLength() * c.normal, image.width, image.height);
    ASSERT_TRUE(tip);
    const Eigen::Vector2d nearTip = *at + 0.8 * (*tip - *at);
    ASSERT_GT((*tip - *at).norm(), 6) << "segment too short to see";
    bool drawn = false;  // a one-pixel line may fall on either side of a pixel edge
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        drawn = drawn || is(image, int(nearTip.x()) + dx, int(nearTip.y()) + dy, Palette::contactNormal);
    EXPECT_TRUE(drawn) << c.point.transpose();
  }
  const Image plain = renderer.render(startPoses(scene), {});
  const auto top = camera.project(contacts[0].point, image.width, image.height);
  EXPECT_FALSE(is(plain, int(top->x()), int(top->y()), Palette::contactDot));
}

TEST(Picture, EveryModelTypeDraws) {
  const std::vector<std::string> sources = {"sphere:r=1", "box:hx=1,hy=0.5,hz=0.3", "capsule:r=0.4,h=1",
                                            "cylinder:r=0.5,h=0.7", "cone:r=0.5,h=0.7", "torus:R=1,r=0.3",
                                            UNIDIST_SCENES_DIR "/ball_r150.unurbs.json",
                                            UNIDIST_SCENES_DIR "/blob.xyz", "plane:nx=0,ny=0,nz=1,d=0"};
  unidist::render::RenderOptions options;
  options.width = 64;
  options.height = 48;
  for (const std::string& source : sources) {
    SCOPED_TRACE(source);
    unidist::Scene scene = oneBody(unidist::loadModel(source), source);
    scene.bodies[0].isStatic = source.rfind("plane", 0) == 0;
    SceneRenderer renderer(scene, options);
    EXPECT_GT(nonBackground(renderer.render(startPoses(scene), {})), 64 * 48 / 20);
  }
}

TEST(Picture, FloorUnderABodyIsInThePicture) {
  unidist::Scene scene = oneBody(std::make_shared<unidist::Sphere>(1), "sphere:r=1");
  scene.bodies[0].pose.translation() = Eigen::Vector3d(0, 0, 3);
  unidist::SceneBody floor;
  floor.name = "floor";
  floor.model = unidist::loadModel("plane:nx=0,ny=0,nz=1,d=0");
  floor.isStatic = true;
  scene.bodies.push_back(floor);
  unidist::render::RenderOptions options;
  options.width = 120;
  options.height = 90;
  SceneRenderer renderer(scene, options);
  EXPECT_EQ(renderer.displayMesh(1).triangleCount(), 2u);
  const Image image = renderer.render(startPoses(scene), {});
  const auto below = renderer.camera().project(Eigen::Vector3d(0, 0, 0), image.width, image.height);
  ASSERT_TRUE(below);
  EXPECT_FALSE(is(image, int(below->x()), int(below->y()), Palette::background));
}

TEST(Picture, BodiesSharingAModelShareOneTessellation) {
  unidist::Scene scene = oneBody(std::make_shared<unidist::Sphere>(1), "sphere:r=1");
  scene.bodies.push_back(scene.bodies[0]);
  scene.bodies[1].name = "twin";
  scene.bodies[1].pose.translation() = Eigen::Vector3d(3, 0, 0);
  SceneRenderer renderer(scene, {});
  EXPECT_EQ(&renderer.displayMesh(0), &renderer.displayMesh(1));
}

TEST(Picture, BadInputIsAnError) {
  const unidist::Scene scene = oneBody(std::make_shared<unidist::Sphere>(1), "sphere:r=1");
  unidist::render::RenderOptions options;
  options.width = 0;
  EXPECT_THROW(SceneRenderer(scene, options), unidist::InputError);
  options.width = 32;
  options.height = 32;
  options.relativeChordError = 0;
  EXPECT_THROW(SceneRenderer(scene, options), unidist::InputError);
  SceneRenderer renderer(scene, {});
  EXPECT_THROW(renderer.render({}, {}), unidist::InputError);
}

TEST(Camera, ProjectAndRayAgree) {
  unidist::Aabb box;
  box.extend(Eigen::Vector3d(-1, -2, 0));
  box.extend(Eigen::Vector3d(3, 1, 2));
  const unidist::render::Camera camera = unidist::render::frameBounds(box, Eigen::Vector3d(0, 0, 2), 4.0 / 3);
  EXPECT_TRUE(camera.project(box.center(), 400, 300)->isApprox(Eigen::Vector2d(200, 150), 1e-9));
  for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(10.5, 20.5), Eigen::Vector2d(399, 1), Eigen::Vector2d(200, 299)}) {
    const auto back = camera.project(camera.eye + 7 * camera.ray(pixel.x(), pixel.y(), 400, 300), 400, 300);
    ASSERT_TRUE(back);
    EXPECT_LT((*back - pixel).norm(), 1e-9);
  }
  for (int corner = 0; corner < 8; ++corner) {  // the whole box is in the picture
    const Eigen::Vector3d p((corner & 1 ? box.max : box.min).x(), (corner & 2 ? box.max : box.min).y(),
                            (corner & 4 ? box.max : box.min).z());
    const auto at = camera.project(p, 400, 300);
    ASSERT_TRUE(at);
    EXPECT_GE(at->x(), 0);
    EXPECT_LE(at->x(), 400);
    EXPECT_GE(at->y(), 0);
    EXPECT_LE(at->y(), 300);
  }
  EXPECT_FALSE(camera.project(camera.eye - camera.ray(200, 150, 400, 300), 400, 300));  // behind
  EXPECT_THROW(unidist::render::frameBounds(unidist::Aabb(), Eigen::Vector3d::UnitZ(), 1), unidist::InputError);
  EXPECT_THROW(unidist::render::frameBounds(box, Eigen::Vector3d::Zero(), 1), unidist::InputError);
}

}  // namespace
