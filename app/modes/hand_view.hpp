#pragma once
// How the app draws the hand (`--hand mesh|skeleton`, `--hand-model FILE.gltf`), the same in
// every mode that draws one. Setup (main) thread only.
#include <memory>
#include <string>

#include "cli.hpp"
#include "vt/renderer/frame.hpp"
#include "vt/scene/hand_mesh.hpp"

namespace vt::renderer {
class Renderer;
}

namespace vt::app {

struct HandViewOptions {
  renderer::HandStyle style = renderer::HandStyle::Mesh;  // --hand mesh|skeleton
  std::string modelFile;                   // --hand-model FILE.gltf|.glb: a skinned right hand
  std::shared_ptr<const HandMesh> model;   // its mesh; null = the generated hand
};

/// Reads --hand and --hand-model and loads the model, so a bad file fails before any device
/// is made (throws vt::Error naming the option or the file and the problem).
HandViewOptions readHandViewOptions(cli::Args& args);

/// Gives the renderer the --hand-model mesh (nothing to do for the generated default).
void applyHandView(renderer::Renderer& gpu, const HandViewOptions& options);

}  // namespace vt::app
