// Outputs written whole or not at all, and input files refused with precise one-line reasons.
#include <catch2/catch.hpp>

#include <fstream>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"

namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
}  // namespace

TEST_CASE("OutputFile replaces its target only on commit and leaves no temporary behind") {
  const fs::path dir = vt::test::outputDir("core_output_file");
  vt::writeFileAtomically(dir / "a.txt", "old");
  {
    vt::OutputFile file(dir / "a.txt");
    file.write(std::string(200000, 'x'));  // past the buffer: written through
    CHECK(slurp(dir / "a.txt") == "old");  // not yet committed
  }  // abandoned (an exception on the way out, say): the old file stays
  CHECK(slurp(dir / "a.txt") == "old");
  vt::OutputFile file(dir / "a.txt");
  file.write("new ");
  file.write(std::string(70000, 'y'));
  file.commit();
  CHECK(slurp(dir / "a.txt").size() == 70004);
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  CHECK_THROWS_WITH(vt::OutputFile(dir / "missing" / "b.txt"), Catch::Contains("b.txt': cannot write: file not found"));
}

TEST_CASE("OutputFile::overwrite patches bytes already written, buffered ones included") {
  const fs::path dir = vt::test::outputDir("core_output_overwrite");
  vt::OutputFile file(dir / "h.bin");
  file.write("HEAD");
  file.write("body");  // still in the buffer: overwrite flushes it first
  file.overwrite(0, "head", 4);
  file.write("tail");
  file.overwrite(4, "BO", 2);
  file.commit();
  CHECK(slurp(dir / "h.bin") == "headBOdytail");
  CHECK_THROWS_WITH(file.overwrite(0, "x", 1), Catch::Contains("h.bin': write after commit"));
}

TEST_CASE("writeFiles refuses a set when any file exists, unless asked to replace") {
  const fs::path dir = vt::test::outputDir("core_write_files");
  vt::writeFileAtomically(dir / "s.bin", "old bin");
  const std::vector<vt::FileContent> set{{dir / "s.gltf", "new gltf"}, {dir / "s.bin", "new bin"}};
  CHECK_THROWS_WITH(vt::writeFiles(set, false), Catch::Contains("s.bin' already exists (use --force"));
  CHECK_FALSE(fs::exists(dir / "s.gltf"));  // nothing of the set was written
  vt::writeFiles(set, true);
  CHECK(slurp(dir / "s.gltf") == "new gltf");
  CHECK(slurp(dir / "s.bin") == "new bin");
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 2);
}

TEST_CASE("StagedFolder refuses an existing folder unless asked, and replaces it whole") {
  const fs::path root = vt::test::outputDir("core_staged_folder");
  {
    vt::StagedFolder staged(root / "obj", false);
    vt::writeFileAtomically(staged.dir() / "one", "1");
    vt::writeFileAtomically(staged.dir() / "stale", "s");
    staged.commit();
  }
  CHECK_THROWS_WITH(vt::StagedFolder(root / "obj", false), Catch::Contains("obj' already exists (use --force"));
  {
    vt::StagedFolder staged(root / "obj", true);
    vt::writeFileAtomically(staged.dir() / "one", "2");
    // Not committed: the previous folder must be untouched and the staging folder gone.
  }
  CHECK(slurp(root / "obj" / "one") == "1");
  {
    vt::StagedFolder staged(root / "obj", true);
    vt::writeFileAtomically(staged.dir() / "one", "2");
    staged.commit();
  }
  CHECK(slurp(root / "obj" / "one") == "2");
  CHECK_FALSE(fs::exists(root / "obj" / "stale"));  // replaced whole: no stale files survive
  CHECK(std::distance(fs::directory_iterator(root), fs::directory_iterator()) == 1);
  {
    vt::StagedFolder staged(root.string() + "/slash/", false);  // a trailing separator names the same folder
    vt::writeFileAtomically(staged.dir() / "one", "3");
    staged.commit();
  }
  CHECK(slurp(root / "slash" / "one") == "3");
  fs::create_directory(root / "empty");
  CHECK_NOTHROW(vt::refuseExisting(root / "empty", false));  // an empty folder holds nothing to lose
}

TEST_CASE("readInputFile names folders, symlink loops, missing files and the size budget") {
  const fs::path dir = vt::test::outputDir("core_read_input");
  vt::writeFileAtomically(dir / "ok.txt", "12345");
  CHECK(vt::readInputFile(dir / "ok.txt", "text", 100) == "12345");
  CHECK_THROWS_WITH(vt::readInputFile(dir / "ok.txt", "text", 4), Catch::Contains("5 bytes is over the limit of 4 bytes"));
  fs::create_directory(dir / "folder.json");
  CHECK_THROWS_WITH(vt::readInputFile(dir / "folder.json", "text", 100), Catch::Contains("folder.json': is a folder, expected a file"));
  fs::create_symlink("loop", dir / "loop");
  CHECK_THROWS_WITH(vt::readInputFile(dir / "loop", "text", 100), Catch::Contains("symlink loop"));
  fs::create_symlink("nowhere", dir / "dangling");
  CHECK_THROWS_WITH(vt::readInputFile(dir / "dangling", "text", 100), Catch::Contains("broken symbolic link"));
  CHECK_THROWS_WITH(vt::readInputFile(dir / "absent", "text", 100), Catch::Contains("absent': file not found"));
}
