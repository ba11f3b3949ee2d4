#include "ccbuild/common/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "ccbuild/common/document.hpp"
#include "test_support.hpp"

namespace ccbuild {
namespace {
namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ccbuild_atomic_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AtomicFile, WritesWholeFileAndLeavesNoTemporary) {
  const fs::path out = dir_ / "out.json";
  write_file_atomically(out, "{\"a\": 1}\n", false);
  EXPECT_EQ(read_text_file(out), "{\"a\": 1}\n");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(AtomicFile, RefusesToOverwriteWithoutBeingAsked) {
  const fs::path out = dir_ / "out.svg";
  std::ofstream(out) << "precious";
  const InputError e =
      testing::expect_input_error([&] { write_file_atomically(out, "new", false); });
  EXPECT_TRUE(testing::contains(e.what(), "--force"));
  EXPECT_EQ(read_text_file(out), "precious");
  write_file_atomically(out, "new", true);
  EXPECT_EQ(read_text_file(out), "new");
}

TEST_F(AtomicFile, NeverOverwritesAnInput) {
  const fs::path input = dir_ / "plan.yaml";
  std::ofstream(input) << "walls: []";
  const InputError e =
      testing::expect_input_error([&] { write_file_atomically(input, "x", true, {input}); });
  EXPECT_TRUE(testing::contains(e.what(), "input"));
  EXPECT_EQ(read_text_file(input), "walls: []");
}

TEST_F(AtomicFile, MissingFolderIsAnInputError) {
  const InputError e = testing::expect_input_error(
      [&] { write_file_atomically(dir_ / "no" / "such" / "x.svg", "x", false); });
  EXPECT_TRUE(testing::contains(e.what(), "does not exist"));
}

}  // namespace
}  // namespace ccbuild
