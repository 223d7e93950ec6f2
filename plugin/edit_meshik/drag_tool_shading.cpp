// Shading while posing: MeshLab draws a flat-shaded layer from face normals, which it can only
// upload as 3 vertices per triangle (its "replicated pipeline"), rebuilt on the GUI thread for every
// pose. On the elephant (84,638 triangles, Mesa's software renderer, 2 busy cores) that upload took
// 4-5.5 ms of each pose's write against about 1.5 ms for one vertex each with smooth shading. So a
// big layer drawn flat is drawn smooth while the tool runs (MeshLab's own edit_paint asks for vertex
// normals for the same reason, through suggestedRenderingData), and gets the artist's shading back
// when the tool ends (unless the artist changed it meanwhile; MeshLab gives nothing back itself).
#include "drag_tool.h"

#include "../layer_arrays.h"

#include <meshlab/glarea.h>

namespace meshik::edit {
namespace {

// From this many triangles on, a flat-shaded rest layer is drawn smooth while posing.
constexpr int kSmoothShadingTriangles = 50000;

// Whether `view` draws its solid mode with face normals (flat shading).
bool flatSolid(const MLRenderingData& view) {
  MLRenderingData::RendAtts solid;
  return view.get(MLRenderingData::PR_SOLID, solid) && solid[MLRenderingData::ATT_NAMES::ATT_FACENORMAL];
}

// `view` with its solid mode drawn with vertex normals instead of face normals (smooth shading).
MLRenderingData smoothSolid(const MLRenderingData& view) {
  MLRenderingData smooth(view);
  smooth.set(MLRenderingData::PR_SOLID, MLRenderingData::ATT_NAMES::ATT_VERTNORMAL, true);
  smooth.set(MLRenderingData::PR_SOLID, MLRenderingData::ATT_NAMES::ATT_FACENORMAL, false);
  return smooth;
}

// Whether the solid modes of `a` and `b` draw the same normals (vertex and face).
bool sameSolidNormals(const MLRenderingData& a, const MLRenderingData& b) {
  MLRenderingData::RendAtts first, second;
  a.get(MLRenderingData::PR_SOLID, first);
  b.get(MLRenderingData::PR_SOLID, second);
  for (auto normals : {MLRenderingData::ATT_NAMES::ATT_VERTNORMAL, MLRenderingData::ATT_NAMES::ATT_FACENORMAL})
    if (first[normals] != second[normals]) return false;
  return true;
}

}  // namespace

MLRenderingData DragTool::viewOf(const MeshModel& layer) const {
  MLRenderingData view;
  if (shared_ != nullptr && area_ != nullptr) shared_->getRenderInfoPerMeshView(layer.id(), area_->context(), view);
  return view;
}

bool DragTool::drawnFlat(const MeshModel& layer) const { return flatSolid(viewOf(layer)); }

void DragTool::shadeSmoothWhilePosing(MeshModel& rest) {
  if (shared_ == nullptr || area_ == nullptr || artist_shading_ || rest.cm.fn < kSmoothShadingTriangles) return;
  const MLRenderingData view = viewOf(rest);
  if (!flatSolid(view)) return;
  artist_shading_.emplace(view);
  shared_->setRenderingDataPerMeshView(rest.id(), area_->context(), smoothSolid(view));
  shared_->manageBuffers(rest.id());
  log(QStringLiteral("%1 drawn smooth while posing (flat shading uploads 3 vertices per triangle to the GPU for "
                     "every pose; the flat shading comes back when the tool ends)")
          .arg(plugin::describeLayer(rest)));
}

void DragTool::restoreArtistShading() {
  if (!artist_shading_) return;
  MeshModel* rest = restLayer();
  if (rest != nullptr && shared_ != nullptr && area_ != nullptr &&
      sameSolidNormals(viewOf(*rest), smoothSolid(*artist_shading_))) {  // not changed by the artist meanwhile
    shared_->setRenderingDataPerMeshView(rest->id(), area_->context(), *artist_shading_);
    shared_->manageBuffers(rest->id());
    area_->update();
  }
  artist_shading_.reset();
}

}  // namespace meshik::edit
