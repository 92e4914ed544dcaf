#pragma once
// A JSON file read and written whole: the glTF tests edit what the writers wrote.
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

inline nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline void writeJson(const std::filesystem::path& path, const nlohmann::json& doc) { std::ofstream(path) << doc.dump(1); }
