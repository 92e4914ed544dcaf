// Hand models as glTF skins: joints named after the OpenXR hand joints (docs/renderer.md).
#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "gltf_document.hpp"
#include "gltf_read.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/scene/hand_mesh.hpp"

namespace vt {
namespace {

using nlohmann::json;

std::string jointNameList() {
  std::string out;
  for (int j = 0; j < kHandJointCount; ++j) out += (j ? ", " : "") + std::string(handJointName(HandJoint(j)));
  return out;
}

// Appends one glTF mesh's triangle primitives, their JOINTS_0 mapped through `joints` to HandJoints.
void readPrimitives(const tinygltf::Mesh& mesh, const gltf::AccessorReader& read,
                    const std::vector<HandJoint>& joints, HandMesh& out, bool& haveNormals) {
  const std::string& source = read.source();
  for (const tinygltf::Primitive& prim : mesh.primitives) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) continue;
    auto attribute = [&](const char* name) {
      const auto it = prim.attributes.find(name);
      return it == prim.attributes.end() ? -1 : it->second;
    };
    if (attribute("JOINTS_1") >= 0 || attribute("WEIGHTS_1") >= 0) {
      fail(source, ": mesh '", mesh.name, "' has more than 4 joint weights per vertex (JOINTS_1/WEIGHTS_1); ",
           "keep the 4 largest");
    }
    if (attribute("POSITION") < 0) fail(source, ": mesh '", mesh.name, "' has a primitive without POSITION");
    if (attribute("JOINTS_0") < 0 || attribute("WEIGHTS_0") < 0) {
      fail(source, ": mesh '", mesh.name, "' has a primitive without JOINTS_0 and WEIGHTS_0 (not skinned)");
    }
    // Half the scene budget: the renderer uploads the mesh twice (right and mirrored left). Counts
    // are checked before anything is read.
    const std::size_t first = out.mesh.vertices.size();
    const std::size_t n = read.count(attribute("POSITION"), "POSITION");
    if (n > budget::kSceneVertices / 2 - first) fail(source, ": more than ", budget::kSceneVertices / 2, " vertices");
    const std::size_t indexCount = prim.indices >= 0 ? read.count(prim.indices, "indices") : n;
    if (indexCount > budget::kSceneIndices / 2 - out.mesh.indices.size()) {
      fail(source, ": more than ", budget::kSceneIndices / 2, " indices");
    }
    const std::vector<float> p = read.floats(attribute("POSITION"), 3, "POSITION");
    const std::vector<std::uint32_t> j = read.uints(attribute("JOINTS_0"), 4, "JOINTS_0");
    const std::vector<float> w = read.floats(attribute("WEIGHTS_0"), 4, "WEIGHTS_0");
    if (j.size() != 4 * n || w.size() != 4 * n) fail(source, ": JOINTS_0/WEIGHTS_0 count differs from POSITION");
    std::vector<float> normals;
    if (attribute("NORMAL") >= 0) {
      normals = read.floats(attribute("NORMAL"), 3, "NORMAL");
      if (normals.size() != p.size()) fail(source, ": NORMAL count differs from POSITION");
    } else {
      haveNormals = false;
    }
    for (std::size_t v = 0; v < n; ++v) {
      Vertex vertex;
      vertex.position = {p[3 * v], p[3 * v + 1], p[3 * v + 2]};
      if (!normals.empty()) vertex.normal = {normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]};
      out.mesh.vertices.push_back(vertex);
      glm::u8vec4 joint(0);
      glm::vec4 weight(0.0f);
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) {
        const float wk = w[4 * v + std::size_t(k)];
        if (wk < 0.0f) fail(source, ": vertex ", v, " has a negative weight");
        if (wk == 0.0f) continue;
        const std::uint32_t index = j[4 * v + std::size_t(k)];
        if (index >= joints.size()) fail(source, ": vertex ", v, " uses joint ", index, " of a skin with ", joints.size());
        joint[k] = std::uint8_t(joints[index]);
        weight[k] = wk;
        sum += wk;
      }
      if (!(sum > 1e-6f)) fail(source, ": vertex ", v, " has no joint weight");
      out.joints.push_back(joint);
      out.weights.push_back(weight / sum);
    }
    std::vector<std::uint32_t> indices;
    if (prim.indices >= 0) {
      indices = read.indices(prim.indices, n);
    } else {
      for (std::uint32_t i = 0; i < n; ++i) indices.push_back(i);
    }
    indices.resize(indices.size() / 3 * 3);
    if (out.mesh.indices.size() + indices.size() > budget::kSceneIndices / 2) {
      fail(source, ": more than ", budget::kSceneIndices / 2, " indices");
    }
    for (std::uint32_t i : indices) out.mesh.indices.push_back(std::uint32_t(first) + i);
  }
}

}  // namespace

HandMesh loadHandModel(const std::filesystem::path& path) {
  const std::string bytes = readInputFile(path, "hand model", budget::kSceneFileBytes);
  const std::filesystem::path baseDir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  return loadHandModel(bytes, path.extension() == ".glb", "hand model '" + path.string() + "'", baseDir);
}

HandMesh loadHandModel(const std::string& bytes, bool binary, const std::string& source,
                       const std::filesystem::path& baseDir) {
  const LoadScope loading(source);
  const tinygltf::Model model = gltf::parseModel(bytes, binary, source, baseDir, {});
  const gltf::AccessorReader read(model, source);

  const tinygltf::Node* skinned = nullptr;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.mesh >= 0 && node.skin >= 0) {
      skinned = &node;
      break;
    }
  }
  if (!skinned) fail(source, ": no skinned mesh (a node with both \"mesh\" and \"skin\")");
  const tinygltf::Skin& skin = read.element(model.skins, skinned->skin, "skin");
  if (skin.joints.empty()) fail(source, ": skin '", skin.name, "' has no joints");
  std::vector<HandJoint> joints;
  std::set<HandJoint> seen;
  for (std::size_t i = 0; i < skin.joints.size(); ++i) {
    const std::string& name = read.element(model.nodes, skin.joints[i], "node").name;
    const std::optional<HandJoint> joint = handJointFromName(name);
    if (!joint) fail(source, ": skin joint ", i, " '", name, "' is not an OpenXR hand joint (", jointNameList(), ")");
    if (!seen.insert(*joint).second) fail(source, ": skin joint ", i, " '", name, "' appears twice");
    joints.push_back(*joint);
  }

  HandMesh out;
  for (glm::mat4& ib : out.inverseBind) ib = glm::mat4(1.0f);
  if (skin.inverseBindMatrices >= 0) {
    if (const std::size_t count = read.count(skin.inverseBindMatrices, "inverseBindMatrices"); count != joints.size())
      fail(source, ": skin has ", joints.size(), " joints but ", count, " inverse bind matrices");
    const std::vector<float> m = read.floats(skin.inverseBindMatrices, 16, "inverseBindMatrices");
    if (m.size() != 16 * joints.size()) fail(source, ": skin has ", joints.size(), " joints but ", m.size() / 16, " inverse bind matrices");
    for (std::size_t i = 0; i < joints.size(); ++i) {
      glm::mat4& ib = out.inverseBind[std::size_t(joints[i])];
      for (int k = 0; k < 16; ++k) ib[k / 4][k % 4] = m[16 * i + std::size_t(k)];  // column-major, as glTF
    }
  }
  if (skin.extras.IsObject() && skin.extras.Has("vtouching")) {
    const tinygltf::Value& radii = skin.extras.Get("vtouching").Get("tip_radius_m");
    if (radii.IsArray()) {
      if (radii.ArrayLen() != kFingerCount) fail(source, ": skin extras.vtouching.tip_radius_m must list 5 radii (thumb first)");
      for (int f = 0; f < kFingerCount; ++f) {
        const tinygltf::Value& r = radii.Get(f);
        const double value = r.IsNumber() ? r.GetNumberAsDouble() : -1.0;
        if (!(value >= 0.0 && value < 0.1)) fail(source, ": skin extras.vtouching.tip_radius_m[", f, "] is not a radius in metres");
        out.tipRadius_m[std::size_t(f)] = float(value);
      }
    }
  }
  bool haveNormals = true;
  readPrimitives(read.element(model.meshes, skinned->mesh, "mesh"), read, joints, out, haveNormals);
  if (!haveNormals) computeNormals(out.mesh);
  validateHandMesh(out, source);
  return out;
}

void saveHandModel(const HandMesh& hand, const std::filesystem::path& path, bool replace) {
  gltf::GltfDocument gltf(path);
  validateHandMesh(hand, "hand model export '" + path.string() + "'");
  json& doc = gltf.doc();
  // Nodes 0..25 are the joints in XrHandJointEXT order, parented along the bone chains from the
  // wrist, each at its bind pose; node 26 holds the skinned mesh.
  json nodes = json::array();
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto joint = HandJoint(j);
    const HandJoint parent = parentJoint(joint);
    const glm::mat4 bind = glm::inverse(hand.inverseBind[std::size_t(j)]);
    const glm::mat4 local = parent == joint ? bind : hand.inverseBind[std::size_t(parent)] * bind;
    json node = {{"name", handJointName(joint)}, {"matrix", json::array()}};
    for (int k = 0; k < 16; ++k) node["matrix"].push_back(local[k / 4][k % 4]);
    for (int c = 0; c < kHandJointCount; ++c) {
      if (c != j && parentJoint(HandJoint(c)) == joint) node["children"].push_back(c);
    }
    nodes.push_back(node);
  }
  std::vector<float> p, n, w, ib;
  std::vector<std::uint8_t> joints;
  for (std::size_t v = 0; v < hand.mesh.vertices.size(); ++v) {
    const Vertex& vertex = hand.mesh.vertices[v];
    p.insert(p.end(), {vertex.position.x, vertex.position.y, vertex.position.z});
    n.insert(n.end(), {vertex.normal.x, vertex.normal.y, vertex.normal.z});
    for (int k = 0; k < 4; ++k) {
      joints.push_back(hand.weights[v][k] == 0.0f ? 0 : hand.joints[v][k]);  // unused influences name joint 0
      w.push_back(hand.weights[v][k]);
    }
  }
  for (const glm::mat4& m : hand.inverseBind) {
    for (int k = 0; k < 16; ++k) ib.push_back(m[k / 4][k % 4]);
  }
  const int jointView = gltf.bufferView(joints.data(), joints.size(), gltf::kArrayBuffer);
  doc["accessors"].push_back({{"bufferView", jointView}, {"componentType", gltf::kUnsignedByte},
                              {"count", hand.joints.size()}, {"type", "VEC4"}});
  const int jointAccessor = int(doc["accessors"].size()) - 1;
  const json attributes = {{"POSITION", gltf.accessor(p, 3, true)}, {"NORMAL", gltf.accessor(n, 3, false)},
                           {"JOINTS_0", jointAccessor}, {"WEIGHTS_0", gltf.accessor(w, 4, false)}};
  const json primitive = {{"attributes", attributes},
                          {"indices", gltf.indexAccessor(hand.mesh.indices, hand.mesh.vertices.size())}};
  doc["meshes"] = json::array({{{"name", "hand"}, {"primitives", json::array({primitive})}}});
  json skin = {{"name", "openxr_hand"}, {"joints", json::array()}, {"skeleton", int(HandJoint::Wrist)},
               {"inverseBindMatrices", gltf.accessor(ib, 16, false)},
               {"extras", {{"vtouching", {{"tip_radius_m", hand.tipRadius_m}}}}}};
  for (int j = 0; j < kHandJointCount; ++j) skin["joints"].push_back(j);
  doc["skins"] = json::array({skin});
  nodes.push_back({{"name", "hand"}, {"mesh", 0}, {"skin", 0}});
  doc["nodes"] = nodes;
  doc["scenes"] = json::array({{{"nodes", {int(HandJoint::Wrist), kHandJointCount}}}});
  doc["scene"] = 0;
  gltf.save(replace);
}

}  // namespace vt
