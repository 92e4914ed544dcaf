#include "gltf_read.hpp"

#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <nlohmann/json.hpp>

#include "vt/core/budgets.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/text_input.hpp"
#include "vt/scene/image.hpp"

namespace vt::gltf {
namespace {

// tinygltf's file access, confined to the scene's folder and held to the file budget; the first
// refusal is kept so the error says it in our words.
struct FileAccess {
  std::filesystem::path baseDir;
  GltfLoadOptions options;
  std::string refusal;
  std::uintmax_t bytesRead = 0;  // every referenced file together is held to the scene budget
};

// Confinement is checked before existence: a URI outside the folder is refused in our words
// whether or not its target exists (tinygltf would otherwise say "File not found").
bool confined(FileAccess& access, const std::string& path) {
  if (access.options.allowOutsideFolder) return true;
  try {
    checkInsideFolder(path, access.baseDir, "URI");
    return true;
  } catch (const Error& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    return false;
  }
}

bool fileExists(const std::string& path, void* user) {
  auto& access = *static_cast<FileAccess*>(user);
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  // tinygltf also looks for a file in "." when it is not beside the scene: a missing file there
  // is no refusal (it made a missing buffer read "outside the scene folder").
  if (!exists && path.rfind(access.baseDir.string(), 0) != 0) return false;
  return confined(access, path) && exists;
}

std::string expandPath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto& access = *static_cast<FileAccess*>(user);
  if (!confined(access, path)) {
    if (err) *err = access.refusal;
    return false;
  }
  try {
    const std::uintmax_t size = checkInputFile(path, "glTF resource", budget::kSceneFileBytes);
    if (size > budget::kSceneFileBytes - access.bytesRead) {
      fail("the files it references hold more than ", budget::kSceneFileBytes, " bytes together ('", path, "' is ", size,
           " bytes after ", access.bytesRead, "; docs/RELIABILITY.md)");
    }
    *out = readInputBytes(path, "glTF resource", budget::kSceneFileBytes - access.bytesRead);
    access.bytesRead += out->size();
    return true;
  } catch (const Error& e) {
    if (access.refusal.empty()) access.refusal = e.what();
    if (err) *err = e.what();
    return false;
  }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "writing is not supported";
  return false;
}

// Textures decode through our PNG/JPEG path: the same size budget and chunk checks as every image.
// Like tinygltf's own loader, 16-bit PNGs stay 16-bit (vibration maps are exported that way).
bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                 const unsigned char* bytes, int size, void*) {
  try {
    const std::span<const std::uint8_t> encoded(bytes, std::size_t(size));
    const std::string source = str("image[", index, "] '", image->name, "'");
    image->component = 4;
    if (is16BitImage(encoded)) {
      const Image16 rgba = loadImage16(encoded, source, 4);
      image->width = rgba.width;
      image->height = rgba.height;
      image->bits = 16;
      image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
      image->image.resize(rgba.pixels.size() * sizeof(std::uint16_t));  // host order, as tinygltf
      std::memcpy(image->image.data(), rgba.pixels.data(), image->image.size());
    } else {
      Image8 rgba = loadImage8(encoded, source, 4);
      image->width = rgba.width;
      image->height = rgba.height;
      image->bits = 8;
      image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
      image->image = std::move(rgba.pixels);
    }
    return true;
  } catch (const Error& e) {
    if (err) *err += e.what();
    return false;
  }
}

// tinygltf ends each of its messages with a newline; ours are one line.
std::string oneLine(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at)) text.replace(at, 1, "; ");
  return text;
}

// Walks a glTF's JSON without building it (nlohmann's SAX parser does not recurse) before tinygltf
// reads it: tinygltf stores indices as 32-bit ints (4294967297 would load as 1) and keeps a tree
// of ~100 bytes per value. Integers must fit in 32 bits except byte sizes, offsets and counts
// (64-bit in tinygltf) and what nobody reads: unknown extensions and extras other than ours.
class GltfJsonCheck {
 public:
  explicit GltfJsonCheck(std::string source) : m_source(std::move(source)) {}

  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(std::int64_t v) { return integer(v >= INT32_MIN && v <= INT32_MAX, std::to_string(v)); }
  bool number_unsigned(std::uint64_t v) { return integer(v <= INT32_MAX, std::to_string(v)); }
  bool number_float(double, const std::string&) { return value(); }
  bool string(std::string&) { return value(); }
  bool binary(std::vector<std::uint8_t>&) { return value(); }
  bool start_object(std::size_t) { return open(false); }
  bool start_array(std::size_t) { return open(true); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(std::string& name) {
    m_levels.back().key = name;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) { return false; }  // tinygltf says it

 private:
  struct Level {
    bool array = false;
    bool unchecked = false;  // integers below are not read by us, or read as 64-bit
    std::size_t index = 0;
    std::string key;
  };

  bool value() {
    if (++m_values > budget::kGltfJsonValues) {
      fail(m_source, ": more than ", budget::kGltfJsonValues, " JSON values (docs/RELIABILITY.md)");
    }
    if (!m_levels.empty() && m_levels.back().array) ++m_levels.back().index;
    return true;
  }
  bool integer(bool fits, const std::string& text) {
    if (!fits && !m_levels.empty() && !m_levels.back().unchecked && !wide(m_levels.back().key)) {
      fail(m_source, ": ", path(), " is ", text, ", which does not fit in 32 bits (indices and sizes in a glTF do)");
    }
    return value();
  }
  static bool wide(const std::string& key) {
    return key == "byteLength" || key == "byteOffset" || key == "byteStride" || key == "count";
  }
  bool open(bool array) {
    Level level{array, false, 0, {}};
    if (!m_levels.empty()) {
      const Level& parent = m_levels.back();
      const std::string key = parent.array ? std::string() : parent.key;
      const bool ours = key == "vtouching" || key == "MPEG_haptic_material" || key == "MPEG_haptics";
      const bool extension = m_levels.size() >= 2 && !parent.array && !m_levels[m_levels.size() - 2].array &&
                             m_levels[m_levels.size() - 2].key == "extensions";
      level.unchecked = !ours && (parent.unchecked || extension || key == "extras" || key == "min" || key == "max");
    }
    m_levels.push_back(level);
    return true;
  }
  bool close() {
    m_levels.pop_back();
    return value();  // a container counts as one value of its parent
  }
  std::string path() const {
    std::string out;
    for (const Level& level : m_levels) {
      if (level.array) out += str("[", level.index, "]");
      else if (!level.key.empty()) out += (out.empty() ? "" : ".") + level.key;
    }
    return out;
  }

  std::string m_source;
  std::vector<Level> m_levels;
  std::uint64_t m_values = 0;
};

// The JSON of a .gltf, or the JSON chunk of a .glb (empty when the header is broken: tinygltf says so).
std::string_view gltfJson(const std::string& bytes, bool binary) {
  if (!binary) return bytes;
  if (bytes.size() < 20) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  if (length > bytes.size() - 20) return {};
  return std::string_view(bytes).substr(20, length);
}

}  // namespace

void checkGltfJson(const std::string& bytes, bool binary, const std::string& source) {
  const std::string_view json = gltfJson(bytes, binary);
  checkJsonNesting(json, source, budget::kJsonDepth);
  GltfJsonCheck check(source);
  nlohmann::json::sax_parse(json, &check, nlohmann::json::input_format_t::json, false);
}

tinygltf::Model parseModel(const std::string& bytes, bool binary, const std::string& source,
                           const std::filesystem::path& baseDir, const GltfLoadOptions& options) {
  if (bytes.size() > budget::kSceneFileBytes) fail(source, ": larger than ", budget::kSceneFileBytes, " bytes");
  checkGltfJson(bytes, binary, source);
  tinygltf::TinyGLTF loader;
  FileAccess access{baseDir, options, {}};
  loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &access});
  loader.SetImageLoader(&decodeImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                       reinterpret_cast<const unsigned char*>(bytes.data()),
                                                       unsigned(bytes.size()), baseDir.string())
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                                      baseDir.string());
  // tinygltf only warns about an image it could not read; a refused file is an error either way.
  if (!access.refusal.empty()) fail(source, ": ", access.refusal);
  if (!ok) fail(source, ": not a valid glTF file (", err.empty() ? "parse error" : oneLine(err), ")");
  return model;
}

// Copies `count` elements of `components` floats from an accessor, checking every bound.
std::vector<float> AccessorReader::floats(int accessorIndex, int components, const char* what) const {
  const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
  if (acc.sparse.isSparse) fail(m_source, ": ", what, " uses a sparse accessor (not supported)");
  if (tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)) != components) {
    fail(m_source, ": ", what, " accessor has ", tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)),
         " components, expected ", components);
  }
  const int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
  const bool isFloat = acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool isNormalised = acc.normalized && (acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                               acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  if (!isFloat && !isNormalised) fail(m_source, ": ", what, " must be float or normalised unsigned data");
  const auto [data, stride] = view(acc, std::size_t(componentSize * components), what);
  std::vector<float> out(acc.count * std::size_t(components));
  for (std::size_t i = 0; i < acc.count; ++i) {
    for (int c = 0; c < components; ++c) {
      const std::uint8_t* p = data + i * stride + std::size_t(c * componentSize);
      float v = 0.0f;
      if (isFloat) std::memcpy(&v, p, 4);
      else if (componentSize == 1) v = float(*p) / 255.0f;
      else {
        std::uint16_t u = 0;
        std::memcpy(&u, p, 2);
        v = float(u) / 65535.0f;
      }
      if (!std::isfinite(v)) fail(m_source, ": ", what, " element ", i, " is NaN or infinite");
      out[i * std::size_t(components) + std::size_t(c)] = v;
    }
  }
  return out;
}

std::size_t AccessorReader::count(int accessorIndex, const char* what) const {
  const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
  const int componentSize = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
  const int components = tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
  if (componentSize <= 0 || components <= 0) fail(m_source, ": ", what, " accessor has an invalid type");
  view(acc, std::size_t(componentSize * components), what);
  return acc.count;
}

std::vector<std::uint32_t> AccessorReader::indices(int accessorIndex, std::size_t vertexCount) const {
  const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
  if (acc.sparse.isSparse || acc.type != TINYGLTF_TYPE_SCALAR) fail(m_source, ": indices must be scalars");
  const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(acc.componentType));
  if (size != 1 && size != 2 && size != 4) fail(m_source, ": indices have an invalid component type");
  const auto [data, stride] = view(acc, std::size_t(size), "indices");
  std::vector<std::uint32_t> out(acc.count);
  for (std::size_t i = 0; i < acc.count; ++i) {
    std::uint32_t v = 0;
    std::memcpy(&v, data + i * stride, std::size_t(size));  // little-endian host
    if (v >= vertexCount) fail(m_source, ": index ", v, " out of range (", vertexCount, " vertices)");
    out[i] = v;
  }
  return out;
}

std::pair<const std::uint8_t*, std::size_t> AccessorReader::view(const tinygltf::Accessor& acc, std::size_t elementSize,
                                                                const char* what) const {
  const tinygltf::BufferView& bv = element(m_model.bufferViews, acc.bufferView, "bufferView");
  const tinygltf::Buffer& buffer = element(m_model.buffers, bv.buffer, "buffer");
  const std::size_t stride = bv.byteStride ? bv.byteStride : elementSize;
  // Every bound without a product or sum that can wrap: counts near 2^64 come from files too.
  const bool viewFits = bv.byteOffset <= buffer.data.size() && bv.byteLength <= buffer.data.size() - bv.byteOffset;
  const bool firstFits = acc.byteOffset <= bv.byteLength && elementSize <= bv.byteLength - acc.byteOffset;
  const bool countFits =
      acc.count == 0 || (firstFits && acc.count - 1 <= (bv.byteLength - acc.byteOffset - elementSize) / stride);
  if (stride < elementSize || !viewFits || !countFits) {
    fail(m_source, ": ", what, " accessor (count ", acc.count, ") reads past the end of its buffer");
  }
  return {buffer.data.data() + bv.byteOffset + acc.byteOffset, stride};
}


std::vector<std::uint32_t> AccessorReader::uints(int accessorIndex, int components, const char* what) const {
  const tinygltf::Accessor& acc = element(m_model.accessors, accessorIndex, "accessor");
  if (acc.sparse.isSparse) fail(m_source, ": ", what, " uses a sparse accessor (not supported)");
  if (tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)) != components) {
    fail(m_source, ": ", what, " accessor has ", tinygltf::GetNumComponentsInType(std::uint32_t(acc.type)),
         " components, expected ", components);
  }
  const int size = acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                   : acc.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                 : 0;
  if (size == 0 || acc.normalized) fail(m_source, ": ", what, " must be unsigned byte or short integers");
  const auto [data, stride] = view(acc, std::size_t(size * components), what);
  std::vector<std::uint32_t> out(acc.count * std::size_t(components));
  for (std::size_t i = 0; i < acc.count; ++i) {
    for (int c = 0; c < components; ++c) {
      std::uint16_t v = 0;
      std::memcpy(&v, data + i * stride + std::size_t(c * size), std::size_t(size));  // little-endian host
      out[i * std::size_t(components) + std::size_t(c)] = v;
    }
  }
  return out;
}

glm::mat4 AccessorReader::localTransform(const tinygltf::Node& node) {
  glm::mat4 local(1.0f);
  if (node.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) glm::value_ptr(local)[i] = float(node.matrix[std::size_t(i)]);
  } else {
    if (node.translation.size() == 3) {
      local = glm::translate(local, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (node.rotation.size() == 4) {
      local *= glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]),
                                        float(node.rotation[2])));
    }
    if (node.scale.size() == 3) local = glm::scale(local, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return local;
}

}  // namespace vt::gltf
