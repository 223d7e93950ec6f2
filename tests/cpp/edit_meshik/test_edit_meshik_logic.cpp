// The GL-free logic of the MeshLab tool "MeshIK: Drag to Pose" (plugin/edit_meshik/logic):
// projection and picking on a known view, the view-plane drag, the coalescing solve worker
// (with the real solver), rotation of handle groups, the rigid fit, the keyframe list, the
// constraint-file writer's checks and latency statistics.
#include "constraint_frames_writer.h"
#include "group_rotation.h"
#include "keyframe_list.h"
#include "meshik/constraints/constraint_file.h"
#include "mirror_pairing.h"
#include "latency_stats.h"
#include "pose_state.h"
#include "rigid_fit.h"
#include "screen_projection.h"
#include "solve_worker.h"
#include "surface_normals.h"
#include "test_meshik_support.h"
#include "vertex_picking.h"
#include "view_plane_drag.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

namespace {

using meshik::edit::ScreenProjection;
using meshik::edit::WindowPoint;

// A perspective view as MeshLab sets one up: the camera at (0, 0, 5) looking down -z with a
// 60 degree vertical field of view, near 0.1, far 100, onto an 800 by 600 viewport.
ScreenProjection cameraOnZAxis() {
  const double fov = 60.0 * M_PI / 180.0, aspect = 800.0 / 600.0, near = 0.1, far = 100.0;
  const double f = 1.0 / std::tan(fov / 2.0);
  const double projection[16] = {f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
                                 0, 0, 2 * far * near / (near - far), 0};
  const double modelview[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1};  // translate by -5 in z
  const int viewport[4] = {0, 0, 800, 600};
  return ScreenProjection(projection, modelview, viewport);
}

TEST(ScreenProjection, ProjectsTheViewCentreToTheViewportCentreAndUnprojectsBack) {
  const ScreenProjection view = cameraOnZAxis();
  const double origin[3] = {0, 0, 0};
  const WindowPoint w = view.project(origin);
  EXPECT_NEAR(w.x, 400.0, 1e-9);
  EXPECT_NEAR(w.y, 300.0, 1e-9);
  EXPECT_GT(w.depth, 0.0);
  EXPECT_LT(w.depth, 1.0);
  const double p[3] = {0.7, -0.4, 1.3};
  double back[3];
  ASSERT_TRUE(view.unproject(view.project(p), back));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], p[k], 1e-9);
  // Nearer points look bigger: x = 1 at z = 1 lands further right than at z = -1.
  const double near_point[3] = {1, 0, 1}, far_point[3] = {1, 0, -1};
  EXPECT_GT(view.project(near_point).x, view.project(far_point).x);
}

// Two vertices on one line of sight (the front one at z = 1, the back one at z = -1) and a third
// off to the side: the click over both means the one whose surface the depth buffer shows.
TEST(VertexPicking, TakesTheVertexOnTheVisibleSurfaceNotTheOneBehindIt) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> vertices = {0, 0, -1, 0, 0, 1, 1, 1, 0};
  const WindowPoint front = view.project(&vertices[3]), back = view.project(&vertices[0]);
  EXPECT_EQ(meshik::edit::pickVertex(view, vertices, front.x + 2, front.y - 1, front.depth, 6.0), 1);
  // With the front vertex's surface gone, the depth buffer reads the back one's depth.
  EXPECT_EQ(meshik::edit::pickVertex(view, vertices, back.x, back.y, back.depth, 6.0), 0);
  EXPECT_EQ(meshik::edit::pickVertex(view, vertices, front.x, front.y, 1.0, 6.0), -1) << "background";
  EXPECT_EQ(meshik::edit::pickVertex(view, vertices, front.x + 40, front.y, front.depth, 6.0), -1)
      << "no vertex within the radius";
  const WindowPoint side = view.project(&vertices[6]);
  EXPECT_EQ(meshik::edit::pickVertex(view, vertices, side.x - 3, side.y, side.depth, 6.0), 2);
}

TEST(VertexPicking, PicksTheHandleMarkerNearestTheClick) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> handles = {0, 0, 0, 0.05, 0, 0, 2, 0, 0};
  const WindowPoint second = view.project(&handles[3]);
  EXPECT_EQ(meshik::edit::pickHandle(view, handles, second.x + 1, second.y, 8.0), 1);
  const WindowPoint third = view.project(&handles[6]);
  EXPECT_EQ(meshik::edit::pickHandle(view, handles, third.x, third.y + 7, 8.0), 2);
  EXPECT_EQ(meshik::edit::pickHandle(view, handles, third.x, third.y + 20, 8.0), -1);
}

// Three vertices inside a rectangle, one hidden behind the front one (the depth buffer shows the
// front surface there), one outside: the rectangle takes the visible ones inside it.
TEST(VertexPicking, ARectangleTakesTheVisibleVerticesInsideIt) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> vertices = {0, 0, 1, 0, 0, -1, 0.3, 0.2, 0, 3, 0, 0};
  const WindowPoint front = view.project(&vertices[0]), side = view.project(&vertices[6]);
  // The depth buffer: the front vertex's depth around it, the side vertex's depth elsewhere.
  const auto depth = [&](int x, int y) {
    return std::abs(x - front.x) < 3 && std::abs(y - front.y) < 3 ? front.depth : side.depth;
  };
  const std::vector<int> picked = meshik::edit::pickVerticesInRectangle(view, vertices, front.x - 20, front.y - 20,
                                                                        side.x + 20, side.y + 20, depth, 0.05);
  EXPECT_EQ(picked, (std::vector<int>{0, 2}));
  EXPECT_TRUE(meshik::edit::pickVerticesInRectangle(view, vertices, 0, 0, 5, 5, depth, 0.05).empty());
}

TEST(ViewPlaneDrag, TheGrabbedTargetFollowsTheCursorAtItsDepthAndTheGroupMovesAlong) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> targets = {0.5, 0.2, 1.0, -1, 0, 0, 0, 1, -2};
  const WindowPoint grabbed = view.project(&targets[0]);
  // Pressed 3 pixels beside the marker: nothing jumps at the press point.
  const meshik::edit::ViewPlaneDrag drag(view, targets, 0, {1}, grabbed.x + 3, grabbed.y - 2);
  const std::vector<double> unmoved = drag.targetsAt(grabbed.x + 3, grabbed.y - 2);
  for (size_t i = 0; i < targets.size(); ++i) EXPECT_NEAR(unmoved[i], targets[i], 1e-9);

  const std::vector<double> moved = drag.targetsAt(grabbed.x + 3 + 120, grabbed.y - 2 + 45);
  const WindowPoint now = view.project(&moved[0]);
  EXPECT_NEAR(now.x, grabbed.x + 120, 1e-6);
  EXPECT_NEAR(now.y, grabbed.y + 45, 1e-6);
  EXPECT_NEAR(now.depth, grabbed.depth, 1e-12);
  // In the view plane: the camera looks down z, so z stays.
  EXPECT_NEAR(moved[2], targets[2], 1e-9);
  EXPECT_GT(moved[0], targets[0]);
  EXPECT_GT(moved[1], targets[1]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moved[3 + k] - targets[3 + k], moved[k] - targets[k], 1e-9) << k;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(moved[6 + k], targets[6 + k]) << "not in the group";
}

// The tube of the solver's tests, and a request moving its two end caps' centres.
struct TubeScene {
  meshik_test::ExampleMeshes meshes = meshik_test::make_tube_examples();
  std::shared_ptr<const meshik::ExampleSet> examples =
      std::make_shared<const meshik::ExampleSet>(meshes.view(), meshes.example_pointers());
  std::vector<int> handles = {meshes.num_vertices() - 2, meshes.num_vertices() - 1};

  meshik::edit::SolveRequest request(double lift) const {
    meshik::edit::SolveRequest r;
    r.handles = handles;
    for (int v : handles)
      for (int k = 0; k < 3; ++k) r.targets.push_back(meshes.rest[3 * v + k] + (k == 1 ? lift * v / 100.0 : 0.0));
    return r;
  }
};

TEST(SolveWorker, MovesPostedDuringASolveCoalesceIntoOneRequestWithTheNewestTargets) {
  TubeScene scene;
  std::mutex mutex;
  std::condition_variable changed;
  int finished = 0;
  bool release = false;
  // The worker calls this after each solve; holding it keeps the worker busy while we post.
  meshik::edit::SolveWorker worker(scene.examples, {}, [&] {
    std::unique_lock<std::mutex> lock(mutex);
    ++finished;
    changed.notify_all();
    changed.wait(lock, [&] { return release || finished > 1; });
  });
  worker.post(scene.request(0.1));
  {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return finished == 1; });
  }
  const auto first_event = meshik::edit::Clock::now();
  std::vector<double> newest;
  for (int i = 1; i <= 10; ++i) {
    meshik::edit::SolveRequest r = scene.request(0.1 + 0.05 * i);
    r.first_event = first_event + std::chrono::milliseconds(i);
    r.quick = i != 4;  // one full request among quick ones makes the folded request full
    newest = r.targets;
    worker.post(std::move(r));
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    release = true;
  }
  changed.notify_all();
  worker.waitIdle();
  const auto counts = worker.counts();
  EXPECT_EQ(counts.moves, 11);
  EXPECT_EQ(counts.solves, 2);
  EXPECT_EQ(counts.coalesced, 9);
  EXPECT_EQ(counts.superseded, 1) << "the first outcome was never taken";
  const auto outcome = worker.take();
  ASSERT_TRUE(outcome.has_value());
  EXPECT_EQ(outcome->number, 2u);
  EXPECT_EQ(outcome->request.moves, 10);
  EXPECT_TRUE(outcome->request.first_event == first_event + std::chrono::milliseconds(1));
  EXPECT_EQ(outcome->request.targets, newest) << "the newest targets";
  EXPECT_FALSE(outcome->request.quick);
  EXPECT_FALSE(outcome->refactored) << "a move never refactors";
  EXPECT_TRUE(outcome->error.empty()) << outcome->error;
  EXPECT_FALSE(worker.take().has_value()) << "the older outcome was dropped, the newest taken";
}

TEST(SolveWorker, NoSolveStartsWhileTheTakenPoseIsBeingWritten) {
  TubeScene scene;
  std::mutex mutex;
  std::condition_variable changed;
  int finished = 0;
  meshik::edit::SolveWorker worker(scene.examples, {}, [&] {
    std::lock_guard<std::mutex> lock(mutex);
    ++finished;
    changed.notify_all();
  });
  const auto wait_for_solves = [&](int count) {
    std::unique_lock<std::mutex> lock(mutex);
    return changed.wait_for(lock, std::chrono::seconds(60), [&] { return finished >= count; });
  };
  worker.post(scene.request(0.1));
  ASSERT_TRUE(wait_for_solves(1));
  const auto first = worker.take();  // the GUI thread takes the pose and writes it...
  ASSERT_TRUE(first && first->error.empty());
  const meshik::edit::SolveRequest next = scene.request(0.2);
  worker.post(next);  // ...while a move arrives
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the tube solves in about 1 ms
  EXPECT_EQ(worker.counts().solves, 1) << "no solve competes with the write";
  EXPECT_FALSE(worker.take().has_value());
  worker.poseWritten();
  ASSERT_TRUE(wait_for_solves(2));
  const auto second = worker.take();
  ASSERT_TRUE(second && second->error.empty());
  EXPECT_EQ(second->request.targets, next.targets);
  EXPECT_EQ(worker.counts().superseded, 0);
}

TEST(SolveWorker, ANewHandleSetRefactorsAndTheSolveMatchesTheSolverWarmStarted) {
  TubeScene scene;
  meshik::edit::SolveWorker worker(scene.examples, {}, {});
  worker.post(scene.request(0.3));
  worker.waitIdle();
  const auto first = worker.take();
  ASSERT_TRUE(first && first->error.empty()) << (first ? first->error : "none");
  EXPECT_TRUE(first->refactored);

  worker.post(scene.request(0.5));
  worker.waitIdle();
  const auto second = worker.take();
  ASSERT_TRUE(second && second->error.empty());
  EXPECT_FALSE(second->refactored);
  const meshik::Solver solver(scene.examples, scene.handles);
  const auto targets = scene.request(0.5).targets;
  const meshik::SolveResult expected = solver.solve(targets.data(), first->result.weights.data());
  EXPECT_EQ(second->result.vertices, expected.vertices) << "warm-started from the previous pose";

  meshik::edit::SolveRequest more = scene.request(0.5);
  more.handles.push_back(0);
  more.targets.insert(more.targets.end(), scene.meshes.rest.begin(), scene.meshes.rest.begin() + 3);
  worker.post(more);
  worker.waitIdle();
  const auto third = worker.take();
  ASSERT_TRUE(third && third->error.empty());
  EXPECT_TRUE(third->refactored);
  EXPECT_NEAR(third->result.vertices[0], scene.meshes.rest[0], 1e-9) << "the new handle holds";
}

TEST(SurfaceNormals, UnitFaceNormalsAndAreaWeightedVertexNormals) {
  // A big triangle in the plane z = 0 (area 2) and a small one (area 0.5) folded up in the plane
  // x = 0: the normals of the two shared vertices lean towards the big one's in proportion to the areas.
  const std::vector<double> folded = {0, 0, 0, 0, 2, 0, -2, 0, 0, 0, 0, 0.5};
  const std::vector<int> triangles = {0, 1, 2, 0, 1, 3};
  const meshik::edit::SurfaceNormals n = meshik::edit::surfaceNormals(folded, triangles);
  ASSERT_EQ(n.faces.size(), 6u);
  ASSERT_EQ(n.vertices.size(), 12u);
  const double big[3] = {0, 0, 1}, small[3] = {1, 0, 0};  // (p1 - p0) x (p2 - p0) of each, normalized
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(n.faces[k], big[k], 1e-15);
    EXPECT_NEAR(n.faces[3 + k], small[k], 1e-15);
  }
  const double length = std::hypot(4.0, 1.0);  // twice the area of each: 4 along z, 1 along x
  for (int v : {0, 1}) {
    EXPECT_NEAR(n.vertices[3 * v], 1.0 / length, 1e-15) << v;
    EXPECT_NEAR(n.vertices[3 * v + 2], 4.0 / length, 1e-15) << v;
  }
  EXPECT_NEAR(n.vertices[3 * 2 + 2], 1.0, 1e-15) << "only in the big triangle";
  EXPECT_NEAR(n.vertices[3 * 3], 1.0, 1e-15) << "only in the small triangle";
}

TEST(SolveWorker, GivenTheTrianglesEachPoseComesWithItsNormals) {
  TubeScene scene;
  meshik::edit::SolveWorker worker(scene.examples, {}, {}, scene.meshes.triangles);
  worker.post(scene.request(0.4));
  worker.waitIdle();
  const auto outcome = worker.take();
  ASSERT_TRUE(outcome && outcome->error.empty()) << (outcome ? outcome->error : "none");
  const meshik::edit::SurfaceNormals expected =
      meshik::edit::surfaceNormals(outcome->result.vertices, scene.meshes.triangles);
  EXPECT_EQ(outcome->normals.faces, expected.faces);
  EXPECT_EQ(outcome->normals.vertices, expected.vertices);
  EXPECT_EQ(outcome->normals.vertices.size(), outcome->result.vertices.size());
}

TEST(SolveWorker, QuickRequestsTakeOneStepAndAFullOneConvergesFromThere) {
  TubeScene scene;
  meshik::edit::SolveWorker worker(scene.examples, {}, {});
  meshik::edit::SolveRequest quick = scene.request(0.4);
  quick.quick = true;
  worker.post(quick);
  worker.waitIdle();
  const auto stepped = worker.take();
  ASSERT_TRUE(stepped && stepped->error.empty());
  EXPECT_EQ(stepped->result.iterations, 1);
  EXPECT_TRUE(stepped->refactored);

  worker.post(scene.request(0.4));
  worker.waitIdle();
  const auto full = worker.take();
  ASSERT_TRUE(full && full->error.empty());
  EXPECT_TRUE(full->refactored) << "the full solver is a second one";
  EXPECT_TRUE(full->result.converged);
  const meshik::Solver solver(scene.examples, scene.handles);
  const auto targets = scene.request(0.4).targets;
  EXPECT_EQ(full->result.vertices, solver.solve(targets.data(), stepped->result.weights.data()).vertices);
}

TEST(SolveWorker, ASolveTheCoreRefusesComesBackAsAnErrorAndTheWorkerGoesOn) {
  TubeScene scene;
  meshik::edit::SolveWorker worker(scene.examples, {}, {});
  meshik::edit::SolveRequest none;
  worker.post(none);
  worker.waitIdle();
  const auto refused = worker.take();
  ASSERT_TRUE(refused.has_value());
  EXPECT_NE(refused->error.find("handle"), std::string::npos) << refused->error;
  EXPECT_TRUE(refused->result.vertices.empty());
  worker.post(scene.request(0.2));
  worker.waitIdle();
  const auto fine = worker.take();
  ASSERT_TRUE(fine.has_value());
  EXPECT_TRUE(fine->error.empty()) << fine->error;
  EXPECT_EQ(fine->result.vertices.size(), scene.meshes.rest.size());
}

// A one-group, one-frame file of the handles 4 and 9 (no rest mesh given: positions only).
meshik::edit::DragFrames someFrames() {
  meshik::edit::DragFrames file;
  file.rest_path = "/data/rest \"quoted\".obj";
  file.example_paths = {"/data/a.obj", "/data/b.obj"};
  meshik::edit::fillOneFrame(file, "drag", {4, 9}, {1, 1}, {0.1, 0.2, 1.0 / 3.0, -5, 6, 7});
  return file;
}

// A fresh empty folder under the temporary directory.
std::filesystem::path emptyFolder(const std::string& name) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

TEST(ConstraintFramesWriter, RefusesANonFiniteTargetNamingTheHandleAndWritesNothing) {
  const std::filesystem::path folder = emptyFolder("meshik_edit_writer_test");
  const std::string path = (folder / "drag.json").string();
  meshik::edit::DragFrames file = someFrames();
  file.frames[0].targets[0][4] = std::nan("");
  try {
    meshik::edit::writeConstraintFrames(path, file, nullptr, 0);
    FAIL() << "no error";
  } catch (const meshik::edit::ConstraintWriteError& error) {
    EXPECT_NE(std::string(error.what()).find("vertex 9 is not finite"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("drag.json"), std::string::npos) << error.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder));

  file = someFrames();
  file.groups[0].vertices = {4, 4};
  EXPECT_THROW(meshik::edit::writeConstraintFrames(path, file, nullptr, 0), meshik::edit::ConstraintWriteError);
  file = someFrames();
  file.rest_path.clear();
  EXPECT_THROW(meshik::edit::writeConstraintFrames(path, file, nullptr, 0), meshik::edit::ConstraintWriteError);
  const std::vector<double> three_vertices(9, 0.0);
  file = someFrames();
  try {
    meshik::edit::writeConstraintFrames(path, file, three_vertices.data(), 3);
    FAIL() << "vertex 4 of 3";
  } catch (const meshik::edit::ConstraintWriteError& error) {
    EXPECT_NE(std::string(error.what()).find("vertex 4 is not on the rest mesh (3 vertices)"), std::string::npos)
        << error.what();
  }

  const meshik::edit::DragFrames saved = someFrames();
  meshik::edit::writeConstraintFrames(path, saved, nullptr, 0);
  const meshik::constraints::ConstraintDocument document = meshik::constraints::read_constraint_file(path);
  EXPECT_EQ(document.rest, saved.rest_path);
  EXPECT_EQ(document.examples, saved.example_paths);
  EXPECT_EQ(document.feature_space, std::optional<std::string>("nonlinear"));
  EXPECT_EQ(document.max_iterations, std::optional<std::int64_t>(saved.max_iterations));
  ASSERT_EQ(document.frames.size(), 1u);
  ASSERT_EQ(document.frames[0].targets.size(), 1u);
  EXPECT_EQ(document.frames[0].targets[0].positions, saved.frames[0].targets[0]) << "every target reads back exactly";
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()), 1)
      << "no temporary file left";
  std::filesystem::remove_all(folder);
}

// A view looking down -z: a dial turned counter-clockwise on the screen turns the group
// counter-clockwise about the view axis (+z here); the centre stays; others do not move.
TEST(GroupRotation, ADialTurnsTheGroupAboutItsCentreAsTheCursorGoesRound) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> targets = {1, 0, 0, -1, 0, 0, 0, 2, 0};
  const WindowPoint right = view.project(&targets[0]);
  meshik::edit::GroupRotation rotation(view, targets, {0, 1}, right.x, right.y);
  EXPECT_NEAR(rotation.centre()[0], 0.0, 1e-12);
  const auto axis = rotation.axisVector();
  EXPECT_NEAR(axis[2], 1.0, 1e-9) << "towards the viewer";
  const WindowPoint centre = view.project(rotation.centre().data());
  // A quarter turn: from the right of the centre to above it.
  const double degrees = rotation.dialDegrees(centre.x, centre.y + (right.x - centre.x));
  EXPECT_NEAR(degrees, 90.0, 1e-6);
  const std::vector<double> turned = rotation.targetsTurnedBy(degrees);
  EXPECT_NEAR(turned[0], 0.0, 1e-6);
  EXPECT_NEAR(turned[1], 1.0, 1e-6);
  EXPECT_NEAR(turned[3], 0.0, 1e-6);
  EXPECT_NEAR(turned[4], -1.0, 1e-6);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(turned[6 + k], targets[6 + k]) << "not in the group";
  EXPECT_EQ(rotation.dialDegrees(centre.x + 1, centre.y), 0.0) << "at the centre the dial means nothing";
}

TEST(GroupRotation, ALockedAxisTurnsAboutThatWorldAxisAndTypedDegreesAreExact) {
  const ScreenProjection view = cameraOnZAxis();
  const std::vector<double> targets = {0, 1, 0, 0, -1, 0};
  meshik::edit::GroupRotation rotation(view, targets, {0, 1}, 400, 300);
  rotation.setAxis(meshik::edit::RotationAxis::kX);
  const std::vector<double> turned = rotation.targetsTurnedBy(90.0);
  EXPECT_NEAR(turned[0], 0.0, 1e-12);
  EXPECT_NEAR(turned[1], 0.0, 1e-12);
  EXPECT_NEAR(turned[2], 1.0, 1e-12) << "y turns into z about x";
  // Seen from +z, an X axis is edge-on: the dial's sign stays; a Z axis pointing away flips it.
  rotation.setAxis(meshik::edit::RotationAxis::kZ);
  EXPECT_EQ(rotation.axisVector()[2], 1.0);
}

TEST(RigidFit, FindsARotationAndTranslationAndRefusesANonRigidMove) {
  const std::vector<double> from = {0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3};
  const ScreenProjection view = cameraOnZAxis();
  meshik::edit::GroupRotation rotation(view, from, {0, 1, 2, 3}, 0, 0);
  rotation.setAxis(meshik::edit::RotationAxis::kY);
  std::vector<double> to = rotation.targetsTurnedBy(33.0);
  for (size_t i = 0; i < to.size(); i += 3) to[i] += 0.5;
  const auto motion = meshik::edit::fitRigidMotion(from.data(), to.data(), 4, 1e-12);
  ASSERT_TRUE(motion.has_value());
  for (size_t p = 0; p < 4; ++p) {
    const double* a = &from[3 * p];
    for (int row = 0; row < 3; ++row) {
      double x = motion->center[row] + motion->translation[row];
      for (int k = 0; k < 3; ++k) x += motion->rotation[3 * row + k] * (a[k] - motion->center[k]);
      EXPECT_NEAR(x, to[3 * p + row], 1e-12);
    }
  }
  EXPECT_NEAR(std::acos((motion->rotation[0] + motion->rotation[4] + motion->rotation[8] - 1) / 2) * 180 / M_PI, 33.0,
              1e-9);
  to[4] += 1e-3;
  EXPECT_FALSE(meshik::edit::fitRigidMotion(from.data(), to.data(), 4, 1e-6).has_value());
}

// A turned group of the tube goes into the file as "rotate" + "translate"; resolved by the
// library it gives back the tool's targets.
TEST(ConstraintFramesWriter, ATurnedGroupIsWrittenAsARotationThatResolvesToItsTargets) {
  const meshik_test::ExampleMeshes meshes = meshik_test::make_tube_examples();
  const int n = meshes.num_vertices();
  const std::vector<int> handles = {0, 1, 2, n - 1};
  const std::vector<int> groups = {1, 1, 1, 2};
  std::vector<double> targets;
  for (int v : handles) targets.insert(targets.end(), &meshes.rest[3 * v], &meshes.rest[3 * v] + 3);
  meshik::edit::GroupRotation rotation(cameraOnZAxis(), targets, meshik::edit::groupMembers(groups, 1), 0, 0);
  rotation.setAxis(meshik::edit::RotationAxis::kZ);
  targets = rotation.targetsTurnedBy(-20.0);
  targets[9 + 1] += 0.25;  // the single handle moves (positions)

  meshik::edit::KeyframeList keyframes;
  std::vector<double> second = targets;
  for (size_t i = 0; i < 9; i += 3) second[i] += 0.1;
  EXPECT_EQ(keyframes.add(keyframes.nextName(), handles, groups, targets), "");
  EXPECT_EQ(keyframes.nextName(), "0002");
  EXPECT_EQ(keyframes.add(keyframes.nextName(), handles, groups, second), "");
  EXPECT_NE(keyframes.add("0003", {0, 1}, {1, 1}, {0, 0, 0, 0, 0, 0}).find("handles changed"), std::string::npos);
  EXPECT_NE(keyframes.add("0001", handles, groups, targets).find("already named"), std::string::npos);
  EXPECT_EQ(keyframes.count(), 2);

  meshik::edit::DragFrames file;
  file.rest_path = "/data/rest.obj";
  file.example_paths = {"/data/a.obj"};
  keyframes.fill(file);
  const std::filesystem::path folder = emptyFolder("meshik_edit_keyframes_test");
  const std::string path = (folder / "frames.json").string();
  meshik::edit::writeConstraintFrames(path, file, meshes.rest.data(), n);
  std::ifstream text(path);
  const std::string json((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"rotate\""), std::string::npos) << json;
  const auto document = meshik::constraints::read_constraint_file(path);
  ASSERT_EQ(document.frames.size(), 2u);
  EXPECT_TRUE(document.frames[0].targets[0].rigid);
  EXPECT_FALSE(document.frames[0].targets[1].rigid) << "one vertex: positions";
  const auto resolved = meshik::constraints::resolve_constraints(document, meshes.rest.data(), n);
  ASSERT_EQ(resolved.handles, std::vector<std::int64_t>(handles.begin(), handles.end()));
  for (size_t i = 0; i < targets.size(); ++i) {
    EXPECT_NEAR(resolved.targets[i], targets[i], 1e-12) << i;
    EXPECT_NEAR(resolved.targets[targets.size() + i], second[i], 1e-12) << i;
  }
  std::filesystem::remove_all(folder);
}

// Four vertices, symmetric about x = 1 but for one that is a little off: the partner is the
// nearest vertex to the mirror image within the tolerance; one without a partner gets -1.
TEST(MirrorPairing, PairsEachVertexWithTheNearestToItsImageWithinTheTolerance) {
  const std::vector<double> rest = {0, 0, 0, 2, 0, 0, 0.5, 1, 0, 1.52, 1, 0, 1, 3, 0, 0.2, 5, 0};
  const meshik::edit::MirrorPlane plane = meshik::edit::MirrorPlane::throughCentre(rest, meshik::edit::axisNormal(0));
  EXPECT_DOUBLE_EQ(plane.offset, 1.0);
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 0, plane, 1e-9), 1);
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 1, plane, 1e-9), 0);
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 2, plane, 1e-9), -1) << "0.02 off";
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 2, plane, 0.05), 3);
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 4, plane, 1e-9), 4) << "on the plane: itself";
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 5, plane, 0.1), -1);
  double image[3];
  plane.reflect(&rest[6], image);
  EXPECT_DOUBLE_EQ(image[0], 1.5);
  EXPECT_DOUBLE_EQ(image[1], 1.0);
  const meshik::edit::MirrorPlane y_plane = meshik::edit::MirrorPlane::throughCentre(rest, meshik::edit::axisNormal(1));
  EXPECT_DOUBLE_EQ(y_plane.offset, 2.5);
}

TEST(PoseState, GroupMembersAndNewNumbers) {
  EXPECT_EQ(meshik::edit::groupMembers({3, 1, 3, 2}, 3), (std::vector<int>{0, 2}));
  EXPECT_EQ(meshik::edit::newGroupNumber({3, 1, 3, 2}), 4);
  EXPECT_EQ(meshik::edit::newGroupNumber({}), 1);
}

// Undo hands the worker the undone pose's weights: the next solve starts from them, not from
// the newest pose's.
TEST(SolveWorker, StartWeightsReplaceTheWarmStart) {
  TubeScene scene;
  meshik::edit::SolveWorker worker(scene.examples, {}, {});
  worker.post(scene.request(0.3));
  worker.waitIdle();
  const auto first = worker.take();
  ASSERT_TRUE(first && first->error.empty());
  worker.post(scene.request(0.6));
  worker.waitIdle();
  ASSERT_TRUE(worker.take().has_value());
  meshik::edit::SolveRequest again = scene.request(0.45);
  again.start_weights = first->result.weights;
  worker.post(again);
  worker.waitIdle();
  const auto third = worker.take();
  ASSERT_TRUE(third && third->error.empty());
  const meshik::Solver solver(scene.examples, scene.handles);
  EXPECT_EQ(third->result.vertices, solver.solve(again.targets.data(), first->result.weights.data()).vertices);
}

// The dock's "Regions" option grows the weights to #regions x #examples: weights kept from
// before (one vector of #E) are no warm start for the new solver, which starts afresh instead
// (reading them would run past their end).
TEST(SolveWorker, WeightsOfAnotherLengthAreNoWarmStart) {
  TubeScene scene;
  meshik::SolverOptions options;
  options.regions = 2;
  options.blend = meshik::Blend::kFree;
  meshik::edit::SolveWorker worker(scene.examples, options, {});
  meshik::edit::SolveRequest request = scene.request(0.4);
  request.start_weights = std::vector<double>(scene.meshes.examples.size(), 0.5);
  worker.post(request);
  worker.waitIdle();
  const auto outcome = worker.take();
  ASSERT_TRUE(outcome && outcome->error.empty()) << (outcome ? outcome->error : "none");
  const meshik::Solver solver(scene.examples, scene.handles, options);
  ASSERT_EQ(solver.num_weights(), 2 * (1 + static_cast<int>(scene.meshes.examples.size())));  // free: rest first
  EXPECT_EQ(outcome->result.weights.size(), static_cast<size_t>(solver.num_weights()));
  EXPECT_EQ(outcome->result.vertices, solver.solve(request.targets.data(), nullptr).vertices);
}

// The dock's blend, regions and handle stiffness are saved, so `meshik pose` replays the tool's poses with them.
TEST(ConstraintFramesWriter, WritesTheBlendAndTheRegions) {
  const std::filesystem::path folder = emptyFolder("meshik_edit_writer_blend_test");
  const std::string path = (folder / "drag.json").string();
  meshik::edit::DragFrames file = someFrames();
  file.free_blend = true;
  file.regions = meshik::kAutomaticRegions;
  file.region_smoothness = 0.5;
  file.handle_stiffness = 0.25;
  meshik::edit::writeConstraintFrames(path, file, nullptr, 0);
  meshik::constraints::ConstraintDocument document = meshik::constraints::read_constraint_file(path);
  EXPECT_EQ(document.handle_stiffness, std::optional<double>(0.25));
  EXPECT_EQ(document.blend, std::optional<std::string>("free"));
  ASSERT_TRUE(document.regions.has_value());
  EXPECT_TRUE(document.regions->automatic);
  EXPECT_EQ(document.region_smoothness, std::optional<double>(0.5));

  file = someFrames();
  file.regions = 3;
  meshik::edit::writeConstraintFrames(path, file, nullptr, 0);
  document = meshik::constraints::read_constraint_file(path);
  EXPECT_EQ(document.blend, std::optional<std::string>("affine"));
  ASSERT_TRUE(document.regions.has_value());
  EXPECT_EQ(document.regions->count, 3);
  EXPECT_FALSE(document.regions->automatic);

  file = someFrames();  // one region, hard handles: the file keeps the global weights' form and no stiffness
  meshik::edit::writeConstraintFrames(path, file, nullptr, 0);
  EXPECT_FALSE(meshik::constraints::read_constraint_file(path).regions.has_value());
  EXPECT_FALSE(meshik::constraints::read_constraint_file(path).handle_stiffness.has_value());
  std::filesystem::remove_all(folder);
}

TEST(LatencyStats, MedianAndMax) {
  meshik::edit::LatencyStats stats;
  EXPECT_EQ(stats.median(), 0.0);
  for (double ms : {5.0, 1.0, 9.0, 3.0}) stats.add(ms);
  EXPECT_EQ(stats.median(), 4.0);
  EXPECT_EQ(stats.max(), 9.0);
  stats.add(2.0);
  EXPECT_EQ(stats.median(), 3.0);
}

}  // namespace

// A plane through a picked point keeps that point's coordinate; a new partner joins the group that
// mirrors its handle's group, unless that is the handle's own group (a handle on the plane).
TEST(MirrorPairing, APickedPlaneGoesThroughThePointAndPartnersJoinTheMirroredGroup) {
  const double point[3] = {0.25, -1.0, 3.0};
  const meshik::edit::MirrorPlane plane = meshik::edit::MirrorPlane::throughPoint(point, meshik::edit::axisNormal(1));
  double image[3];
  const double p[3] = {1.0, 2.0, 3.0};
  plane.reflect(p, image);
  EXPECT_EQ(image[0], 1.0);
  EXPECT_EQ(image[1], -4.0);
  EXPECT_EQ(image[2], 3.0);
  // Handles: vertex 10 (group 1) mirrored by 20 (group 2); vertex 11 just added to group 1.
  const std::vector<int> handles{10, 20, 11}, groups{1, 2, 1}, mirrors{20, 10, -1};
  EXPECT_EQ(meshik::edit::partnerGroup(handles, groups, mirrors, 2), 2);
  EXPECT_EQ(meshik::edit::partnerGroup(handles, groups, mirrors, 1), -1) << "group 2 has no other member";
  // A group whose other handle lies on the plane (its own mirror, in its own group): a new group.
  const std::vector<int> on_plane_groups{1, 1, 1}, on_plane_mirrors{10, -1, -1};
  EXPECT_EQ(meshik::edit::partnerGroup(handles, on_plane_groups, on_plane_mirrors, 2), -1);
}

// The view's vertical plane from a turned, scaled view (as MeshLab's trackball makes one): mirroring
// across it through a point c swaps left and right on the screen about c (orthographic view: the
// image of p is drawn at 2 c_x - p_x, at p's height and depth); the default view gives plane x.
TEST(MirrorPairing, TheViewsVerticalPlaneSwapsLeftAndRightOnTheScreen) {
  const Eigen::Affine3d view = Eigen::Translation3d(0.3, -0.2, -5.0) * Eigen::Scaling(2.5) *
                         Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()) *
                         Eigen::AngleAxisd(-1.1, Eigen::Vector3d(0.2, 1.0, 0.4).normalized());
  const double l = -4, r = 4, b = -3, t = 3, n = 0.1, f = 100;
  const double orthographic[16] = {2 / (r - l), 0, 0, 0, 0, 2 / (t - b), 0, 0, 0, 0, -2 / (f - n), 0,
                                   -(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n), 1};
  const int viewport[4] = {0, 0, 800, 600};
  const ScreenProjection screen(orthographic, view.matrix().data(), viewport);
  const meshik::edit::Direction normal = meshik::edit::viewVerticalNormal(screen.modelview());
  EXPECT_NEAR(std::hypot(normal[0], normal[1], normal[2]), 1.0, 1e-15);
  const double c[3] = {0.4, 0.1, -0.3}, p[3] = {-0.5, 0.8, 0.6};
  const meshik::edit::MirrorPlane plane = meshik::edit::MirrorPlane::throughPoint(c, normal);
  double image[3];
  plane.reflect(p, image);
  const WindowPoint wc = screen.project(c), wp = screen.project(p), wi = screen.project(image);
  EXPECT_GT(std::abs(wp.x - wc.x), 10.0) << "p is off the plane on the screen";
  EXPECT_NEAR(wi.x, 2 * wc.x - wp.x, 1e-9);
  EXPECT_NEAR(wi.y, wp.y, 1e-9);
  EXPECT_NEAR(wi.depth, wp.depth, 1e-12);

  const double centred[16] = {1.7, 0, 0, 0, 0, 1.7, 0, 0, 0, 0, 1.7, 0, 0, 0, -5, 1};
  const meshik::edit::Direction x =
      meshik::edit::viewVerticalNormal(ScreenProjection(orthographic, centred, viewport).modelview());
  EXPECT_EQ(x, meshik::edit::axisNormal(0));
  const std::vector<double> rest = {-1, 0, 0, 1, 0, 0, 0, 2, 0};
  EXPECT_EQ(meshik::edit::MirrorPlane::throughCentre(rest, x).offset, 0.0);
  EXPECT_EQ(meshik::edit::mirrorPartner(rest, 0, meshik::edit::MirrorPlane::throughCentre(rest, x), 1e-12), 1);
}
