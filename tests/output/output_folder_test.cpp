// The output folder of a run: one run at a time, no mixing with an earlier run's results, and
// the temporaries of killed runs swept away.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "rktsph/core/error.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/output_folder.hpp"

namespace rktsph::output_folder_test {
namespace {

namespace fs = std::filesystem;

std::string read_whole_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

class OutputFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("rktsph_folder_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    run_ = root_ / "run";
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }

  // The files of a finished run with `fields` field files.
  void plant_results(int fields) {
    fs::create_directories(run_ / "fields");
    for (const char* name : {"summary.json", "case.yaml", "series.pvd", "probes.csv", "run.log"})
      std::ofstream(run_ / name) << "old\n";
    for (int i = 0; i < fields; ++i) {
      char name[32];
      std::snprintf(name, sizeof name, "fields_%06d.vtu", i);
      std::ofstream(run_ / "fields" / name) << "old\n";
    }
  }

  fs::path root_;
  fs::path run_;
};

TEST_F(OutputFolderTest, CreatesTheFolderAndHoldsItsLock) {
  {
    const OutputFolder folder(run_, ExistingResults::Refuse);
    EXPECT_TRUE(fs::is_directory(run_));
    EXPECT_EQ(read_whole_file(run_ / kOutputLockName), std::to_string(::getpid()) + "\n");
  }
  // Released with the folder: the next run takes it.
  EXPECT_NO_THROW(OutputFolder(run_, ExistingResults::Refuse));
}

TEST_F(OutputFolderTest, ASecondRunIntoAFolderInUseFailsAtOnceNamingItAndTheHolder) {
  const OutputFolder first(run_, ExistingResults::Refuse);
  try {
    const OutputFolder second(run_, ExistingResults::Refuse);
    FAIL() << "expected RunError";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'" + run_.string() + "' is in use"), std::string::npos) << message;
    EXPECT_NE(message.find("pid " + std::to_string(::getpid())), std::string::npos) << message;
  }
}

TEST_F(OutputFolderTest, TheLockOfAnotherProcessIsSeenToo) {
  fs::create_directories(run_);
  const int descriptor = ::open((run_ / kOutputLockName).c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(descriptor, 0);
  ASSERT_EQ(::flock(descriptor, LOCK_EX), 0);
  EXPECT_THROW(OutputFolder(run_, ExistingResults::Overwrite), RunError);
  ::close(descriptor);
  EXPECT_NO_THROW(OutputFolder(run_, ExistingResults::Refuse));
}

TEST_F(OutputFolderTest, EarlierResultsAreRefusedAndListed) {
  plant_results(172);
  try {
    const OutputFolder folder(run_, ExistingResults::Refuse);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(run_.string()), std::string::npos) << message;
    EXPECT_NE(message.find("summary.json"), std::string::npos) << message;
    EXPECT_NE(message.find("172 field files"), std::string::npos) << message;
    EXPECT_NE(message.find("--overwrite"), std::string::npos) << message;
  }
  EXPECT_EQ(run_result_files(run_).size(), 5u + 172u);  // nothing removed
}

TEST_F(OutputFolderTest, OverwriteRemovesOnlyTheEarlierRunsOwnFiles) {
  plant_results(172);
  std::ofstream(run_ / "notes.txt") << "mine\n";
  std::ofstream(run_ / "fields" / "picture.png") << "mine\n";
  std::ofstream(run_ / "plot.vtu") << "mine\n";
  const OutputFolder folder(run_, ExistingResults::Overwrite);
  EXPECT_EQ(folder.removed_results(), 5u + 172u);
  EXPECT_TRUE(run_result_files(run_).empty());
  EXPECT_EQ(read_whole_file(run_ / "notes.txt"), "mine\n");
  EXPECT_EQ(read_whole_file(run_ / "fields" / "picture.png"), "mine\n");
  EXPECT_EQ(read_whole_file(run_ / "plot.vtu"), "mine\n");
}

TEST_F(OutputFolderTest, ContinueKeepsTheResults) {
  plant_results(3);
  const OutputFolder folder(run_, ExistingResults::Continue);
  EXPECT_EQ(run_result_files(run_).size(), 5u + 3u);
}

TEST_F(OutputFolderTest, TemporariesOfKilledRunsAreRemovedAndLinksNotFollowed) {
  fs::create_directories(run_ / "fields");
  std::ofstream(run_ / "summary.json.tmp-99999") << "partial";
  std::ofstream(run_ / "fields" / "fields_000004.vtu.tmp-99999") << "partial";
  std::ofstream(run_ / "probes.csv.tmp-99999-2") << "partial";
  const fs::path victim = root_ / "victim.txt";
  std::ofstream(victim) << "precious\n";
  fs::create_symlink(victim, run_ / "case.yaml.tmp-99999");
  std::ofstream(run_ / "notes.tmp-draft") << "mine\n";  // not a name rktsph gives
  const OutputFolder folder(run_, ExistingResults::Refuse);
  EXPECT_EQ(folder.removed_temporaries(), 4u);
  for (const auto& entry : fs::recursive_directory_iterator(run_))
    EXPECT_FALSE(is_temporary_file_name(entry.path().filename().string())) << entry.path();
  EXPECT_EQ(read_whole_file(victim), "precious\n");
  EXPECT_TRUE(fs::exists(run_ / "notes.tmp-draft"));
}

TEST_F(OutputFolderTest, AFolderThatCannotBeCreatedIsBadInputNamingTheSystemReason) {
  const fs::path impossible = "/dev/null/run";
  try {
    const OutputFolder folder(impossible, ExistingResults::Refuse);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'/dev/null/run'"), std::string::npos) << message;
    EXPECT_NE(message.find("Not a directory"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace rktsph::output_folder_test
