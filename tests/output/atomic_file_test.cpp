#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rktsph/core/error.hpp"
#include "rktsph/output/atomic_file.hpp"

namespace rktsph {
namespace {

namespace fs = std::filesystem;

std::string read_whole_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("rktsph_atomic_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
  }

  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(directory_), {}));
  }

  fs::path directory_;
};

TEST_F(AtomicFileTest, WritesAndReplacesContent) {
  const fs::path file = directory_ / "summary.json";
  write_file_atomically(file, std::string("first\n"));
  EXPECT_EQ(read_whole_file(file), "first\n");
  write_file_atomically(file, [](std::ostream& out) { out << "second " << 2 << '\n'; });
  EXPECT_EQ(read_whole_file(file), "second 2\n");
  EXPECT_EQ(file_count(), 1u);  // no temporary left behind
}

TEST_F(AtomicFileTest, BinaryContentIsWrittenUnchanged) {
  const std::string content("a\0b\r\n\xff", 6);
  const fs::path file = directory_ / "binary";
  write_file_atomically(file, content);
  EXPECT_EQ(read_whole_file(file), content);
}

TEST_F(AtomicFileTest, TemporaryIsInTheSameDirectoryAndNamedAfterThePid) {
  const fs::path file = directory_ / "a.csv";
  const fs::path temporary = temporary_path_for(file);
  EXPECT_EQ(temporary.parent_path(), file.parent_path());
  EXPECT_EQ(temporary.filename().string(), "a.csv.tmp-" + std::to_string(::getpid()));
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsRunErrorNamingThePathAndLeavesNothing) {
  const fs::path missing_directory = directory_ / "does_not_exist";
  const fs::path file = missing_directory / "out.vtu";
  try {
    write_file_atomically(file, std::string("x"));
    FAIL() << "expected RunError";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(missing_directory.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
  EXPECT_FALSE(fs::exists(missing_directory));
  EXPECT_FALSE(fs::exists(temporary_path_for(file)));
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(AtomicFileTest, ThrowingWriterKeepsPreviousContentAndRemovesTemporary) {
  const fs::path file = directory_ / "probes.csv";
  write_file_atomically(file, std::string("complete old content\n"));
  const auto failing_writer = [](std::ostream& out) {
    out << "partial new cont";
    out.flush();  // the partial text really reaches the temporary file before the failure
    throw std::runtime_error("simulated failure mid-write");
  };
  EXPECT_THROW(write_file_atomically(file, failing_writer), std::runtime_error);
  EXPECT_EQ(read_whole_file(file), "complete old content\n");
  EXPECT_FALSE(fs::exists(temporary_path_for(file)));
  EXPECT_EQ(file_count(), 1u);
}

TEST_F(AtomicFileTest, FailedStreamIsReportedAsRunError) {
  const fs::path file = directory_ / "state";
  const auto breaking_writer = [](std::ostream& out) { out.setstate(std::ios::badbit); };
  EXPECT_THROW(write_file_atomically(file, breaking_writer), RunError);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_EQ(file_count(), 0u);
}

TEST_F(AtomicFileTest, RenameOntoADirectoryThrowsRunErrorAndCleansUp) {
  const fs::path target = directory_ / "occupied";
  fs::create_directories(target / "child");
  EXPECT_THROW(write_file_atomically(target, std::string("x")), RunError);
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_FALSE(fs::exists(temporary_path_for(target)));
}

}  // namespace
}  // namespace rktsph
