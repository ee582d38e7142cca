// Files written atomically (DESIGN §8: temporary file + rename). Test problem: a fresh folder
// under the test's temporary directory. Known answers, from the contract in atomic_file.h:
//  - after write_file_atomically the file holds exactly the new contents (a shorter rewrite leaves
//    no tail of the old one) and the folder holds nothing else;
//  - missing folders on the way are made;
//  - a writer that throws leaves the old file as it was, no temporary, and its exception reaches
//    the caller unchanged;
//  - a target that cannot be written (its folder is a regular file; the target is a folder)
//    throws InputError whose file is the target's path, and leaves no temporary;
//  - the temporary sits in the target's folder, is not the target, keeps its extension and
//    carries the process id.
#include "atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "input_error.h"

namespace fibrecheck {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(::testing::TempDir()) /
              ("atomic_file_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_;
};

TEST_F(AtomicFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const std::string path = (folder_ / "result.json").string();
  write_file_atomically(path, "a long first version of the file\n");
  EXPECT_EQ(read(path), "a long first version of the file\n");
  write_file_atomically(path, "short");
  EXPECT_EQ(read(path), "short");
  write_file_atomically(path, "");
  EXPECT_EQ(read(path), "");
  EXPECT_EQ(names_in(folder_), (std::vector<std::string>{"result.json"}));
  // Binary contents pass unchanged (no newline translation, embedded NUL kept).
  const std::string binary("a\0b\r\n\xff", 6);
  write_file_atomically(path, binary);
  EXPECT_EQ(read(path), binary);
}

TEST_F(AtomicFile, AStaleTemporaryOfAnEarlierRunIsOverwrittenNotAppendedTo) {
  // A run killed while writing left its temporary behind; a later run with the same process id
  // (containers reuse them) must not append to it.
  const std::string path = (folder_ / "result.json").string();
  std::string temporary;
  write_atomically(path, [&](const std::string& t) {
    temporary = t;
    std::ofstream(t) << "first";
  });
  std::ofstream(temporary) << "left over from a killed run, longer than the new contents";
  write_file_atomically(path, "second");
  EXPECT_EQ(read(path), "second");
  EXPECT_FALSE(fs::exists(temporary));
}

TEST_F(AtomicFile, MakesMissingFolders) {
  const fs::path path = folder_ / "deep" / "er" / "out.csv";
  write_file_atomically(path.string(), "x,y\n1,2\n");
  EXPECT_EQ(read(path), "x,y\n1,2\n");
  EXPECT_EQ(names_in(path.parent_path()), (std::vector<std::string>{"out.csv"}));
}

TEST_F(AtomicFile, ThrowingWriterLeavesTheTargetAndNoTemporary) {
  const std::string path = (folder_ / "result.json").string();
  write_file_atomically(path, "old");
  struct Interrupted : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  std::string seen;
  try {
    write_atomically(path, [&](const std::string& temporary) {
      seen = temporary;
      std::ofstream(temporary) << "half a fi";  // written, then interrupted
      throw Interrupted("stopped");
    });
    FAIL() << "the writer's exception did not pass through";
  } catch (const Interrupted& e) {
    EXPECT_STREQ(e.what(), "stopped");
  }
  EXPECT_FALSE(seen.empty());
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_EQ(read(path), "old");
  EXPECT_EQ(names_in(folder_), (std::vector<std::string>{"result.json"}));
  // Without an old file, nothing at all is left.
  const std::string fresh = (folder_ / "fresh.json").string();
  EXPECT_THROW(write_atomically(fresh, [](const std::string&) { throw 42; }), int);
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_EQ(names_in(folder_), (std::vector<std::string>{"result.json"}));
}

TEST_F(AtomicFile, WriterThatWritesNothingLeavesNoTemporaryEither) {
  // A writer that throws before creating the temporary: removing it must not fail.
  const std::string path = (folder_ / "r.vtk").string();
  EXPECT_THROW(write_atomically(path, [](const std::string&) { throw std::logic_error("no"); }),
               std::logic_error);
  EXPECT_TRUE(names_in(folder_).empty());
}

TEST_F(AtomicFile, UnwritableTargetIsAnInputErrorNamingThePath) {
  // The folder of the target is a regular file.
  const fs::path blocker = folder_ / "not_a_folder";
  std::ofstream(blocker) << "I am a file";
  const std::string under_file = (blocker / "result.json").string();
  try {
    write_file_atomically(under_file, "x");
    FAIL() << "no error for " << under_file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), under_file);
    EXPECT_NE(std::string(e.what()).find(under_file), std::string::npos) << e.what();
  }
  EXPECT_EQ(read(blocker), "I am a file");
  // The target is a folder: the temporary is written, the rename fails, the temporary goes.
  const fs::path folder_target = folder_ / "taken.json";
  fs::create_directories(folder_target);
  try {
    write_file_atomically(folder_target.string(), "x");
    FAIL() << "no error for " << folder_target;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), folder_target.string());
    EXPECT_NE(std::string(e.what()).find(folder_target.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_directory(folder_target));
  EXPECT_EQ(names_in(folder_), (std::vector<std::string>{"not_a_folder", "taken.json"}));
}

TEST_F(AtomicFile, TemporaryKeepsTheExtensionAndSitsBesideTheTarget) {
  for (const std::string name : {"result.json", "fibres.vtk", "table.tar.gz"}) {
    const fs::path target = folder_ / name;
    std::string temporary;
    bool existed_during_write = true;
    write_atomically(target.string(), [&](const std::string& t) {
      temporary = t;
      existed_during_write = fs::exists(target);
      std::ofstream(t) << name;
    });
    const fs::path tmp(temporary);
    EXPECT_EQ(tmp.parent_path(), target.parent_path()) << temporary;
    EXPECT_NE(tmp.filename(), target.filename()) << temporary;
    EXPECT_EQ(tmp.extension(), target.extension()) << temporary;
    EXPECT_NE(tmp.filename().string().find(std::to_string(getpid())), std::string::npos)
        << temporary;
    EXPECT_FALSE(existed_during_write) << name;  // the target appears only at the rename
    EXPECT_FALSE(fs::exists(tmp)) << temporary;
    EXPECT_EQ(read(target), name);
  }
}

TEST_F(AtomicFile, TemporaryOfATargetWithoutExtensionHasNoExtension) {
  // "noextension" has none; a writer that chooses its format by the extension (gmsh::write in
  // meshes/fibre_mesh.cc) must see none on the temporary either.
  const fs::path target = folder_ / "noextension";
  std::string temporary;
  write_atomically(target.string(), [&](const std::string& t) {
    temporary = t;
    std::ofstream(t) << "x";
  });
  EXPECT_EQ(fs::path(temporary).extension(), "") << temporary;
  EXPECT_EQ(read(target), "x");
}

TEST(AtomicFileFolder, CreateParentFolderAcceptsABareFileNameAndExistingFolders) {
  EXPECT_NO_THROW(create_parent_folder("just_a_name.json"));
  EXPECT_NO_THROW(create_parent_folder(::testing::TempDir() + "x.json"));
}

}  // namespace
}  // namespace fibrecheck
