#include "gltf_haptic_material.hpp"

#include <cmath>
#include <cstring>

#include "vt/core/error.hpp"

namespace vt::gltf {
namespace {

const tinygltf::Value* member(const tinygltf::Value& object, const char* key) {
  return object.IsObject() && object.Has(key) ? &object.Get(key) : nullptr;
}

// The vibration map from a decoded glTF image: channel 0 (red or grey) as [0,1] floats, with the
// same scaling as loadChannelAsFloat (8-bit values are widened by 257 first), so a map embedded in
// a glTF file and the same PNG read from a dataset folder give identical floats.
ImageF channelAsFloat(const tinygltf::Image& img, const std::string& where) {
  const int bytesPerComponent = img.bits == 16 ? 2 : 1;
  const std::size_t pixels = std::size_t(std::max(img.width, 0)) * std::size_t(std::max(img.height, 0));
  if (pixels == 0 || img.component < 1 || img.component > 4 ||
      img.image.size() < pixels * std::size_t(img.component * bytesPerComponent)) {
    fail(where, ": the texture's image has no or inconsistent pixel data");
  }
  ImageF out(img.width, img.height, 1);
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::size_t offset = i * std::size_t(img.component) * std::size_t(bytesPerComponent);
    std::uint16_t v = 0;
    if (bytesPerComponent == 2) std::memcpy(&v, img.image.data() + offset, 2);  // host (little-endian) order
    else v = std::uint16_t(img.image[offset] * 257u);
    out.pixels[i] = float(v) / 65535.0f;
  }
  return out;
}

// Picks the entry a texture renderer should use: High_Resolution first, then Low_Resolution, then
// Other. "Reference" entries point into MPEG_haptic's media, which V-Touching does not read.
const tinygltf::Value* pickTexture(const tinygltf::Value& list, const std::string& where) {
  if (!list.IsArray()) fail(where, " must be an array");
  const tinygltf::Value* best = nullptr;
  int bestRank = 99;
  for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
    const tinygltf::Value& entry = list.Get(int(i));
    const tinygltf::Value* type = member(entry, "type");
    if (!member(entry, "texture") || !type || !type->IsString()) {
      fail(where, "[", i, "] needs 'texture' and a 'type' string");
    }
    const std::string t = type->Get<std::string>();
    const int rank = t == "High_Resolution" ? 0 : t == "Low_Resolution" ? 1 : t == "Other" ? 2 : t == "Reference" ? 3 : -1;
    if (rank < 0) fail(where, "[", i, "].type '", t, "' is not High_Resolution, Low_Resolution, Reference or Other");
    if (rank < 3 && rank < bestRank) best = &entry, bestRank = rank;
  }
  return best;
}

// Texture `t`'s image as a vibration map appended to the scene; returns its index.
int addMapFromTexture(const tinygltf::Model& model, int t, const std::string& field, Scene& scene) {
  if (t < 0 || std::size_t(t) >= model.textures.size()) fail(field, ": texture ", t, " out of range");
  const int image = model.textures[std::size_t(t)].source;
  if (image < 0 || std::size_t(image) >= model.images.size()) fail(field, ": texture ", t, " has no image");
  scene.vibrationMaps.push_back(channelAsFloat(model.images[std::size_t(image)], field));
  return int(scene.vibrationMaps.size()) - 1;
}

}  // namespace

void readTactileSettings(const tinygltf::Value& t, const std::string& where, Material& out) {
  if (!t.IsObject()) fail(where, " must be an object");
  auto number = [&](const char* key, float& into, float lo, float hi) {
    if (!t.Has(key)) return;
    const tinygltf::Value& v = t.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
    if (!(d >= lo && d <= hi)) fail(where, ".", key, " must be a number in [", lo, ", ", hi, "]");
    into = float(d);
  };
  number("gain", out.tactileGain, 0.0f, 10.0f);
  number("physical_width_m", out.physicalWidth_m, 0.0f, 100.0f);
  if (t.Has("wrap")) {
    if (!t.Get("wrap").IsBool()) fail(where, ".wrap must be true or false");
    out.wrapUv = t.Get("wrap").Get<bool>();
  }
  if (t.Has("scan_direction_uv")) {
    const tinygltf::Value& d = t.Get("scan_direction_uv");
    const bool pair = d.IsArray() && d.ArrayLen() == 2 && d.Get(0).IsNumber() && d.Get(1).IsNumber();
    const glm::vec2 uv = pair ? glm::vec2(float(d.Get(0).GetNumberAsDouble()), float(d.Get(1).GetNumberAsDouble()))
                              : glm::vec2(0.0f);
    const float length = glm::length(uv);
    if (!(length > 0.0f) || !std::isfinite(length)) fail(where, ".scan_direction_uv must be a direction [u, v]");
    out.scanDirectionUv = uv / length;
  }
}

int hapticMaterialIndex(const tinygltf::Model& model, const tinygltf::Mesh& mesh, const std::string& source) {
  const auto it = mesh.extensions.find(kHapticMaterialExtension);
  if (it == mesh.extensions.end()) return -1;
  const std::string where = str(source, ": mesh '", mesh.name, "' extensions.", kHapticMaterialExtension);
  const tinygltf::Value* index = member(it->second, "hapticMaterialIndex");
  if (!index || !index->IsInt()) fail(where, ".hapticMaterialIndex must be an integer");
  const int value = index->GetNumberAsInt();
  const auto root = model.extensions.find(kHapticMaterialExtension);
  const tinygltf::Value* list = root == model.extensions.end() ? nullptr : member(root->second, "materials");
  const int count = list && list->IsArray() ? int(list->ArrayLen()) : 0;
  if (value < 0 || value >= count) {
    fail(where, ".hapticMaterialIndex ", value, " out of range (the file defines ", count, " haptic materials)");
  }
  return value;
}

void applyHapticMaterial(const tinygltf::Model& model, int index, const std::string& source, Material& out,
                         Scene& scene) {
  const tinygltf::Value& haptic = model.extensions.at(kHapticMaterialExtension).Get("materials").Get(index);
  const std::string where = str(source, ": ", kHapticMaterialExtension, ".materials[", index, "]");
  if (!haptic.IsObject()) fail(where, " must be an object");
  const tinygltf::Value* name = member(haptic, "name");
  const std::string label = name && name->IsString() ? name->Get<std::string>() : str("#", index);

  const char* used = member(haptic, "vibrotactileTexture") ? "vibrotactileTexture" : "vibration";
  if (const tinygltf::Value* list = member(haptic, used)) {
    const std::string field = str(where, ".", used);
    if (const tinygltf::Value* entry = pickTexture(*list, field)) {
      const tinygltf::Value* texture = member(*entry, "texture");
      const tinygltf::Value* texIndex = texture ? member(*texture, "index") : nullptr;
      if (!texIndex || !texIndex->IsInt()) fail(field, ": texture.index must be an integer");
      out.vibrationMap = addMapFromTexture(model, texIndex->GetNumberAsInt(), field, scene);
    }
  }
  if (const tinygltf::Value* extras = member(haptic, "extras"); extras && extras->Has("vtouching")) {
    const tinygltf::Value& ours = extras->Get("vtouching");
    readTactileSettings(ours, where + ".extras.vtouching", out);
    // A scan in two directions: the map scanned across the main direction, as a texture index.
    if (const tinygltf::Value* across = member(ours, "across_texture")) {
      const std::string field = where + ".extras.vtouching.across_texture";
      if (!across->IsInt()) fail(field, " must be an integer");
      out.vibrationMapAcross = addMapFromTexture(model, across->GetNumberAsInt(), field, scene);
    }
  }
  // Kept in the file, reported: V-Touching renders vibration, not these.
  for (const char* kind : {"stiffness", "friction", "temperature", "custom", "vibration"}) {
    if (kind == std::string(used)) continue;
    const tinygltf::Value* list = member(haptic, kind);
    if (list && list->IsArray() && list->ArrayLen() > 0) {
      scene.unused.push_back(str("haptic material '", label, "': ", kind, " (", list->ArrayLen(),
                                 " texture(s)) not rendered"));
    }
  }
}

void readFileExtras(const tinygltf::Model& model, const std::string& source, Scene& scene) {
  const tinygltf::Value* ours = member(model.extras, "vtouching");
  const tinygltf::Value* intensity = ours ? member(*ours, "intensity") : nullptr;
  if (!intensity) return;
  if (!intensity->IsString()) fail(source, ": extras.vtouching.intensity must be a string");
  scene.intensity = intensity->Get<std::string>();
}

}  // namespace vt::gltf
