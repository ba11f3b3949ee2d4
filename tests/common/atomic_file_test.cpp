#include "ccbuild/common/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <algorithm>

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

/// The entries of a folder, by name (temporary files would show here).
std::vector<std::string> entries_of(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST_F(AtomicFile, ADeviceIsNeverAnOutput) {
  for (const char* device : {"/dev/null", "/dev/full", "/dev/zero"}) {
    OutputClaims outputs;
    const InputError e =
        testing::expect_input_error([&] { outputs.claim_file("-o", device, true); });
    EXPECT_TRUE(testing::contains(e.what(), "character device")) << device;
  }
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST_F(AtomicFile, AFileThisProcessReadIsAnInputWithoutBeingNamed) {
  const fs::path read = dir_ / "site.yaml";
  std::ofstream(read) << "start: 2027-03-01 07:00\n";
  OutputClaims before;  // claimed before the file is read: refused when committed
  before.claim_file("--report", read, true);
  before.write(read, "replaced");
  EXPECT_EQ(read_text_file(read), "start: 2027-03-01 07:00\n");
  const InputError late = testing::expect_input_error([&] { before.commit(); });
  EXPECT_TRUE(testing::contains(late.what(), "input file"));
  OutputClaims after;
  const InputError e =
      testing::expect_input_error([&] { after.claim_file("-o", dir_ / "x/../site.yaml", true); });
  EXPECT_TRUE(testing::contains(e.what(), "input file"));
  EXPECT_EQ(read_text_file(read), "start: 2027-03-01 07:00\n");
  EXPECT_EQ(entries_of(dir_), std::vector<std::string>{"site.yaml"});
}

TEST_F(AtomicFile, AnInputAddedAfterAClaimIsRefused) {
  OutputClaims outputs;
  outputs.claim_file("--output", dir_ / "report.html", false);
  const InputError e =
      testing::expect_input_error([&] { outputs.add_input(dir_ / "report.html"); });
  EXPECT_TRUE(testing::contains(e.what(), "--output"));
}

TEST_F(AtomicFile, AllOutputsOfARunOrNone) {
  // (read with slurp: a file read through read_text_file is an input of this process)
  const fs::path first = dir_ / "schedule.json", other = dir_ / "sub", second = other / "r.html";
  fs::create_directories(other);
  std::ofstream(first) << "old";
  {
    OutputClaims outputs;
    outputs.claim_file("-o", first, true);
    outputs.claim_file("--report", second, false);
    outputs.write(first, "new");
    outputs.write(second, "page");
    fs::remove_all(other);  // the second cannot be put in place
    const InputError e = testing::expect_input_error([&] { outputs.commit(); });
    EXPECT_TRUE(testing::contains(e.what(), "no output of this run was written"));
  }
  EXPECT_EQ(testing::slurp(first), "old");  // put back as it was
  EXPECT_EQ(entries_of(dir_), std::vector<std::string>{"schedule.json"});
  {
    OutputClaims outputs;  // a run that stops before committing leaves nothing
    outputs.claim_file("--svg", dir_ / "plan.svg", false);
    outputs.write(dir_ / "plan.svg", "<svg/>");
  }
  EXPECT_EQ(entries_of(dir_), std::vector<std::string>{"schedule.json"});
  fs::create_directories(other);
  OutputClaims outputs;
  outputs.claim_file("-o", first, true);
  outputs.claim_file("--report", second, false);
  outputs.write(first, "new");
  outputs.write(second, "page");
  outputs.commit();
  EXPECT_EQ(testing::slurp(first), "new");
  EXPECT_EQ(testing::slurp(second), "page");
  EXPECT_EQ(entries_of(dir_), (std::vector<std::string>{"schedule.json", "sub"}));
}

TEST_F(AtomicFile, AWriteErrorNamesThePathAndLeavesNothing) {
  // A file-size limit makes the write fail as a full disk would.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit small{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &small);
    OutputClaims outputs;
    outputs.claim_file("-o", dir_ / "big.json", false);
    try {
      outputs.write(dir_ / "big.json", std::string(100000, 'x'));
    } catch (const InputError& e) {
      const std::string text = e.what();
      ::_exit(text.find("big.json") != std::string::npos &&
                      text.find("cannot write output file") != std::string::npos
                  ? 0
                  : 1);
    }
    ::_exit(2);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(entries_of(dir_).empty());
}

TEST_F(AtomicFile, ADerivedNameReplacesOnlyTheFileWrittenBesideTheSameOutput) {
  const fs::path urdf = dir_ / "fitted.urdf";
  const std::string mark = "<!-- ccbuild fit: the URDF of fitted.yaml -->";
  std::ofstream(urdf) << "<?xml version=\"1.0\"?>\n<robot name=\"someone's\"/>\n";
  OutputClaims outputs;
  const InputError e = testing::expect_input_error(
      [&] { outputs.claim_derived("-o (its URDF)", urdf, dir_ / "fitted.yaml", true, mark); });
  EXPECT_TRUE(testing::contains(e.what(), "is not the file ccbuild wrote beside"));
  std::ofstream(urdf) << "<?xml version=\"1.0\"?>\n" << mark << "\n<robot/>\n";
  OutputClaims without_force;
  const InputError exists = testing::expect_input_error([&] {
    without_force.claim_derived("-o (its URDF)", urdf, dir_ / "fitted.yaml", false, mark);
  });
  EXPECT_TRUE(testing::contains(exists.what(), "--force"));
  OutputClaims again;
  again.claim_derived("-o (its URDF)", urdf, dir_ / "fitted.yaml", true, mark);
  again.write(urdf, "new");
  again.commit();
  EXPECT_EQ(testing::slurp(urdf), "new");
}

}  // namespace
}  // namespace ccbuild
