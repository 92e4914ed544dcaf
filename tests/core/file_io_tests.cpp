// Outputs written whole or not at all, and input files refused with precise one-line reasons.
#include <catch2/catch.hpp>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <chrono>
#include <fstream>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"
#include "vt/core/text_input.hpp"

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
  CHECK_THROWS_WITH(vt::OutputFile(dir / "missing" / "b.txt"),
                    Catch::Contains("b.txt': cannot write: the folder '") && Catch::Contains("missing' does not exist"));
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

namespace {
// A process id no process has now (for temporaries "left by a killed run").
long deadPid() {
  for (long pid = 4000000;; --pid)
    if (!fs::exists("/proc/" + std::to_string(pid))) return pid;
}
}  // namespace

TEST_CASE("OutputFile refuses a folder or a FIFO before writing and writes a device in place") {
  const fs::path dir = vt::test::outputDir("core_output_special");
  fs::create_directory(dir / "folder.csv");
  CHECK_THROWS_WITH(vt::OutputFile(dir / "folder.csv"), Catch::Contains("folder.csv': cannot write: is a folder"));
  REQUIRE(::mkfifo((dir / "pipe.csv").c_str(), 0600) == 0);
  CHECK_THROWS_WITH(vt::OutputFile(dir / "pipe.csv"), Catch::Contains("pipe.csv': cannot write: it is a named pipe (FIFO)"));
  CHECK(fs::is_fifo(dir / "pipe.csv"));  // not replaced
  // A character device is written in place: as root a null device of our own (the system's
  // /dev/null must never be at stake), else /dev/null (which nobody else may replace anyway).
  fs::path device = "/dev/null";
  if (::geteuid() == 0 && ::mknod((dir / "null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) device = dir / "null";
  vt::OutputFile out(device);
  out.write("header and body");
  out.overwrite(0, "HEAD", 4);
  out.commit();
  struct stat st {};
  REQUIRE(::stat(device.c_str(), &st) == 0);
  CHECK(S_ISCHR(st.st_mode));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == (device == "/dev/null" ? 2 : 3));
}

TEST_CASE("Temporaries a killed run left are removed, and a folder it moved aside is put back") {
  const long dead = deadPid();
  const fs::path other = vt::test::outputDir("core_stale_temporaries");
  const auto name = [](const char* target, const char* kind, long pid) {
    return std::string(".") + target + "." + kind + "-" + std::to_string(pid) + "-0";
  };
  // Made by hand: any OutputFile here would clean the folder now, before the leftovers exist.
  const auto put = [](const fs::path& path, const char* text) { std::ofstream(path, std::ios::binary) << text; };
  put(other / name("a.csv", "tmp", dead), "half");
  put(other / name("b.csv", "tmp", ::getpid()), "in use");  // a live writer's
  fs::create_directories(other / name("obj", "staging", dead) / "x");
  fs::create_directories(other / name("ds", "old", dead));
  put(other / name("ds", "old", dead) / "one", "previous");
  put(other / name("c.csv", "tmp", dead), "a writer we cannot see, still writing");
  const auto old = fs::file_time_type::clock::now() - std::chrono::minutes(10);
  for (const char* leftover : {"a.csv", "b.csv", "obj", "ds"}) {
    for (const char* kind : {"tmp", "staging", "old"}) {
      for (const long pid : {dead, long(::getpid())})
        if (fs::exists(other / name(leftover, kind, pid))) fs::last_write_time(other / name(leftover, kind, pid), old);
    }
  }
  vt::writeFileAtomically(other / "new.csv", "n");  // the first output into the folder cleans it
  CHECK_FALSE(fs::exists(other / name("a.csv", "tmp", dead)));
  CHECK(fs::exists(other / name("b.csv", "tmp", ::getpid())));
  CHECK_FALSE(fs::exists(other / name("obj", "staging", dead)));
  CHECK(slurp(other / "ds" / "one") == "previous");  // its place was empty: put back
  CHECK_FALSE(fs::exists(other / name("ds", "old", dead)));
  CHECK(fs::exists(other / name("c.csv", "tmp", dead)));  // written just now: kept
}

TEST_CASE("Two outputs naming one file are refused before anything is written") {
  const fs::path dir = vt::test::outputDir("core_shared_outputs");
  CHECK_NOTHROW(vt::refuseSharedOutputs({{"--record-csv", dir / "a.csv"}, {"--record-wav", dir / "a.wav"}, {"--record", ""}}));
  CHECK_THROWS_WITH(vt::refuseSharedOutputs({{"--record-csv", dir / "x"}, {"--record-wav", dir / "sub" / ".." / "x"}}),
                    Catch::Contains("--record-csv and --record-wav both name"));
  vt::writeFileAtomically(dir / "real", "r");
  fs::create_symlink("real", dir / "link");
  CHECK_THROWS_WITH(vt::refuseSharedOutputs({{"--video", dir / "real"}, {"--record", dir / "link"}}),
                    Catch::Contains("--video and --record both name"));
  CHECK_NOTHROW(vt::refuseSharedOutputs({{"--record-csv", "/dev/null"}, {"--record-wav", "/dev/null"}}));
}

TEST_CASE("Text inputs with a byte-order mark, UTF-16 or deep JSON nesting are refused as such") {
  CHECK_NOTHROW(vt::checkTextEncoding("name,gain\nplate,1\n", "gains"));
  CHECK_THROWS_WITH(vt::checkTextEncoding("\xEF\xBB\xBFname,gain", "gains"), Catch::Contains("gains: starts with a UTF-8 byte-order mark"));
  CHECK_THROWS_WITH(vt::checkTextEncoding(std::string("\xFF\xFEn\0a\0", 6), "key"), Catch::Contains("key: is UTF-16 text"));
  CHECK_THROWS_WITH(vt::checkTextEncoding(std::string("n\0a\0", 4), "key"), Catch::Contains("NUL bytes"));
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  CHECK_THROWS_WITH(vt::checkJsonNesting(deep, "x.gltf", 64), Catch::Contains("x.gltf: JSON nested deeper than 64 levels at byte 64"));
  CHECK_NOTHROW(vt::checkJsonNesting(std::string(64, '[') + std::string(64, ']'), "x", 64));
  CHECK_NOTHROW(vt::checkJsonNesting(R"({"a": "[[[[[[[[\"[[[[[[", "b": [1, {"c": 2}]})", "x", 3));  // brackets in strings
}

TEST_CASE("An allocation failure names what was being loaded") {
  CHECK_THROWS_AS(([] {
                    const vt::LoadScope outer("glTF 'big.gltf'");
                    const vt::LoadScope inner("image 'photo.png'");
                    throw std::bad_alloc();
                  })(),
                  std::bad_alloc);
  CHECK(vt::failedLoad() == "image 'photo.png'");  // the innermost
  { const vt::LoadScope next("trajectory 't.csv'"); }
  CHECK(vt::failedLoad().empty());  // a new load that went well forgets it
}
