#include "modes/hand_view.hpp"

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/renderer.hpp"

namespace vt::app {

HandViewOptions readHandViewOptions(cli::Args& args) {
  HandViewOptions options;
  const std::string style = args.valueOr("hand", "mesh");
  if (style == "skeleton") options.style = renderer::HandStyle::Skeleton;
  else if (style != "mesh") fail(args.command(), ": --hand '", style, "' is not mesh or skeleton");
  options.modelFile = args.valueOr("hand-model", "");
  if (options.modelFile.empty()) return options;
  if (options.style == renderer::HandStyle::Skeleton) {
    fail(args.command(), ": --hand-model draws a mesh; it cannot go with --hand skeleton");
  }
  options.model = std::make_shared<const HandMesh>(loadHandModel(options.modelFile));
  return options;
}

void applyHandView(renderer::Renderer& gpu, const HandViewOptions& options) {
  if (!options.model) return;
  gpu.setHandModel(*options.model);
  log::info("hand model: ", options.modelFile, " (", options.model->mesh.vertices.size(), " vertices, ",
            options.model->mesh.triangleCount(), " triangles)");
}

}  // namespace vt::app
