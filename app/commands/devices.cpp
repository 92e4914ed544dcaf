// `vtouching devices`: what this machine offers V-Touching: Avatar-style gloves (hidapi), audio
// playback devices for --output audio (ALSA), the active OpenXR runtime (its manifest only; the
// runtime is not loaded) and the Vulkan devices.
#include <vulkan/vulkan.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/devices/audio_output.hpp"
#include "vt/haptics/devices/glove_protocol.hpp"
#include "vt/haptics/devices/hid_transport.hpp"

namespace {

namespace glove = vt::haptics::glove;
using nlohmann::json;

std::uint16_t parseHex16(const std::string& option, const std::string& text) {
  std::string_view digits = text;
  if (digits.rfind("0x", 0) == 0 || digits.rfind("0X", 0) == 0) digits.remove_prefix(2);
  std::uint16_t value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value, 16);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
    vt::fail("devices: option --", option, " expects a 16-bit hex id like 1209, got '", text, "'");
  }
  return value;
}

std::string hex4(std::uint16_t v) {
  char text[8];
  std::snprintf(text, sizeof text, "%04x", v);
  return text;
}

// Each glove, with its device-info report when the device can be opened (permissions allowing).
json listGloves(std::uint16_t vendorId, std::uint16_t productId) {
  json out = {{"vid", hex4(vendorId)}, {"pid", hex4(productId)}, {"devices", json::array()}};
  try {
    auto backend = glove::makeHidapiBackend();
    for (const auto& d : backend->enumerate(vendorId, productId)) {
      json entry = {{"path", d.path}, {"serial", d.serial}, {"manufacturer", d.manufacturer}, {"product", d.product}};
      std::string error;
      if (auto device = backend->open(d.path, error)) {
        glove::Report report{};
        report[0] = glove::kDeviceInfoReportId;
        glove::DeviceInfo info;
        const int n = device->getFeature(report);
        const glove::ReportError e =
            n < 0 ? glove::ReportError::TooShort : glove::decode(std::span(report.data(), std::size_t(n)), info);
        if (n < 0) {
          entry["info_error"] = "feature report: " + device->lastError();
        } else if (e != glove::ReportError::None) {
          entry["info_error"] = std::string("device-info report rejected: ") + std::string(glove::reportErrorName(e));
        } else {
          json layout = json::array();
          for (int i = 0; i < info.actuatorCount; ++i) {
            layout.push_back(std::string(vt::haptics::actuatorName(vt::haptics::ActuatorId(info.layout[std::size_t(i)]))));
          }
          entry["protocol_version"] = info.protocolVersion;
          entry["actuators"] = layout;
          entry["max_update_rate_hz"] = info.maxUpdateRate_hz;
          entry["keep_alive_ms"] = info.keepAliveTimeout_ms;
          entry["firmware_version"] = info.firmwareVersion;
          entry["device_serial"] = std::string(info.serial.data());
        }
      } else {
        entry["info_error"] = error;
      }
      out["devices"].push_back(entry);
    }
  } catch (const vt::Error& e) {
    out["error"] = e.what();
  }
  return out;
}

// The OpenXR loader's search order on Linux for the active runtime manifest.
std::vector<std::filesystem::path> runtimeCandidates() {
  std::vector<std::filesystem::path> dirs;
  if (const char* home = std::getenv("XDG_CONFIG_HOME"); home && *home) {
    dirs.emplace_back(home);
  } else if (const char* userHome = std::getenv("HOME"); userHome && *userHome) {
    dirs.emplace_back(std::filesystem::path(userHome) / ".config");
  }
  const char* configDirs = std::getenv("XDG_CONFIG_DIRS");
  std::string list = configDirs && *configDirs ? configDirs : "/etc/xdg";
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t colon = std::min(list.find(':', start), list.size());
    if (colon > start) dirs.emplace_back(list.substr(start, colon - start));
    start = colon + 1;
  }
  dirs.emplace_back("/etc");
  std::vector<std::filesystem::path> out;
  for (const auto& dir : dirs) {
    out.push_back(dir / "openxr/1/active_runtime.x86_64.json");  // architecture-specific first
    out.push_back(dir / "openxr/1/active_runtime.json");
  }
  return out;
}

json findOpenXrRuntime() {
  std::filesystem::path manifest;
  std::string source;
  std::vector<std::string> searched;
  if (const char* env = std::getenv("XR_RUNTIME_JSON"); env && *env) {
    manifest = env;
    source = "XR_RUNTIME_JSON";
  } else {
    for (const auto& candidate : runtimeCandidates()) {
      searched.push_back(candidate.string());
      std::error_code ec;
      if (std::filesystem::exists(candidate, ec)) {
        manifest = candidate;
        source = "active_runtime.json";
        break;
      }
    }
  }
  if (manifest.empty()) return {{"found", false}, {"searched", searched}};
  json out = {{"found", true}, {"manifest", manifest.string()}, {"source", source}};
  std::ifstream in(manifest);
  if (!in) {
    out["error"] = "cannot read the manifest";
    return out;
  }
  const json parsed = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded() || !parsed.contains("runtime") || !parsed["runtime"].is_object()) {
    out["error"] = "not an OpenXR runtime manifest (no \"runtime\" object)";
    return out;
  }
  const json& runtime = parsed["runtime"];
  out["name"] = runtime.value("name", "");
  out["library_path"] = runtime.value("library_path", "");
  return out;
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

json listVulkanDevices() {
  json out = {{"devices", json::array()}};
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vtouching devices";
  app.apiVersion = VK_API_VERSION_1_0;
  VkInstanceCreateInfo create{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  create.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  if (const VkResult r = vkCreateInstance(&create, nullptr, &instance); r != VK_SUCCESS) {
    out["error"] = vt::str("vkCreateInstance failed (VkResult ", int(r), ")");
    return out;
  }
  std::uint32_t count = 0;
  VkResult r = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  if (r == VK_SUCCESS) r = vkEnumeratePhysicalDevices(instance, &count, devices.data());
  if (r != VK_SUCCESS && r != VK_INCOMPLETE) {
    out["error"] = vt::str("vkEnumeratePhysicalDevices failed (VkResult ", int(r), ")");
  }
  devices.resize(count);
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties p{};
    vkGetPhysicalDeviceProperties(device, &p);
    out["devices"].push_back({{"name", p.deviceName},
                              {"type", deviceTypeName(p.deviceType)},
                              {"api_version", vt::str(VK_API_VERSION_MAJOR(p.apiVersion), '.',
                                                      VK_API_VERSION_MINOR(p.apiVersion), '.',
                                                      VK_API_VERSION_PATCH(p.apiVersion))},
                              {"vendor_id", hex4(std::uint16_t(p.vendorID))},
                              {"device_id", hex4(std::uint16_t(p.deviceID))}});
  }
  vkDestroyInstance(instance, nullptr);
  return out;
}

void printText(const json& report) {
  const json& gloves = report["gloves"];
  std::printf("Gloves (hidapi, %s:%s):\n", gloves["vid"].get<std::string>().c_str(), gloves["pid"].get<std::string>().c_str());
  if (gloves.contains("error")) std::printf("  hidapi unavailable: %s\n", gloves["error"].get<std::string>().c_str());
  if (gloves["devices"].empty()) std::printf("  none found\n");
  for (const auto& g : gloves["devices"]) {
    std::printf("  %s  serial %s  %s %s\n", g["path"].get<std::string>().c_str(), g["serial"].get<std::string>().c_str(),
                g["manufacturer"].get<std::string>().c_str(), g["product"].get<std::string>().c_str());
    if (g.contains("info_error")) {
      std::printf("    (no device info: %s)\n", g["info_error"].get<std::string>().c_str());
    } else {
      std::printf("    protocol %d, %zu actuators, up to %d Hz, keep-alive %d ms\n", g["protocol_version"].get<int>(),
                  g["actuators"].size(), g["max_update_rate_hz"].get<int>(), g["keep_alive_ms"].get<int>());
    }
  }
  std::printf("Audio outputs (ALSA; --output audio:NAME):\n");
  if (report["audio"].empty()) std::printf("  none\n");
  for (const auto& a : report["audio"])
    std::printf("  %s  %s\n", a["name"].get<std::string>().c_str(), a["description"].get<std::string>().c_str());
  const json& xr = report["openxr"];
  std::printf("OpenXR runtime:\n");
  if (!xr["found"].get<bool>()) {
    std::printf("  none (set XR_RUNTIME_JSON or install an active_runtime.json)\n");
  } else {
    std::printf("  %s  %s (from %s)\n", xr.value("name", "?").c_str(), xr["manifest"].get<std::string>().c_str(),
                xr["source"].get<std::string>().c_str());
    if (xr.contains("error")) std::printf("    %s\n", xr["error"].get<std::string>().c_str());
  }
  const json& vk = report["vulkan"];
  std::printf("Vulkan devices:\n");
  if (vk.contains("error")) std::printf("  %s\n", vk["error"].get<std::string>().c_str());
  if (vk["devices"].empty()) std::printf("  none\n");
  int index = 0;
  for (const auto& d : vk["devices"]) {
    std::printf("  %d: %s (%s, Vulkan %s)\n", index++, d["name"].get<std::string>().c_str(),
                d["type"].get<std::string>().c_str(), d["api_version"].get<std::string>().c_str());
  }
}

}  // namespace

VT_COMMAND(devices) {
  const bool asJson = args.flag("json");
  const auto vid = args.value("vid");
  const auto pid = args.value("pid");
  args.finish();
  const std::uint16_t vendorId = vid ? parseHex16("vid", *vid) : glove::kDefaultVendorId;
  const std::uint16_t productId = pid ? parseHex16("pid", *pid) : glove::kDefaultProductId;
  json audio = json::array();
  for (const auto& d : vt::haptics::listAudioDevices()) audio.push_back({{"name", d.name}, {"description", d.description}});
  const json report = {{"gloves", listGloves(vendorId, productId)},
                       {"audio", audio},
                       {"openxr", findOpenXrRuntime()},
                       {"vulkan", listVulkanDevices()}};
  if (asJson) {
    std::printf("%s\n", report.dump(2).c_str());
  } else {
    printText(report);
  }
  return 0;
}
